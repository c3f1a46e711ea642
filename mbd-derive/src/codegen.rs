//! Stage 4: equations -> straight-line Rust. The only module that knows the runtime's paths.
//!
//! Each generated function evaluates one shared block: the scheduled DAG nodes its results
//! need, each once, as `let` temporaries (hash-consing made them common subexpressions),
//! then fills only the non-zero entries of its static-size results. Parts a model does not
//! have (constraints, outputs, events, Jacobians) are not generated at all.

mod items;

pub use items::emit;

use crate::model::{Equations, Role};
use crate::parse::Mechanism;
use crate::sym::{self, Expr, Func, Node};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::{HashMap, HashSet};

/// Above this many temporaries a body declares them in groups (see [`Block::new`]).
const FLAT_LIMIT: usize = 1024;
/// Temporaries per declaration in a long body.
const GROUP: usize = 1024;

/// One function body under construction.
pub(crate) struct Block<'a> {
    eq: &'a Equations,
    names: HashMap<Expr, TokenStream>,
    stmts: Vec<TokenStream>,
    /// Temporaries bound (one per scheduled node), whatever the layout.
    len: usize,
    /// Arguments whose `sin` and `cos` are both bound here: they call `mbd_core::trig`,
    /// which shares one range reduction between the two once inlined. A lone `sin` or `cos`
    /// keeps the platform's (its latency is the shorter: pendulum in a dependent chain of
    /// calls 12.9 ns against 17.1, `overhead` bench).
    paired: HashSet<Expr>,
}

impl<'a> Block<'a> {
    /// Schedule `roots` and bind every interior node to a temporary.
    ///
    /// Every `let` opens a lexical scope that holds the rest of the body, and with debug
    /// information LLVM walks these scopes recursively: rustc overflowed its stack on a
    /// 32-link chain's articulated-body recursion (3387 nested `let`s) in the default `dev`
    /// profile. So a body of more than [`FLAT_LIMIT`] temporaries declares them first, a
    /// [`GROUP`] per `let (t0, t1, ..): (f64, f64, ..);`, then assigns each once: the
    /// nesting depth is the number of groups, and the optimised code is the same.
    pub(crate) fn new(eq: &'a Equations, roots: &[Expr]) -> Self {
        Self::after(eq, roots, &HashMap::new(), 0)
    }

    /// A block that follows others in the same function: nodes they bound (`known`) are
    /// reused, new temporaries are numbered from `first`.
    fn after(
        eq: &'a Equations,
        roots: &[Expr],
        known: &HashMap<Expr, TokenStream>,
        first: usize,
    ) -> Self {
        let mut b = Block {
            eq,
            names: known.clone(),
            stmts: Vec::new(),
            len: 0,
            paired: HashSet::new(),
        };
        let mut order = sym::schedule(&eq.g, roots);
        order.retain(|e| !known.contains_key(e));
        b.paired = paired_trig(&eq.g, &order);
        parameters_first(eq, &mut order);
        b.len = order.len();
        let grouped = order.len() > FLAT_LIMIT;
        let name = |i: usize| format_ident!("t{}", first + i);
        if grouped {
            for start in (0..order.len()).step_by(GROUP) {
                let names: Vec<_> = (start..order.len().min(start + GROUP)).map(name).collect();
                let types = names.iter().map(|_| quote!(f64));
                b.stmts.push(quote!(let (#(#names,)*): (#(#types,)*);));
            }
        }
        for (i, &e) in order.iter().enumerate() {
            let value = b.node(e);
            let t = name(i);
            b.stmts.push(if grouped {
                quote!(#t = #value;)
            } else {
                quote!(let #t: f64 = #value;)
            });
            b.names.insert(e, quote!(#t));
        }
        b
    }

    /// The number of temporaries (scheduled nodes).
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    pub(crate) fn leaf(&self, e: Expr) -> TokenStream {
        if let Some(n) = self.names.get(&e) {
            return n.clone();
        }
        match self.eq.g.node(e) {
            Node::Const(c) => literal(c.value()),
            Node::Sym(s) => match self.eq.roles.get(&s) {
                Some(Role::Time) => quote!(t),
                Some(Role::Param(p)) => quote!(self.#p),
                Some(Role::Q(i)) => quote!(q[#i]),
                Some(Role::Qd(i)) => quote!(qd[#i]),
                Some(Role::Qdd(i)) => quote!(qdd[#i]),
                Some(Role::Lambda(k)) => quote!(lambda[#k]),
                Some(Role::FrictionDirection(k)) => quote!(direction[#k]),
                Some(Role::RunLocal { per_link }) => {
                    let name = format_ident!("{}", self.eq.g.sym_name(s));
                    if *per_link {
                        quote!(#name[link])
                    } else {
                        quote!(#name)
                    }
                }
                None => {
                    // A driven/relaxed symbol left after reduction would be a bug in the
                    // mechanics stage; fail the build loudly rather than compute garbage.
                    let msg = format!(
                        "mbd internal error: unbound symbol `{}`",
                        self.eq.g.sym_name(s)
                    );
                    quote!(::core::compile_error!(#msg))
                }
            },
            _ => unreachable!("interior nodes are bound before use"),
        }
    }

    fn node(&self, e: Expr) -> TokenStream {
        let l = |x: Expr| self.leaf(x);
        match self.eq.g.node(e) {
            Node::Add(a, b) => {
                let (a, b) = (l(a), l(b));
                quote!(#a + #b)
            }
            Node::Mul(a, b) => {
                let (a, b) = (l(a), l(b));
                quote!(#a * #b)
            }
            Node::Div(a, b) => {
                let (a, b) = (l(a), l(b));
                quote!(#a / #b)
            }
            Node::Neg(a) => {
                let a = l(a);
                quote!(-#a)
            }
            Node::Powi(a, 2) => {
                let a = l(a);
                quote!(#a * #a)
            }
            Node::Powi(a, n) => {
                let a = l(a);
                quote!(#a.powi(#n))
            }
            Node::Powf(a, b) => {
                let (a, b) = (l(a), l(b));
                quote!(#a.powf(#b))
            }
            Node::Call(Func::Sin, a) if self.paired.contains(&a) => {
                let a = l(a);
                quote!(::mbd::__private::trig::sin(#a))
            }
            Node::Call(Func::Cos, a) if self.paired.contains(&a) => {
                let a = l(a);
                quote!(::mbd::__private::trig::cos(#a))
            }
            Node::Call(f, a) => {
                let a = l(a);
                let m = format_ident!("{}", method(f));
                quote!(#a.#m())
            }
            Node::Atan2(y, x) => {
                let (y, x) = (l(y), l(x));
                quote!(#y.atan2(#x))
            }
            Node::Min(a, b) => {
                let (a, b) = (l(a), l(b));
                quote!(#a.min(#b))
            }
            Node::Max(a, b) => {
                let (a, b) = (l(a), l(b));
                quote!(#a.max(#b))
            }
            Node::Const(_) | Node::Sym(_) => self.leaf(e),
        }
    }

    pub(crate) fn stmts(&self) -> TokenStream {
        let s = &self.stmts;
        quote!(#(#s)*)
    }

    /// `let mut name = Vector::<N>::zeros(); name[i] = ..;` for the non-zero entries.
    pub(crate) fn vector(&self, name: &str, n: usize, entries: &[Expr]) -> TokenStream {
        let id = format_ident!("{}", name);
        let sets = self.sets(name, entries);
        quote!(let mut #id = ::mbd::__private::Vector::<#n>::zeros(); #sets)
    }

    /// `name[i] = entry;` for the non-zero entries (into a vector declared elsewhere).
    fn sets(&self, name: &str, entries: &[Expr]) -> TokenStream {
        let id = format_ident!("{}", name);
        let sets = entries
            .iter()
            .enumerate()
            .filter(|(_, e)| !self.eq.g.is_zero(**e))
            .map(|(i, e)| {
                let v = self.leaf(*e);
                quote!(#id[#i] = #v;)
            });
        quote!(#(#sets)*)
    }

    pub(crate) fn matrix(
        &self,
        name: &str,
        r: usize,
        c: usize,
        entries: &[Vec<Expr>],
    ) -> TokenStream {
        let id = format_ident!("{}", name);
        let mut sets = Vec::new();
        for (i, row) in entries.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                if !self.eq.g.is_zero(*e) {
                    let v = self.leaf(*e);
                    sets.push(quote!(#id[(#i, #j)] = #v;));
                }
            }
        }
        quote!(let mut #id = ::mbd::__private::Matrix::<#r, #c>::zeros(); #(#sets)*)
    }

    /// `let name = [(i, j, entry), ..];` for the non-zero entries (`lower`: on and below the
    /// diagonal only, for a symmetric matrix): a large assembly's sparse `M` and `Phi_q`.
    pub(crate) fn triplets(&self, name: &str, entries: &[Vec<Expr>], lower: bool) -> TokenStream {
        let id = format_ident!("{}", name);
        let mut items = Vec::new();
        for (i, row) in entries.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                if !self.eq.g.is_zero(*e) && (!lower || j <= i) {
                    let v = self.leaf(*e);
                    items.push(quote!((#i, #j, #v)));
                }
            }
        }
        quote!(let #id: [(usize, usize, f64); _] = [#(#items),*];)
    }
}

/// Minimal coordinates of a closed loop: every `asin`/`acos` argument of the closed forms
/// checked to lie strictly inside `(-1, 1)` (`q` in scope), else `SingularPosition`, or the
/// failed parameter check that explains it (a NaN length is not a toggle position).
fn closure_check(eq: &Equations, n: usize) -> Option<TokenStream> {
    let domain = eq.closure_domain.as_ref().filter(|d| !d.is_empty())?;
    let args: Vec<Expr> = domain.iter().map(|d| d.arg).collect();
    let b = Block::new(eq, &args);
    let (s, checks) = (b.stmts(), domain_checks(&b, domain, n));
    Some(quote!({ #s #checks }))
}

/// The closed loop's domain arguments when `acceleration`'s body checks them itself
/// (`inline`: its block computes them beside `M` and `f`, so that a dependent angle's
/// `sin u` is not evaluated again, apart, by the platform's `sin`); else none.
fn closure_domain(eq: &Equations, inline: bool) -> &[crate::closure::Domain] {
    match &eq.closure_domain {
        Some(d) if inline => d,
        _ => &[],
    }
}

/// [`closure_check`]'s checks on the arguments `b` bound (`q` in scope), before the solve.
fn domain_checks(b: &Block<'_>, domain: &[crate::closure::Domain], n: usize) -> TokenStream {
    let checks = domain.iter().map(|d| {
        let (arg, coord) = (b.leaf(d.arg), &d.coord);
        quote! {
            ::mbd::__private::closure::check_domain(t, #arg, #coord,
                &<Self as ::mbd::__private::Mechanism<#n>>::COORDINATES, q.as_slice())
                .map_err(|e| self.diagnose(e))?;
        }
    });
    quote!(#(#checks)*)
}

/// `Mechanism::chart_margin` and its `OdeSystem` twin for minimal coordinates of a closed
/// loop: `min (1 - |u|)` over the closed forms' `asin`/`acos` arguments `u` (see
/// [`closure_check`]), which fixed-step integrators watch for a limit position.
fn chart_margin(eq: &Equations, n: usize) -> Option<(TokenStream, TokenStream)> {
    let domain = eq.closure_domain.as_ref().filter(|d| !d.is_empty())?;
    let args: Vec<Expr> = domain.iter().map(|d| d.arg).collect();
    let b = Block::new(eq, &args);
    let s = b.stmts();
    let margins = domain.iter().map(|d| {
        let arg = b.leaf(d.arg);
        quote!(1.0 - f64::abs(#arg))
    });
    let v = quote!(::mbd::__private::Vector);
    let mechanism = quote! {
        fn chart_margin(&self, t: f64, q: &#v<#n>) -> ::std::option::Option<f64> {
            #s
            Some(f64::INFINITY #(.min(#margins))*)
        }
    };
    let d = 2 * n;
    let ode = quote! {
        fn chart_margin(&self, t: f64, y: &#v<#d>) -> ::std::option::Option<f64> {
            ::mbd::__private::Mechanism::<#n>::chart_margin(self, t, &y.fixed_rows::<#n>(0).into_owned())
        }
    };
    Some((mechanism, ode))
}

/// Reorders a schedule so that the nodes of parameters and constants alone come first (a
/// stable partition, so children still precede parents): they do not wait for the state,
/// so a quotient of parameters overlaps a `sin` call instead of following it, and a loop's
/// invariants stand apart from its body.
fn parameters_first(eq: &Equations, order: &mut Vec<Expr>) {
    let mut varying: HashSet<Expr> = HashSet::new();
    for &e in order.iter() {
        let state = eq.g.node(e).children().any(|c| {
            varying.contains(&c)
                || match eq.g.node(c) {
                    Node::Sym(s) => !matches!(eq.roles.get(&s), Some(Role::Param(_))),
                    _ => false,
                }
        });
        if state {
            varying.insert(e);
        }
    }
    let (fixed, state): (Vec<Expr>, Vec<Expr>) = order.iter().partition(|e| !varying.contains(e));
    *order = fixed;
    order.extend(state);
}

/// The body of `acceleration` for a joint tree whose tail run of identical links is rolled
/// into three loops ([`crate::model::Equations::rolled`]): the rest of the tree unrolled
/// around them, one link's code per loop. Returns the code and its number of temporaries.
fn rolled_recursion(
    eq: &Equations,
    rolled: &crate::tree::Rolled,
    first: usize,
    qdd: &[Expr],
) -> (TokenStream, usize) {
    let (len, per) = (rolled.len, rolled.per);
    let ident = |e: Expr| {
        let s = eq.g.as_sym(e).expect("a placeholder is a symbol");
        format_ident!("{}", eq.g.sym_name(s))
    };
    let mut temporaries = 0;
    let mut code = Vec::new();
    // The other joints' accelerations, once the inward loop has handed on the run.
    let others: Vec<(usize, Expr)> = qdd
        .iter()
        .enumerate()
        .filter(|(i, e)| !(first..first + len * per).contains(i) && !eq.g.is_zero(**e))
        .map(|(i, &e)| (i, e))
        .collect();
    let all_roots: Vec<Expr> = (rolled.loops.iter())
        .flat_map(|l| {
            let carried = l.carried.iter().flat_map(|c| [c.1, c.2]);
            carried
                .chain(l.stored.iter().map(|st| st.1))
                .chain(l.qdd.iter().copied())
        })
        .chain(others.iter().map(|o| o.1))
        .collect();
    let (angles, mut known) = batched_trig(eq, &all_roots, Some((rolled, first)));
    code.push(angles);
    for (index, l) in rolled.loops.iter().enumerate() {
        // A value kept per link that is an entry of the angles' batch (a link's `cos` and
        // `sin`) is read from the batch by the later loops, not copied.
        let (batch, stored): (Vec<&(Expr, Expr)>, Vec<_>) =
            l.stored.iter().partition(|st| known.contains_key(&st.1));
        for st in batch {
            known.insert(st.0, known[&st.1].clone());
        }
        // Outward velocities first (they read the coordinates), accelerations last.
        let (velocities, accelerations) = (index == 0, index == rolled.loops.len() - 1);
        // Before the loop: the carried values' starts (and, before the last loop, the
        // other joints' accelerations).
        let mut roots: Vec<Expr> = l.carried.iter().map(|c| c.1).collect();
        if accelerations {
            roots.extend(others.iter().map(|o| o.1));
        }
        let before = Block::after(eq, &roots, &known, temporaries);
        temporaries += before.len();
        let (stmts, carried) = (
            before.stmts(),
            l.carried.iter().map(|c| {
                let (name, start) = (ident(c.0), before.leaf(c.1));
                quote!(let mut #name: f64 = #start;)
            }),
        );
        let arrays = stored.iter().map(|st| {
            let name = ident(st.0);
            quote!(let mut #name = [0.0f64; #len];)
        });
        code.push(quote!(#stmts #(#carried)* #(#arrays)*));
        if accelerations {
            let sets = others.iter().map(|(i, e)| {
                let v = before.leaf(*e);
                quote!(qdd[#i] = #v;)
            });
            code.push(quote!(#(#sets)*));
        }
        known = before.names.clone();

        // One link.
        let mut roots: Vec<Expr> = l.carried.iter().map(|c| c.2).collect();
        roots.extend(l.stored.iter().map(|st| st.1));
        roots.extend(l.qdd.iter().copied());
        let body = Block::after(eq, &roots, &known, temporaries);
        temporaries += body.len();
        let coordinate = velocities.then(|| {
            let reads = rolled.coords.iter().enumerate().map(|(k, &(q, qd))| {
                let (q, qd) = (ident(q), ident(qd));
                quote! {
                    let #q = q[#first + #per * link + #k];
                    let #qd = qd[#first + #per * link + #k];
                }
            });
            quote!(#(#reads)*)
        });
        let stmts = body.stmts();
        let stores = stored.iter().map(|st| {
            let (name, v) = (ident(st.0), body.leaf(st.1));
            quote!(#name[link] = #v;)
        });
        let acc = l.qdd.iter().enumerate().map(|(k, &e)| {
            let v = body.leaf(e);
            quote!(qdd[#first + #per * link + #k] = #v;)
        });
        let (names, next): (Vec<_>, Vec<_>) = l
            .carried
            .iter()
            .map(|c| (ident(c.0), body.leaf(c.2)))
            .unzip();
        let range = if l.reverse {
            quote!((0..#len).rev())
        } else {
            quote!(0..#len)
        };
        code.push(quote! {
            for link in #range {
                #coordinate
                #stmts
                #(#stores)*
                #(#acc)*
                (#(#names,)*) = (#(#next,)*);
            }
        });
    }
    (quote!(#(#code)*), temporaries)
}

/// The sines and cosines of a joint tree's angles, all taken by one
/// `trig::sin_cos_array` call ahead of the recursion (the same values as one at a time,
/// several per vector instruction): the statement, and the names of the batch's entries
/// for the blocks that follow (`known`). Batched: the paired (`sin` and `cos` both used)
/// functions of a coordinate, and in a rolled run of the placeholder angle of each link
/// (read as `[offset + link]` in the loops). Measured on the 8-link chain's generated rhs
/// (`chain` bench): 155 ns one at a time, 119 ns batched.
fn batched_trig(
    eq: &Equations,
    roots: &[Expr],
    run: Option<(&crate::tree::Rolled, usize)>,
) -> (TokenStream, HashMap<Expr, TokenStream>) {
    let order = sym::schedule(&eq.g, roots);
    let paired = paired_trig(&eq.g, &order);
    // Each batched angle: its position in the batch and whether it is a run's (per link).
    let mut slot: HashMap<Expr, (usize, bool)> = HashMap::new();
    let mut elements = Vec::new();
    let mut coordinates: Vec<(usize, Expr)> = (paired.iter())
        .filter_map(|&e| match eq.roles.get(&eq.g.as_sym(e)?) {
            Some(Role::Q(i)) => Some((*i, e)),
            _ => None,
        })
        .collect();
    coordinates.sort_unstable();
    for (i, e) in coordinates {
        slot.insert(e, (elements.len(), false));
        elements.push(quote!(q[#i]));
    }
    if let Some((rolled, first)) = run {
        for (k, &(angle, _)) in rolled.coords.iter().enumerate() {
            if paired.contains(&angle) {
                slot.insert(angle, (elements.len(), true));
                elements.extend((0..rolled.len).map(|link| {
                    let i = first + rolled.per * link + k;
                    quote!(q[#i])
                }));
            }
        }
    }
    let mut known = HashMap::new();
    if elements.len() < 2 {
        return (TokenStream::new(), known);
    }
    for &e in &order {
        let (name, a) = match eq.g.node(e) {
            Node::Call(Func::Sin, a) => (quote!(__mbd_sin), a),
            Node::Call(Func::Cos, a) => (quote!(__mbd_cos), a),
            _ => continue,
        };
        if let Some(&(at, per_link)) = slot.get(&a) {
            let index = if per_link {
                quote!(#at + link)
            } else {
                quote!(#at)
            };
            known.insert(e, quote!(#name[#index]));
        }
    }
    let code = quote! {
        let (__mbd_sin, __mbd_cos) = ::mbd::__private::trig::sin_cos_array([#(#elements),*]);
    };
    (code, known)
}

/// `impl PartialEq` for a generated struct of `f64` fields, comparing them as two arrays:
/// the derive's `a == b && ..` chain of thousands of fields (a model's outputs) overflows
/// rustc's stack (at about 5500), an array literal does not.
pub(crate) fn flat_partial_eq(name: &syn::Ident, fields: &[&syn::Ident]) -> TokenStream {
    let k = fields.len();
    quote! {
        impl ::core::cmp::PartialEq for #name {
            fn eq(&self, other: &Self) -> bool {
                let (a, b): ([f64; #k], [f64; #k]) = ([#(self.#fields),*], [#(other.#fields),*]);
                a == b
            }
        }
    }
}

/// `check_parameters`: every parameter finite, and every mass, inertia, stiffness, damping
/// and friction coefficient that is not a constant (constants are checked at compile time)
/// of its sign; `diagnose` puts a failed check in place of the error of a solve it explains
/// (a NaN parameter is not a "singular mass matrix").
fn parameter_checks(
    ast: &Mechanism,
    eq: &Equations,
    recursive: bool,
) -> (TokenStream, Option<TokenStream>) {
    let finite = ast.params.iter().map(|p| {
        let (id, name) = (&p.name, p.name.to_string());
        quote! {
            if !self.#id.is_finite() {
                return Err(::mbd::__private::Error::InvalidParameter {
                    what: ::std::format!("parameter `{}`", #name), value: self.#id, requirement: "finite" });
            }
        }
    });
    // `which`: Some(true) the eager checks, Some(false) the others, None all. A value shared
    // by several bodies (a chain's `m`) is checked once, under the first body's name.
    let checks = |which: Option<bool>| {
        let mut seen = std::collections::HashSet::new();
        let checks: Vec<_> = eq
            .checks
            .iter()
            .filter(|c| eq.g.as_const(c.expr).is_none() && which.is_none_or(|e| c.eager == e))
            .filter(|c| seen.insert((c.expr, c.positive)))
            .collect();
        let roots: Vec<Expr> = checks.iter().map(|c| c.expr).collect();
        let b = Block::new(eq, &roots);
        let s = b.stmts();
        let tests: Vec<TokenStream> = checks.iter().map(|c| {
            let v = b.leaf(c.expr);
            let what = &c.what;
            let (ok, requirement) = if c.positive {
                (quote!(v > 0.0), "positive")
            } else {
                (quote!(v >= 0.0), "zero or positive")
            };
            quote! {
                let v: f64 = #v;
                if !(#ok) {
                    return Err(::mbd::__private::Error::InvalidParameter {
                        what: ::std::string::String::from(#what), value: v, requirement: #requirement });
                }
            }
        }).collect();
        (!tests.is_empty()).then(|| quote!(#s #(#tests)*))
    };
    let (all, eager, masses) = (checks(None), checks(Some(true)), checks(Some(false)));
    let masses_fn = recursive.then(|| {
        quote! {
            /// The mass and inertia checks, for the articulated-body recursion (no pivot sign
            /// of a mass-matrix solve reveals a negative mass there).
            #[inline]
            fn check_masses(&self) -> ::mbd::__private::Result<()> {
                let t = 0.0_f64;
                #masses
                Ok(())
            }
        }
    });
    let eager_fn = eager.as_ref().map(|code| {
        quote! {
            /// The checks no solve would notice (stiffnesses, dampings, friction coefficients),
            /// at the time `t` of the evaluation: a stiffness may be a function of time.
            #[inline]
            fn check_elements(&self, t: f64) -> ::mbd::__private::Result<()> {
                let _ = t;
                #code
                Ok(())
            }
        }
    });
    // In minimal coordinates of a closed loop, `M = J^T M_bodies J` (`J` the closed form's
    // Jacobian) with valid parameters fails its factorisation only where `J` loses rank or
    // grows without bound: a singular position of the chart the `asin`/`acos` domain does not
    // bound (a five-bar's crank tips meeting). Say so, not "a negative mass".
    let chart_singular = if eq.closure_domain.is_some() {
        quote! {
            match err {
                ::mbd::__private::Error::MassMatrixNotPositiveDefinite { t }
                | ::mbd::__private::Error::SingularMassMatrix { t } => ::mbd::__private::Error::SingularPosition {
                    t,
                    detail: ::std::string::String::from(
                        "the mass matrix in the loop's minimal coordinates is singular (every parameter valid): \
                         the loop is at, or within rounding of, a singular position of its closed form \
                         (two of its joints meeting, say), where the closure does not determine the motion; \
                         `#[mechanism(augmented)]` keeps every coordinate and can pass it"),
                },
                e => e,
            }
        }
    } else {
        quote!(err)
    };
    let code = quote! {
        /// Whether the parameters mean a mechanism: each finite, and every mass, inertia,
        /// stiffness, damping and friction coefficient of its sign. The accelerations report
        /// a failed check (at once for elements, in place of the solve's error for masses).
        pub fn check_parameters(&self) -> ::mbd::__private::Result<()> {
            let t = 0.0_f64;
            #(#finite)*
            #all
            Ok(())
        }
        #eager_fn
        #masses_fn
        /// `err`, or the failed parameter check that explains it.
        #[cold]
        fn diagnose(&self, err: ::mbd::__private::Error) -> ::mbd::__private::Error {
            self.check_parameters().err().unwrap_or_else(|| #chart_singular)
        }
    };
    (code, eager.map(|_| quote!(self.check_elements(t)?;)))
}

/// The arguments of which `order` computes both `sin` and `cos` (see `Block::paired`).
fn paired_trig(g: &sym::Graph, order: &[Expr]) -> HashSet<Expr> {
    let (mut sin, mut cos) = (HashSet::new(), HashSet::new());
    for &e in order {
        match g.node(e) {
            Node::Call(Func::Sin, a) => sin.insert(a),
            Node::Call(Func::Cos, a) => cos.insert(a),
            _ => false,
        };
    }
    sin.intersection(&cos).copied().collect()
}

fn method(f: Func) -> &'static str {
    match f {
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

fn literal(v: f64) -> TokenStream {
    // A constant folded to a non-finite value (a division by an exact zero: a model
    // singular at every state) stays one, for the run-time checks to report.
    if v.is_nan() {
        return quote!(f64::NAN);
    }
    if v.is_infinite() {
        return if v > 0.0 {
            quote!(f64::INFINITY)
        } else {
            quote!(f64::NEG_INFINITY)
        };
    }
    let lit = Literal::f64_suffixed(v.abs());
    if v.is_sign_negative() {
        quote!((-#lit))
    } else {
        quote!(#lit)
    }
}

fn uses(eq: &Equations, roots: &[Expr], pred: impl Fn(&Role) -> bool) -> bool {
    roots.iter().any(|e| {
        eq.g.free_symbols(*e)
            .iter()
            .any(|s| eq.roles.get(s).is_some_and(&pred))
    })
}

/// The body of `mass_matrix`: the entries written out, or, for a long tree, one column at a
/// time from `M qdd` with `qdd` a column of the identity (O(n) code; O(n^2) work per call);
/// checked as [`checked_value`] says.
fn mass_matrix_body(eq: &Equations, n: usize) -> (TokenStream, usize) {
    match &eq.mass_times {
        Some(rows) => {
            let b = Block::new(eq, rows);
            let (s, fill) = (b.stmts(), b.vector("column", n, rows));
            let check = closure_check(eq, n);
            let code = quote! {
                #check
                let mut mass = ::mbd::__private::Matrix::<#n, #n>::zeros();
                for j in 0..#n {
                    let mut qdd = ::mbd::__private::Vector::<#n>::zeros();
                    qdd[j] = 1.0;
                    #s
                    #fill
                    mass.set_column(j, &column);
                }
                ::mbd::__private::closure::finite_value(t, mass).map_err(|e| self.diagnose(e))
            };
            (code, b.len())
        }
        None => {
            let roots: Vec<Expr> = eq.mass.iter().flatten().copied().collect();
            checked_value(
                eq,
                n,
                &roots,
                |b| b.matrix("mass", n, n, &eq.mass),
                quote!(mass),
            )
        }
    }
}

/// A fallible body (`Result`) that computes `roots` into `value` with `fill`: a closed loop's
/// domain checked first, on arguments computed in the same block as the roots (shared, as
/// in `acceleration`), then the value's finiteness, each failure diagnosed (a bad parameter
/// named as such). `mass_matrix`, `forces` and `energy` never hand out a NaN.
fn checked_value(
    eq: &Equations,
    n: usize,
    roots: &[Expr],
    fill: impl FnOnce(&Block<'_>) -> TokenStream,
    value: TokenStream,
) -> (TokenStream, usize) {
    let domain = eq.closure_domain.as_deref().unwrap_or(&[]);
    let all: Vec<Expr> = (roots.iter().copied())
        .chain(domain.iter().map(|d| d.arg))
        .collect();
    let b = Block::new(eq, &all);
    let (s, checks, fill) = (b.stmts(), domain_checks(&b, domain, n), fill(&b));
    let code = quote! {
        #s
        #checks
        #fill
        ::mbd::__private::closure::finite_value(t, #value).map_err(|e| self.diagnose(e))
    };
    (code, b.len())
}
