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
        roots.extend([f.normal, f.mu, f.mu_static]);
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
    let normal = eq.frictions.iter().map(|f| b.leaf(f.normal));
    let mu_k = eq.frictions.iter().map(|f| b.leaf(f.mu));
    let mu_s = eq.frictions.iter().map(|f| b.leaf(f.mu_static));
    let along = eq.frictions.iter().map(|f| f.coord);
    let p = quote!(::mbd::__private);
    let project = (m > 0).then(|| {
        quote! {
            fn project_in(&self, t: f64, y: &mut #p::Vector<#d>, mode: &Self::Mode) -> #p::Result<()> {
                #p::OdeSystem::<#d>::project(self, t, y)?;
                #p::friction::project_in::<#n, #nf, #d>(&<Self as #p::Frictional<#n, #m, #nf, #a>>::ALONG, y, mode);
                Ok(())
            }
        }
    });
    let sliding_check = (m > 0).then(|| quote!(self.check_parameters()?;));
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
        }
        /// Coulomb friction as discrete modes (slip forward, slip backward, stick per
        /// contact, in declaration order): integrate with `mbd::hybrid::solve`.
        #[automatically_derived]
        impl #p::Hybrid<#d> for #ident {
            type Mode = [#p::Slip; #nf];
            const SWITCHES: usize = #nf;
            fn rhs_in(&self, t: f64, y: &#p::Vector<#d>, mode: &Self::Mode) -> #p::Result<#p::Vector<#d>> {
                // Every contact sliding: the straight-line forces with the directions given
                // (the sliding view's), no stuck rows to solve. Its element checks and the
                // mass solve's pivots refuse bad parameters (constrained: the LU does not).
                if mode.iter().all(|m| *m != #p::Slip::Stick) {
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
            fn switching_state(&self, mode: &Self::Mode, k: usize) -> Option<(usize, f64)> {
                #p::friction::switching_state::<#n, #nf>(&<Self as #p::Frictional<#n, #m, #nf, #a>>::ALONG, mode, k)
            }
            fn mode_at(&self, t: f64, y: &#p::Vector<#d>) -> #p::Result<Self::Mode> {
                #p::friction::mode_at::<Self, #n, #m, #nf, #a, #d>(self, t, y)
            }
            fn switch(&self, t: f64, y: &mut #p::Vector<#d>, mode: &Self::Mode, k: usize) -> #p::Result<Self::Mode> {
                #p::friction::switch::<Self, #n, #m, #nf, #a, #d>(self, t, y, mode, k)
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
    f: &crate::parse::Friction,
    errors: &mut crate::parse::Errors,
) {
    use syn::spanned::Spanned;
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
