//! Property tests of the symbolic engine against an independent tree evaluator, and
//! growth tests on deep shared expressions.
//!
//! The reference is `Tree`, a plain boxed expression with its own `f64` evaluator and
//! its own forward-mode (dual number) derivative; it shares no code with the engine.
//! The generators keep every value in `[-3.2, 3.2]`: each operation is scaled or shifted
//! so that its output stays in that range for inputs in it (`(a + b)/2`, `a b / 4`,
//! `a / (2 + b^2)`, `ln(1 + a^2)`, `sqrt(1 + a^2/4)`, `asin(a/4)`, `tan(a/3)`, …). So no
//! function is evaluated near a singularity, and every first to third derivative is
//! bounded by modest constants.

use std::collections::HashMap;

use proptest::prelude::*;

use super::{Expr, Func, Graph, Sym};

#[derive(Clone, Debug)]
enum Tree {
    X,
    Y,
    C(f64),
    Add(Box<Tree>, Box<Tree>),
    Sub(Box<Tree>, Box<Tree>),
    Mul(Box<Tree>, Box<Tree>),
    Div(Box<Tree>, Box<Tree>),
    Neg(Box<Tree>),
    Powi(Box<Tree>, i32),
    Powf(Box<Tree>, Box<Tree>),
    Call(Func, Box<Tree>),
    Atan2(Box<Tree>, Box<Tree>),
    Min(Box<Tree>, Box<Tree>),
    Max(Box<Tree>, Box<Tree>),
}

use Tree as T;

fn b(t: Tree) -> Box<Tree> {
    Box::new(t)
}

/// A value with its derivative along one direction (forward-mode AD), plus what the
/// tolerances need: the largest magnitude seen and the distance to the nearest kink.
#[derive(Clone, Copy, Debug)]
struct Dual {
    v: f64,
    d: f64,
}

#[derive(Debug)]
struct Report {
    value: Dual,
    /// max |value| and |derivative| over all subtrees
    scale: f64,
    /// min distance of a non-smooth operation's argument from its kink
    margin: f64,
}

fn eval_tree(t: &Tree, x: Dual, y: Dual) -> Report {
    let mut scale = 0.0f64;
    let mut margin = f64::INFINITY;
    let value = eval_rec(t, x, y, &mut scale, &mut margin);
    Report {
        value,
        scale,
        margin,
    }
}

fn eval_rec(t: &Tree, x: Dual, y: Dual, scale: &mut f64, margin: &mut f64) -> Dual {
    let mut ev = |t: &Tree| eval_rec(t, x, y, scale, margin);
    let r = match t {
        T::X => x,
        T::Y => y,
        T::C(c) => Dual { v: *c, d: 0.0 },
        T::Add(p, q) => {
            let (p, q) = (ev(p), ev(q));
            Dual {
                v: p.v + q.v,
                d: p.d + q.d,
            }
        }
        T::Sub(p, q) => {
            let (p, q) = (ev(p), ev(q));
            Dual {
                v: p.v - q.v,
                d: p.d - q.d,
            }
        }
        T::Mul(p, q) => {
            let (p, q) = (ev(p), ev(q));
            Dual {
                v: p.v * q.v,
                d: p.d * q.v + p.v * q.d,
            }
        }
        T::Div(p, q) => {
            let (p, q) = (ev(p), ev(q));
            Dual {
                v: p.v / q.v,
                d: (p.d * q.v - p.v * q.d) / (q.v * q.v),
            }
        }
        T::Neg(p) => {
            let p = ev(p);
            Dual { v: -p.v, d: -p.d }
        }
        T::Powi(p, n) => {
            let p = ev(p);
            let n = *n;
            Dual {
                v: p.v.powi(n),
                d: f64::from(n) * p.v.powi(n - 1) * p.d,
            }
        }
        T::Powf(p, q) => {
            let (p, q) = (ev(p), ev(q));
            let v = p.v.powf(q.v);
            Dual {
                v,
                d: v * (q.d * p.v.ln() + q.v * p.d / p.v),
            }
        }
        T::Call(f, p) => {
            let p = ev(p);
            let (v, slope) = match f {
                Func::Sin => (p.v.sin(), p.v.cos()),
                Func::Cos => (p.v.cos(), -p.v.sin()),
                Func::Tan => (p.v.tan(), 1.0 / (p.v.cos() * p.v.cos())),
                Func::Asin => (p.v.asin(), 1.0 / (1.0 - p.v * p.v).sqrt()),
                Func::Acos => (p.v.acos(), -1.0 / (1.0 - p.v * p.v).sqrt()),
                Func::Atan => (p.v.atan(), 1.0 / (1.0 + p.v * p.v)),
                Func::Sinh => (p.v.sinh(), p.v.cosh()),
                Func::Cosh => (p.v.cosh(), p.v.sinh()),
                Func::Tanh => (p.v.tanh(), 1.0 / (p.v.cosh() * p.v.cosh())),
                Func::Exp => (p.v.exp(), p.v.exp()),
                Func::Ln => (p.v.ln(), 1.0 / p.v),
                Func::Sqrt => (p.v.sqrt(), 0.5 / p.v.sqrt()),
                Func::Abs => {
                    *margin = margin.min(p.v.abs());
                    (p.v.abs(), if p.v < 0.0 { -1.0 } else { 1.0 })
                }
                Func::Signum => {
                    *margin = margin.min(p.v.abs());
                    (if p.v < 0.0 { -1.0 } else { 1.0 }, 0.0)
                }
            };
            Dual { v, d: slope * p.d }
        }
        T::Atan2(p, q) => {
            let (p, q) = (ev(p), ev(q));
            Dual {
                v: p.v.atan2(q.v),
                d: (q.v * p.d - p.v * q.d) / (p.v * p.v + q.v * q.v),
            }
        }
        T::Min(p, q) | T::Max(p, q) => {
            let (p, q) = (ev(p), ev(q));
            *margin = margin.min((p.v - q.v).abs());
            let first = if matches!(t, T::Min(..)) {
                p.v < q.v
            } else {
                p.v > q.v
            };
            if first { p } else { q }
        }
    };
    *scale = scale.max(r.v.abs()).max(r.d.abs());
    r
}

fn build(g: &mut Graph, t: &Tree) -> Expr {
    match t {
        T::X => g.symbol("x"),
        T::Y => g.symbol("y"),
        T::C(c) => g.constant(*c),
        T::Add(p, q) => bin(g, p, q, Graph::add),
        T::Sub(p, q) => bin(g, p, q, Graph::sub),
        T::Mul(p, q) => bin(g, p, q, Graph::mul),
        T::Div(p, q) => bin(g, p, q, Graph::div),
        T::Powf(p, q) => bin(g, p, q, Graph::powf),
        T::Atan2(p, q) => bin(g, p, q, Graph::atan2),
        T::Min(p, q) => bin(g, p, q, Graph::min),
        T::Max(p, q) => bin(g, p, q, Graph::max),
        T::Neg(p) => {
            let p = build(g, p);
            g.neg(p)
        }
        T::Powi(p, n) => {
            let p = build(g, p);
            g.powi(p, *n)
        }
        T::Call(f, p) => {
            let p = build(g, p);
            g.call(*f, p)
        }
    }
}

fn bin(g: &mut Graph, p: &Tree, q: &Tree, op: fn(&mut Graph, Expr, Expr) -> Expr) -> Expr {
    let (p, q) = (build(g, p), build(g, q));
    op(g, p, q)
}

/// The tree with the operands of every commutative operation swapped.
fn mirror(t: &Tree) -> Tree {
    let m = |t: &Tree| b(mirror(t));
    match t {
        T::X | T::Y | T::C(_) => t.clone(),
        T::Add(p, q) => T::Add(m(q), m(p)),
        T::Mul(p, q) => T::Mul(m(q), m(p)),
        T::Min(p, q) => T::Min(m(q), m(p)),
        T::Max(p, q) => T::Max(m(q), m(p)),
        T::Sub(p, q) => T::Sub(m(p), m(q)),
        T::Div(p, q) => T::Div(m(p), m(q)),
        T::Powf(p, q) => T::Powf(m(p), m(q)),
        T::Atan2(p, q) => T::Atan2(m(p), m(q)),
        T::Neg(p) => T::Neg(m(p)),
        T::Powi(p, n) => T::Powi(m(p), *n),
        T::Call(f, p) => T::Call(*f, m(p)),
    }
}

/// Expressions whose every subexpression stays in `[-3.2, 3.2]` when the leaves do
/// (see the module doc); `leaf` chooses the leaves.
fn tame(leaf: BoxedStrategy<Tree>) -> impl Strategy<Value = Tree> {
    let c = |v: f64| b(T::C(v));
    leaf.prop_recursive(5, 48, 2, move |inner| {
        let pair = (inner.clone(), inner.clone());
        prop_oneof![
            pair.clone()
                .prop_map(move |(p, q)| T::Div(b(T::Add(b(p), b(q))), c(2.0))),
            pair.clone()
                .prop_map(move |(p, q)| T::Div(b(T::Sub(b(p), b(q))), c(2.0))),
            pair.clone()
                .prop_map(move |(p, q)| T::Div(b(T::Mul(b(p), b(q))), c(4.0))),
            pair.clone()
                .prop_map(move |(p, q)| T::Div(b(p), b(T::Add(c(2.0), b(T::Powi(b(q), 2)))))),
            pair.clone().prop_map(move |(p, q)| T::Powf(
                b(T::Add(
                    c(1.0),
                    b(T::Div(b(T::Mul(b(p.clone()), b(p))), c(9.0)))
                )),
                b(T::Div(b(q), c(3.0)))
            )),
            pair.clone().prop_map(move |(p, q)| T::Atan2(
                b(p),
                b(T::Add(c(2.0), b(T::Mul(b(q.clone()), b(q)))))
            )),
            pair.clone().prop_map(|(p, q)| T::Min(b(p), b(q))),
            pair.clone().prop_map(|(p, q)| T::Max(b(p), b(q))),
            // same operand twice: exercises x - x, x x, x + x
            inner.clone().prop_map(|p| T::Sub(b(p.clone()), b(p))),
            inner
                .clone()
                .prop_map(move |p| T::Div(b(T::Mul(b(p.clone()), b(p))), c(4.0))),
            inner
                .clone()
                .prop_map(move |p| T::Div(b(T::Add(b(p.clone()), b(p))), c(2.0))),
            inner.clone().prop_map(|p| T::Neg(b(p))),
            inner
                .clone()
                .prop_map(move |p| T::Div(b(T::Powi(b(p), 3)), c(16.0))),
            inner
                .clone()
                .prop_map(move |p| T::Powi(b(T::Add(c(1.0), b(T::Powi(b(p), 2)))), -2)),
            inner.clone().prop_map(|p| T::Call(Func::Sin, b(p))),
            inner.clone().prop_map(|p| T::Call(Func::Cos, b(p))),
            inner.clone().prop_map(|p| T::Call(Func::Tanh, b(p))),
            inner.clone().prop_map(|p| T::Call(Func::Atan, b(p))),
            inner.clone().prop_map(|p| T::Call(Func::Abs, b(p))),
            inner.clone().prop_map(|p| T::Call(Func::Signum, b(p))),
            inner
                .clone()
                .prop_map(move |p| T::Call(Func::Tan, b(T::Div(b(p), c(3.0))))),
            inner
                .clone()
                .prop_map(move |p| T::Call(Func::Asin, b(T::Div(b(p), c(4.0))))),
            inner
                .clone()
                .prop_map(move |p| T::Call(Func::Acos, b(T::Div(b(p), c(4.0))))),
            inner
                .clone()
                .prop_map(move |p| T::Call(Func::Exp, b(T::Div(b(p), c(3.0))))),
            inner
                .clone()
                .prop_map(move |p| T::Call(Func::Sinh, b(T::Div(b(p), c(3.0))))),
            inner
                .clone()
                .prop_map(move |p| T::Call(Func::Cosh, b(T::Div(b(p), c(3.0))))),
            inner
                .clone()
                .prop_map(move |p| T::Call(Func::Ln, b(T::Add(c(1.0), b(T::Powi(b(p), 2)))))),
            inner.prop_map(move |p| T::Call(
                Func::Sqrt,
                b(T::Add(c(1.0), b(T::Div(b(T::Powi(b(p), 2)), c(4.0)))))
            )),
        ]
    })
}

fn leaf_xy() -> BoxedStrategy<Tree> {
    prop_oneof![Just(T::X), Just(T::Y), (-3.0..3.0f64).prop_map(T::C)].boxed()
}

fn leaf_y() -> BoxedStrategy<Tree> {
    prop_oneof![Just(T::Y), (-3.0..3.0f64).prop_map(T::C)].boxed()
}

/// Unscaled expressions with every operation, for structural properties only.
fn raw() -> impl Strategy<Value = Tree> {
    leaf_xy().prop_recursive(5, 48, 2, |inner| {
        let pair = (inner.clone(), inner.clone());
        let funcs = prop_oneof![
            Just(Func::Sin),
            Just(Func::Exp),
            Just(Func::Ln),
            Just(Func::Abs),
            Just(Func::Sqrt)
        ];
        prop_oneof![
            pair.clone().prop_map(|(p, q)| T::Add(b(p), b(q))),
            pair.clone().prop_map(|(p, q)| T::Sub(b(p), b(q))),
            pair.clone().prop_map(|(p, q)| T::Mul(b(p), b(q))),
            pair.clone().prop_map(|(p, q)| T::Div(b(p), b(q))),
            pair.clone().prop_map(|(p, q)| T::Powf(b(p), b(q))),
            pair.clone().prop_map(|(p, q)| T::Atan2(b(p), b(q))),
            pair.clone().prop_map(|(p, q)| T::Min(b(p), b(q))),
            pair.prop_map(|(p, q)| T::Max(b(p), b(q))),
            inner.clone().prop_map(|p| T::Neg(b(p))),
            (inner.clone(), -3..4i32).prop_map(|(p, n)| T::Powi(b(p), n)),
            (funcs, inner).prop_map(|(f, p)| T::Call(f, b(p))),
        ]
    })
}

fn setup(t: &Tree) -> (Graph, Expr, Sym, Sym) {
    let mut g = Graph::new();
    let (x, y) = (g.symbol("x"), g.symbol("y"));
    let (sx, sy) = (g.as_sym(x).unwrap(), g.as_sym(y).unwrap());
    let e = build(&mut g, t);
    (g, e, sx, sy)
}

fn env(sx: Sym, x: f64, y: f64) -> impl Fn(Sym) -> f64 {
    move |s| if s == sx { x } else { y }
}

fn at(x: f64, dx: f64) -> Dual {
    Dual { v: x, d: dx }
}

/// Kinks closer than this to the sample point are skipped: the two sides of a kink are
/// different functions, and a rounding-level difference picks either.
const KINK_MARGIN: f64 = 1e-6;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Rewrites are exact in real arithmetic; in `f64` they only reorder rounding. With
    /// at most 48 operations, each off by <= 1 ulp of a magnitude <= scale, and each error
    /// amplified by < 4 per level over <= 5 levels (the largest slope of a generator
    /// operation is 3 a^2/16 ≈ 1.9; (1 + a^2)^-2 has slope < 0.65), the total is below
    /// 48 · 4^5 · 2.2e-16 · scale ≈ 1.1e-11 · scale. Tolerance 1e-10 · (1 + scale).
    #[test]
    fn simplified_graph_has_the_value_of_the_tree(
        t in tame(leaf_xy()), x in -2.0..2.0f64, y in -2.0..2.0f64
    ) {
        let r = eval_tree(&t, at(x, 0.0), at(y, 0.0));
        prop_assume!(r.margin > KINK_MARGIN);
        let (g, e, sx, _) = setup(&t);
        let got = g.eval(e, &env(sx, x, y));
        prop_assert!((got - r.value.v).abs() <= 1e-10 * (1.0 + r.scale),
            "{} = {got}, tree {t:?} = {}", g.display(e), r.value.v);
    }

    /// Forward mode on the tree is exact up to rounding, like the symbolic derivative, so
    /// the same rounding argument applies, with the derivative parts in `scale`.
    #[test]
    fn derivative_matches_forward_mode(
        t in tame(leaf_xy()), x in -2.0..2.0f64, y in -2.0..2.0f64
    ) {
        let (mut g, e, sx, sy) = setup(&t);
        for (s, seed) in [(sx, (1.0, 0.0)), (sy, (0.0, 1.0))] {
            let r = eval_tree(&t, at(x, seed.0), at(y, seed.1));
            prop_assume!(r.margin > KINK_MARGIN);
            let d = g.diff(e, s);
            let got = g.eval(d, &env(sx, x, y));
            prop_assert!((got - r.value.d).abs() <= 1e-10 * (1.0 + r.scale),
                "d/d{} {} = {got}, forward mode {}", g.sym_name(s), g.display(e), r.value.d);
        }
    }

    /// Central difference (f(x+h) - f(x-h)) / 2h on the tree's own evaluator. Its error is
    /// h^2/6 |f'''| (truncation) + eps |f| / h (rounding). With h = 1e-5, |f| <= 3.2 and
    /// |f'''| bounded by products of the generator's slopes (< 1e3 for these depths), that
    /// is < 1.7e-8 + 7e-11; tolerance 1e-6 · (1 + |f'|). Points within 1e-3 of a kink are
    /// skipped so that x ± h stays on one side (slopes < 4 per level: 4^5 h ≈ 1e-2 · 1e-1).
    #[test]
    fn derivative_matches_central_difference(
        t in tame(leaf_xy()), x in -2.0..2.0f64, y in -2.0..2.0f64
    ) {
        let h = 1e-5;
        let r = eval_tree(&t, at(x, 0.0), at(y, 0.0));
        prop_assume!(r.margin > 1e-3);
        let (mut g, e, sx, _) = setup(&t);
        let d = g.diff(e, sx);
        let plus = eval_tree(&t, at(x + h, 0.0), at(y, 0.0));
        let minus = eval_tree(&t, at(x - h, 0.0), at(y, 0.0));
        prop_assume!(plus.margin > 1e-3 && minus.margin > 1e-3);
        let fd = (plus.value.v - minus.value.v) / (2.0 * h);
        let got = g.eval(d, &env(sx, x, y));
        prop_assert!((got - fd).abs() <= 1e-6 * (1.0 + fd.abs()),
            "d/dx {} = {got}, central difference {fd}", g.display(e));
    }

    /// Substituting `x := s(y)` gives the value of the tree at `(s(y), y)`; the
    /// substituted leaves stay in the generator's range, so the rounding bound above holds
    /// with twice the depth: 48 · 4^10 · 2.2e-16 ≈ 1.1e-8 · scale. Tolerance 1e-7 (1 + scale).
    #[test]
    fn substitution_preserves_value(
        t in tame(leaf_xy()), s in tame(leaf_y()), y in -2.0..2.0f64
    ) {
        let rs = eval_tree(&s, at(0.0, 0.0), at(y, 0.0));
        let r = eval_tree(&t, at(rs.value.v, 0.0), at(y, 0.0));
        prop_assume!(r.margin > KINK_MARGIN && rs.margin > KINK_MARGIN);
        let (mut g, e, sx, _) = setup(&t);
        let se = build(&mut g, &s);
        let map: HashMap<Sym, Expr> = [(sx, se)].into();
        let sub = g.substitute(e, &map);
        prop_assert!(!g.depends_on(sub, sx));
        let got = g.eval(sub, &|_| y);
        prop_assert!((got - r.value.v).abs() <= 1e-7 * (1.0 + r.scale.max(rs.scale)),
            "{} = {got}, tree {}", g.display(sub), r.value.v);
    }

    /// Swapping x and y is one simultaneous substitution, not two in a row.
    #[test]
    fn substitution_is_simultaneous(
        t in tame(leaf_xy()), x in -2.0..2.0f64, y in -2.0..2.0f64
    ) {
        let r = eval_tree(&t, at(y, 0.0), at(x, 0.0));
        prop_assume!(r.margin > KINK_MARGIN);
        let (mut g, e, sx, sy) = setup(&t);
        let map: HashMap<Sym, Expr> = [(sx, g.sym(sy)), (sy, g.sym(sx))].into();
        let swapped = g.substitute(e, &map);
        let got = g.eval(swapped, &env(sx, x, y));
        prop_assert!((got - r.value.v).abs() <= 1e-10 * (1.0 + r.scale));
    }

    /// Every node is already simplified, so rebuilding it changes nothing.
    #[test]
    fn identity_substitution_returns_the_same_node(t in raw()) {
        let (mut g, e, sx, sy) = setup(&t);
        let map: HashMap<Sym, Expr> = [(sx, g.sym(sx)), (sy, g.sym(sy))].into();
        prop_assert_eq!(g.substitute(e, &map), e);
    }

    /// Hash-consing and canonical operand order: building a tree again, or its mirror
    /// image under commutativity, gives the same node and no new ones.
    #[test]
    fn commuted_expressions_intern_to_one_node(t in raw()) {
        let (mut g, e, _, _) = setup(&t);
        let len = g.len();
        prop_assert_eq!(build(&mut g, &t), e);
        prop_assert_eq!(g.len(), len);
        prop_assert_eq!(build(&mut g, &mirror(&t)), e);
    }

    /// The schedule is closed under operands, ordered children-first, duplicate-free, and
    /// the use counts add up to the operand slots of scheduled nodes that hold scheduled
    /// nodes, plus the roots that are scheduled nodes.
    #[test]
    fn schedule_is_a_topological_order(t in raw(), u in raw()) {
        let (mut g, e, _, _) = setup(&t);
        let f = build(&mut g, &u);
        let roots = [e, f, e];
        let order = super::schedule(&g, &roots);
        let pos: HashMap<Expr, usize> = order.iter().enumerate().map(|(i, &n)| (n, i)).collect();
        prop_assert_eq!(pos.len(), order.len());
        let mut slots = roots.iter().filter(|r| pos.contains_key(r)).count();
        for (i, &n) in order.iter().enumerate() {
            prop_assert!(!g.node(n).is_leaf());
            for c in g.node(n).children() {
                if !g.node(c).is_leaf() {
                    prop_assert!(pos[&c] < i);
                    slots += 1;
                }
            }
        }
        for r in roots {
            prop_assert_eq!(pos.contains_key(&r), !g.node(r).is_leaf());
        }
        let counts = super::use_counts(&g, &roots);
        prop_assert_eq!(counts.len(), order.len());
        prop_assert_eq!(counts.values().sum::<usize>(), slots);
        prop_assert!(counts.values().all(|&c| c >= 1));
    }

    /// `free_symbols` lists exactly the symbols `depends_on` reports, and the derivative
    /// by an absent symbol is the zero node.
    #[test]
    fn dependency_queries_agree(t in raw()) {
        let (mut g, e, sx, sy) = setup(&t);
        let free = g.free_symbols(e);
        for s in [sx, sy] {
            prop_assert_eq!(free.contains(&s), g.depends_on(e, s));
            if !g.depends_on(e, s) {
                let d = g.diff(e, s);
                prop_assert!(g.is_zero(d));
            }
        }
        let d = g.diff(e, sx);
        prop_assert!(g.free_symbols(d).is_subset(&free));
    }
}

/// `e_{k+1} = e_k sin(e_k) + cos(e_k)^2 / 2`, `e_0 = x`: a DAG of 32 levels whose tree
/// has ~3^32 leaves. Memoised differentiation adds a bounded number of nodes per level
/// (the product rule, two chain rules, the sum: < 20), and the derivative agrees with
/// forward mode on the recurrence,
/// `e'_{k+1} = (sin e + e cos e - cos e sin e) e'_k`, to rounding.
#[test]
fn deep_shared_chain_differentiates_in_linear_size() {
    const LEVELS: usize = 32;
    let mut g = Graph::new();
    let x = g.symbol("x");
    let sx = g.as_sym(x).unwrap();
    let half = g.constant(0.5);
    let mut e = x;
    for _ in 0..LEVELS {
        let s = g.call(Func::Sin, e);
        let c = g.call(Func::Cos, e);
        let es = g.mul(e, s);
        let c2 = g.powi(c, 2);
        let hc2 = g.mul(half, c2);
        e = g.add(es, hc2);
    }
    let before = g.len();
    let d = g.diff(e, sx);
    let added = g.len() - before;
    assert!(added <= 20 * LEVELS, "{added} nodes for {LEVELS} levels");

    let x0 = 0.3f64;
    let (mut v, mut dv) = (x0, 1.0);
    for _ in 0..LEVELS {
        dv *= v.sin() + v * v.cos() - v.cos() * v.sin();
        v = v * v.sin() + 0.5 * v.cos().powi(2);
    }
    // the factors are in [0.6, 0.9] here (fixed point near 0.9): no cancellation, so
    // 32 levels of ~10 roundings each stay below 1e-12 relative
    let got = g.eval(d, &|_| x0);
    assert!((got - dv).abs() <= 1e-12 * dv.abs(), "{got} vs {dv}");
    assert!((g.eval(e, &|_| x0) - v).abs() <= 1e-12 * v.abs());
}

/// Mass matrix of a planar chain of `n` links (length `l`, point mass `m` at each tip,
/// relative angles `q_i`, rates `u_i`), obtained the way the derive obtains it:
/// `M_ij = d²T / du_i du_j` with `T = m/2 Σ_k |v_k|²`, `v_k = Σ_j (dp_k/dq_j) u_j`.
fn chain_mass_matrix(n: usize) -> (Graph, Vec<Vec<Expr>>, Vec<Sym>) {
    let mut g = Graph::new();
    let (l, m) = (g.symbol("l"), g.symbol("m"));
    let q: Vec<Expr> = (0..n).map(|i| g.symbol(&format!("q{i}"))).collect();
    let u: Vec<Expr> = (0..n).map(|i| g.symbol(&format!("u{i}"))).collect();
    let qs: Vec<Sym> = q.iter().map(|&e| g.as_sym(e).unwrap()).collect();
    let us: Vec<Sym> = u.iter().map(|&e| g.as_sym(e).unwrap()).collect();
    let (mut phi, mut px, mut py) = (g.zero(), g.zero(), g.zero());
    let mut kinetic = Vec::new();
    for &qk in &q {
        phi = g.add(phi, qk);
        let c = g.call(Func::Cos, phi);
        let s = g.call(Func::Sin, phi);
        let lc = g.mul(l, c);
        let ls = g.mul(l, s);
        px = g.add(px, lc);
        py = g.add(py, ls);
        let jx: Vec<Expr> = qs.iter().map(|&qj| g.diff(px, qj)).collect();
        let jy: Vec<Expr> = qs.iter().map(|&qj| g.diff(py, qj)).collect();
        let vx = g.dot(&jx, &u);
        let vy = g.dot(&jy, &u);
        let vx2 = g.powi(vx, 2);
        let vy2 = g.powi(vy, 2);
        kinetic.push(vx2);
        kinetic.push(vy2);
    }
    let half_m = {
        let half = g.constant(0.5);
        g.mul(half, m)
    };
    let sum = g.sum(kinetic);
    let t = g.mul(half_m, sum);
    let momenta: Vec<Expr> = us.iter().map(|&ui| g.diff(t, ui)).collect();
    let mass = momenta
        .iter()
        .map(|&p| us.iter().map(|&uj| g.diff(p, uj)).collect())
        .collect();
    let mut params = vec![g.as_sym(l).unwrap(), g.as_sym(m).unwrap()];
    params.extend(qs);
    (g, mass, params)
}

/// Growth stays polynomial: doubling the chain from 16 to 32 links multiplies the graph
/// by less than 2^3 (kinematics and Jacobian are O(n²), `T` and the momenta O(n²) new
/// nodes, the mass matrix O(n²) entries of O(n) new nodes each: O(n³) at most). An
/// exponential blow-up would multiply it by thousands.
#[test]
fn chain_of_32_links_stays_polynomial() {
    let (g16, _, _) = chain_mass_matrix(16);
    let (g32, mass, params) = chain_mass_matrix(32);
    let ratio = g32.len() as f64 / g16.len() as f64;
    assert!(
        ratio < 8.0,
        "{} -> {} nodes: ratio {ratio}",
        g16.len(),
        g32.len()
    );
    assert!(g32.len() < 32 * 32 * 32 * 8, "{} nodes", g32.len());

    // Independent closed form: dp_k/dq_j = l Σ_{a=j..k} (-sin φ_a, cos φ_a) for j <= k,
    // so M_ij = m l² Σ_{k >= max(i,j)} Σ_{a=i..k} Σ_{b=j..k} cos(φ_a - φ_b).
    let n = 32;
    let (l, m) = (0.7, 1.3);
    let q: Vec<f64> = (0..n)
        .map(|i| 0.3 * ((i * 7 % 11) as f64 - 5.0) / 5.0)
        .collect();
    let phi: Vec<f64> = q
        .iter()
        .scan(0.0, |acc, &qi| {
            *acc += qi;
            Some(*acc)
        })
        .collect();
    let env = |s: Sym| {
        let i = params
            .iter()
            .position(|&p| p == s)
            .expect("mass matrix free of rates");
        match i {
            0 => l,
            1 => m,
            _ => q[i - 2],
        }
    };
    for (i, j) in [(0, 0), (0, 31), (5, 17), (17, 5), (31, 31), (12, 13)] {
        let mut exact = 0.0;
        for k in i.max(j)..n {
            for a in i..=k {
                for b2 in j..=k {
                    exact += (phi[a] - phi[b2]).cos();
                }
            }
        }
        exact *= m * l * l;
        let got = g32.eval(mass[i][j], &env);
        // sums of <= 32³ terms of size <= m l²: rounding far below 1e-10 relative
        assert!(
            (got - exact).abs() <= 1e-10 * exact.abs(),
            "M[{i}][{j}] = {got} vs {exact}"
        );
    }
}

/// Every pass works bottom-up over ids instead of recursing, so expression depth is not
/// limited by the stack (a 20 000-deep chain here; `display` is the one recursive pass).
/// `e_k = sin(e_{k-1}) + x`: its x-derivative obeys `e'_k = cos(e_{k-1}) e'_{k-1} + 1`.
#[test]
fn very_deep_expressions_do_not_recurse() {
    const DEPTH: usize = 20_000;
    let mut g = Graph::new();
    let x = g.symbol("x");
    let (sx, y) = (g.as_sym(x).unwrap(), g.symbol("y"));
    let mut e = x;
    for _ in 0..DEPTH {
        let s = g.call(Func::Sin, e);
        e = g.add(s, x);
    }
    let d = g.diff(e, sx);
    let x0 = 0.4f64;
    let (mut v, mut dv) = (x0, 1.0f64);
    for _ in 0..DEPTH {
        dv = v.cos() * dv + 1.0;
        v = v.sin() + x0;
    }
    // a contraction (|cos| < 0.8 at the fixed point near 1.4): rounding does not accumulate
    assert!((g.eval(d, &|_| x0) - dv).abs() <= 1e-12 * dv.abs());
    let swapped = g.substitute(e, &[(sx, y)].into());
    assert!((g.eval(swapped, &|_| x0) - v).abs() <= 1e-12 * v.abs());
    assert_eq!(super::schedule(&g, &[e]).len(), 2 * DEPTH);
}

/// Pythagoras as a mass matrix meets it: `m (l cos u)^2 + m (l sin u)^2 = m l^2`, in
/// either order and bare (`sin^2 + cos^2 = 1`); unlike arguments or factors stay apart.
#[test]
fn pythagoras_collapses_rotating_point_sums() {
    let mut g = Graph::new();
    let (u, v, l, m) = (g.symbol("u"), g.symbol("v"), g.symbol("l"), g.symbol("m"));
    let (s, c) = (g.call(Func::Sin, u), g.call(Func::Cos, u));
    let (ls, lc) = (g.mul(l, s), g.mul(l, c));
    let (ls2, lc2) = (g.powi(ls, 2), g.powi(lc, 2));
    let l2 = g.powi(l, 2);
    assert_eq!(g.add(lc2, ls2), l2);
    assert_eq!(g.add(ls2, lc2), l2);
    let three = g.constant(3.0);
    let (a, b) = (g.mul(three, ls2), g.mul(three, lc2));
    let three_l2 = g.mul(three, l2);
    assert_eq!(g.add(a, b), three_l2);
    let (s2, c2) = (g.powi(s, 2), g.powi(c, 2));
    assert_eq!(g.add(s2, c2), g.one());
    // Different angles, different factors, unequal coefficients: no rewrite.
    let cv = g.call(Func::Cos, v);
    let cv2 = g.powi(cv, 2);
    let mixed = g.add(s2, cv2);
    assert!(g.as_const(mixed).is_none());
    let mc = g.mul(m, c);
    let mc2b = g.powi(mc, 2);
    let uneven = g.add(ls2, mc2b);
    assert!(!matches!(g.node(uneven), super::Node::Powi(_, 2)));
    let two = g.constant(2.0);
    let two_s2 = g.mul(two, s2);
    let uneq = g.add(two_s2, c2);
    assert!(g.as_const(uneq).is_none());
}

/// One product associated two ways cancels in a difference; different products do not.
#[test]
fn reassociated_products_cancel() {
    let mut g = Graph::new();
    let (u, w, l) = (g.symbol("u"), g.symbol("w"), g.symbol("l"));
    let (s, c) = (g.call(Func::Sin, u), g.call(Func::Cos, u));
    let (ls, lc) = (g.mul(l, s), g.mul(l, c));
    // l cos(u) (w (w l sin u)) - l sin(u) (w (w l cos u))
    let (wls, wlc) = (g.mul(w, ls), g.mul(w, lc));
    let (wwls, wwlc) = (g.mul(w, wls), g.mul(w, wlc));
    let (a, b) = (g.mul(lc, wwls), g.mul(ls, wwlc));
    assert_eq!(g.sub(a, b), g.zero());
    // w^2 l as a power and as a product.
    let w2 = g.powi(w, 2);
    let (p, ww) = (g.mul(w2, l), g.mul(w, w));
    let wwl = g.mul(ww, l);
    let wl = g.mul(w, l);
    let wwl2 = g.mul(w, wl);
    assert_eq!(g.sub(p, wwl2), g.zero());
    assert_eq!(g.sub(wwl, wwl2), g.zero());
    // Not the same product: kept.
    let other = g.mul(w, ls);
    let d = g.sub(other, wl);
    assert!(g.as_const(d).is_none());
}

/// A shared operand comes out of a sum (`p x + r x = (p + r) x`, and `p x - r x`); products
/// without one stay apart.
#[test]
fn shared_operand_is_factored_out() {
    let mut g = Graph::new();
    let (p, r, x, y) = (g.symbol("p"), g.symbol("r"), g.symbol("x"), g.symbol("y"));
    let (px, rx, xr) = (g.mul(p, x), g.mul(r, x), g.mul(x, r));
    let sum = g.add(px, rx);
    let p_plus_r = g.add(p, r);
    assert_eq!(sum, g.mul(p_plus_r, x));
    assert_eq!(g.add(px, xr), sum);
    let diff = g.sub(px, rx);
    let p_minus_r = g.sub(p, r);
    assert_eq!(diff, g.mul(p_minus_r, x));
    let ry = g.mul(r, y);
    let apart = g.add(px, ry);
    assert!(matches!(g.node(apart), super::Node::Add(..)));
    // Values: 2 * 5 + 3 * 5 at p = 2, r = 3, x = 5.
    let vals = |s: Sym| match g.sym_name(s) {
        "p" => 2.0,
        "r" => 3.0,
        _ => 5.0,
    };
    assert_eq!(g.eval(sum, &vals), 25.0);
}

/// `y - x` after `x - y` is the first difference negated (one node shared); a sum of two
/// positive terms, or a difference not yet in the graph, is built as it is.
#[test]
fn difference_reuses_its_negation() {
    let mut g = Graph::new();
    let (x, y, z) = (g.symbol("x"), g.symbol("y"), g.symbol("z"));
    let x_minus_y = g.sub(x, y);
    let y_minus_x = g.sub(y, x);
    assert_eq!(g.node(y_minus_x), super::Node::Neg(x_minus_y));
    let z_minus_x = g.sub(z, x);
    assert!(matches!(g.node(z_minus_x), super::Node::Add(..)));
    let x_plus_y = g.add(x, y);
    assert!(matches!(g.node(x_plus_y), super::Node::Add(..)));
}
