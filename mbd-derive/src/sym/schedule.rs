//! The order and sharing information code generation needs.

use std::collections::HashMap;

use super::expr::{Expr, Graph};

/// Code-generation order: every non-leaf node reachable from `roots`, children before
/// parents, each once. (Ids are topological, so this is the reachable set sorted by id.)
pub fn schedule(g: &Graph, roots: &[Expr]) -> Vec<Expr> {
    let mut order = g.reachable(roots.iter().copied(), |c| !g.node(c).is_leaf());
    order.retain(|&e| !g.node(e).is_leaf());
    order
}

/// How many times each scheduled node is used as an operand of other scheduled nodes or
/// as a root (counted per occurrence), so code generation can inline single-use nodes.
pub fn use_counts(g: &Graph, roots: &[Expr]) -> HashMap<Expr, usize> {
    let order = schedule(g, roots);
    let mut counts: HashMap<Expr, usize> = order.iter().map(|&e| (e, 0)).collect();
    let uses = order
        .iter()
        .flat_map(|&e| g.node(e).children())
        .chain(roots.iter().copied());
    for u in uses {
        if let Some(c) = counts.get_mut(&u) {
            *c += 1;
        }
    }
    counts
}
