//! Initial positions and velocities of the free coordinates (parameters allowed); a
//! dependent coordinate's follow from the closure. Which positions and rates `init` gives
//! is kept: the augmented form completes the others from the position and velocity
//! constraints (codegen/items.rs).

use super::Ast;
use super::scope::Scope;
use super::{Coord, CoordKind};
use crate::lower::Context;
use crate::sym::Expr;

pub(super) fn initial_conditions(
    ast: &Ast,
    scope: &mut Scope,
    coords: &[Coord],
    free_idx: &[usize],
) -> (Vec<Expr>, Vec<Expr>, [Vec<bool>; 2]) {
    let zero = scope.g.zero();
    let n = free_idx.len();
    let mut init_q = vec![zero; n];
    let mut init_qd = vec![zero; n];
    let mut rate_given = vec![false; n];
    let mut position_given = vec![false; n];
    for i in &ast.inits {
        let dependent = |c: &Coord| matches!(c.kind, CoordKind::Dependent(_));
        if coords.iter().any(|c| c.name == i.coord && dependent(c)) {
            continue;
        }
        let Some(a) = free_idx.iter().position(|&j| coords[j].name == i.coord) else {
            let name = i.coord.to_string();
            let rate = name
                .strip_suffix("_dot")
                .filter(|b| free_idx.iter().any(|&j| coords[j].name == b));
            let hint = match rate {
                Some(base) if !i.velocity => format!(": give its rate as `der({base}) = ..`"),
                _ => String::new(),
            };
            scope.errors.at(
                i.coord.span(),
                format!("`{name}` is not a free coordinate{hint}"),
            );
            continue;
        };
        if let Some(v) = scope.lowerer(None).scalar(&i.value, Context::Constant) {
            if i.velocity {
                init_qd[a] = v;
                rate_given[a] = true;
            } else {
                init_q[a] = v;
                position_given[a] = true;
            }
        }
    }
    (init_q, init_qd, [position_given, rate_given])
}
