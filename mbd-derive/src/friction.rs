//! Coulomb friction in generated code: the model's contacts for the core's mode logic
//! (`Frictional`), and the model as a hybrid system (`Hybrid`: modes, switching functions,
//! switches), all forwarding to `mbd_core::friction`.

use crate::codegen::Block;
use crate::model::Equations;
use proc_macro2::TokenStream;
use quote::quote;
use syn::Ident;

/// `impl Frictional` and `impl Hybrid` for a model with friction, and the statements emitted.
pub fn emit(
    ident: &Ident,
    eq: &Equations,
    frictionless: &[crate::sym::Expr],
) -> (TokenStream, usize) {
    let (n, m, nf) = (eq.free.len(), eq.phi.len(), eq.frictions.len());
    let (a, d) = (n + m + nf, 2 * n);
    let mut roots: Vec<_> = eq
        .mass
        .iter()
        .flatten()
        .chain(frictionless)
        .copied()
        .collect();
    roots.extend(eq.phi_q.iter().flatten().chain(&eq.gamma));
    for f in &eq.frictions {
        roots.extend([f.mu, f.mu_static]);
        // An implicit normal names `qdd` and `lambda`: it is `normals`' (below).
        roots.extend(f.implicit.is_none().then_some(f.normal));
    }
    let b = Block::new(eq, &roots);
    let (s, mass, forces) = (
        b.stmts(),
        b.matrix("mass", n, n, &eq.mass),
        b.vector("f", n, frictionless),
    );
    let (pq, gm) = (
        b.matrix("phi_q", m, n, &eq.phi_q),
        b.vector("gamma", m, &eq.gamma),
    );
    let normal = eq.frictions.iter().map(|f| match f.implicit {
        None => b.leaf(f.normal),
        Some(_) => quote!(0.0),
    });
    let implicit = eq.frictions.iter().any(|f| f.implicit.is_some());
    let normals = implicit.then(|| normals(eq));
    let mu_k = eq.frictions.iter().map(|f| b.leaf(f.mu));
    let mu_s = eq.frictions.iter().map(|f| b.leaf(f.mu_static));
    let along = eq.frictions.iter().map(|f| f.coord);
    let p = quote!(::mbd::__private);
    // The model's own projection in every mode: a loop's constraints, and a ball joint's
    // chart switch (`chart.rs`) also in a model without constraints.
    let onto_modes = (m > 0).then(|| {
        quote!(#p::friction::project_in::<#n, #nf, #d>(&<Self as #p::Frictional<#n, #m, #nf, #a>>::ALONG, y, mode);)
    });
    let project = quote! {
        fn project_in(&self, t: f64, y: &mut #p::Vector<#d>, mode: &Self::Mode) -> #p::Result<()> {
            #p::OdeSystem::<#d>::project(self, t, y)?;
            let _ = mode;
            #onto_modes
            Ok(())
        }
    };
    let sliding_check = (m > 0).then(|| quote!(self.check_parameters()?;));
    // Implicit normals: the sliding view goes through the core's Newton too.
    let fast = !implicit;
    let code = quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic, reason = "generated straight-line code")]
        impl #p::Frictional<#n, #m, #nf, #a> for #ident {
            const ALONG: [usize; #nf] = [#(#along),*];
            fn contacts(&self, t: f64, q: &#p::Vector<#n>, qd: &#p::Vector<#n>) -> #p::Contacts<#n, #m, #nf> {
                #s #mass #forces #pq #gm
                #p::Contacts { mass, forces: f, phi_q, gamma,
                    normal: [#(#normal),*], mu_k: [#(#mu_k),*], mu_s: [#(#mu_s),*] }
            }
            #normals
        }
        /// Coulomb friction as discrete modes (slip forward, slip backward, stick per
        /// contact, in declaration order): any integrator's ordinary `solve` runs them, as
        /// `mbd::hybrid::solve` does with its settings.
        #[automatically_derived]
        impl #p::Hybrid<#d> for #ident {
            type Mode = [#p::Slip; #nf];
            const SWITCHES: usize = #nf;
            fn rhs_in(&self, t: f64, y: &#p::Vector<#d>, mode: &Self::Mode) -> #p::Result<#p::Vector<#d>> {
                // Every contact sliding: the straight-line forces with the directions given
                // (the sliding view's), no stuck rows to solve. Its element checks and the
                // mass solve's pivots refuse bad parameters (constrained: the LU does not).
                if #fast && mode.iter().all(|m| *m != #p::Slip::Stick) {
                    #sliding_check
                    let direction = mode.map(|m| if m == #p::Slip::Forward { 1.0 } else { -1.0 });
                    return #p::solve::second_order_rhs::<#n, #d>(y, |q, qd| self.acceleration_sliding(t, q, qd, &direction))
                        .map_err(|e| self.diagnose(e));
                }
                // A negative coefficient or mass passed at run time: no stuck-row solve
                // would notice it.
                self.check_parameters()?;
                #p::friction::rhs_in::<Self, #n, #m, #nf, #a, #d>(self, t, y, mode)
            }
            fn switching(&self, t: f64, y: &#p::Vector<#d>, mode: &Self::Mode, k: usize) -> f64 {
                #p::friction::switching::<Self, #n, #m, #nf, #a, #d>(self, t, y, mode, k)
            }
            const KINKS: usize = #nf;
            fn kink(&self, t: f64, y: &#p::Vector<#d>, mode: &Self::Mode, k: usize) -> f64 {
                #p::friction::kink::<Self, #n, #m, #nf, #a, #d>(self, t, y, mode, k)
            }
            fn switching_state(&self, mode: &Self::Mode, k: usize) -> Option<(usize, f64)> {
                #p::friction::switching_state::<#n, #nf>(&<Self as #p::Frictional<#n, #m, #nf, #a>>::ALONG, mode, k)
            }
            // A failed solve explained by a bad parameter names it (a negative mass is not
            // "a mass matrix not positive definite", a NaN coefficient is the parameter's).
            fn mode_at(&self, t: f64, y: &#p::Vector<#d>) -> #p::Result<Self::Mode> {
                #p::friction::mode_at::<Self, #n, #m, #nf, #a, #d>(self, t, y).map_err(|e| self.diagnose(e))
            }
            fn switch(&self, t: f64, y: &mut #p::Vector<#d>, mode: &Self::Mode, k: usize) -> #p::Result<Self::Mode> {
                #p::friction::switch::<Self, #n, #m, #nf, #a, #d>(self, t, y, mode, k).map_err(|e| self.diagnose(e))
            }
            #project
        }
    };
    (code, b.len())
}

/// The accelerations (and multipliers) of the plain model: modes from the state, at rest
/// from the loads (`mbd_core::friction::acceleration_and_multipliers`).
pub fn acceleration(eq: &Equations) -> TokenStream {
    let (n, m, nf) = (eq.free.len(), eq.phi.len(), eq.frictions.len());
    let a = n + m + nf;
    quote!(::mbd::__private::friction::acceleration_and_multipliers::<Self, #n, #m, #nf, #a>(self, t, q, qd))
}

/// The plain model's forces, friction included as in the state's modes
/// (`mbd_core::friction::forces`).
pub fn forces(eq: &Equations) -> TokenStream {
    let (n, m, nf) = (eq.free.len(), eq.phi.len(), eq.frictions.len());
    let a = n + m + nf;
    quote!(::mbd::__private::friction::forces::<Self, #n, #m, #nf, #a>(self, t, q, qd))
}

/// Coefficients known at compile time must satisfy `0 <= mu_k <= mu_s` (parameters are
/// checked at run time, by `mbd_core::friction`).
pub fn check_coefficients(
    g: &crate::sym::Graph,
    mu_k: crate::sym::Expr,
    mu_s: crate::sym::Expr,
    f: &crate::parse::Friction<crate::lowered::Term>,
    errors: &mut crate::parse::Errors,
) {
    if let Some(k) = g.as_const(mu_k).filter(|k| *k < 0.0) {
        errors.at(
            f.mu.span(),
            format!("a friction coefficient is not negative, got {k}"),
        );
    }
    if let (Some(k), Some(s)) = (g.as_const(mu_k), g.as_const(mu_s))
        && s < k
    {
        let span = f.mu_static.as_ref().map_or(f.span, |e| e.span());
        errors.at(
            span,
            format!("the static coefficient {s} is below the kinetic one {k}: need `mu_s >= mu_k`"),
        );
    }
}

/// The normal force without the accelerations and multipliers when it does not depend on
/// them, although it names them: a reaction projected on the direction its
/// acceleration-dependent part is orthogonal to (a pin's force along the rod). Every
/// derivative by an acceleration or multiplier must simplify to zero; then setting them to
/// zero is exact. `None` when one does not (the friction would be implicit).
pub fn explicit_normal(
    g: &mut crate::sym::Graph,
    roles: &std::collections::HashMap<crate::sym::Sym, crate::model::Role>,
    normal: crate::sym::Expr,
) -> Option<crate::sym::Expr> {
    use crate::model::Role;
    let implicit: Vec<_> = g
        .free_symbols(normal)
        .into_iter()
        .filter(|s| matches!(roles.get(s), Some(Role::Qdd(_) | Role::Lambda(_))))
        .collect();
    for s in &implicit {
        let d = g.diff(normal, *s);
        if !g.is_zero(d) {
            return None;
        }
    }
    let zero = g.zero();
    let map = implicit.into_iter().map(|s| (s, zero)).collect();
    Some(g.substitute(normal, &map))
}

/// `const IMPLICIT` and `fn normals` of `Frictional`: every contact's normal force at
/// `(qdd, lambda)` and its derivatives by them (zero for an explicit one).
fn normals(eq: &Equations) -> TokenStream {
    use crate::model::Role;
    let (n, m, nf) = (eq.free.len(), eq.phi.len(), eq.frictions.len());
    let mut roots: Vec<_> = eq.frictions.iter().map(|f| f.normal).collect();
    for f in &eq.frictions {
        roots.extend(f.implicit.iter().flatten().map(|(_, d)| *d));
    }
    let b = Block::new(eq, &roots);
    let s = b.stmts();
    let value = eq.frictions.iter().map(|f| b.leaf(f.normal));
    let mut sets = Vec::new();
    for (k, f) in eq.frictions.iter().enumerate() {
        for (role, d) in f.implicit.iter().flatten() {
            let v = b.leaf(*d);
            sets.push(match role {
                Role::Qdd(i) => quote!(d_qdd[#k][#i] += #v;),
                Role::Lambda(j) => quote!(d_lambda[#k][#j] += #v;),
                _ => continue,
            });
        }
    }
    let p = quote!(::mbd::__private);
    quote! {
        const IMPLICIT: bool = true;
        fn normals(&self, t: f64, q: &#p::Vector<#n>, qd: &#p::Vector<#n>, qdd: &#p::Vector<#n>,
            lambda: &#p::Vector<#m>) -> Option<#p::Normals<#n, #m, #nf>> {
            #s
            let mut d_qdd = [#p::Vector::<#n>::zeros(); #nf];
            let mut d_lambda = [#p::Vector::<#m>::zeros(); #nf];
            #(#sets)*
            Some(#p::Normals { value: [#(#value),*], d_qdd, d_lambda })
        }
    }
}

/// A normal force that depends on the accelerations or multipliers (the magnitude of a
/// revolute joint's reaction): its derivatives by each of them, for the core's Newton
/// iteration (`mbd_core::friction::resolve`). Refused with `#[mechanism(jacobian)]`: the
/// generated Jacobian differentiates the forces, which do not hold this friction.
pub fn implicit_normal(
    g: &mut crate::sym::Graph,
    roles: &std::collections::HashMap<crate::sym::Sym, crate::model::Role>,
    f: &crate::model::FrictionEq,
    jacobian: bool,
    errors: &mut crate::parse::Errors,
) -> Option<Vec<(crate::model::Role, crate::sym::Expr)>> {
    use crate::model::Role;
    if jacobian {
        errors.at(
            f.span,
            "this normal force depends on the accelerations (implicit friction, solved with them): \
             `#[mechanism(jacobian)]` is not generated for it",
        );
        return None;
    }
    let named: Vec<_> = g
        .free_symbols(f.normal)
        .into_iter()
        .filter_map(|s| match roles.get(&s) {
            Some(r @ (Role::Qdd(_) | Role::Lambda(_))) => Some((s, r.clone())),
            _ => None,
        })
        .collect();
    Some(
        named
            .into_iter()
            .map(|(s, r)| (r, g.diff(f.normal, s)))
            .collect(),
    )
}

/// The sliding view's accelerations where a normal force is implicit: the core's solve in
/// the given directions (`None` where every normal is explicit: the straight-line code).
pub fn sliding_acceleration(eq: &Equations) -> Option<TokenStream> {
    eq.frictions.iter().any(|f| f.implicit.is_some()).then(|| {
        let (n, m, nf) = (eq.free.len(), eq.phi.len(), eq.frictions.len());
        let a = n + m + nf;
        quote! {
            let modes = (*direction).map(|d| if d > 0.0 { ::mbd::__private::Slip::Forward } else { ::mbd::__private::Slip::Backward });
            ::mbd::__private::friction::acceleration_in::<Self, #n, #m, #nf, #a>(self, t, q, qd, &modes)
        }
    })
}

/// `<coord>_sticks` where the contact's normal force is implicit: the core's stuck solve
/// with the normals at its solution (`None` for an explicit one: the straight-line code).
pub fn sticks(eq: &Equations, k: usize) -> Option<TokenStream> {
    eq.frictions[k].implicit.is_some().then(|| {
        let (n, m, nf) = (eq.free.len(), eq.phi.len(), eq.frictions.len());
        let (a, d) = (n + m + nf, 2 * n);
        let coord = &eq.free[eq.frictions[k].coord];
        let fname = quote::format_ident!("{}_sticks", coord);
        let doc = format!(
            "At rest along `{coord}` (`der({coord}) = 0`): whether static friction can hold it, i.e. whether the \
             force needed to keep `{coord}` still is at most `mu_static |N|` (`N` at that solution)."
        );
        quote! {
            #[doc = #doc]
            pub fn #fname(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<bool> {
                ::mbd::__private::friction::sticks::<Self, #n, #m, #nf, #a, #d>(self, t, y, #k)
            }
        }
    })
}
