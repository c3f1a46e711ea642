//! Sums regrouped for rounding: the terms that do not vary with the state first.

use super::expr::{Expr, Graph, Node, Sym};

impl Graph {
    /// `e` with its sum regrouped as `c + v`: `c` the terms free of `varying` with like terms
    /// collected (`3 l - 4 l` is `-l`, exactly), `v` the other terms in their order; `e`
    /// itself when it has no such terms. A residual that adds constant offsets to terms of
    /// the coordinates (the pins' ground positions in a loop's closure, 40 m along an
    /// assembly) then rounds at the size of what is left, not at the offsets' size.
    pub fn constants_first(&mut self, e: Expr, varying: &[Sym]) -> Expr {
        let mask = self.symbol_mask(varying.iter().copied());
        let (mut fixed, mut moving) = (Vec::new(), Vec::new());
        self.split_sum(e, false, &mask, (&mut fixed, &mut moving));
        if fixed.is_empty() || moving.is_empty() {
            return e;
        }
        let mut collected: Vec<(f64, Expr)> = Vec::new();
        for t in fixed {
            let (k, base) = self.coefficient(t);
            match collected.iter_mut().find(|(_, b)| *b == base) {
                Some(c) => c.0 += k,
                None => collected.push((k, base)),
            }
        }
        let terms: Vec<Expr> = collected
            .into_iter()
            .map(|(k, base)| {
                let k = self.constant(k);
                self.mul(k, base)
            })
            .collect();
        let c = self.sum(terms);
        let v = self.sum(moving);
        self.add(c, v)
    }

    /// Pushes the terms of the sum `e` (negated if `negate`) to `fixed` (free of `mask`'s
    /// symbols) or `moving`. A sub-sum without fixed terms stays one term, its node shared.
    fn split_sum(
        &mut self,
        e: Expr,
        negate: bool,
        mask: &[u64],
        (fixed, moving): (&mut Vec<Expr>, &mut Vec<Expr>),
    ) {
        let signed = |g: &mut Self| if negate { g.neg(e) } else { e };
        if !self.depends_on_any(e, mask) {
            fixed.push(signed(self));
            return;
        }
        match self.node(e) {
            Node::Add(a, b) => {
                let (f, m) = (fixed.len(), moving.len());
                self.split_sum(a, negate, mask, (fixed, moving));
                self.split_sum(b, negate, mask, (fixed, moving));
                if fixed.len() == f {
                    moving.truncate(m);
                    moving.push(signed(self));
                }
            }
            Node::Neg(x) => self.split_sum(x, !negate, mask, (fixed, moving)),
            _ => moving.push(signed(self)),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::sym::Graph;

    /// A closing pin's row, `3 l + l cos c - (4 l + l cos d)`: the offsets cancel to `-l`
    /// before the cosines are added, and a row without offsets is returned as it is.
    #[test]
    fn offsets_are_summed_before_the_coordinates() {
        let mut g = Graph::new();
        let (l, c, d) = (g.symbol("l"), g.symbol("c"), g.symbol("d"));
        let vary = [g.as_sym(c).unwrap(), g.as_sym(d).unwrap()];
        let (cc, cd) = (
            g.call(crate::sym::Func::Cos, c),
            g.call(crate::sym::Func::Cos, d),
        );
        let (lc, ld) = (g.mul(l, cc), g.mul(l, cd));
        let (k3, k4) = (g.constant(3.0), g.constant(4.0));
        let (x3, x4) = (g.mul(k3, l), g.mul(k4, l));
        let (a, b) = (g.add(x3, lc), g.add(x4, ld));
        let row = g.sub(a, b);
        let regrouped = g.constants_first(row, &vary);
        let minus_l = g.neg(l);
        let moving = g.sub(lc, ld);
        assert_eq!(regrouped, g.add(minus_l, moving));
        assert_eq!(g.constants_first(moving, &vary), moving);
        let only_offsets = g.sub(x3, l);
        assert_eq!(g.constants_first(only_offsets, &vary), only_offsets);
    }
}
