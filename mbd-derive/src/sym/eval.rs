//! Numeric evaluation, with exactly the `f64` operations generated code performs, so that
//! constant folding at compile time and evaluation at run time agree.

use super::expr::{Expr, Func, Graph, Node, Sym};
use super::hash::FastMap;

impl Func {
    /// `f(x)` by the `f64` method of the same name.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sinh => x.sinh(),
            Func::Cosh => x.cosh(),
            Func::Tanh => x.tanh(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Sqrt => x.sqrt(),
            Func::Abs => x.abs(),
            Func::Signum => x.signum(),
        }
    }
}

/// The value of `node` given its operands' values `a` and `b` (`b` unused by unary nodes).
/// Leaves: a constant's value; a symbol has none here and gives NaN.
pub(super) fn apply(node: Node, a: f64, b: f64) -> f64 {
    match node {
        Node::Const(c) => c.value(),
        Node::Sym(_) => f64::NAN,
        Node::Add(..) => a + b,
        Node::Mul(..) => a * b,
        Node::Neg(_) => -a,
        Node::Div(..) => a / b,
        Node::Powi(_, n) => a.powi(n),
        Node::Powf(..) => a.powf(b),
        Node::Call(f, _) => f.apply(a),
        Node::Atan2(..) => a.atan2(b),
        Node::Min(..) => a.min(b),
        Node::Max(..) => a.max(b),
    }
}

impl Graph {
    /// The value of `e` with each symbol `s` set to `env(s)`. Each shared node is
    /// evaluated once; no recursion, so deep expressions are fine.
    pub fn eval(&self, e: Expr, env: &dyn Fn(Sym) -> f64) -> f64 {
        let mut values: FastMap<Expr, f64> = FastMap::default();
        for n in self.reachable([e], |_| true) {
            let node = self.node(n);
            let v = match node {
                Node::Sym(s) => env(s),
                _ => {
                    let mut args = node.children().map(|c| values[&c]);
                    let a = args.next().unwrap_or(f64::NAN);
                    let b = args.next().unwrap_or(f64::NAN);
                    apply(node, a, b)
                }
            };
            values.insert(n, v);
        }
        values[&e]
    }
}
