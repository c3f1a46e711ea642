//! The `geometry` part (`#[mechanism(geometry)]`): what to draw of a mechanism at a state,
//! for reports that draw and animate it (`impl Drawable`, `mbd_core::geometry`).
//!
//! Each shape is written as ordinary output expressions of the language (`position(b)`,
//! `position(b, [h, 0.0])`, a point's name, a spring end's expression), lowered and reduced
//! like the user's outputs, and emitted as one straight-line function. So it follows every
//! form the mechanics takes (drives, closed-form closures, trees) without knowing it.
//! A rigid body has no extent in the language: it is drawn as the slender bar of its mass
//! and central inertia (half-length `sqrt(3 I / m)`) along its body x axis; a spatial body
//! with a diagonal inertia by its three body axes (`principal_ends`); a tree body as the
//! segment from its joint through its mass centre to twice that offset.

use crate::codegen::Block;
use crate::model::Equations;
use crate::parse::{BodyKind, Dim, End, Mechanism};
use crate::sym::Expr;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::parse_quote;

/// One shape: its kind (a `ShapeKind` variant), its name, its points (each a position
/// vector: syntax before lowering, `dim` symbolic values after).
pub struct Shape<P> {
    pub kind: &'static str,
    pub name: String,
    pub points: Vec<P>,
}

/// The shapes of `ast` as expressions of the language, in declaration order (none unless
/// `#[mechanism(geometry)]` asks for them).
pub fn shapes(ast: &Mechanism) -> Vec<Shape<syn::Expr>> {
    if !ast.geometry {
        return Vec::new();
    }
    let zero: syn::Expr = match ast.dim {
        Dim::Planar => parse_quote!([0.0, 0.0]),
        Dim::Spatial => parse_quote!([0.0, 0.0, 0.0]),
    };
    let is_body = |id: &syn::Ident| {
        ast.bodies.iter().any(|b| &b.name == id) || ast.tree.iter().any(|b| &b.name == id)
    };
    let mut out = Vec::new();
    for b in &ast.bodies {
        let name = &b.name;
        let mut points: Vec<syn::Expr> = vec![parse_quote!(position(#name))];
        let kind = match b.kind {
            BodyKind::Particle => "Particle",
            BodyKind::Rigid | BodyKind::Rigid3 => "Rigid",
        };
        if let (BodyKind::Rigid, Dim::Planar, Some(m), Some(i)) =
            (&b.kind, ast.dim, &b.mass, &b.inertia)
        {
            let h: syn::Expr = parse_quote!(sqrt(3.0 * (#i) / (#m)));
            points.push(parse_quote!(position(#name, [#h, 0.0])));
            points.push(parse_quote!(position(#name, [-(#h), 0.0])));
        }
        if let (BodyKind::Rigid3, Some(m), Some(i)) = (&b.kind, &b.mass, &b.inertia) {
            points.extend(principal_ends(name, m, i));
        }
        out.push(Shape {
            kind,
            name: name.to_string(),
            points,
        });
    }
    for b in &ast.tree {
        let name = &b.name;
        let parent: syn::Expr = match &b.parent {
            Some(p) => parse_quote!(position(#p, #zero)),
            None => parse_quote!(position(#name, #zero)),
        };
        let far: syn::Expr = match &b.com {
            Some(syn::Expr::Array(a)) => {
                let twice = a
                    .elems
                    .iter()
                    .map(|c| -> syn::Expr { parse_quote!(2.0 * (#c)) });
                parse_quote!(position(#name, [#(#twice),*]))
            }
            _ => parse_quote!(position(#name)),
        };
        out.push(Shape {
            kind: "Link",
            name: name.to_string(),
            points: vec![
                parent,
                parse_quote!(position(#name, #zero)),
                parse_quote!(position(#name)),
                far,
            ],
        });
    }
    for p in &ast.points {
        let name = &p.name;
        out.push(Shape {
            kind: "Point",
            name: name.to_string(),
            points: vec![parse_quote!(#name)],
        });
    }
    let end = |e: &End| -> syn::Expr {
        match e {
            End::Named(id) if is_body(id) => parse_quote!(position(#id)),
            End::Named(id) => parse_quote!(#id),
            End::At(e) => e.clone(),
        }
    };
    for s in &ast.springs {
        out.push(Shape {
            kind: "Spring",
            name: s.name.to_string(),
            points: vec![end(&s.from), end(&s.to)],
        });
    }
    for d in &ast.dampers {
        out.push(Shape {
            kind: "Damper",
            name: d.name.to_string(),
            points: vec![end(&d.from), end(&d.to)],
        });
    }
    out
}

/// A spatial body with `inertia = diag(a, b, c)`: the ends of its three body axes at the
/// half-lengths `sqrt(3 J_k / m)` of a uniform box of the same second moments
/// `J_k = (a + b + c)/2 - I_k` (a slender bar's ends, exactly; a report draws a body with two
/// such axes as the plate or disk they span). Another inertia form: none.
fn principal_ends(name: &syn::Ident, m: &syn::Expr, inertia: &syn::Expr) -> Vec<syn::Expr> {
    let syn::Expr::Call(call) = inertia else {
        return Vec::new();
    };
    let is_diag = matches!(&*call.func, syn::Expr::Path(p) if p.path.is_ident("diag"));
    let moments: Vec<&syn::Expr> = call.args.iter().collect();
    let [a, b, c] = moments.as_slice() else {
        return Vec::new();
    };
    if !is_diag {
        return Vec::new();
    }
    [a, b, c]
        .into_iter()
        .enumerate()
        .map(|(k, ik)| {
            let j: syn::Expr = parse_quote!(((#a) + (#b) + (#c)) / 2.0 - (#ik));
            let h: syn::Expr = parse_quote!(sqrt(3.0 * abs((#j) / (#m))));
            let mut axis: Vec<syn::Expr> = vec![parse_quote!(0.0); 3];
            axis[k] = h;
            parse_quote!(position(#name, [#(#axis),*]))
        })
        .collect()
}

/// Lower every point with `vector` (the model's output lowering); a shape with a point that
/// does not lower is left out (its error is already reported).
pub fn lower<P>(
    shapes: Vec<Shape<P>>,
    mut vector: impl FnMut(&P) -> Option<Vec<Expr>>,
) -> Vec<Shape<Vec<Expr>>> {
    shapes
        .into_iter()
        .filter_map(|s| {
            let points = s.points.iter().map(&mut vector).collect::<Option<_>>()?;
            Some(Shape {
                kind: s.kind,
                name: s.name,
                points,
            })
        })
        .collect()
}

/// Applies `f` to every coordinate of every point (the reduction to free coordinates).
pub fn map(shapes: &mut [Shape<Vec<Expr>>], mut f: impl FnMut(Expr) -> Expr) {
    for x in shapes
        .iter_mut()
        .flat_map(|s| s.points.iter_mut().flatten())
    {
        *x = f(*x);
    }
}

/// `impl Drawable` for `ident`: `split` binds `q`, `qd` from `y`, `check` is the closure's
/// domain check. Returns the code and its statements.
pub fn emit(
    ident: &syn::Ident,
    eq: &Equations,
    d: usize,
    split: &TokenStream,
    check: &Option<TokenStream>,
) -> (TokenStream, usize) {
    let roots: Vec<Expr> = eq
        .geometry
        .iter()
        .flat_map(|s| s.points.iter().flatten().copied())
        .collect();
    let b = Block::new(eq, &roots);
    let s = b.stmts();
    let p = quote!(::mbd::__private);
    let shapes = eq.geometry.iter().map(|shape| {
        let kind = format_ident!("{}", shape.kind);
        let name = &shape.name;
        let points = shape.points.iter().map(|pt| {
            let c: Vec<TokenStream> = pt.iter().map(|e| b.leaf(*e)).collect();
            let z = c.get(2).cloned().unwrap_or_else(|| quote!(0.0));
            let (x, y) = (&c[0], &c[1]);
            quote!([#x, #y, #z])
        });
        quote!(#p::Shape { kind: #p::ShapeKind::#kind, name: #name, points: vec![#(#points),*] })
    });
    let code = quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic, reason = "generated straight-line code")]
        impl #p::Drawable<#d> for #ident {
            fn geometry(&self, t: f64, y: &#p::Vector<#d>) -> #p::Result<::std::vec::Vec<#p::Shape>> {
                #split
                #check
                #s
                Ok(vec![#(#shapes),*])
            }
        }
    };
    (code, b.len())
}

/// `impl Drawable` beside a failed derive's errors (see `skeleton.rs`), where asked for.
pub fn skeleton(ast: &Mechanism, d: usize, never: &TokenStream) -> Option<TokenStream> {
    let (ident, p) = (&ast.ident, quote!(::mbd::__private));
    ast.geometry.then(|| {
        quote! {
            #[allow(unused_variables, unreachable_code, clippy::all)]
            impl #p::Drawable<#d> for #ident {
                fn geometry(&self, t: f64, y: &#p::Vector<#d>) -> #p::Result<::std::vec::Vec<#p::Shape>> { #never }
            }
        }
    })
}
