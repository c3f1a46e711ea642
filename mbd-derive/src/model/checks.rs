//! What the equations must satisfy before code is generated: parameter checks for run
//! time, no non-finite constant, and the default configuration on the constraints.

use super::Ast;
use super::kinematics::BodyKin;
use super::{Equations, Names, ParamCheck, Role};
use crate::lower::{Binding, Context, Lowerer};
use crate::parse::Errors;
use crate::sym::{Expr, Graph, Sym};
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
/// mass), named by the body; a spatial inertia of parameters is also checked to be one a
/// body can have (`inertia_checks`).
pub(super) fn body_checks(g: &mut Graph, names: &Names, bodies: &[BodyKin]) -> Vec<ParamCheck> {
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
            if b.rot.is_some() {
                out.extend(inertia_checks(g, name, inertia));
            }
        }
    }
    out
}

/// Each prismatic joint's axis of parameters is not zero (its squared length `> 0`): the
/// joint moves its body by `s axis`, so a zero axis leaves the coordinate without inertia,
/// which the recursion would meet as a division by zero. Not eager: `check_masses` runs it
/// before the recursion and `diagnose` in place of a mass-matrix solve's error.
pub(super) fn axis_checks(g: &mut Graph, axes: &[(String, Vec<Expr>)]) -> Vec<ParamCheck> {
    axes.iter()
        .map(|(name, axis)| {
            let squares: Vec<Expr> = axis.iter().map(|&a| g.mul(a, a)).collect();
            let length2 = g.sum(squares);
            let what = format!("the squared length of the prismatic joint axis of `{name}`");
            ParamCheck {
                eager: false,
                ..check(what, length2, true)
            }
        })
        .collect()
}

/// A spatial inertia `I` of parameters is a body's when `S = tr(I)/2 E - I` (the second
/// moment of its mass) is positive semi-definite: every principal moment at most the sum of
/// the other two, hence none negative. A positive definite `M` does not follow from that nor
/// show its absence (other bodies add to it), so these checks are eager. Each principal minor
/// of `S` (twice the diagonal; the 2x2 ones and the determinant where `I` has products of inertia)
/// may fall below zero by `1e-12` of `tr(I)` to its power, as at compile time: a disk's
/// `diag(a, a, 2a)` is on the boundary.
fn inertia_checks(g: &mut Graph, name: &str, i: &[[Expr; 3]; 3]) -> Vec<ParamCheck> {
    if i.iter().flatten().all(|&e| g.as_const(e).is_some()) {
        return Vec::new(); // checked at compile time
    }
    let trace = g.sum([i[0][0], i[1][1], i[2][2]]);
    let half = g.constant(0.5);
    let half = g.mul(half, trace);
    let s: [[Expr; 3]; 3] = std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            if r == c {
                g.sub(half, i[r][c])
            } else {
                g.neg(i[r][c])
            }
        })
    });
    let slack = |g: &mut Graph, power: i32, e: Expr| {
        let tol = g.constant(1e-12);
        let scale = (1..power).fold(trace, |acc, _| g.mul(acc, trace));
        let tol = g.mul(tol, scale);
        g.add(e, tol)
    };
    let axes = ["x", "y", "z"];
    let mut out = Vec::new();
    for k in 0..3 {
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        let sum = g.add(i[a][a], i[b][b]);
        let margin = g.sub(sum, i[k][k]);
        out.push(check(
            format!(
                "`I_{a}{a} + I_{b}{b} - I_{c}{c}` of `{name}` (a principal moment of inertia is at \
                 most the sum of the other two)",
                a = axes[a],
                b = axes[b],
                c = axes[k]
            ),
            slack(g, 1, margin),
            false,
        ));
    }
    let products = [(0, 1), (0, 2), (1, 2)]
        .iter()
        .any(|&(r, c)| !g.is_zero(i[r][c]));
    if products {
        for (r, c) in [(0, 1), (0, 2), (1, 2)] {
            let d = g.mul(s[r][r], s[c][c]);
            let o = g.mul(s[r][c], s[c][r]);
            let minor = g.sub(d, o);
            out.push(check(
                format!("a 2x2 principal minor of `tr(I)/2 - I` for the inertia of `{name}` (its principal moments: each between zero and the sum of the other two)"),
                slack(g, 2, minor),
                false,
            ));
        }
        let det = det3(g, &s);
        out.push(check(
            format!("the determinant of `tr(I)/2 - I` for the inertia of `{name}` (its principal moments: each between zero and the sum of the other two)"),
            slack(g, 3, det),
            false,
        ));
    }
    out
}

fn det3(g: &mut Graph, m: &[[Expr; 3]; 3]) -> Expr {
    let minor = |g: &mut Graph, r: usize, c: usize| {
        let (r1, r2, c1, c2) = ((r + 1) % 3, (r + 2) % 3, (c + 1) % 3, (c + 2) % 3);
        let d = g.mul(m[r1][c1], m[r2][c2]);
        let o = g.mul(m[r1][c2], m[r2][c1]);
        g.sub(d, o)
    };
    let terms: Vec<Expr> = (0..3)
        .map(|c| {
            let cof = minor(g, 0, c);
            g.mul(m[0][c], cof)
        })
        .collect();
    g.sum(terms)
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
