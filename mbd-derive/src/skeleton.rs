//! What a failed derive still emits beside its errors: every item a successful one would
//! (the trait impls, `initial_state`, `outputs`, `events`, the state and outputs structs,
//! ...) with the same signatures and sizes, and bodies that are never run (the crate does
//! not build). Without them each use of a missing item is one more error (E0599, E0277), and
//! the one real mistake drowns in its consequences.

use crate::parse::Mechanism;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::Ident;

/// The skeleton of `ast`'s generated code. Sizes are the ones the model would have had: the
/// free coordinates (joint coordinates included, driven ones not) and the constraint
/// equations (one per `constraint`, two or three per `close`).
pub fn emit(ast: &Mechanism) -> TokenStream {
    let ident = &ast.ident;
    let free: Vec<_> = unique(
        ast.coords
            .iter()
            .filter(|c| !ast.drives.iter().any(|d| d.name == **c)),
    );
    let n = free.len();
    let d = 2 * n;
    let m = ast.constraints.len()
        + (ast.closures.iter())
            .map(|cl| crate::close::equations(cl, ast.dim))
            .sum::<usize>();
    let never = quote!(::core::unreachable!(
        "`#[derive(Mechanism)]` failed: see its error"
    ));
    let v = |k: usize| quote!(::mbd::__private::Vector<#k>);
    let (vn, vd, vm) = (v(n), v(d), v(m));
    let mat = |r: usize, c: usize| quote!(::mbd::__private::Matrix<#r, #c>);
    let (mnn, mmn, mdd) = (mat(n, n), mat(m, n), mat(d, d));
    let res = |t: TokenStream| quote!(::mbd::__private::Result<#t>);
    let names: Vec<String> = free.iter().map(|c| c.to_string()).collect();
    let constrained = (m > 0).then(|| {
        let r_both = res(quote!((#vn, #vm)));
        quote! {
            impl ::mbd::__private::Constrained<#n, #m> for #ident {
                fn phi(&self, t: f64, q: &#vn) -> #vm { #never }
                fn phi_q(&self, t: f64, q: &#vn) -> #mmn { #never }
                fn phi_t(&self, t: f64, q: &#vn) -> #vm { #never }
                fn gamma(&self, t: f64, q: &#vn, qd: &#vn) -> #vm { #never }
                fn acceleration_and_multipliers(&self, t: f64, q: &#vn, qd: &#vn) -> #r_both { #never }
            }
        }
    });
    let state = format_ident!("{}State", ident);
    // The state's fields, each once (a coordinate named like another's `_dot` is an error).
    let dots: Vec<_> = free.iter().map(|c| format_ident!("{}_dot", c)).collect();
    let fields = unique(free.iter().copied().chain(&dots));
    let outputs = (!ast.outputs.is_empty()).then(|| {
        let s = format_ident!("{}Outputs", ident);
        let names = output_fields(ast);
        let k = names.len();
        let (ro, rk) = (res(quote!(#s)), res(quote!([f64; #k])));
        let eq = crate::codegen::flat_partial_eq(&s, &names.iter().collect::<Vec<_>>());
        quote! {
            #[derive(Debug, Clone, Copy)]
            pub struct #s { #(pub #names: f64,)* }
            #eq
            impl #ident {
                pub const OUTPUTS: [&'static str; #k] = [""; #k];
                pub fn outputs(&self, t: f64, y: &#vd) -> #ro { #never }
                pub fn output_values(&self, t: f64, y: &#vd) -> #rk { #never }
            }
        }
    });
    let events = (!ast.events.is_empty()).then(|| {
        let names = unique(ast.events.iter().map(|e| &e.name));
        let fns = names.iter().map(|e| format_ident!("event_{}", e));
        let r = res(quote!(f64));
        quote! {
            impl #ident {
                #(pub fn #fns(&self, t: f64, y: &#vd) -> #r { #never })*
                pub fn events(&self) -> ::std::vec::Vec<::mbd::__private::integrate::Event<'_, #d>> { #never }
            }
        }
    });
    let friction = (!ast.frictions.is_empty()).then(|| {
        let nf = ast.frictions.len();
        let nmf = n + m + nf;
        let along = unique(ast.frictions.iter().map(|f| &f.along));
        let sticks = along.iter().map(|c| format_ident!("{}_sticks", c));
        let sliding = format_ident!("{}Sliding", ident);
        let (rb, rv) = (res(quote!(bool)), res(quote!(#vn)));
        quote! {
            impl #ident {
                #(pub fn #sticks(&self, t: f64, y: &#vd) -> #rb { #never })*
                pub fn acceleration_sliding(&self, t: f64, q: &#vn, qd: &#vn, direction: &[f64; #nf]) -> #rv { #never }
                pub fn sliding(&self, direction: [f64; #nf]) -> #sliding<'_> { #never }
            }
            #[derive(Clone, Copy)]
            pub struct #sliding<'a> { pub model: &'a #ident, pub direction: [f64; #nf] }
            impl ::mbd::__private::OdeSystem<#d> for #sliding<'_> {
                fn rhs(&self, t: f64, y: &#vd) -> ::mbd::__private::Result<#vd> { #never }
            }
            impl ::mbd::__private::Frictional<#n, #m, #nf, #nmf> for #ident {
                const ALONG: [usize; #nf] = [0; #nf];
                fn contacts(&self, t: f64, q: &#vn, qd: &#vn) -> ::mbd::__private::Contacts<#n, #m, #nf> { #never }
            }
            impl ::mbd::__private::Hybrid<#d> for #ident {
                type Mode = [::mbd::__private::Slip; #nf];
                const SWITCHES: usize = #nf;
                fn rhs_in(&self, t: f64, y: &#vd, mode: &Self::Mode) -> ::mbd::__private::Result<#vd> { #never }
                fn switching(&self, t: f64, y: &#vd, mode: &Self::Mode, k: usize) -> f64 { #never }
                fn mode_at(&self, t: f64, y: &#vd) -> ::mbd::__private::Result<Self::Mode> { #never }
                fn switch(&self, t: f64, y: &mut #vd, mode: &Self::Mode, k: usize) -> ::mbd::__private::Result<Self::Mode> { #never }
            }
        }
    });
    let (r_vn, r_vd, r_unit) = (res(vn.clone()), res(vd.clone()), res(quote!(())));
    let geometry = crate::geometry::skeleton(ast, d, &never);
    quote! {
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        pub struct #state { #(pub #fields: f64,)* }
        impl ::core::convert::From<&#vd> for #state { fn from(y: &#vd) -> Self { #never } }
        impl ::core::convert::From<#state> for #vd { fn from(s: #state) -> Self { #never } }
        #[allow(unused_variables, unreachable_code, clippy::all)]
        impl #ident {
            pub const DOF: usize = #n;
            pub const GENERATED: ::mbd::__private::Generated = ::mbd::__private::Generated {
                parts: &[], statements: 0, constraints: #m,
            };
            pub fn initial_state(&self) -> #vd { #never }
            pub fn check_parameters(&self) -> #r_unit { #never }
        }
        #[allow(unused_variables, unreachable_code, clippy::all)]
        const _: () = {
            impl ::mbd::__private::Mechanism<#n> for #ident {
                const COORDINATES: [&'static str; #n] = [#(#names),*];
                fn mass_matrix(&self, t: f64, q: &#vn) -> ::mbd::__private::Result<#mnn> { #never }
                fn forces(&self, t: f64, q: &#vn, qd: &#vn) -> #r_vn { #never }
                fn acceleration(&self, t: f64, q: &#vn, qd: &#vn) -> #r_vn { #never }
                fn energy(&self, t: f64, q: &#vn, qd: &#vn) -> ::mbd::__private::Result<f64> { #never }
            }
            #constrained
            impl ::mbd::__private::OdeSystem<#d> for #ident {
                fn rhs(&self, t: f64, y: &#vd) -> #r_vd { #never }
                fn jacobian(&self, t: f64, y: &#vd) -> ::mbd::__private::Result<#mdd> { #never }
            }
        };
        #outputs
        #events
        #friction
        #geometry
    }
}

/// The outputs struct's fields, each once: a vector output's components (`p_x`, `p_y`
/// (, `p_z`)) where its expression is one by its form (a point, a vector literal, a body
/// query that gives a vector), so that the user's `out.p_x` adds no error of its own.
fn output_fields(ast: &Mechanism) -> Vec<Ident> {
    let dim = match ast.dim {
        crate::parse::Dim::Planar => 2,
        crate::parse::Dim::Spatial => 3,
    };
    let mut fields = Vec::new();
    for o in &ast.outputs {
        match vector_len(ast, &o.expr, dim) {
            Some(len) => fields.extend(
                ["x", "y", "z"][..len.min(3)]
                    .iter()
                    .map(|axis| format_ident!("{}_{}", o.name, axis)),
            ),
            None => fields.push(o.name.clone()),
        }
    }
    let mut seen = std::collections::HashSet::new();
    fields.retain(|f| seen.insert(f.to_string()));
    fields
}

/// How many components `e` has when its form says it is a vector.
fn vector_len(ast: &Mechanism, e: &syn::Expr, dim: usize) -> Option<usize> {
    let name = |e: &syn::Expr| match e {
        syn::Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
        _ => None,
    };
    match e {
        syn::Expr::Paren(p) => vector_len(ast, &p.expr, dim),
        syn::Expr::Array(a) => Some(a.elems.len()),
        syn::Expr::Call(c) => match name(&c.func)?.as_str() {
            "position" | "velocity" | "acceleration" => Some(dim),
            "angular_velocity" | "angular_acceleration" | "cross" if dim == 3 => Some(3),
            _ => None,
        },
        _ => {
            let n = name(e)?;
            ast.points.iter().any(|p| p.name == n).then_some(dim)
        }
    }
}

/// Each name once, in first-seen order: a duplicated name is one of the errors reported,
/// and must not come back as a duplicate item.
fn unique<'a>(names: impl Iterator<Item = &'a Ident>) -> Vec<&'a Ident> {
    let mut seen = std::collections::HashSet::new();
    names.filter(|n| seen.insert(n.to_string())).collect()
}
