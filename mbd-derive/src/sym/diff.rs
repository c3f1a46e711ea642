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
                // (1/2) (sqrt a)^-1: the reciprocal `asin`'s derivative forms too, so a closed
                // loop's `cos(asin u) = sqrt(1 - u^2)` and `asin u` share one division.
                let half = self.constant(0.5);
                let inv = self.powi(fa, -1);
                self.mul(half, inv)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-derived derivatives, checked at a generic point. Both sides are evaluated in
    /// `f64` with a handful of operations, so they agree to a few ulps: 1e-14 relative.
    struct Case {
        name: &'static str,
        build: fn(&mut Graph, Expr, Expr) -> Expr,
        /// (d/dx, d/dy) at (x, y)
        exact: fn(f64, f64) -> (f64, f64),
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-14 * (1.0 + b.abs())
    }

    const CASES: &[Case] = &[
        Case {
            name: "sin(x)^2",
            build: |g, x, _| {
                let s = g.call(Func::Sin, x);
                g.powi(s, 2)
            },
            exact: |x, _| (2.0 * x.sin() * x.cos(), 0.0),
        },
        Case {
            name: "atan2(y, x)",
            build: |g, x, y| g.atan2(y, x),
            exact: |x, y| (-y / (x * x + y * y), x / (x * x + y * y)),
        },
        Case {
            name: "x^y",
            build: |g, x, y| g.powf(x, y),
            exact: |x, y| (y * x.powf(y - 1.0), x.powf(y) * x.ln()),
        },
        Case {
            name: "x^2.5",
            build: |g, x, _| {
                let c = g.constant(2.5);
                g.powf(x, c)
            },
            exact: |x, _| (2.5 * x.powf(1.5), 0.0),
        },
        Case {
            name: "x^-3 y",
            build: |g, x, y| {
                let p = g.powi(x, -3);
                g.mul(p, y)
            },
            exact: |x, y| (-3.0 * y / x.powi(4), 1.0 / x.powi(3)),
        },
        Case {
            name: "x / y",
            build: |g, x, y| g.div(x, y),
            exact: |x, y| (1.0 / y, -x / (y * y)),
        },
        Case {
            name: "ln(x) / x",
            build: |g, x, _| {
                let l = g.call(Func::Ln, x);
                g.div(l, x)
            },
            exact: |x, _| ((1.0 - x.ln()) / (x * x), 0.0),
        },
        Case {
            name: "exp(sin(x^2 y))",
            build: |g, x, y| {
                let x2 = g.powi(x, 2);
                let a = g.mul(x2, y);
                let s = g.call(Func::Sin, a);
                g.call(Func::Exp, s)
            },
            exact: |x, y| {
                let outer = (x * x * y).sin().exp() * (x * x * y).cos();
                (outer * 2.0 * x * y, outer * x * x)
            },
        },
        Case {
            name: "sqrt(x^2 + y^2)",
            build: |g, x, y| {
                let x2 = g.powi(x, 2);
                let y2 = g.powi(y, 2);
                let r2 = g.add(x2, y2);
                g.call(Func::Sqrt, r2)
            },
            exact: |x, y| (x / x.hypot(y), y / x.hypot(y)),
        },
        Case {
            name: "tan(x y)",
            build: |g, x, y| {
                let a = g.mul(x, y);
                g.call(Func::Tan, a)
            },
            exact: |x, y| (y / (x * y).cos().powi(2), x / (x * y).cos().powi(2)),
        },
        Case {
            name: "asin(x) + acos(y)",
            build: |g, x, y| {
                let a = g.call(Func::Asin, x);
                let b = g.call(Func::Acos, y);
                g.add(a, b)
            },
            exact: |x, y| (1.0 / (1.0 - x * x).sqrt(), -1.0 / (1.0 - y * y).sqrt()),
        },
        Case {
            name: "atan(x) - y cos(x)",
            build: |g, x, y| {
                let a = g.call(Func::Atan, x);
                let c = g.call(Func::Cos, x);
                let yc = g.mul(y, c);
                g.sub(a, yc)
            },
            exact: |x, y| (1.0 / (1.0 + x * x) + y * x.sin(), -x.cos()),
        },
        Case {
            name: "sinh(x) cosh(y) + tanh(x)",
            build: |g, x, y| {
                let a = g.call(Func::Sinh, x);
                let b = g.call(Func::Cosh, y);
                let t = g.call(Func::Tanh, x);
                let ab = g.mul(a, b);
                g.add(ab, t)
            },
            exact: |x, y| {
                let sech2 = 1.0 / x.cosh().powi(2);
                (x.cosh() * y.cosh() + sech2, x.sinh() * y.sinh())
            },
        },
        Case {
            name: "-(x^3)",
            build: |g, x, _| {
                let c = g.powi(x, 3);
                g.neg(c)
            },
            exact: |x, _| (-3.0 * x * x, 0.0),
        },
        Case {
            name: "|x - y|",
            build: |g, x, y| {
                let d = g.sub(x, y);
                g.call(Func::Abs, d)
            },
            exact: |x, y| ((x - y).signum(), -(x - y).signum()),
        },
        Case {
            name: "signum(x) y",
            build: |g, x, y| {
                let s = g.call(Func::Signum, x);
                g.mul(s, y)
            },
            exact: |x, _| (0.0, x.signum()),
        },
        Case {
            name: "min(x^2, y)",
            build: |g, x, y| {
                let x2 = g.powi(x, 2);
                g.min(x2, y)
            },
            exact: |x, y| {
                if x * x < y {
                    (2.0 * x, 0.0)
                } else {
                    (0.0, 1.0)
                }
            },
        },
        Case {
            name: "max(x^2, y)",
            build: |g, x, y| {
                let x2 = g.powi(x, 2);
                g.max(x2, y)
            },
            exact: |x, y| {
                if x * x > y {
                    (2.0 * x, 0.0)
                } else {
                    (0.0, 1.0)
                }
            },
        },
    ];

    #[test]
    fn hand_checked_derivatives() {
        // points on both sides of every kink above; all inside every function's domain
        let points = [(0.7, 0.3), (0.4, 0.9), (0.9, -0.6), (0.55, 0.2)];
        for case in CASES {
            let mut g = Graph::new();
            let (x, y) = (g.symbol("x"), g.symbol("y"));
            let (sx, sy) = (g.as_sym(x).unwrap(), g.as_sym(y).unwrap());
            let f = (case.build)(&mut g, x, y);
            let dx = g.diff(f, sx);
            let dy = g.diff(f, sy);
            for (px, py) in points {
                let env = |s: Sym| if s == sx { px } else { py };
                let (ex, ey) = (case.exact)(px, py);
                let (gx, gy) = (g.eval(dx, &env), g.eval(dy, &env));
                assert!(
                    close(gx, ex),
                    "d/dx {} at ({px}, {py}): {gx} vs {ex}",
                    case.name
                );
                assert!(
                    close(gy, ey),
                    "d/dy {} at ({px}, {py}): {gy} vs {ey}",
                    case.name
                );
            }
        }
    }

    #[test]
    fn derivatives_of_leaves_and_independent_terms_are_exact() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let sx = g.as_sym(x).unwrap();
        let (zero, one) = (g.zero(), g.one());
        assert_eq!(g.diff(x, sx), one);
        assert_eq!(g.diff(y, sx), zero);
        let c = g.constant(4.0);
        assert_eq!(g.diff(c, sx), zero);
        let s = g.call(Func::Sin, y);
        assert_eq!(g.diff(s, sx), zero);
        // d/dx (3x + sin y) = 3, exactly, thanks to the simplifier
        let three = g.constant(3.0);
        let tx = g.mul(three, x);
        let e = g.add(tx, s);
        assert_eq!(g.diff(e, sx), three);
        // d/dx x^3 = 3 x^2 as a node
        let x3 = g.powi(x, 3);
        let x2 = g.powi(x, 2);
        let expected = g.mul(three, x2);
        assert_eq!(g.diff(x3, sx), expected);
        // d/dx signum(x) = 0
        let sg = g.call(Func::Signum, x);
        assert_eq!(g.diff(sg, sx), zero);
    }

    #[test]
    fn derivatives_are_memoised() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let sx = g.as_sym(x).unwrap();
        let s = g.call(Func::Sin, x);
        let e = g.mul(s, x);
        let d = g.diff(e, sx);
        let len = g.len();
        assert_eq!(g.diff(e, sx), d);
        assert_eq!(g.len(), len);
        let cos = g.call(Func::Cos, x);
        assert_eq!(
            g.diff(s, sx),
            cos,
            "the operand's derivative was stored too"
        );
    }

    /// Second derivatives go through the same machinery: d²/dx² sin(x)^2 = 2 cos(2x).
    #[test]
    fn second_derivative() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let sx = g.as_sym(x).unwrap();
        let s = g.call(Func::Sin, x);
        let f = g.powi(s, 2);
        let d1 = g.diff(f, sx);
        let d2 = g.diff(d1, sx);
        for v in [-1.3, 0.2, 0.9, 2.0] {
            let got = g.eval(d2, &|_| v);
            assert!(close(got, 2.0 * (2.0 * v).cos()), "{got} at {v}");
        }
    }
}
