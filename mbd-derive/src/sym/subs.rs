//! Substitution of expressions for symbols.

use std::collections::HashMap;

use super::expr::{Expr, Graph, Node, Sym};

impl Graph {
    /// `e` with every symbol `s` in `map` replaced by `map[s]`, all at once (a symbol
    /// inside a replacement is not replaced again). The affected nodes are rebuilt
    /// through the simplifying constructors, bottom-up; nodes free of the mapped symbols
    /// are kept as they are.
    pub fn substitute(&mut self, e: Expr, map: &HashMap<Sym, Expr>) -> Expr {
        let mask = self.symbol_mask(map.keys().copied());
        if !self.depends_on_any(e, &mask) {
            return e;
        }
        let affected = self.reachable([e], |c| self.depends_on_any(c, &mask));
        let mut image: HashMap<Expr, Expr> = HashMap::new();
        for n in affected {
            let node = self.node(n);
            let rebuilt = match node {
                Node::Sym(s) => map.get(&s).copied().unwrap_or(n),
                _ => {
                    let new = |c: Expr| image.get(&c).copied().unwrap_or(c);
                    let node = match node {
                        Node::Const(_) | Node::Sym(_) => node,
                        Node::Add(a, b) => Node::Add(new(a), new(b)),
                        Node::Mul(a, b) => Node::Mul(new(a), new(b)),
                        Node::Neg(a) => Node::Neg(new(a)),
                        Node::Div(a, b) => Node::Div(new(a), new(b)),
                        Node::Powi(a, k) => Node::Powi(new(a), k),
                        Node::Powf(a, b) => Node::Powf(new(a), new(b)),
                        Node::Call(f, a) => Node::Call(f, new(a)),
                        Node::Atan2(y, x) => Node::Atan2(new(y), new(x)),
                        Node::Min(a, b) => Node::Min(new(a), new(b)),
                        Node::Max(a, b) => Node::Max(new(a), new(b)),
                    };
                    self.build(node)
                }
            };
            image.insert(n, rebuilt);
        }
        image[&e]
    }
}
