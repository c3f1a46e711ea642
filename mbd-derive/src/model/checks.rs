//! What the equations must satisfy before code is generated: parameter checks for run
//! time, no non-finite constant, and the default configuration on the constraints.

use super::Ast;
use super::kinematics::BodyKin;
use super::{Equations, Names, ParamCheck, Role};
use crate::lower::{Binding, Context, Lowerer};
use crate::parse::Errors;
use crate::sym::{Expr, Sym};
use std::collections::HashMap;
use syn::Ident;

/// A check of an element's constant (stiffness, damping, friction): eager.
pub(super) fn check(what: String, expr: Expr, positive: bool) -> ParamCheck {
    ParamCheck {
        what,
        expr,
        positive,
        eager: true,
    }
}

/// Every body's mass (> 0) and diagonal inertias (>= 0: a zero one of a free body makes the
/// mass matrix singular, which the solve reports; a tree body's zero inertia is a point
/// mass), named by the body.
pub(super) fn body_checks(names: &Names, bodies: &[BodyKin]) -> Vec<ParamCheck> {
    let mut by_index: Vec<(usize, &String)> = names
        .iter()
        .filter_map(|(n, b)| match b {
            Binding::Body(i) => Some((*i, n)),
            _ => None,
        })
        .collect();
    by_index.sort();
    let mut out = Vec::new();
    for (i, name) in by_index {
        let b = &bodies[i];
        out.push(ParamCheck {
            eager: false,
            ..check(format!("the mass of `{name}`"), b.mass, true)
        });
        if let Some(inertia) = &b.inertia {
            let axes = if b.rot.is_some() { 3 } else { 1 };
            for (k, row) in inertia.iter().enumerate().take(axes) {
                let what = if axes == 1 {
                    format!("the inertia of `{name}`")
                } else {
                    format!("the inertia of `{name}` about its axis {k}")
                };
                out.push(ParamCheck {
                    eager: false,
                    ..check(what, row[k], false)
                });
            }
        }
    }
    out
}

/// When every parameter has a default and the initial positions are given, the default
/// configuration must satisfy the constraints: checked here, at compile time.
pub(super) fn check_default_configuration(
    ast: &Ast,
    eqs: &mut Equations,
    spans: &[&proc_macro2::TokenStream],
    errors: &mut Errors,
) {
    let Equations {
        g,
        phi,
        init_q,
        roles,
        ..
    } = eqs;
    let (g, roles) = (g, &*roles);
    let positioned = |c: &Ident| ast.inits.iter().any(|i| !i.velocity && i.coord == *c);
    if phi.is_empty()
        || ast.params.iter().any(|p| p.default.is_none())
        || !ast.coords.iter().all(positioned)
    {
        return;
    }
    let mut values: HashMap<Sym, f64> = HashMap::new();
    let no_names = HashMap::new();
    let mut scratch = Errors::default();
    for p in &ast.params {
        let e = Lowerer {
            g,
            names: &no_names,
            struct_name: "",
            model: None,
            errors: &mut scratch,
        }
        .scalar(p.default.as_ref().expect("checked"), Context::Constant);
        match e.and_then(|e| g.as_const(e)) {
            Some(v) => {
                let s = g.symbol(&p.name.to_string());
                values.insert(g.as_sym(s).expect("symbol"), v);
            }
            None => return,
        }
    }
    let env_params = values.clone();
    for (a, e) in init_q.iter().enumerate() {
        let v = g.eval(*e, &|s| env_params.get(&s).copied().unwrap_or(f64::NAN));
        if let Some((s, _)) = roles.iter().find(|(_, r)| **r == Role::Q(a)) {
            values.insert(*s, v);
        }
    }
    for (k, p) in phi.iter().enumerate() {
        let r = g.eval(*p, &|s| {
            if g_is_time(roles, s) {
                0.0
            } else {
                values.get(&s).copied().unwrap_or(f64::NAN)
            }
        });
        if r.is_finite() && r.abs() > 1e-9 {
            errors.over(
                spans[k],
                format!("the default configuration (parameter defaults and `init` positions at t = 0) violates this constraint: residual {r:.3e}"),
            );
        }
    }
}

fn g_is_time(roles: &HashMap<Sym, Role>, s: Sym) -> bool {
    roles.get(&s) == Some(&Role::Time)
}

/// Folding constants can produce inf or NaN (`1.0 / 0.0`, `ln(-1.0)`, a derivative of
/// `sqrt` at a point where its argument vanishes): refused at compile time, not at run time.
pub(super) fn non_finite(ast: &Ast, eqs: &Equations, errors: &mut Errors) {
    let mut roots: Vec<Expr> = eqs
        .mass
        .iter()
        .flatten()
        .chain(&eqs.forces)
        .chain(&eqs.phi)
        .chain(&eqs.phi_t)
        .chain(&eqs.gamma)
        .copied()
        .collect();
    roots.extend(eqs.phi_q.iter().flatten());
    roots.extend(
        eqs.outputs
            .iter()
            .map(|o| o.expr)
            .chain(eqs.events.iter().map(|e| e.expr)),
    );
    roots.extend(eqs.init_q.iter().chain(&eqs.init_qd));
    roots.push(eqs.energy);
    if let Some(j) = &eqs.jacobian {
        roots.extend(
            j.r_q
                .iter()
                .chain(&j.r_qd)
                .chain(&j.c_q)
                .chain(&j.c_qd)
                .flatten(),
        );
    }
    if roots.iter().any(|e| eqs.g.has_nonfinite_constant(*e)) {
        errors.at(
            ast.ident.span(),
            "the model's equations contain a non-finite constant (a division by zero, the log or square root of a negative number, or the derivative of `sqrt` where its argument is zero)",
        );
    }
}
