//! The simplifying constructors: the only way new operations enter the graph.
//!
//! Each constructor folds constants (with the same `f64` operations `eval` uses) and
//! applies a few local rewrites that keep the value:
//!
//! - identities: `x + 0 = x`, `0 * x = 0`, `1 * x = x`, `-1 * x = -x`, `x / 1 = x`,
//!   `0 / x = 0`, `-(-x) = x`, `x^0 = 1`, `x^1 = x`, `1^y = 1`;
//! - like terms and powers: `a x + b x = (a + b) x` (so `x - x = 0`, `x + x = 2 x`),
//!   `x^a x^b = x^(a+b)` (so `x x = x^2`), `(x^a)^b = x^(a b)`, all for integer powers;
//! - constants float outwards one level and collect: `c1 + (c2 + x) = (c1 + c2) + x`,
//!   `(c1 + x) + y = c1 + (x + y)`, and the same for products, so `c1 (c2 x) = (c1 c2) x`;
//! - signs move outwards: `(-a) b = -(a b)`, `-(c x) = (-c) x`, `(-a)/b = -(a/b)`,
//!   `(-x)^n = ±x^n`, `|-x| = |x|`;
//! - `x / c = (1/c) x` only when `c` is a power of two (then `1/c` is exact);
//! - `powf(x, n)` with an integer constant `n` becomes `powi(x, n)`;
//! - commutative operands (`Add`, `Mul`, `Min`, `Max`) are put in a canonical order
//!   (constant first, then by id), so `a + b` and `b + a` are one node.
//!
//! Not done, on purpose: `sqrt(x^2) = x` and `sqrt(x)^2 = x` (wrong for `x < 0`), `x / x = 1`.
//!
//! IEEE caveats: the rewrites are identities of real arithmetic on finite values.
//! `0 * x = 0` and `x - x = 0` differ from IEEE when `x` is infinite or NaN, `0 / x = 0`
//! when `x = 0`, and `x^a x^b = x^(a+b)` when `x = 0` and `a + b = 0`; `x + 0 = x` may
//! flip the sign of a zero result. Reassociating constants and collecting like terms
//! change rounding, by a few ulps of the operands' magnitude.

use super::eval::apply;
use super::expr::{Const, Expr, Func, Graph, Node};

impl Graph {
    pub fn constant(&mut self, v: f64) -> Expr {
        self.intern(Node::Const(Const::new(v)))
    }

    pub fn zero(&mut self) -> Expr {
        self.constant(0.0)
    }

    pub fn one(&mut self) -> Expr {
        self.constant(1.0)
    }

    /// `node` rebuilt through the simplifying constructors (its operands must exist).
    pub fn build(&mut self, node: Node) -> Expr {
        match node {
            Node::Const(_) | Node::Sym(_) => self.intern(node),
            Node::Add(a, b) => self.add(a, b),
            Node::Mul(a, b) => self.mul(a, b),
            Node::Neg(a) => self.neg(a),
            Node::Div(a, b) => self.div(a, b),
            Node::Powi(a, n) => self.powi(a, n),
            Node::Powf(a, b) => self.powf(a, b),
            Node::Call(f, a) => self.call(f, a),
            Node::Atan2(y, x) => self.atan2(y, x),
            Node::Min(a, b) => self.min(a, b),
            Node::Max(a, b) => self.max(a, b),
        }
    }

    /// Folds `node` if all its operands are constants.
    fn fold(&mut self, node: Node) -> Option<Expr> {
        let mut values = [0.0; 2];
        for (slot, c) in values.iter_mut().zip(node.children()) {
            *slot = self.as_const(c)?;
        }
        Some(self.constant(apply(node, values[0], values[1])))
    }

    /// Operands of a commutative node: a constant first, otherwise the smaller id first.
    fn ordered(&self, a: Expr, b: Expr) -> (Expr, Expr) {
        let key = |e: Expr| (self.as_const(e).is_none(), e);
        if key(a) <= key(b) { (a, b) } else { (b, a) }
    }

    /// `(c, r)` if `e` is `Add(Const c, r)`.
    fn const_plus(&self, e: Expr) -> Option<(f64, Expr)> {
        match self.node(e) {
            Node::Add(c, r) => Some((self.as_const(c)?, r)),
            _ => None,
        }
    }

    /// `(c, r)` if `e` is `Mul(Const c, r)`.
    fn const_times(&self, e: Expr) -> Option<(f64, Expr)> {
        match self.node(e) {
            Node::Mul(c, r) => Some((self.as_const(c)?, r)),
            _ => None,
        }
    }

    /// `e` as `coefficient * term` for collecting like terms.
    fn coefficient(&self, e: Expr) -> (f64, Expr) {
        match self.node(e) {
            Node::Neg(t) => (-1.0, t),
            _ => self.const_times(e).unwrap_or((1.0, e)),
        }
    }

    /// `e` as `base^exponent` for collecting powers.
    fn power(&self, e: Expr) -> (Expr, i32) {
        match self.node(e) {
            Node::Powi(b, n) => (b, n),
            _ => (e, 1),
        }
    }

    pub fn add(&mut self, a: Expr, b: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Add(a, b)) {
            return e;
        }
        if self.is_zero(a) {
            return b;
        }
        if self.is_zero(b) {
            return a;
        }
        if self.const_plus(a).is_some() || self.const_plus(b).is_some() {
            let split = |g: &Self, e: Expr| match (g.as_const(e), g.const_plus(e)) {
                (Some(c), _) => (c, None),
                (None, Some((c, r))) => (c, Some(r)),
                (None, None) => (0.0, Some(e)),
            };
            let ((ca, ra), (cb, rb)) = (split(self, a), split(self, b));
            let rest = match (ra, rb) {
                (Some(x), Some(y)) => self.add(x, y),
                (Some(x), None) | (None, Some(x)) => x,
                (None, None) => self.zero(),
            };
            let c = self.constant(ca + cb);
            return self.add(c, rest);
        }
        let ((ka, ta), (kb, tb)) = (self.coefficient(a), self.coefficient(b));
        if ta == tb {
            let k = self.constant(ka + kb);
            return self.mul(k, ta);
        }
        let (a, b) = self.ordered(a, b);
        self.intern(Node::Add(a, b))
    }

    pub fn sub(&mut self, a: Expr, b: Expr) -> Expr {
        let minus_b = self.neg(b);
        self.add(a, minus_b)
    }

    pub fn neg(&mut self, a: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Neg(a)) {
            return e;
        }
        if let Node::Neg(x) = self.node(a) {
            return x;
        }
        if let Some((c, r)) = self.const_times(a) {
            let minus_c = self.constant(-c);
            return self.mul(minus_c, r);
        }
        self.intern(Node::Neg(a))
    }

    pub fn mul(&mut self, a: Expr, b: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Mul(a, b)) {
            return e;
        }
        for (c, x) in [(a, b), (b, a)] {
            match self.as_const(c) {
                Some(0.0) => return c,
                Some(1.0) => return x,
                Some(-1.0) => return self.neg(x),
                _ => {}
            }
        }
        if let Node::Neg(p) = self.node(a) {
            let pb = self.mul(p, b);
            return self.neg(pb);
        }
        if let Node::Neg(q) = self.node(b) {
            let aq = self.mul(a, q);
            return self.neg(aq);
        }
        if self.const_times(a).is_some() || self.const_times(b).is_some() {
            let split = |g: &Self, e: Expr| match (g.as_const(e), g.const_times(e)) {
                (Some(c), _) => (c, None),
                (None, Some((c, r))) => (c, Some(r)),
                (None, None) => (1.0, Some(e)),
            };
            let ((ca, ra), (cb, rb)) = (split(self, a), split(self, b));
            let rest = match (ra, rb) {
                (Some(x), Some(y)) => self.mul(x, y),
                (Some(x), None) | (None, Some(x)) => x,
                (None, None) => self.one(),
            };
            let c = self.constant(ca * cb);
            return self.mul(c, rest);
        }
        let ((ba, na), (bb, nb)) = (self.power(a), self.power(b));
        if ba == bb
            && let Some(n) = na.checked_add(nb)
        {
            return self.powi(ba, n);
        }
        let (a, b) = self.ordered(a, b);
        self.intern(Node::Mul(a, b))
    }

    pub fn div(&mut self, a: Expr, b: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Div(a, b)) {
            return e;
        }
        if self.is_zero(a) {
            return a;
        }
        if let Some(c) = self.as_const(b) {
            let inverse = 1.0 / c;
            // exact only for powers of two: zero mantissa, and 1/c neither overflows nor is subnormal
            let power_of_two = c.to_bits() & ((1 << 52) - 1) == 0 && inverse.is_normal();
            if c.is_normal() && power_of_two {
                let k = self.constant(inverse);
                return self.mul(k, a);
            }
        }
        if let Node::Neg(p) = self.node(a) {
            let pb = self.div(p, b);
            return self.neg(pb);
        }
        if let Node::Neg(q) = self.node(b) {
            let aq = self.div(a, q);
            return self.neg(aq);
        }
        if let Some((c, r)) = self.const_times(a) {
            let rb = self.div(r, b);
            let k = self.constant(c);
            return self.mul(k, rb);
        }
        self.intern(Node::Div(a, b))
    }

    pub fn powi(&mut self, a: Expr, n: i32) -> Expr {
        if let Some(e) = self.fold(Node::Powi(a, n)) {
            return e;
        }
        match n {
            0 => return self.one(),
            1 => return a,
            _ => {}
        }
        match self.node(a) {
            Node::Powi(b, m) => {
                if let Some(mn) = m.checked_mul(n) {
                    return self.powi(b, mn);
                }
            }
            Node::Neg(b) => {
                let p = self.powi(b, n);
                return if n % 2 == 0 { p } else { self.neg(p) };
            }
            _ => {}
        }
        self.intern(Node::Powi(a, n))
    }

    pub fn powf(&mut self, a: Expr, b: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Powf(a, b)) {
            return e;
        }
        if self.as_const(a) == Some(1.0) {
            return a;
        }
        if let Some(n) = self.as_const(b)
            && n.fract() == 0.0
            && n.abs() <= f64::from(i32::MAX)
        {
            return self.powi(a, n as i32);
        }
        self.intern(Node::Powf(a, b))
    }

    pub fn call(&mut self, f: Func, a: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Call(f, a)) {
            return e;
        }
        match (f, self.node(a)) {
            (Func::Abs, Node::Neg(x)) => self.call(Func::Abs, x),
            (Func::Abs, Node::Call(Func::Abs, _)) => a,
            _ => self.intern(Node::Call(f, a)),
        }
    }

    /// `y.atan2(x)`: the angle of the point `(x, y)`.
    pub fn atan2(&mut self, y: Expr, x: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Atan2(y, x)) {
            return e;
        }
        self.intern(Node::Atan2(y, x))
    }

    pub fn min(&mut self, a: Expr, b: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Min(a, b)) {
            return e;
        }
        if a == b {
            return a;
        }
        let (a, b) = self.ordered(a, b);
        self.intern(Node::Min(a, b))
    }

    pub fn max(&mut self, a: Expr, b: Expr) -> Expr {
        if let Some(e) = self.fold(Node::Max(a, b)) {
            return e;
        }
        if a == b {
            return a;
        }
        let (a, b) = self.ordered(a, b);
        self.intern(Node::Max(a, b))
    }

    /// `t1 + t2 + …`; `0` for no terms.
    pub fn sum(&mut self, terms: impl IntoIterator<Item = Expr>) -> Expr {
        let zero = self.zero();
        terms.into_iter().fold(zero, |acc, t| self.add(acc, t))
    }

    /// `a · b = Σ a_i b_i`. The slices must have equal length.
    pub fn dot(&mut self, a: &[Expr], b: &[Expr]) -> Expr {
        assert_eq!(a.len(), b.len(), "dot product of vectors of unequal length");
        let products: Vec<Expr> = a.iter().zip(b).map(|(&x, &y)| self.mul(x, y)).collect();
        self.sum(products)
    }
}
