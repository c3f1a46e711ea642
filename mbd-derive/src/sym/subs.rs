//! Substitution of expressions for symbols.

use std::collections::HashMap;

use super::expr::{Expr, Graph, Node, Sym};
use super::hash::FastMap;

impl Graph {
    /// `e` with every symbol `s` in `map` replaced by `map[s]`, all at once (a symbol
    /// inside a replacement is not replaced again). The affected nodes are rebuilt
    /// through the simplifying constructors, bottom-up; nodes free of the mapped symbols
    /// are kept as they are.
    pub fn substitute(&mut self, e: Expr, map: &HashMap<Sym, Expr>) -> Expr {
        self.substitute_all(&[e], map)[0]
    }

    /// [`Graph::substitute`] applied to each of `roots`, rebuilding each shared node once:
    /// use it for the entries of a matrix, which share most of their nodes.
    pub fn substitute_all(&mut self, roots: &[Expr], map: &HashMap<Sym, Expr>) -> Vec<Expr> {
        let mask = self.symbol_mask(map.keys().copied());
        let affected = self.reachable(
            roots
                .iter()
                .copied()
                .filter(|&r| self.depends_on_any(r, &mask)),
            |c| self.depends_on_any(c, &mask),
        );
        let mut image: FastMap<Expr, Expr> = FastMap::default();
        for n in affected {
            let node = self.node(n);
            let rebuilt = match node {
                Node::Sym(s) => map.get(&s).copied().unwrap_or(n),
                _ => {
                    let node = node.with_children(|c| image.get(&c).copied().unwrap_or(c));
                    self.build(node)
                }
            };
            image.insert(n, rebuilt);
        }
        roots
            .iter()
            .map(|r| image.get(r).copied().unwrap_or(*r))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sym::Func;

    #[test]
    fn substitution_rebuilds_through_the_simplifier() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let sx = g.as_sym(x).unwrap();
        let s = g.call(Func::Sin, x);
        let e = g.mul(s, y);
        // x := 2 folds sin(2) to a constant
        let two = g.constant(2.0);
        let folded = g.substitute(e, &[(sx, two)].into());
        let sin2 = g.constant(2f64.sin());
        assert_eq!(folded, g.mul(sin2, y));
        // x := y gives sin(y) y, and x := 0 kills the product
        let sy = g.call(Func::Sin, y);
        assert_eq!(g.substitute(e, &[(sx, y)].into()), g.mul(sy, y));
        let zero = g.zero();
        assert_eq!(g.substitute(e, &[(sx, zero)].into()), zero);
    }

    #[test]
    fn untouched_expressions_are_returned_as_they_are() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let sx = g.as_sym(x).unwrap();
        let e = g.call(Func::Exp, y);
        let len = g.len();
        let two = g.constant(2.0);
        assert_eq!(g.substitute(e, &[(sx, two)].into()), e);
        assert_eq!(g.substitute(x, &HashMap::new()), x);
        assert_eq!(g.len(), len + 1, "only the constant 2 was added");
    }

    #[test]
    fn batch_substitution_matches_one_by_one() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let (sx, sy) = (g.as_sym(x).unwrap(), g.as_sym(y).unwrap());
        let c = g.call(Func::Cos, x);
        let roots = [g.mul(c, y), g.add(c, y), g.powi(c, 3), y];
        let half = g.constant(0.5);
        let map: HashMap<Sym, Expr> = [(sx, half), (sy, x)].into();
        let batch = g.substitute_all(&roots, &map);
        let one_by_one: Vec<Expr> = roots.iter().map(|&r| g.substitute(r, &map)).collect();
        assert_eq!(batch, one_by_one);
        assert_eq!(batch[3], x);
    }
}
