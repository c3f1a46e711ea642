//! The arena: hash-consed nodes, the symbol table, and per-node summaries (free symbols,
//! non-smooth operations) computed once when a node is interned.
//!
//! Every node is created after its children, so ids are a topological order of the DAG:
//! a child's id is always smaller than its parent's. `diff`, `substitute`, `eval` and
//! `schedule` rely on this to work bottom-up without recursion.

use std::collections::{BTreeSet, HashMap};

use super::hash::{FastMap, FastSet};
use std::fmt;

/// A node of the expression DAG, an index into [`Graph`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct Expr(u32);

/// A named scalar symbol (coordinate, speed, parameter, time).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct Sym(u32);

impl Expr {
    pub(super) fn index(self) -> usize {
        self.0 as usize
    }
}

impl Sym {
    fn index(self) -> usize {
        self.0 as usize
    }
}

/// Elementary functions of one argument, named as the `f64` methods that evaluate them.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Ln,
    Sqrt,
    Abs,
    /// `f64::signum`: `+1` for `+0.0` and positive numbers, `-1` for `-0.0` and negative ones.
    Signum,
}

impl Func {
    const ALL: [Func; 14] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Sinh,
        Func::Cosh,
        Func::Tanh,
        Func::Exp,
        Func::Ln,
        Func::Sqrt,
        Func::Abs,
        Func::Signum,
    ];

    /// The function whose `f64` method is called `name` (`"sin"`, `"ln"`, `"signum"`, …).
    pub fn from_name(name: &str) -> Option<Func> {
        Self::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The name of the `f64` method that evaluates this function.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Sqrt => "sqrt",
            Func::Abs => "abs",
            Func::Signum => "signum",
        }
    }

    /// Whether the function is differentiable wherever it is defined (not `abs`, `signum`).
    pub fn is_smooth(self) -> bool {
        !matches!(self, Func::Abs | Func::Signum)
    }
}

/// A numeric constant stored as `f64` bits so that it can be hashed and interned.
/// `-0.0` is stored as `0.0` and every NaN as the one `f64::NAN`, so equal-looking
/// constants share a node.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Const(u64);

impl Const {
    /// The constant `v`, normalised (`-0.0` → `0.0`, any NaN → `f64::NAN`).
    pub fn new(v: f64) -> Const {
        let v = if v == 0.0 {
            0.0
        } else if v.is_nan() {
            f64::NAN
        } else {
            v
        };
        Const(v.to_bits())
    }

    pub fn value(self) -> f64 {
        f64::from_bits(self.0)
    }
}

/// One interned operation. Subtraction is `Add(a, Neg(b))`; there is no `Sub` node.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    Const(Const),
    Sym(Sym),
    Add(Expr, Expr),
    Mul(Expr, Expr),
    Neg(Expr),
    Div(Expr, Expr),
    Powi(Expr, i32),
    Powf(Expr, Expr),
    Call(Func, Expr),
    /// `y.atan2(x)`, operands in that order.
    Atan2(Expr, Expr),
    Min(Expr, Expr),
    Max(Expr, Expr),
}

impl Node {
    /// The operands, in order.
    pub fn children(self) -> impl Iterator<Item = Expr> {
        let (a, b) = match self {
            Node::Const(_) | Node::Sym(_) => (None, None),
            Node::Neg(a) | Node::Powi(a, _) | Node::Call(_, a) => (Some(a), None),
            Node::Add(a, b)
            | Node::Mul(a, b)
            | Node::Div(a, b)
            | Node::Powf(a, b)
            | Node::Atan2(a, b)
            | Node::Min(a, b)
            | Node::Max(a, b) => (Some(a), Some(b)),
        };
        a.into_iter().chain(b)
    }

    /// The same operation with each operand `c` replaced by `f(c)`.
    pub fn with_children(self, mut f: impl FnMut(Expr) -> Expr) -> Node {
        match self {
            Node::Const(_) | Node::Sym(_) => self,
            Node::Add(a, b) => Node::Add(f(a), f(b)),
            Node::Mul(a, b) => Node::Mul(f(a), f(b)),
            Node::Neg(a) => Node::Neg(f(a)),
            Node::Div(a, b) => Node::Div(f(a), f(b)),
            Node::Powi(a, n) => Node::Powi(f(a), n),
            Node::Powf(a, b) => Node::Powf(f(a), f(b)),
            Node::Call(func, a) => Node::Call(func, f(a)),
            Node::Atan2(y, x) => Node::Atan2(f(y), f(x)),
            Node::Min(a, b) => Node::Min(f(a), f(b)),
            Node::Max(a, b) => Node::Max(f(a), f(b)),
        }
    }

    /// Constants and symbols: the nodes code generation reads rather than computes.
    pub fn is_leaf(self) -> bool {
        matches!(self, Node::Const(_) | Node::Sym(_))
    }

    /// This node's own flags: its non-smooth operation (bit `i` for `NONSMOOTH_NAMES[i]`)
    /// or `NONFINITE` for a NaN or infinite constant.
    fn own_flags(self) -> u8 {
        match self {
            Node::Call(Func::Abs, _) => 1,
            Node::Call(Func::Signum, _) => 2,
            Node::Min(..) => 4,
            Node::Max(..) => 8,
            Node::Const(c) if !c.value().is_finite() => NONFINITE,
            _ => 0,
        }
    }
}

/// Names reported by [`Graph::nonsmooth_calls`], indexed by flag bit.
const NONSMOOTH_NAMES: [&str; 4] = ["abs", "signum", "min", "max"];

/// Flag bit of a NaN or infinite constant.
const NONFINITE: u8 = 16;

/// Free-symbol sets of all nodes as one flat bit table, `words` `u64`s per node.
/// A node only depends on symbols that existed when it was created; the table is widened
/// (rarely: symbols are usually declared first) when the symbol count outgrows it.
#[derive(Default, Debug, Clone)]
struct SymSets {
    words: usize,
    bits: Vec<u64>,
}

impl SymSets {
    fn row(&self, e: Expr) -> &[u64] {
        &self.bits[e.index() * self.words..(e.index() + 1) * self.words]
    }

    fn contains(&self, e: Expr, s: Sym) -> bool {
        let (w, b) = (s.index() / 64, s.index() % 64);
        w < self.words && self.bits[e.index() * self.words + w] & (1 << b) != 0
    }

    /// Makes room for `symbols` symbols in each of the `rows` existing rows.
    fn widen_for(&mut self, symbols: usize, rows: usize) {
        let needed = symbols.div_ceil(64);
        if needed <= self.words {
            return;
        }
        let words = needed.max(2 * self.words);
        let mut bits = vec![0; rows * words];
        for r in 0..rows {
            bits[r * words..r * words + self.words]
                .copy_from_slice(&self.bits[r * self.words..(r + 1) * self.words]);
        }
        self.words = words;
        self.bits = bits;
    }

    /// Appends the row of a new node: the union of its children's rows, plus `own`.
    fn push(&mut self, children: impl Iterator<Item = Expr>, own: Option<Sym>) {
        let start = self.bits.len();
        self.bits.resize(start + self.words, 0);
        for c in children {
            for w in 0..self.words {
                self.bits[start + w] |= self.bits[c.index() * self.words + w];
            }
        }
        if let Some(s) = own {
            self.bits[start + s.index() / 64] |= 1 << (s.index() % 64);
        }
    }
}

/// The expression arena. Structurally equal expressions are one node (hash-consing), so
/// common subexpressions are shared by construction. Build nodes with the simplifying
/// constructors (`add`, `mul`, …, in `simplify.rs`); `Node`s are only read back.
#[derive(Default, Debug, Clone)]
pub struct Graph {
    nodes: Vec<Node>,
    interned: FastMap<Node, Expr>,
    names: Vec<String>,
    symbols: HashMap<String, Sym>,
    symbol_exprs: Vec<Expr>,
    free: SymSets,
    /// Per node: the union of `Node::own_flags` over the node and everything below it.
    flags: Vec<u8>,
    /// `d e / d x` for every `(e, x)` differentiated so far.
    pub(super) derivatives: FastMap<(Expr, Sym), Expr>,
}

impl Graph {
    pub fn new() -> Self {
        Self::default()
    }

    /// The node of `node`, creating it if it is new. No simplification happens here.
    /// The node's expression if it is in the graph already (nothing is added).
    pub(super) fn existing(&self, node: Node) -> Option<Expr> {
        self.interned.get(&node).copied()
    }

    pub(super) fn intern(&mut self, node: Node) -> Expr {
        if let Some(&e) = self.interned.get(&node) {
            return e;
        }
        let id = u32::try_from(self.nodes.len()).expect("expression graph exceeds 2^32 nodes");
        let e = Expr(id);
        let own = match node {
            Node::Sym(s) => Some(s),
            _ => None,
        };
        self.free.push(node.children(), own);
        let mask = node
            .children()
            .fold(node.own_flags(), |m, c| m | self.flags[c.index()]);
        self.flags.push(mask);
        self.nodes.push(node);
        self.interned.insert(node, e);
        e
    }

    /// The symbol called `name`; the same name always gives the same expression.
    pub fn symbol(&mut self, name: &str) -> Expr {
        if let Some(&s) = self.symbols.get(name) {
            return self.symbol_exprs[s.index()];
        }
        let s = Sym(u32::try_from(self.names.len()).expect("more than 2^32 symbols"));
        self.names.push(name.to_owned());
        self.symbols.insert(name.to_owned(), s);
        self.free.widen_for(self.names.len(), self.nodes.len());
        let e = self.intern(Node::Sym(s));
        self.symbol_exprs.push(e);
        e
    }

    /// The expression of an existing symbol.
    pub fn sym(&self, s: Sym) -> Expr {
        self.symbol_exprs[s.index()]
    }

    pub fn as_sym(&self, e: Expr) -> Option<Sym> {
        match self.node(e) {
            Node::Sym(s) => Some(s),
            _ => None,
        }
    }

    pub fn sym_name(&self, s: Sym) -> &str {
        &self.names[s.index()]
    }

    pub fn node(&self, e: Expr) -> Node {
        self.nodes[e.index()]
    }

    /// The node of id `i` (ids are a topological order).
    pub(super) fn node_at(&self, i: usize) -> Node {
        self.nodes[i]
    }

    pub fn as_const(&self, e: Expr) -> Option<f64> {
        match self.node(e) {
            Node::Const(c) => Some(c.value()),
            _ => None,
        }
    }

    /// Whether `e` is the constant `0` (`-0.0` is stored as `0.0`).
    pub fn is_zero(&self, e: Expr) -> bool {
        self.as_const(e) == Some(0.0)
    }

    /// Whether `x` occurs in `e`. O(1): a bit lookup in the free-symbol table.
    pub fn depends_on(&self, e: Expr, x: Sym) -> bool {
        self.free.contains(e, x)
    }

    /// Whether any symbol of the bit set `mask` (indexed by symbol, as built by
    /// [`Graph::symbol_mask`]) occurs in `e`.
    pub(super) fn depends_on_any(&self, e: Expr, mask: &[u64]) -> bool {
        self.free.row(e).iter().zip(mask).any(|(a, b)| a & b != 0)
    }

    /// The bit set of `symbols`, in the layout of the free-symbol table.
    pub(super) fn symbol_mask(&self, symbols: impl IntoIterator<Item = Sym>) -> Vec<u64> {
        let mut mask = vec![0; self.free.words];
        for s in symbols {
            mask[s.index() / 64] |= 1 << (s.index() % 64);
        }
        mask
    }

    pub fn free_symbols(&self, e: Expr) -> BTreeSet<Sym> {
        let mut out = BTreeSet::new();
        for (w, &word) in self.free.row(e).iter().enumerate() {
            let mut bits = word;
            while bits != 0 {
                let b = bits.trailing_zeros() as usize;
                out.insert(Sym((w * 64 + b) as u32));
                bits &= bits - 1;
            }
        }
        out
    }

    /// Names (`"abs"`, `"signum"`, `"min"`, `"max"`) of the non-smooth operations inside `e`,
    /// in that order, each once.
    pub fn nonsmooth_calls(&self, e: Expr) -> Vec<&'static str> {
        let mask = self.flags[e.index()];
        (0..NONSMOOTH_NAMES.len())
            .filter(|b| mask & (1 << b) != 0)
            .map(|b| NONSMOOTH_NAMES[b])
            .collect()
    }

    /// Whether a NaN or infinite constant occurs in `e` (constant folding of `ln(-1)`,
    /// `1/0`, or a substitution that puts a singular point in): such an expression has no
    /// meaningful value and no Rust float literal.
    pub fn has_nonfinite_constant(&self, e: Expr) -> bool {
        self.flags[e.index()] & NONFINITE != 0
    }

    /// Number of interned nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Every interned node, in id (topological) order.
    pub fn exprs(&self) -> impl Iterator<Item = Expr> + use<> {
        (0..self.nodes.len() as u32).map(Expr)
    }

    /// Nodes reachable from `roots` (roots included) through operands for which `descend`
    /// holds, each once, in increasing id order, so children come before parents.
    pub(super) fn reachable(
        &self,
        roots: impl IntoIterator<Item = Expr>,
        mut descend: impl FnMut(Expr) -> bool,
    ) -> Vec<Expr> {
        let mut seen = FastSet::default();
        let mut stack: Vec<Expr> = roots.into_iter().filter(|&r| seen.insert(r)).collect();
        let mut out = Vec::new();
        while let Some(e) = stack.pop() {
            out.push(e);
            for c in self.node(e).children() {
                if descend(c) && seen.insert(c) {
                    stack.push(c);
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// A readable infix rendering of `e`, for messages and test failures. Recursive and
    /// unshared (a DAG prints as its tree): meant for small expressions.
    pub fn display(&self, e: Expr) -> impl fmt::Display + '_ {
        Display { graph: self, e }
    }
}

struct Display<'g> {
    graph: &'g Graph,
    e: Expr,
}

impl fmt::Display for Display<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let g = self.graph;
        let d = |e| Display { graph: g, e };
        match g.node(self.e) {
            Node::Const(c) => write!(f, "{}", c.value()),
            Node::Sym(s) => f.write_str(g.sym_name(s)),
            Node::Add(a, b) => write!(f, "({} + {})", d(a), d(b)),
            Node::Mul(a, b) => write!(f, "({} * {})", d(a), d(b)),
            Node::Neg(a) => write!(f, "-{}", d(a)),
            Node::Div(a, b) => write!(f, "({} / {})", d(a), d(b)),
            Node::Powi(a, n) => write!(f, "{}^{n}", d(a)),
            Node::Powf(a, b) => write!(f, "{}^{}", d(a), d(b)),
            Node::Call(func, a) => write!(f, "{}({})", func.name(), d(a)),
            Node::Atan2(y, x) => write!(f, "atan2({}, {})", d(y), d(x)),
            Node::Min(a, b) => write!(f, "min({}, {})", d(a), d(b)),
            Node::Max(a, b) => write!(f, "max({}, {})", d(a), d(b)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_name_gives_same_symbol() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("y");
        assert_eq!(g.symbol("x"), x);
        assert_ne!(x, y);
        let sx = g.as_sym(x).unwrap();
        assert_eq!(g.sym(sx), x);
        assert_eq!(g.sym_name(sx), "x");
        assert_eq!(g.as_sym(g.sym(g.as_sym(y).unwrap())), g.as_sym(y));
    }

    #[test]
    fn structurally_equal_expressions_share_one_node() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let s1 = g.call(Func::Sin, x);
        let p1 = g.mul(s1, y);
        let before = g.len();
        let s2 = g.call(Func::Sin, x);
        let p2 = g.mul(y, s2);
        assert_eq!((s1, p1), (s2, p2));
        assert_eq!(
            g.len(),
            before,
            "rebuilding an existing expression adds no node"
        );
        let a = g.add(x, y);
        let b = g.add(y, x);
        assert_eq!(a, b);
    }

    #[test]
    fn constants_are_normalised_before_interning() {
        let mut g = Graph::new();
        assert_eq!(g.constant(-0.0), g.constant(0.0));
        assert_eq!(g.constant(f64::NAN), g.constant(-f64::NAN));
        let minus_zero = g.constant(-0.0);
        assert!(g.is_zero(minus_zero));
        assert_eq!(Const::new(-0.0).value().to_bits(), 0.0f64.to_bits());
        let c = g.constant(2.5);
        assert_eq!(g.as_const(c), Some(2.5));
    }

    #[test]
    fn free_symbols_and_depends_on_agree() {
        let mut g = Graph::new();
        let c = g.constant(3.0); // created before any symbol exists: row widened later
        let syms: Vec<Expr> = (0..150).map(|i| g.symbol(&format!("q{i}"))).collect();
        let e = g.add(syms[3], syms[140]);
        let e = g.mul(e, c);
        let e = g.call(Func::Cos, e);
        let expected: BTreeSet<Sym> = [3, 140]
            .iter()
            .map(|&i| g.as_sym(syms[i]).unwrap())
            .collect();
        assert_eq!(g.free_symbols(e), expected);
        for (i, &s) in syms.iter().enumerate() {
            let s = g.as_sym(s).unwrap();
            assert_eq!(g.depends_on(e, s), i == 3 || i == 140, "symbol q{i}");
            assert!(!g.depends_on(c, s));
        }
        assert!(g.free_symbols(c).is_empty());
    }

    #[test]
    fn nonsmooth_calls_are_reported_once_each() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let a = g.call(Func::Abs, x);
        let m = g.max(a, y);
        let m2 = g.max(m, x);
        let s = g.call(Func::Sin, m2);
        assert_eq!(g.nonsmooth_calls(s), vec!["abs", "max"]);
        let sg = g.call(Func::Signum, y);
        let mn = g.min(sg, s);
        assert_eq!(g.nonsmooth_calls(mn), vec!["abs", "signum", "min", "max"]);
        let smooth = g.call(Func::Exp, x);
        assert!(g.nonsmooth_calls(smooth).is_empty());
    }

    #[test]
    fn nonfinite_constants_are_flagged() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let sx = g.as_sym(x).unwrap();
        let root = g.call(Func::Sqrt, x);
        let slope = g.diff(root, sx);
        assert!(!g.has_nonfinite_constant(slope));
        let zero = g.zero();
        let at_zero = g.substitute(slope, &[(sx, zero)].into());
        assert_eq!(g.as_const(at_zero), Some(f64::INFINITY));
        assert!(g.has_nonfinite_constant(at_zero));
        let minus_one = g.constant(-1.0);
        let nan = g.call(Func::Ln, minus_one);
        let e = g.add(x, nan);
        assert!(g.has_nonfinite_constant(e));
        assert!(!g.has_nonfinite_constant(x));
    }

    #[test]
    fn func_names_round_trip() {
        for f in Func::ALL {
            assert_eq!(Func::from_name(f.name()), Some(f));
            assert_eq!(f.is_smooth(), !matches!(f, Func::Abs | Func::Signum));
        }
        assert_eq!(Func::from_name("log"), None);
    }

    #[test]
    fn display_renders_infix() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let s = g.call(Func::Sin, x);
        let e = g.sub(s, y);
        assert_eq!(g.display(e).to_string(), "(sin(x) + -y)");
    }
}
