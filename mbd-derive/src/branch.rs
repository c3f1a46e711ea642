//! Whether an `init` position of a coordinate the closure solves can choose its branch.
//!
//! A dependent coordinate's closed form has two branches where it takes an `asin` or `acos`
//! (a four-bar's two elbows); closure.rs picks the one that reproduces the default
//! configuration. When that configuration cannot be evaluated (a parameter in the closure
//! has no `#[default]`), the principal branch is taken whatever `init` says, so a numeric
//! `init` of a dependent coordinate would be silently ignored: it is refused here instead.
//! So is a non-zero `init` rate of a dependent coordinate: the state holds only the
//! independent coordinates' rates, and the dependent ones follow from them.

use crate::closure::Solution;
use crate::lowered::{Kind, Term};
use crate::model::Coord;
use crate::parse::{Errors, Mechanism};
use crate::sym::{Graph, Sym};
use std::collections::HashMap;

/// An error at each `init` position of a solved coordinate when a branch of the closure
/// could not be chosen from the default configuration `env`.
pub fn check_inits(
    g: &Graph,
    solution: &Solution,
    coords: &[Coord],
    env: &HashMap<Sym, f64>,
    ast: &Mechanism<Term>,
    errors: &mut Errors,
) {
    rates(solution, coords, ast, errors);
    let value = |s: Sym| env.get(&s).copied().unwrap_or(f64::NAN);
    let Some(open) = solution
        .domain
        .iter()
        .find(|d| !g.eval(d.arg, &value).is_finite())
    else {
        return;
    };
    // The symbols the argument reads: those `eval` asks for.
    let read = std::cell::RefCell::new(Vec::new());
    g.eval(open.arg, &|s| {
        read.borrow_mut().push(s);
        value(s)
    });
    let in_arg: Vec<&str> = read
        .into_inner()
        .into_iter()
        .map(|s| g.sym_name(s))
        .collect();
    let missing: Vec<String> = ast
        .params
        .iter()
        .filter(|p| p.default.is_none() && in_arg.contains(&p.name.to_string().as_str()))
        .map(|p| format!("`{}`", p.name))
        .collect();
    // An `init` that folds to a number: the user asked for a configuration the closed form
    // might not take. (One written with parameters, `asin(h / l)`, cannot be compared here.)
    let numeric = |c: &syn::Ident| {
        solution.solved.iter().any(|(i, _)| {
            coords[*i].name == *c && g.as_sym(coords[*i].z).is_some_and(|s| env.contains_key(&s))
        })
    };
    for init in ast
        .inits
        .iter()
        .filter(|i| !i.velocity && numeric(&i.coord))
    {
        errors.at(
            init.coord.span(),
            format!(
                "this `init` cannot choose the closure's branch: the closed form of `{}` (an asin/acos) takes the branch of the default configuration, and parameters {} have no `#[default]`, so the principal branch would be taken whatever `init` says; give them `#[default]`s, or write `#[mechanism(augmented)]` and start from an assembled state",
                open.coord,
                missing.join(", ")
            ),
        );
    }
}

/// An error at each `init(der(x) = v)` of a coordinate `x` the closure solves, unless `v` is
/// the constant zero (at rest): `x`'s rate is not in the state, so it would be dropped.
fn rates(solution: &Solution, coords: &[Coord], ast: &Mechanism<Term>, errors: &mut Errors) {
    let independent: Vec<String> = coords
        .iter()
        .enumerate()
        .filter(|(i, c)| {
            matches!(c.kind, crate::model::CoordKind::Free)
                && !solution.solved.iter().any(|(j, _)| j == i)
        })
        .map(|(_, c)| format!("`der({})`", c.name))
        .collect();
    let solved = |c: &syn::Ident| solution.solved.iter().any(|(i, _)| coords[*i].name == *c);
    for init in ast
        .inits
        .iter()
        .filter(|i| i.velocity && solved(&i.coord) && !zero(&i.value))
    {
        errors.at(
            init.coord.span(),
            format!(
                "the rate of `{}` follows from the closure (the state holds {}): this `init` would be dropped; give the independent rates instead",
                init.coord,
                independent.join(", ")
            ),
        );
    }
}

/// Whether a lowered term is the number zero (`0.0`, `-0.0`, `(0.0)`).
fn zero(term: &Term) -> bool {
    match &term.kind {
        Kind::Number(v) => *v == 0.0,
        Kind::Wrap(inner) | Kind::Neg(inner) => zero(inner),
        _ => false,
    }
}
