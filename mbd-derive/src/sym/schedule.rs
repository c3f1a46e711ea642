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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sym::Func;

    #[test]
    fn schedule_puts_children_first_once_without_leaves() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let xy = g.mul(x, y);
        let s = g.call(Func::Sin, xy);
        let c = g.call(Func::Cos, xy);
        let f = g.add(s, c);
        let h = g.div(s, y);
        let order = schedule(&g, &[f, h, f]);
        assert_eq!(order.len(), 5, "x*y, sin, cos, sum, quotient");
        let pos = |e| order.iter().position(|&o| o == e).unwrap();
        assert!(pos(xy) < pos(s) && pos(xy) < pos(c));
        assert!(pos(s) < pos(f) && pos(c) < pos(f) && pos(s) < pos(h));
        assert!(order.iter().all(|&e| !g.node(e).is_leaf()));
        assert!(schedule(&g, &[x]).is_empty());
    }

    #[test]
    fn use_counts_count_operand_and_root_occurrences() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let xy = g.mul(x, y);
        let s = g.call(Func::Sin, xy);
        let c = g.call(Func::Cos, xy);
        let f = g.add(s, c);
        let counts = use_counts(&g, &[f, s]);
        // x*y feeds sin and cos; sin feeds the sum and is a root; cos feeds the sum;
        // the sum is a root
        let expected: HashMap<Expr, usize> = [(xy, 2), (s, 2), (c, 1), (f, 1)].into();
        assert_eq!(counts, expected);
    }
}
