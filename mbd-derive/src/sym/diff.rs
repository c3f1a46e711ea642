//! Exact symbolic differentiation.
//!
//! `d e / d x` is memoised per `(e, x)` in the graph and computed bottom-up over the
//! nodes of `e` that depend on `x`, so differentiating a shared DAG costs time and new
//! nodes linear in its size, not in the size of the tree it unfolds to.
//!
//! Non-smooth operations are differentiated piecewise, giving the derivative of the
//! branch taken at the evaluation point (at a kink: one of the one-sided derivatives):
//!
//! - `d|a| = signum(a) da` (at `a = +0`, `f64::signum` gives the right derivative `da`);
//! - `d signum(a) = 0` (the impulse at `a = 0` is dropped);
//! - `d min(a, b) = (da + db)/2 - signum(a - b) (da - db)/2`, which is `da` where `a < b`
//!   and `db` where `a > b`; `max` likewise with `+`. At `a = b` (where `signum(0) = 1`)
//!   `min` gives `db` and `max` gives `da`.

use super::expr::{Expr, Func, Graph, Node, Sym};

impl Graph {
    /// `d e / d x`, exact (up to the piecewise rules above), memoised per `(e, x)`.
    pub fn diff(&mut self, e: Expr, x: Sym) -> Expr {
        if !self.depends_on(e, x) {
            return self.zero();
        }
        if let Some(&d) = self.derivatives.get(&(e, x)) {
            return d;
        }
        let pending = self.reachable([e], |c| {
            self.depends_on(c, x) && !self.derivatives.contains_key(&(c, x))
        });
        for n in pending {
            let d = self.diff_node(n, x);
            self.derivatives.insert((n, x), d);
        }
        self.derivatives[&(e, x)]
    }

    /// The derivative of an operand already handled (or independent of `x`).
    fn known(&mut self, e: Expr, x: Sym) -> Expr {
        match self.derivatives.get(&(e, x)) {
            Some(&d) => d,
            None => self.zero(),
        }
    }

    /// `d n / d x` from the derivatives of `n`'s operands.
    fn diff_node(&mut self, n: Expr, x: Sym) -> Expr {
        match self.node(n) {
            Node::Const(_) => self.zero(),
            Node::Sym(s) => {
                if s == x {
                    self.one()
                } else {
                    self.zero()
                }
            }
            Node::Add(a, b) => {
                let (da, db) = (self.known(a, x), self.known(b, x));
                self.add(da, db)
            }
            Node::Mul(a, b) => {
                let (da, db) = (self.known(a, x), self.known(b, x));
                let t1 = self.mul(da, b);
                let t2 = self.mul(a, db);
                self.add(t1, t2)
            }
            Node::Neg(a) => {
                let da = self.known(a, x);
                self.neg(da)
            }
            Node::Div(a, b) => {
                // d(a/b) = (da - (a/b) db) / b, reusing the node a/b itself
                let (da, db) = (self.known(a, x), self.known(b, x));
                let q_db = self.mul(n, db);
                let num = self.sub(da, q_db);
                self.div(num, b)
            }
            Node::Powi(a, k) => {
                // d a^k = k a^(k-1) da; for k = i32::MIN, a^(k-1) is written a^k / a
                let da = self.known(a, x);
                let lower = match k.checked_sub(1) {
                    Some(k1) => self.powi(a, k1),
                    None => self.div(n, a),
                };
                let kc = self.constant(f64::from(k));
                let slope = self.mul(kc, lower);
                self.mul(slope, da)
            }
            Node::Powf(a, b) => {
                let (da, db) = (self.known(a, x), self.known(b, x));
                if self.is_zero(db) {
                    // d a^b = b a^(b-1) da: also right for a <= 0, where ln a is undefined
                    let one = self.one();
                    let b1 = self.sub(b, one);
                    let lower = self.powf(a, b1);
                    let slope = self.mul(b, lower);
                    self.mul(slope, da)
                } else {
                    // d a^b = a^b (db ln a + b da / a)
                    let ln_a = self.call(Func::Ln, a);
                    let t1 = self.mul(db, ln_a);
                    let b_da = self.mul(b, da);
                    let t2 = self.div(b_da, a);
                    let rate = self.add(t1, t2);
                    self.mul(n, rate)
                }
            }
            Node::Call(f, a) => {
                let da = self.known(a, x);
                let slope = self.func_slope(f, a, n);
                self.mul(slope, da)
            }
            Node::Atan2(y, x_arg) => {
                // d atan2(y, x) = (x dy - y dx) / (x^2 + y^2)
                let (dy, dx) = (self.known(y, x), self.known(x_arg, x));
                let t1 = self.mul(x_arg, dy);
                let t2 = self.mul(y, dx);
                let num = self.sub(t1, t2);
                let x2 = self.powi(x_arg, 2);
                let y2 = self.powi(y, 2);
                let den = self.add(x2, y2);
                self.div(num, den)
            }
            Node::Min(a, b) => self.diff_min_max(a, b, x, -1.0),
            Node::Max(a, b) => self.diff_min_max(a, b, x, 1.0),
        }
    }

    /// `f'(a)`, given `fa = f(a)` for the functions whose derivative reuses it.
    fn func_slope(&mut self, f: Func, a: Expr, fa: Expr) -> Expr {
        let one = self.one();
        match f {
            Func::Sin => self.call(Func::Cos, a),
            Func::Cos => {
                let s = self.call(Func::Sin, a);
                self.neg(s)
            }
            Func::Tan => {
                // 1 + tan^2 a
                let t2 = self.powi(fa, 2);
                self.add(one, t2)
            }
            Func::Asin | Func::Acos => {
                // ±1 / sqrt(1 - a^2)
                let a2 = self.powi(a, 2);
                let r = self.sub(one, a2);
                let s = self.call(Func::Sqrt, r);
                let inv = self.powi(s, -1);
                if f == Func::Asin { inv } else { self.neg(inv) }
            }
            Func::Atan => {
                let a2 = self.powi(a, 2);
                let den = self.add(one, a2);
                self.powi(den, -1)
            }
            Func::Sinh => self.call(Func::Cosh, a),
            Func::Cosh => self.call(Func::Sinh, a),
            Func::Tanh => {
                // 1 - tanh^2 a
                let t2 = self.powi(fa, 2);
                self.sub(one, t2)
            }
            Func::Exp => fa,
            Func::Ln => self.powi(a, -1),
            Func::Sqrt => {
                // 1 / (2 sqrt a)
                let two = self.constant(2.0);
                let den = self.mul(two, fa);
                self.powi(den, -1)
            }
            Func::Abs => self.call(Func::Signum, a),
            Func::Signum => self.zero(),
        }
    }

    /// `d min(a, b)` (`sign = -1`) or `d max(a, b)` (`sign = +1`):
    /// `(da + db)/2 + sign · signum(a - b) (da - db)/2`.
    fn diff_min_max(&mut self, a: Expr, b: Expr, x: Sym, sign: f64) -> Expr {
        let (da, db) = (self.known(a, x), self.known(b, x));
        let half = self.constant(0.5);
        let signed_half = self.constant(0.5 * sign);
        let mean = self.add(da, db);
        let mean = self.mul(half, mean);
        let gap = self.sub(a, b);
        let side = self.call(Func::Signum, gap);
        let spread = self.sub(da, db);
        let jump = self.mul(side, spread);
        let jump = self.mul(signed_half, jump);
        self.add(mean, jump)
    }
}
