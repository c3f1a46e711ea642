//! Interval bounds of expressions over every value of their symbols: enough to tell that a
//! constraint such as `x * x == -1` or `sin(x) + cos(y) == 3` holds at no configuration.

use super::expr::{Expr, Func, Graph, Node};
use std::f64::consts::{FRAC_PI_2, PI};

/// A closed interval `[lo, hi]`, possibly unbounded.
type Range = (f64, f64);

const ALL: Range = (f64::NEG_INFINITY, f64::INFINITY);

impl Graph {
    /// Bounds of each of `roots` for every value of every symbol (coordinates, parameters
    /// and `t` alike), from the operations' ranges bottom-up (a square `a * a` and even
    /// powers are non-negative). Sound but loose: the true range lies inside.
    pub fn ranges(&self, roots: &[Expr]) -> Vec<(f64, f64)> {
        let Some(last) = roots.iter().map(|e| e.index()).max() else {
            return Vec::new();
        };
        let mut r: Vec<Range> = Vec::with_capacity(last + 1);
        for i in 0..=last {
            let node = self.node_at(i);
            let at = |e: Expr| r[e.index()];
            let v = match node {
                Node::Const(c) => (c.value(), c.value()),
                Node::Sym(_) => ALL,
                Node::Add(a, b) => add(at(a), at(b)),
                Node::Mul(a, b) if a == b => even(at(a), 2),
                Node::Mul(a, b) => mul(at(a), at(b)),
                Node::Neg(a) => (-at(a).1, -at(a).0),
                Node::Div(a, b) => div(at(a), at(b)),
                Node::Powi(a, n) if n > 0 && n % 2 == 0 => even(at(a), n),
                Node::Powi(a, n) if n > 0 => (at(a).0.powi(n), at(a).1.powi(n)),
                Node::Powi(_, n) if n % 2 == 0 => (0.0, f64::INFINITY),
                Node::Powf(a, _) if at(a).0 >= 0.0 => (0.0, f64::INFINITY),
                Node::Call(f, a) => call(f, at(a)),
                Node::Atan2(..) => (-PI, PI),
                Node::Min(a, b) => (at(a).0.min(at(b).0), at(a).1.min(at(b).1)),
                Node::Max(a, b) => (at(a).0.max(at(b).0), at(a).1.max(at(b).1)),
                _ => ALL,
            };
            r.push(clean(v));
        }
        roots.iter().map(|e| r[e.index()]).collect()
    }
}

/// NaN ends (`inf - inf`, `0 * inf`) widen to unbounded.
fn clean((lo, hi): Range) -> Range {
    (
        if lo.is_nan() { f64::NEG_INFINITY } else { lo },
        if hi.is_nan() { f64::INFINITY } else { hi },
    )
}

fn add(a: Range, b: Range) -> Range {
    (a.0 + b.0, a.1 + b.1)
}

fn mul(a: Range, b: Range) -> Range {
    let p = [a.0 * b.0, a.0 * b.1, a.1 * b.0, a.1 * b.1];
    if p.iter().any(|v| v.is_nan()) {
        return ALL;
    }
    (
        p.iter().copied().fold(f64::INFINITY, f64::min),
        p.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

fn div(a: Range, b: Range) -> Range {
    if b.0 > 0.0 || b.1 < 0.0 {
        mul(a, (1.0 / b.1, 1.0 / b.0))
    } else {
        ALL
    }
}

/// `a^n` for an even `n > 0`.
fn even(a: Range, n: i32) -> Range {
    let (small, big) = (a.0.abs().min(a.1.abs()), a.0.abs().max(a.1.abs()));
    let lo = if a.0 <= 0.0 && a.1 >= 0.0 {
        0.0
    } else {
        small.powi(n)
    };
    (lo, big.powi(n))
}

fn call(f: Func, a: Range) -> Range {
    match f {
        Func::Sin | Func::Cos | Func::Tanh | Func::Signum => (-1.0, 1.0),
        Func::Atan | Func::Asin => (-FRAC_PI_2, FRAC_PI_2),
        Func::Acos => (0.0, PI),
        Func::Exp => (a.0.exp(), a.1.exp()),
        Func::Sinh => (a.0.sinh(), a.1.sinh()),
        Func::Sqrt => (a.0.max(0.0).sqrt(), a.1.sqrt()),
        Func::Cosh => (1.0, f64::INFINITY),
        Func::Abs => (0.0, a.0.abs().max(a.1.abs())),
        Func::Ln | Func::Tan => ALL,
    }
}
