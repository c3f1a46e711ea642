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
//! - `x / c = (1/c) x` only when `c` is a power of two (then `1/c` is exact), and
//!   `(c x) / y = c (x / y)`;
//! - `powf(x, n)` with an integer constant `n` becomes `powi(x, n)`;
//! - one product associated two ways cancels: `(x y) z - x (y z) = 0`;
//! - Pythagoras: `k (A sin u)^2 + k (A cos u)^2 = k A^2` and `k sin(u)^2 + k cos(u)^2 = k`
//!   (when the two terms meet in one `add`);
//! - a shared operand comes out: `k p x ± k r x = k (p ± r) x`;
//! - a difference whose negation is in the graph already is that node negated: `y - x`
//!   after `x - y` is `-(x - y)`;
//! - commutative operands (`Add`, `Mul`, `Min`, `Max`) are put in a canonical order
//!   (constant first, then by id), so `a + b` and `b + a` are one node.
//!
//! Not done, on purpose: `sqrt(x^2) = x` and `sqrt(x)^2 = x` (wrong for `x < 0`), `x / x = 1`
//! (wrong for `x = 0`). Not done for now: flattening sums and products into a canonical
//! n-ary form, so like terms are collected only when they meet in one `add`
//! (`(a + b) + a` stays as it is) and products are compared as factor lists only there.
//!
//! IEEE caveats: the rewrites are identities of real arithmetic on finite values.
//! `0 * x = 0` and `x - x = 0` differ from IEEE when `x` is infinite or NaN, `0 / x = 0`
//! when `x = 0`, and `x^a x^b = x^(a+b)` when `x = 0` and `a + b = 0`; `x + 0 = x` may
//! flip the sign of a zero result. Reassociating constants, collecting like terms and
//! powers, and `powf(x, n) = powi(x, n)` change rounding (by a few ulps of the operands'
//! magnitude), and `(x^a)^b = x^(a b)` can avoid or cause an intermediate overflow.

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
    pub(super) fn coefficient(&self, e: Expr) -> (f64, Expr) {
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
        if ka == -kb && self.same_product(ta, tb) {
            return self.zero();
        }
        if ka == kb
            && let Some(s) = self.pythagoras(ta, tb)
        {
            let k = self.constant(ka);
            return self.mul(k, s);
        }
        if ka.abs() == kb.abs()
            && let Some((p, r, x)) = self.common_factor(ta, tb)
        {
            let sum = if ka == kb {
                self.add(p, r)
            } else {
                self.sub(p, r)
            };
            let k = self.constant(ka);
            let kx = self.mul(k, x);
            return self.mul(sum, kx);
        }
        if let Some(e) = self.negated_sum(a, b) {
            return self.neg(e);
        }
        let (a, b) = self.ordered(a, b);
        self.intern(Node::Add(a, b))
    }

    /// `(p, r, x)` if `a = p x` and `b = r x` (one shared operand), for `p x + r x = (p + r) x`:
    /// two products and a sum become a sum and a product (`m1 g X + m2 g X`).
    fn common_factor(&self, a: Expr, b: Expr) -> Option<(Expr, Expr, Expr)> {
        let (Node::Mul(a0, a1), Node::Mul(b0, b1)) = (self.node(a), self.node(b)) else {
            return None;
        };
        [
            (a0, a1, b0, b1),
            (a0, a1, b1, b0),
            (a1, a0, b0, b1),
            (a1, a0, b1, b0),
        ]
        .into_iter()
        .find(|&(x, _, y, _)| x == y)
        .map(|(x, p, _, r)| (p, r, x))
    }

    /// `e` when `a + b` is `-e` and `e` is in the graph already (`y - x` after `x - y`): the
    /// second difference becomes a negation of the first, shared, one.
    fn negated_sum(&self, a: Expr, b: Expr) -> Option<Expr> {
        let (x, y) = match (self.node(a), self.node(b)) {
            (Node::Neg(_), Node::Neg(_)) => return None,
            (Node::Neg(x), _) => (x, b),
            (_, Node::Neg(y)) => (y, a),
            _ => return None,
        };
        let minus_y = self.existing(Node::Neg(y))?;
        let (p, q) = self.ordered(x, minus_y);
        self.existing(Node::Add(p, q))
    }

    /// Whether `a` and `b` are one product associated differently, `(x y) z` and `x (y z)`:
    /// the same factors with the same coefficient. Kane's velocity-product terms cancel
    /// this way (`l cos(u) (u' (u' l sin u)) - l sin(u) (u' (u' l cos u))`).
    fn same_product(&self, a: Expr, b: Expr) -> bool {
        /// Products longer than this are left alone (the check stays cheap).
        const MAX_FACTORS: usize = 24;
        let factors = |e: Expr| -> Option<(f64, Vec<Expr>)> {
            let (mut k, mut out, mut stack) = (1.0, Vec::new(), vec![(e, 1)]);
            while let Some((x, n)) = stack.pop() {
                match self.node(x) {
                    Node::Mul(p, q) => stack.extend([(p, n), (q, n)]),
                    Node::Neg(p) => {
                        k = -k;
                        stack.push((p, n));
                    }
                    Node::Powi(p, m) if m > 0 => stack.push((p, n * m)),
                    Node::Const(c) => k *= c.value().powi(n),
                    _ => out.extend(std::iter::repeat_n(x, n as usize)),
                }
                if out.len() > MAX_FACTORS {
                    return None;
                }
            }
            out.sort_unstable();
            Some((k, out))
        };
        a != b && matches!((factors(a), factors(b)), (Some(x), Some(y)) if x == y)
    }

    /// `(A sin u)^2 + (A cos u)^2 = A^2` and `sin(u)^2 + cos(u)^2 = 1`: the sum every
    /// rotating point puts into a mass matrix (`m |dr/dq|^2`).
    fn pythagoras(&mut self, a: Expr, b: Expr) -> Option<Expr> {
        // `e` as `(A, u, is_sin)` if it is `(A trig(u))^2` or `trig(u)^2`.
        let square = |g: &Self, e: Expr| -> Option<(Option<Expr>, Expr, bool)> {
            let Node::Powi(base, 2) = g.node(e) else {
                return None;
            };
            let trig = |x: Expr| match g.node(x) {
                Node::Call(Func::Sin, u) => Some((u, true)),
                Node::Call(Func::Cos, u) => Some((u, false)),
                _ => None,
            };
            if let Some((u, s)) = trig(base) {
                return Some((None, u, s));
            }
            let Node::Mul(x, y) = g.node(base) else {
                return None;
            };
            match (trig(x), trig(y)) {
                (Some((u, s)), _) => Some((Some(y), u, s)),
                (None, Some((u, s))) => Some((Some(x), u, s)),
                (None, None) => None,
            }
        };
        let ((fa, ua, sa), (fb, ub, sb)) = (square(self, a)?, square(self, b)?);
        if fa != fb || ua != ub || sa == sb {
            return None;
        }
        Some(match fa {
            Some(f) => self.powi(f, 2),
            None => self.one(),
        })
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
        if n < -1 {
            // x^-n as (1/x)^n: the reciprocal is shared with x^-1 (one division, not two).
            let r = self.powi(a, -1);
            return self.intern(Node::Powi(r, -n));
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

    /// `a / b` with the factors the two products share cancelled, and the numerator's
    /// `constant` factors divided first: `-(m g l sin q) / (m l^2)` is `(-g / l) sin q`, the
    /// quotient of parameters computed apart from (and before) what depends on the state.
    /// Only for a caller that has checked `b != 0` itself (a cancelled factor that is zero
    /// would otherwise turn `0 / 0` into a number).
    pub fn quotient_cancelled(
        &mut self,
        a: Expr,
        b: Expr,
        constant: impl Fn(&Self, Expr) -> bool,
    ) -> Expr {
        let (mut ca, mut fa) = (1.0, Vec::new());
        let (mut cb, mut fb) = (1.0, Vec::new());
        self.factors(a, &mut ca, &mut fa);
        self.factors(b, &mut cb, &mut fb);
        for (base, na) in fa.iter_mut() {
            if let Some((_, nb)) = fb.iter_mut().find(|(x, _)| x == base) {
                let k = (*na).min(*nb);
                *na -= k;
                *nb -= k;
            }
        }
        let (fixed, varying): (Vec<_>, Vec<_>) =
            fa.into_iter().partition(|&(base, _)| constant(self, base));
        let numerator = self.product(ca, &fixed);
        let denominator = self.product(cb, &fb);
        let ratio = self.div(numerator, denominator);
        let rest = self.product(1.0, &varying);
        self.mul(ratio, rest)
    }

    /// `e` as `coefficient * prod base^n` (bases with positive integer powers).
    fn factors(&self, e: Expr, coefficient: &mut f64, out: &mut Vec<(Expr, i32)>) {
        match self.node(e) {
            Node::Const(c) => *coefficient *= c.value(),
            Node::Neg(x) => {
                *coefficient = -*coefficient;
                self.factors(x, coefficient, out);
            }
            Node::Mul(x, y) => {
                self.factors(x, coefficient, out);
                self.factors(y, coefficient, out);
            }
            _ => {
                let (base, n) = match self.power(e) {
                    (b, n) if n > 0 => (b, n),
                    _ => (e, 1),
                };
                match out.iter_mut().find(|(x, _)| *x == base) {
                    Some((_, k)) => *k += n,
                    None => out.push((base, n)),
                }
            }
        }
    }

    /// `coefficient * prod base^n`, skipping zero powers.
    fn product(&mut self, coefficient: f64, factors: &[(Expr, i32)]) -> Expr {
        let mut p = self.constant(coefficient);
        for &(base, n) in factors.iter().filter(|(_, n)| *n > 0) {
            let f = self.powi(base, n);
            p = self.mul(p, f);
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> (Graph, Expr, Expr) {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("y");
        (g, x, y)
    }

    #[test]
    fn quotient_cancels_shared_factors() {
        let (mut g, x, y) = setup();
        let (m, l) = (g.symbol("m"), g.symbol("l"));
        let s = g.call(crate::sym::Func::Sin, x);
        let parameter = |g: &Graph, e: Expr| !g.free_symbols(e).contains(&g.as_sym(x).unwrap());
        // -(m y l sin x) / (m l^2) = (-y / l) sin x.
        let my = g.mul(m, y);
        let myl = g.mul(my, l);
        let f = g.mul(myl, s);
        let f = g.neg(f);
        let l2 = g.powi(l, 2);
        let mass = g.mul(m, l2);
        let q = g.quotient_cancelled(f, mass, parameter);
        let minus_y = g.neg(y);
        let ratio = g.div(minus_y, l);
        assert_eq!(q, g.mul(ratio, s));
        // Nothing shared: the plain quotient, times the varying part.
        let plain = g.quotient_cancelled(s, l, parameter);
        let one = g.one();
        let one_over_l = g.div(one, l);
        assert_eq!(plain, g.mul(one_over_l, s));
    }

    #[test]
    fn identities() {
        let (mut g, x, _) = setup();
        let (zero, one) = (g.zero(), g.one());
        let minus_one = g.constant(-1.0);
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.add(zero, x), x);
        assert_eq!(g.mul(zero, x), zero);
        assert_eq!(g.mul(x, zero), zero);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.mul(x, one), x);
        assert_eq!(g.div(x, one), x);
        assert_eq!(g.div(zero, x), zero);
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
        assert_eq!(g.mul(minus_one, x), nx);
        assert_eq!(g.div(x, minus_one), nx);
        assert_eq!(g.sub(x, x), zero);
        assert_eq!(g.powi(x, 0), one);
        assert_eq!(g.powi(x, 1), x);
        assert_eq!(g.powf(one, x), one);
        assert_eq!(g.node(nx), Node::Neg(x));
    }

    #[test]
    fn powers_collect() {
        let (mut g, x, y) = setup();
        let x2 = g.powi(x, 2);
        assert_eq!(g.mul(x, x), x2);
        assert_eq!(g.node(x2), Node::Powi(x, 2));
        let x3 = g.powi(x, 3);
        assert_eq!(g.mul(x2, x), x3);
        let x6 = g.powi(x, 6);
        assert_eq!(g.powi(x2, 3), x6);
        let x_inv = g.powi(x, -1);
        assert_eq!(g.mul(x_inv, x2), x);
        let nx = g.neg(x);
        assert_eq!(g.powi(nx, 2), x2);
        let nx3 = g.neg(x3);
        assert_eq!(g.powi(nx, 3), nx3);
        let two = g.constant(2.0);
        assert_eq!(g.powf(x, two), x2);
        let half = g.constant(0.5);
        let xh = g.powf(x, half);
        assert_eq!(g.node(xh), Node::Powf(x, half));
        let xy = g.powf(x, y);
        assert_eq!(g.node(xy), Node::Powf(x, y));
        // an exponent that overflows i32 is left as a product
        let big = g.powi(x, i32::MAX);
        let product = g.mul(big, x);
        assert!(matches!(g.node(product), Node::Mul(..)));
    }

    /// `sqrt(x^2) = |x|` and `sqrt(x)^2 = x` only for `x >= 0`: neither is rewritten.
    #[test]
    fn square_roots_keep_their_meaning() {
        let (mut g, x, _) = setup();
        let x2 = g.powi(x, 2);
        let root = g.call(Func::Sqrt, x2);
        assert_eq!(g.node(root), Node::Call(Func::Sqrt, x2));
        let s = g.call(Func::Sqrt, x);
        let s2 = g.powi(s, 2);
        assert_eq!(g.node(s2), Node::Powi(s, 2));
        assert!(g.eval(s2, &|_| -4.0).is_nan());
        assert_eq!(g.eval(root, &|_| -4.0), 4.0);
    }

    #[test]
    fn commutative_operands_are_canonical() {
        let (mut g, x, y) = setup();
        let s = g.call(Func::Sin, y);
        for (a, b) in [(x, y), (x, s), (s, y)] {
            assert_eq!(g.add(a, b), g.add(b, a));
            assert_eq!(g.mul(a, b), g.mul(b, a));
            assert_eq!(g.min(a, b), g.min(b, a));
            assert_eq!(g.max(a, b), g.max(b, a));
        }
        let three = g.constant(3.0);
        let sum = g.add(x, three);
        assert_eq!(g.node(sum), Node::Add(three, x), "constant first");
        assert_eq!(g.min(x, x), x);
        assert_eq!(g.max(s, s), s);
    }

    #[test]
    fn constants_fold_in_every_operation() {
        let (mut g, _, _) = setup();
        let (a, b) = (g.constant(0.3), g.constant(-1.7));
        let cases = [
            (g.add(a, b), 0.3 + -1.7),
            (g.sub(a, b), 0.3 - -1.7),
            (g.mul(a, b), 0.3 * -1.7),
            (g.div(a, b), 0.3 / -1.7),
            (g.neg(a), -0.3),
            (g.powi(b, 3), (-1.7f64).powi(3)),
            (g.powf(a, b), 0.3f64.powf(-1.7)),
            (g.atan2(a, b), 0.3f64.atan2(-1.7)),
            (g.min(a, b), -1.7),
            (g.max(a, b), 0.3),
            (g.call(Func::Ln, a), 0.3f64.ln()),
            (g.call(Func::Signum, b), -1.0),
            (g.call(Func::Abs, b), 1.7),
            (g.call(Func::Acos, a), 0.3f64.acos()),
        ];
        for (e, v) in cases {
            assert_eq!(g.as_const(e), Some(v), "{}", g.display(e));
        }
        // a domain error folds to NaN, as it would evaluate at run time
        let ln = g.call(Func::Ln, b);
        assert!(g.as_const(ln).unwrap().is_nan());
    }

    #[test]
    fn constants_collect_across_one_level() {
        let (mut g, x, y) = setup();
        let (c1, c2) = (g.constant(2.0), g.constant(3.0));
        let six = g.constant(6.0);
        let five = g.constant(5.0);
        let c2x = g.mul(c2, x);
        let six_x = g.mul(six, x);
        assert_eq!(g.mul(c1, c2x), six_x);
        let x_c1 = g.add(x, c1);
        let x_5 = g.add(x, five);
        assert_eq!(g.add(x_c1, c2), x_5);
        // constants float out of nested sums and products
        let y_c2 = g.add(y, c2);
        let xy = g.add(x, y);
        let expected = g.add(five, xy);
        assert_eq!(g.add(x_c1, y_c2), expected);
        let c1y = g.mul(c1, y);
        let xy = g.mul(x, y);
        let expected = g.mul(six, xy);
        assert_eq!(g.mul(c2x, c1y), expected);
        // like terms
        let two_x = g.mul(c1, x);
        assert_eq!(g.add(x, x), two_x);
        let five_x = g.mul(five, x);
        assert_eq!(g.add(c2x, two_x), five_x);
        let neg_c2x = g.neg(c2x);
        assert_eq!(g.add(c2x, neg_c2x), g.zero());
        assert_eq!(g.node(neg_c2x), Node::Mul(g.constant(-3.0), x));
    }

    #[test]
    fn signs_move_outwards() {
        let (mut g, x, y) = setup();
        let (nx, ny) = (g.neg(x), g.neg(y));
        let xy = g.mul(x, y);
        let neg_xy = g.neg(xy);
        assert_eq!(g.mul(nx, ny), xy);
        assert_eq!(g.mul(nx, y), neg_xy);
        let q = g.div(x, y);
        let neg_q = g.neg(q);
        assert_eq!(g.div(nx, y), neg_q);
        assert_eq!(g.div(x, ny), neg_q);
        assert_eq!(g.div(nx, ny), q);
        let two = g.constant(2.0);
        let minus_two = g.constant(-2.0);
        let m = g.mul(two, nx);
        assert_eq!(g.node(m), Node::Mul(minus_two, x));
        let abs = g.call(Func::Abs, x);
        assert_eq!(g.call(Func::Abs, nx), abs);
        assert_eq!(g.call(Func::Abs, abs), abs);
        assert_eq!(g.neg(two), minus_two);
    }

    /// Division by a power of two is an exact multiplication; by anything else it is kept.
    #[test]
    fn division_by_constants() {
        let (mut g, x, _) = setup();
        let (four, quarter, three) = (g.constant(4.0), g.constant(0.25), g.constant(3.0));
        let q = g.div(x, four);
        assert_eq!(g.node(q), Node::Mul(quarter, x));
        let t = g.div(x, three);
        assert_eq!(g.node(t), Node::Div(x, three));
        let zero = g.zero();
        let inf = g.div(x, zero);
        assert_eq!(g.node(inf), Node::Div(x, zero));
        // 1/c = 2^1022 is exact
        let tiny = g.constant(f64::MIN_POSITIVE);
        let q = g.div(x, tiny);
        let big = g.constant(2f64.powi(1022));
        assert_eq!(g.node(q), Node::Mul(big, x));
        // 1/c = 2^-1023 is subnormal: multiplying by it could round where dividing does not
        let huge = g.constant(2f64.powi(1023));
        let q = g.div(x, huge);
        assert_eq!(g.node(q), Node::Div(x, huge));
    }

    #[test]
    fn sum_and_dot() {
        let (mut g, x, y) = setup();
        assert_eq!(g.sum([]), g.zero());
        let two = g.constant(2.0);
        let one = g.one();
        let s = g.sum([x, one, y, two]);
        let xy = g.add(x, y);
        let three = g.constant(3.0);
        assert_eq!(s, g.add(three, xy));
        assert_eq!(g.node(s), Node::Add(three, xy));
        let d = g.dot(&[x, y], &[y, x]);
        let xy = g.mul(x, y);
        assert_eq!(d, g.mul(two, xy));
    }

    #[test]
    fn build_of_an_existing_node_returns_it() {
        let (mut g, x, y) = setup();
        let s = g.call(Func::Sin, x);
        let e = g.atan2(s, y);
        let e = g.powf(e, x);
        let _ = g.sub(e, y);
        for n in g.exprs().collect::<Vec<_>>() {
            assert_eq!(g.build(g.node(n)), n, "{}", g.display(n));
        }
    }
}
