//! Constraints: the user's equations and the loop-closing joints in full coordinates
//! (`gather`), then, reduced, their Jacobians and `gamma` in the free coordinates
//! (`in_free_coordinates`) and what makes a set of them unusable (`check`).

use super::Ast;
use super::kinematics::{Frame, Kinematics};
use super::scope::Scope;
use super::{Coord, Role};
use crate::close;
use crate::closure;
use crate::lower::{Context, Lowerer};
use crate::lowered::Term;
use crate::parse::{Dim, Errors};
use crate::sym::{Expr, Graph, Sym};
use crate::tree;
use proc_macro2::TokenStream;
use syn::Ident;

/// The constraint equations `Phi = 0` with the tokens each error is reported over.
pub(super) struct Constraints<'a> {
    pub phi: Vec<Expr>,
    pub tokens: Vec<&'a TokenStream>,
}

/// The reduced constraints in the free coordinates, with a multiplier symbol each.
pub(super) struct InFree {
    pub phi_q: Vec<Vec<Expr>>,
    pub phi_t: Vec<Expr>,
    pub gamma: Vec<Expr>,
    pub lambdas: Vec<Expr>,
}

/// `#[constraint(..)]`s, then the equations of each closing joint (close.rs).
pub(super) fn gather<'a>(ast: &'a Ast, scope: &mut Scope, kin: &Kinematics) -> Constraints<'a> {
    let mut out = Constraints {
        phi: Vec::new(),
        tokens: Vec::new(),
    };
    for c in &ast.constraints {
        let mut lw = scope.lowerer(None);
        if let (Some(l), Some(r)) = (
            lw.scalar(&c.lhs, Context::Kinematics),
            lw.scalar(&c.rhs, Context::Kinematics),
        ) {
            out.phi.push(scope.g.sub(l, r));
            out.tokens.push(&c.tokens);
        }
    }
    // Loop-closing joints (close.rs): two coincident points in a plane (a revolute joint);
    // in space a spherical, revolute, universal or prismatic joint.
    for cl in &ast.closures {
        let pa = closure_point(scope, kin, &cl.a, &cl.at_a);
        let pb = closure_point(scope, kin, &cl.b, &cl.at_b);
        let (Some(pa), Some(pb)) = (pa, pb) else {
            continue;
        };
        let Scope {
            g,
            names,
            struct_name,
            errors,
            dim,
            ..
        } = scope;
        let rows = match dim {
            Dim::Planar => close::planar_rows(g, errors, cl, (&pa, &pb)),
            Dim::Spatial => close::rows(g, errors, cl, (&pa, &pb), &mut |g, errors, e| {
                Lowerer {
                    g,
                    names,
                    struct_name,
                    model: None,
                    errors,
                }
                .vector(e, Context::Constant, 3)
            }),
        };
        for row in rows.into_iter().flatten() {
            out.phi.push(row);
            out.tokens.push(&cl.tokens);
        }
    }
    // The constant offsets of each row (pins' ground positions) cancel among themselves
    // before the coordinates' terms are added: the residual rounds at its own size.
    let mut varying = kin.z_syms(&scope.g);
    varying.extend(scope.g.as_sym(scope.t));
    for row in &mut out.phi {
        *row = scope.g.constants_first(*row, &varying);
    }
    out
}

/// A point of a tree body (`None`: the ground) at `at` in its frame, with the frame's
/// rotation in space.
fn closure_point(
    scope: &mut Scope,
    kin: &Kinematics,
    body: &Option<Ident>,
    at: &Option<Term>,
) -> Option<close::Side> {
    let dim = scope.dim;
    let local = match at {
        Some(e) => scope
            .lowerer(None)
            .vector(e, Context::Constant, dim.len())?,
        None => vec![scope.g.zero(); dim.len()],
    };
    let unknown = |scope: &mut Scope, b: &Ident| {
        scope.errors.at(
            b.span(),
            format!("unknown tree body `{b}`: a closure joins `body`/`chain` bodies or `ground`"),
        );
    };
    let g = &mut scope.g;
    let point = match (body, dim) {
        (None, _) => local,
        (Some(b), Dim::Planar) => {
            let Some(&i) = kin.planar.node_of.get(&b.to_string()) else {
                unknown(scope, b);
                return None;
            };
            let node = &kin.planar.nodes[i];
            let arm = tree::rotate(g, node.angle, [local[0], local[1]]);
            let origin = node.origin;
            vec![g.add(origin[0], arm[0]), g.add(origin[1], arm[1])]
        }
        (Some(b), Dim::Spatial) => {
            let Some(&i) = kin.spatial.frame_of.get(&b.to_string()) else {
                unknown(scope, b);
                return None;
            };
            let Frame { origin, rot, .. } = kin.spatial.frames[i];
            let point = (0..3)
                .map(|k| {
                    let arm = g.dot(&rot[k], &local);
                    g.add(origin[k], arm)
                })
                .collect();
            return Some(close::Side {
                rot: Some(rot),
                point,
            });
        }
    };
    Some(close::Side { rot: None, point })
}

/// `Phi_q`, `Phi_t` and `gamma = -(d/dt (Phi_q q' + Phi_t))|_{q''=0}` of the reduced `phi`
/// over free coordinates `free_idx`, and a multiplier per constraint.
pub(super) fn in_free_coordinates(
    scope: &mut Scope,
    coords: &[Coord],
    free_idx: &[usize],
    qsyms: &[Sym],
    phi: &[Expr],
) -> InFree {
    let g = &mut scope.g;
    let ts = g.as_sym(scope.t).expect("symbol");
    let phi_q: Vec<Vec<Expr>> = phi
        .iter()
        .map(|p| qsyms.iter().map(|s| g.diff(*p, *s)).collect())
        .collect();
    let phi_t: Vec<Expr> = phi.iter().map(|p| g.diff(*p, ts)).collect();
    let qd: Vec<Expr> = free_idx.iter().map(|&i| coords[i].zd).collect();
    let mut gamma = Vec::new();
    for (k, row) in phi_q.iter().enumerate() {
        let phidot0 = g.dot(row, &qd);
        let phidot = g.add(phidot0, phi_t[k]);
        let mut terms: Vec<Expr> = qsyms
            .iter()
            .zip(&qd)
            .map(|(s, v)| {
                let d = g.diff(phidot, *s);
                g.mul(d, *v)
            })
            .collect();
        terms.push(g.diff(phidot, ts));
        let s = g.sum(terms);
        gamma.push(g.neg(s));
    }
    let lambdas: Vec<Expr> = (0..phi.len())
        .map(|k| {
            let s = scope.g.symbol(&format!("lambda:{k}"));
            scope.role(s, Role::Lambda(k));
            s
        })
        .collect();
    InFree {
        phi_q,
        phi_t,
        gamma,
        lambdas,
    }
}

/// A row equal to an earlier one or to its negative (a pin or a constraint written twice,
/// whatever its shape): its Jacobian rows repeat at every configuration. Rows already told
/// (constant-coefficient dependence) or over-determining are skipped.
fn repeated_rows(
    g: &mut Graph,
    errors: &mut Errors,
    phi: &[Expr],
    tokens: &[&TokenStream],
    told: &[usize],
    n: usize,
) {
    for k in 0..phi.len().min(n) {
        if told.contains(&k) {
            continue;
        }
        let repeats = (0..k).any(|j| {
            let (d, s) = (g.sub(phi[k], phi[j]), g.add(phi[k], phi[j]));
            g.is_zero(d) || g.is_zero(s)
        });
        if repeats {
            errors.over(tokens[k], "this constraint repeats an earlier one (the same equation, or a joint closing the same points twice): the constraint Jacobian would be singular everywhere; remove it");
        }
    }
}

/// Constraints that over-determine, repeat, contradict or miss the coordinates, and free
/// coordinates that neither move a mass nor are constrained.
pub(super) fn check(
    scope: &mut Scope,
    coords: &[Coord],
    free_idx: &[usize],
    (phi, tokens): (&[Expr], &[&TokenStream]),
    qsyms: &[Sym],
    mass: &[Vec<Expr>],
) {
    let (n, m_con) = (free_idx.len(), phi.len());
    let (g, errors) = (&mut scope.g, &mut scope.errors);
    if m_con > n {
        for tokens in &tokens[n..] {
            errors.over(tokens, format!("more constraints ({m_con}) than free coordinates ({n}): this one over-determines the mechanism"));
        }
    }
    let dependence = closure::constant_dependence(g, phi, qsyms);
    let told: Vec<usize> = dependence.iter().map(|d| d.0).collect();
    repeated_rows(g, errors, phi, tokens, &told, n);
    for (k, how) in dependence {
        if m_con > n && k >= n {
            continue; // already an over-determining constraint
        }
        let why = match how {
            closure::Dependence::NoCoordinate => "the coordinate terms of this constraint cancel: it relates only parameters and `t`, so it cannot hold the mechanism".to_string(),
            closure::Dependence::Redundant => "this constraint repeats earlier ones (a combination of them with constant coefficients): the constraint Jacobian would be singular everywhere; remove it".to_string(),
            closure::Dependence::Contradictory(v) => format!("this constraint contradicts earlier ones: its coordinate part is a constant combination of theirs but its constant part differs by {v}"),
            closure::Dependence::Dependent => "this constraint's coordinate part is a constant combination of earlier constraints': it is redundant or contradicts them (depending on the parameters), and the constraint Jacobian would be singular everywhere".to_string(),
        };
        errors.over(tokens[k], why);
    }
    // Bounds that exclude zero, unless a closed form already said so (`sin(x) == 2`).
    let ranges = g.ranges(phi);
    let bounded = errors.is_empty();
    for (k, p) in phi.iter().enumerate() {
        if told.contains(&k) && !qsyms.iter().any(|s| g.depends_on(*p, *s)) {
            continue; // already said by the dependence check
        } else if !qsyms.iter().any(|s| g.depends_on(*p, *s)) {
            let why = match names_a_coordinate(tokens[k], coords) {
                true => {
                    "the coordinate terms of this constraint cancel: it relates only parameters and `t`, so it cannot hold the mechanism"
                }
                false => {
                    "this constraint involves no coordinate: it relates only parameters and `t`, so it cannot hold the mechanism"
                }
            };
            errors.over(tokens[k], why);
        } else if bounded && !told.contains(&k) && (ranges[k].0 > 0.0 || ranges[k].1 < 0.0) {
            let gap = ranges[k].0.max(-ranges[k].1);
            errors.over(tokens[k], format!("this constraint holds at no configuration: its two sides differ by at least {gap} whatever the coordinates and parameters (a square, an even power, `sqrt` or `abs` is never negative; `sin` and `cos` stay within [-1, 1])"));
        }
    }
    for (a, &i) in free_idx.iter().enumerate() {
        let in_constraint = phi.iter().any(|p| g.depends_on(*p, qsyms[a]));
        if g.is_zero(mass[a][a]) && !in_constraint {
            errors.at(
                coords[i].name.span(),
                format!("coordinate `{}` moves no mass and no constraint fixes it: the mass matrix would be singular", coords[i].name),
            );
        }
    }
}

/// Whether the written constraint names a coordinate (whose terms then cancelled).
fn names_a_coordinate(tokens: &TokenStream, coords: &[Coord]) -> bool {
    tokens.clone().into_iter().any(|t| match t {
        proc_macro2::TokenTree::Ident(i) => coords.iter().any(|c| c.name == i),
        proc_macro2::TokenTree::Group(g) => names_a_coordinate(&g.stream(), coords),
        _ => false,
    })
}
