//! Stage 4: equations -> straight-line Rust. The only module that knows the runtime's paths.
//!
//! Each generated function evaluates one shared block: the scheduled DAG nodes its results
//! need, each once, as `let` temporaries (hash-consing made them common subexpressions),
//! then fills only the non-zero entries of its static-size results. Parts a model does not
//! have (constraints, outputs, events, Jacobians) are not generated at all.

use crate::model::{Equations, Role};
use crate::parse::{Direction, Mechanism};
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
        };
        let mut order = sym::schedule(&eq.g, roots);
        order.retain(|e| !known.contains_key(e));
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
}

/// Minimal coordinates of a closed loop: every `asin`/`acos` argument of the closed forms
/// checked to lie strictly inside `(-1, 1)` (`q` in scope), else `SingularPosition`.
fn closure_check(eq: &Equations, n: usize) -> Option<TokenStream> {
    let domain = eq.closure_domain.as_ref().filter(|d| !d.is_empty())?;
    let args: Vec<Expr> = domain.iter().map(|d| d.arg).collect();
    let b = Block::new(eq, &args);
    let s = b.stmts();
    let checks = domain.iter().map(|d| {
        let (arg, coord) = (b.leaf(d.arg), &d.coord);
        quote! {
            ::mbd::__private::closure::check_domain(t, #arg, #coord,
                &<Self as ::mbd::__private::Mechanism<#n>>::COORDINATES, q.as_slice())?;
        }
    });
    Some(quote!({ #s #(#checks)* }))
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
    let len = rolled.len;
    let ident = |e: Expr| {
        let s = eq.g.as_sym(e).expect("a placeholder is a symbol");
        format_ident!("{}", eq.g.sym_name(s))
    };
    let mut known: HashMap<Expr, TokenStream> = HashMap::new();
    let mut temporaries = 0;
    let mut code = Vec::new();
    // The other joints' accelerations, once the inward loop has handed on the run.
    let others: Vec<(usize, Expr)> = qdd
        .iter()
        .enumerate()
        .filter(|(i, e)| !(first..first + len).contains(i) && !eq.g.is_zero(**e))
        .map(|(i, &e)| (i, e))
        .collect();
    for (index, l) in rolled.loops.iter().enumerate() {
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
        let arrays = l.stored.iter().map(|st| {
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
        roots.extend(l.qdd);
        let body = Block::after(eq, &roots, &known, temporaries);
        temporaries += body.len();
        let coordinate = velocities.then(|| {
            let (q, qd) = (ident(rolled.q), ident(rolled.qd));
            quote! {
                let #q = q[#first + link];
                let #qd = qd[#first + link];
            }
        });
        let stmts = body.stmts();
        let stores = l.stored.iter().map(|st| {
            let (name, v) = (ident(st.0), body.leaf(st.1));
            quote!(#name[link] = #v;)
        });
        let acc = l.qdd.map(|e| {
            let v = body.leaf(e);
            quote!(qdd[#first + link] = #v;)
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
                #acc
                (#(#names,)*) = (#(#next,)*);
            }
        });
    }
    (quote!(#(#code)*), temporaries)
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
            /// The checks no solve would notice (stiffnesses, dampings, friction coefficients).
            #[inline]
            fn check_elements(&self) -> ::mbd::__private::Result<()> {
                let t = 0.0_f64;
                #code
                Ok(())
            }
        }
    });
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
            self.check_parameters().err().unwrap_or(err)
        }
    };
    (code, eager.map(|_| quote!(self.check_elements()?;)))
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

/// Counts what was generated, for the validation report.
struct Parts {
    names: Vec<&'static str>,
    statements: usize,
}

pub fn emit(ast: &Mechanism, eq: &Equations) -> TokenStream {
    let ident = &ast.ident;
    let n = eq.free.len();
    let m = eq.phi.len();
    let d = 2 * n;
    let a = n + m;
    let constrained = m > 0;
    let mut parts = Parts {
        names: vec!["mass_matrix", "forces", "energy"],
        statements: 0,
    };

    let coord_names: Vec<String> = eq.free.iter().map(|c| c.to_string()).collect();
    let check = closure_check(eq, n);
    match (&eq.closure_domain, constrained) {
        (Some(_), _) => parts.names.push("minimal_closed_form"),
        (None, true) => parts.names.push("augmented"),
        (None, false) => {}
    }
    // Friction directions: the sign of the sliding velocities (sliding view: given).
    let friction_coords: Vec<usize> = eq.frictions.iter().map(|f| f.coord).collect();
    let nf = friction_coords.len();
    // At rest (`+0.0` or `-0.0`) the direction is 0: the friction force there is a reaction,
    // found with the accelerations (`mbd_core::friction`), not a sign bit's guess.
    let direction = (nf > 0).then(|| {
        quote!(let direction: [f64; #nf] = [#(::mbd::__private::friction::direction(qd[#friction_coords])),*];)
    });
    let split = quote! {
        let q = y.fixed_rows::<#n>(0).into_owned();
        let qd = y.fixed_rows::<#n>(#n).into_owned();
    };

    // M and f from one block, so that they share subexpressions.
    let mf_roots: Vec<Expr> = eq
        .mass
        .iter()
        .flatten()
        .chain(&eq.forces)
        .copied()
        .collect();
    // (Only where the acceleration is a mass-matrix solve.)
    let mass_solve = eq.recursive_qdd.is_none() && eq.single_qdd.is_none() && !constrained;
    let (mf_stmts, mass_fill, force_fill) = if mass_solve {
        let mf = Block::new(eq, &mf_roots);
        parts.statements += mf.len();
        (
            mf.stmts(),
            mf.matrix("mass", n, n, &eq.mass),
            mf.vector("f", n, &eq.forces),
        )
    } else {
        Default::default()
    };
    let (mass_matrix, mass_len) = mass_matrix_body(eq, n);
    let force_only = Block::new(eq, &eq.forces);
    let energy = Block::new(eq, &[eq.energy]);
    let (fo_stmts, fo_fill) = (force_only.stmts(), force_only.vector("f", n, &eq.forces));
    let (en_stmts, en_value) = (energy.stmts(), energy.leaf(eq.energy));

    // The articulated-body recursion writes `qdd[i]` into a vector declared around it: a
    // fresh one in `acceleration`, the lower half of `y'` in `rhs` (no copies of the state).
    let recursion = if constrained {
        None
    } else if let (Some((rolled, first)), Some(qdd)) = (&eq.rolled, &eq.recursive_qdd) {
        parts.names.extend(["articulated_body", "rolled_chain"]);
        let (code, statements) = rolled_recursion(eq, rolled, *first, qdd);
        parts.statements += statements;
        Some(code)
    } else if let Some(qdd) = &eq.recursive_qdd {
        parts.names.push("articulated_body");
        let b = Block::new(eq, qdd);
        parts.statements += b.len();
        let (s, fill) = (b.stmts(), b.sets("qdd", qdd));
        Some(quote!(#s #fill))
    } else {
        None
    };
    let friction_acceleration = (nf > 0).then(|| crate::friction::acceleration(eq));
    let acceleration = if let Some(solve) = &friction_acceleration {
        quote!(#solve.map(|(qdd, _)| qdd).map_err(|e| self.diagnose(e)))
    } else if constrained {
        quote!(::mbd::__private::Constrained::<#n, #m>::acceleration_and_multipliers(self, t, q, qd).map(|(qdd, _)| qdd))
    } else if let Some(code) = &recursion {
        quote! {
            self.check_masses()?;
            let mut qdd = ::mbd::__private::Vector::<#n>::zeros();
            #code
            ::mbd::__private::solve::finite(t, qdd).map_err(|e| self.diagnose(e))
        }
    } else if let Some(qdd) = eq.single_qdd {
        let mass = eq.mass[0][0];
        let b = Block::new(eq, &[mass, qdd]);
        let (s, m, a) = (b.stmts(), b.leaf(mass), b.leaf(qdd));
        quote! {
            #s
            ::mbd::__private::solve::one_coordinate(t, #m, #a).map_err(|e| self.diagnose(e))
        }
    } else {
        quote! {
            #mf_stmts
            #mass_fill
            #force_fill
            ::mbd::__private::solve::solve_mass::<#n>(t, &mass, &f).map_err(|e| self.diagnose(e))
        }
    };

    let (check_parameters, check_elements) = parameter_checks(ast, eq, recursion.is_some());
    // A one-coordinate acceleration is a few operations: called out of line from another
    // crate (where integrators and `rhs` are instantiated), the call costs as much as the body.
    let inline_acceleration = eq.single_qdd.is_some().then(|| quote!(#[inline]));
    let forces_body = match nf {
        0 => quote!(#fo_stmts #fo_fill f),
        _ => crate::friction::forces(eq),
    };
    let mechanism_impl = quote! {
        impl ::mbd::__private::Mechanism<#n> for #ident {
            const COORDINATES: [&'static str; #n] = [#(#coord_names),*];
            fn mass_matrix(&self, t: f64, q: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Matrix<#n, #n> {
                #mass_matrix
            }
            fn forces(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Vector<#n> {
                #forces_body
            }
            #inline_acceleration
            fn acceleration(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>)
                -> ::mbd::__private::Result<::mbd::__private::Vector<#n>> {
                #check_elements
                #direction
                // The domain check after the body: its `sin` shares the body's basic block
                // with the `cos`, so the two become one `sincos` call.
                let qdd = { #acceleration };
                #check
                qdd
            }
            fn energy(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>) -> f64 {
                #en_stmts
                #en_value
            }
        }
    };

    // Constraints: only in a model that has them.
    let constrained_impl = constrained.then(|| {
        parts.names.extend(["phi", "phi_q", "phi_t", "gamma", "multipliers", "projection"]);
        let phi = Block::new(eq, &eq.phi);
        let phi_q_roots: Vec<Expr> = eq.phi_q.iter().flatten().copied().collect();
        let phi_q = Block::new(eq, &phi_q_roots);
        let phi_t = Block::new(eq, &eq.phi_t);
        let gamma = Block::new(eq, &eq.gamma);
        let all: Vec<Expr> = mf_roots.iter().chain(&phi_q_roots).chain(&eq.gamma).copied().collect();
        let full = Block::new(eq, &all);
        parts.statements += full.len() + phi.len();
        let (p_s, p_f) = (phi.stmts(), phi.vector("phi", m, &eq.phi));
        let (pq_s, pq_f) = (phi_q.stmts(), phi_q.matrix("phi_q", m, n, &eq.phi_q));
        let (pt_s, pt_f) = (phi_t.stmts(), phi_t.vector("phi_t", m, &eq.phi_t));
        let (g_s, g_f) = (gamma.stmts(), gamma.vector("gamma", m, &eq.gamma));
        let (f_s, f_m, f_f, f_pq, f_g) = (
            full.stmts(),
            full.matrix("mass", n, n, &eq.mass),
            full.vector("f", n, &eq.forces),
            full.matrix("phi_q", m, n, &eq.phi_q),
            full.vector("gamma", m, &eq.gamma),
        );
        let solve_full = match &friction_acceleration {
            Some(solve) => solve.clone(),
            None => quote! {
                #f_s #f_m #f_f #f_pq #f_g
                ::mbd::__private::solve::solve_augmented::<#n, #m, #a>(t, &mass, &f, &phi_q, &gamma).map_err(|e| self.diagnose(e))
            },
        };
        quote! {
            impl ::mbd::__private::Constrained<#n, #m> for #ident {
                fn phi(&self, t: f64, q: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Vector<#m> { #p_s #p_f phi }
                fn phi_q(&self, t: f64, q: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Matrix<#m, #n> { #pq_s #pq_f phi_q }
                fn phi_t(&self, t: f64, q: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Vector<#m> { #pt_s #pt_f phi_t }
                fn gamma(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Vector<#m> { #g_s #g_f gamma }
                fn acceleration_and_multipliers(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>)
                    -> ::mbd::__private::Result<(::mbd::__private::Vector<#n>, ::mbd::__private::Vector<#m>)> {
                    #solve_full
                }
            }
        }
    });

    // `qdd` and `lambda` for code that needs them (outputs, events, Jacobians).
    let solve_qdd_lambda = if constrained {
        quote!(let (qdd, lambda) = ::mbd::__private::Constrained::<#n, #m>::acceleration_and_multipliers(self, t, &q, &qd)?;)
    } else {
        quote! {
            let qdd = ::mbd::__private::Mechanism::<#n>::acceleration(self, t, &q, &qd)?;
            let lambda = ::mbd::__private::Vector::<0>::zeros();
        }
    };
    let m_or_0 = if constrained { m } else { 0 };

    let jacobian = eq.jacobian.as_ref().map(|jac| {
        parts.names.push("jacobian");
        let mut roots: Vec<Expr> = eq.mass.iter().flatten().copied().collect();
        roots.extend(eq.phi_q.iter().flatten());
        for mat in [&jac.r_q, &jac.r_qd, &jac.c_q, &jac.c_qd] {
            roots.extend(mat.iter().flatten());
        }
        let b = Block::new(eq, &roots);
        parts.statements += b.len();
        let (s, mass, pq, rq, rqd, cq, cqd) = (
            b.stmts(),
            b.matrix("mass", n, n, &eq.mass),
            b.matrix("phi_q", m_or_0, n, &eq.phi_q),
            b.matrix("r_q", n, n, &jac.r_q),
            b.matrix("r_qd", n, n, &jac.r_qd),
            b.matrix("c_q", m_or_0, n, &jac.c_q),
            b.matrix("c_qd", m_or_0, n, &jac.c_qd),
        );
        let a_or_n = n + m_or_0;
        quote! {
            const EXACT_JACOBIAN: bool = true;
            fn jacobian(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<::mbd::__private::Matrix<#d, #d>> {
                #split
                #solve_qdd_lambda
                #direction
                #s #mass #pq #rq #rqd #cq #cqd
                let (a_q, a_qd) = ::mbd::__private::solve::acceleration_jacobian::<#n, #m_or_0, #a_or_n>(
                    t, &mass, &phi_q, &r_q, &r_qd, &c_q, &c_qd)?;
                Ok(::mbd::__private::solve::second_order_jacobian::<#n, #d>(&a_q, &a_qd))
            }
        }
    });
    let project = constrained.then(|| {
        quote! {
            fn project(&self, t: f64, y: &mut ::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<()> {
                ::mbd::__private::analysis::projection::project_state::<Self, #n, #m, #d>(self, t, y)
            }
        }
    });
    let rhs_body = match &recursion {
        Some(code) => quote! {
            self.check_masses()?;
            #check_elements
            let q = y.fixed_rows::<#n>(0);
            let qd = y.fixed_rows::<#n>(#n);
            let mut dy = ::mbd::__private::Vector::<#d>::from_fn(|i, _| if i < #n { qd[i] } else { 0.0 });
            {
                let mut qdd = dy.fixed_rows_mut::<#n>(#n);
                #code
            }
            ::mbd::__private::solve::finite_accelerations::<#n, #d>(t, dy).map_err(|e| self.diagnose(e))
        },
        None => quote! {
            ::mbd::__private::solve::second_order_rhs::<#n, #d>(y, |q, qd| ::mbd::__private::Mechanism::<#n>::acceleration(self, t, q, qd))
        },
    };
    let ode_impl = quote! {
        impl ::mbd::__private::OdeSystem<#d> for #ident {
            #[inline]
            fn rhs(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<::mbd::__private::Vector<#d>> {
                #rhs_body
            }
            #jacobian
            #project
        }
    };

    // Outputs, events, initial state, typed state.
    let outputs_struct = format_ident!("{}Outputs", ident);
    let out_names: Vec<_> = eq.outputs.iter().map(|o| o.name.clone()).collect();
    let out_strs: Vec<String> = out_names.iter().map(|o| o.to_string()).collect();
    let k = out_names.len();
    let outputs = (!eq.outputs.is_empty()).then(|| {
        parts.names.push("outputs");
        let roots: Vec<Expr> = eq.outputs.iter().map(|o| o.expr).collect();
        let b = Block::new(eq, &roots);
        parts.statements += b.len();
        let needs_qdd = uses(eq, &roots, |r| matches!(r, Role::Qdd(_) | Role::Lambda(_)));
        let pre = needs_qdd.then(|| solve_qdd_lambda.clone());
        let s = b.stmts();
        let vals: Vec<TokenStream> = roots.iter().map(|e| b.leaf(*e)).collect();
        let doc = format!("The outputs of [`{ident}`], evaluated by [`{ident}::outputs`].");
        quote! {
            #[doc = #doc]
            #[derive(Debug, Clone, Copy, PartialEq)]
            pub struct #outputs_struct { #(pub #out_names: f64,)* }
            #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
            impl #ident {
                /// Names of the outputs, in declaration order.
                pub const OUTPUTS: [&'static str; #k] = [#(#out_strs),*];
                /// Evaluate the outputs at `(t, y)`, solving for accelerations and reactions when they need them.
                pub fn outputs(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<#outputs_struct> {
                    #split
                    #check
                    #pre
                    #s
                    Ok(#outputs_struct { #(#out_names: #vals,)* })
                }
                /// The outputs as an array, in the order of [`Self::OUTPUTS`].
                pub fn output_values(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<[f64; #k]> {
                    let o = self.outputs(t, y)?;
                    Ok([#(o.#out_names),*])
                }
            }
        }
    });
    let events = (!eq.events.is_empty()).then(|| {
        parts.names.push("events");
        let fns = eq.events.iter().map(|ev| {
            let b = Block::new(eq, &[ev.expr]);
            let needs_qdd = uses(eq, &[ev.expr], |r| matches!(r, Role::Qdd(_) | Role::Lambda(_)));
            let pre = needs_qdd.then(|| solve_qdd_lambda.clone());
            let (s, v) = (b.stmts(), b.leaf(ev.expr));
            let fname = format_ident!("event_{}", ev.name);
            let doc = format!("The event function `{}`: its zero crossings are the events.", ev.name);
            quote! {
                #[doc = #doc]
                pub fn #fname(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<f64> {
                    #split
                    #check
                    #pre
                    #s
                    Ok(#v)
                }
            }
        });
        let makes = eq.events.iter().map(|ev| {
            let fname = format_ident!("event_{}", ev.name);
            let name = ev.name.to_string();
            let dir = match ev.direction {
                Direction::Rising => quote!(Rising),
                Direction::Falling => quote!(Falling),
                Direction::Either => quote!(Either),
            };
            let terminal = ev.terminal.then(|| quote!(.terminal()));
            quote! {
                ::mbd::__private::integrate::Event::fallible(
                    #name,
                    // An event function that cannot be evaluated (singular position) stops
                    // the integration with its error.
                    move |t, y| self.#fname(t, y),
                    ::mbd::__private::integrate::Direction::#dir,
                ) #terminal
            }
        });
        quote! {
            #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
            impl #ident {
                #(#fns)*
                /// The model's events, for an integrator's `solve`.
                pub fn events(&self) -> ::std::vec::Vec<::mbd::__private::integrate::Event<'_, #d>> {
                    ::std::vec![#(#makes),*]
                }
            }
        }
    });

    // Coulomb friction: the stick test at rest, per friction.
    let frictions = eq.frictionless.as_ref().map(|frictionless| {
        parts.names.push("friction");
        let m1 = m + 1;
        let a1 = n + m1;
        let fns = eq.frictions.iter().map(|fr| {
            let mut roots: Vec<Expr> = eq.mass.iter().flatten().chain(frictionless).copied().collect();
            roots.extend(eq.phi_q.iter().flatten().chain(&eq.gamma));
            roots.extend([fr.normal, fr.mu_static]);
            let b = Block::new(eq, &roots);
            let (s, mass, f) = (b.stmts(), b.matrix("mass", n, n, &eq.mass), b.vector("f", n, frictionless));
            let mut rows = eq.phi_q.clone();
            let mut e_s = vec![eq.g_zero(); n];
            e_s[fr.coord] = eq.g_one();
            rows.push(e_s);
            let mut gamma = eq.gamma.clone();
            gamma.push(eq.g_zero());
            let (pq, gm) = (b.matrix("phi_q", m1, n, &rows), b.vector("gamma", m1, &gamma));
            let (normal, mu_static) = (b.leaf(fr.normal), b.leaf(fr.mu_static));
            let coord = &eq.free[fr.coord];
            let fname = format_ident!("{}_sticks", coord);
            let doc = format!(
                "At rest along `{coord}` (`der({coord}) = 0`): whether static friction can hold it, i.e. whether the \
                 force needed to keep `{coord}` still is at most `mu_static |N|`."
            );
            quote! {
                #[doc = #doc]
                pub fn #fname(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<bool> {
                    #split
                    #s #mass #f #pq #gm
                    let (_, lambda) = ::mbd::__private::solve::solve_augmented::<#n, #m1, #a1>(t, &mass, &f, &phi_q, &gamma)?;
                    Ok(lambda[#m].abs() <= #mu_static * (#normal).abs())
                }
            }
        });
        // The sliding view: friction directions fixed, so the right-hand side stays smooth
        // through the stop and the stop is found as an event (never `sign(0)` in a step).
        let sliding = format_ident!("{}Sliding", ident);
        let mut roots: Vec<Expr> = eq.mass.iter().flatten().chain(&eq.forces).copied().collect();
        roots.extend(eq.phi_q.iter().flatten().chain(&eq.gamma));
        let b = Block::new(eq, &roots);
        let (s, mass, f) = (b.stmts(), b.matrix("mass", n, n, &eq.mass), b.vector("f", n, &eq.forces));
        let solve = if constrained {
            let (pq, gm) = (b.matrix("phi_q", m, n, &eq.phi_q), b.vector("gamma", m, &eq.gamma));
            quote!(#pq #gm ::mbd::__private::solve::solve_augmented::<#n, #m, #a>(t, &mass, &f, &phi_q, &gamma).map(|(qdd, _)| qdd))
        } else {
            quote!(::mbd::__private::solve::solve_mass::<#n>(t, &mass, &f))
        };
        let project = constrained.then(|| {
            quote! {
                fn project(&self, t: f64, y: &mut ::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<()> {
                    ::mbd::__private::analysis::projection::project_state::<#ident, #n, #m, #d>(self.model, t, y)
                }
            }
        });
        let doc = format!(
            "[`{ident}`] sliding in fixed directions (`+1`/`-1` per friction, in declaration order): integrate this \
             view from a sliding state to a stop event, then test [`{ident}`]'s `*_sticks`."
        );
        let (modes, statements) = crate::friction::emit(ident, eq, frictionless);
        parts.statements += statements;
        quote! {
            #modes
            #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
            impl #ident {
                #(#fns)*
                /// The accelerations with the friction directions given instead of `sign(qd)`.
                pub fn acceleration_sliding(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>,
                    direction: &[f64; #nf]) -> ::mbd::__private::Result<::mbd::__private::Vector<#n>> {
                    #check_elements
                    #s #mass #f #solve
                }
                /// The sliding view of this model (see its type).
                pub fn sliding(&self, direction: [f64; #nf]) -> #sliding<'_> {
                    #sliding { model: self, direction }
                }
            }
            #[doc = #doc]
            #[derive(Debug, Clone, Copy)]
            pub struct #sliding<'a> {
                pub model: &'a #ident,
                pub direction: [f64; #nf],
            }
            #[automatically_derived]
            impl ::mbd::__private::OdeSystem<#d> for #sliding<'_> {
                fn rhs(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<::mbd::__private::Vector<#d>> {
                    ::mbd::__private::solve::second_order_rhs::<#n, #d>(y, |q, qd| self.model.acceleration_sliding(t, q, qd, &self.direction))
                }
                #project
            }
        }
    });

    let init_roots: Vec<Expr> = eq.init_q.iter().chain(&eq.init_qd).copied().collect();
    let init = Block::new(eq, &init_roots);
    let (init_s, init_v) = (init.stmts(), init.vector("y", d, &init_roots));
    let state_struct = format_ident!("{}State", ident);
    let q_ids: Vec<_> = eq.free.clone();
    let qd_ids: Vec<_> = eq.free.iter().map(|c| format_ident!("{}_dot", c)).collect();
    let q_idx: Vec<usize> = (0..n).collect();
    let qd_idx: Vec<usize> = (n..d).collect();
    parts.statements += mass_len + force_only.len() + energy.len();
    let part_names = &parts.names;
    let statements = parts.statements;
    let state_doc = format!(
        "The state of [`{ident}`] by coordinate name: positions, then velocities (`_dot`)."
    );

    quote! {
        #[doc = #state_doc]
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        pub struct #state_struct { #(pub #q_ids: f64,)* #(pub #qd_ids: f64,)* }
        impl ::core::convert::From<&::mbd::__private::Vector<#d>> for #state_struct {
            fn from(y: &::mbd::__private::Vector<#d>) -> Self {
                #state_struct { #(#q_ids: y[#q_idx],)* #(#qd_ids: y[#qd_idx],)* }
            }
        }
        impl ::core::convert::From<#state_struct> for ::mbd::__private::Vector<#d> {
            fn from(s: #state_struct) -> Self {
                let mut y = ::mbd::__private::Vector::<#d>::zeros();
                #(y[#q_idx] = s.#q_ids;)*
                #(y[#qd_idx] = s.#qd_ids;)*
                y
            }
        }
        #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
        impl #ident {
            /// Free coordinates.
            pub const DOF: usize = #n;
            /// What the derive generated for this model, and how many statements.
            pub const GENERATED: ::mbd::__private::Generated = ::mbd::__private::Generated {
                parts: &[#(#part_names),*],
                statements: #statements,
                constraints: #m,
            };
            #check_parameters
            /// The initial state `[q; qd]` given by `#[init(..)]` (zero where not given).
            pub fn initial_state(&self) -> ::mbd::__private::Vector<#d> {
                let t = 0.0_f64;
                #init_s
                #init_v
                y
            }
        }
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic, reason = "generated straight-line code")]
        const _: () = {
            #mechanism_impl
            #constrained_impl
            #ode_impl
        };
        #outputs
        #events
        #frictions
    }
}

/// The body of `mass_matrix`: the entries written out, or, for a long tree, one column at a
/// time from `M qdd` with `qdd` a column of the identity (O(n) code; O(n^2) work per call).
fn mass_matrix_body(eq: &Equations, n: usize) -> (TokenStream, usize) {
    match &eq.mass_times {
        Some(rows) => {
            let b = Block::new(eq, rows);
            let (s, fill) = (b.stmts(), b.vector("column", n, rows));
            let code = quote! {
                let mut mass = ::mbd::__private::Matrix::<#n, #n>::zeros();
                for j in 0..#n {
                    let mut qdd = ::mbd::__private::Vector::<#n>::zeros();
                    qdd[j] = 1.0;
                    #s
                    #fill
                    mass.set_column(j, &column);
                }
                mass
            };
            (code, b.len())
        }
        None => {
            let b = Block::new(eq, &eq.mass.iter().flatten().copied().collect::<Vec<_>>());
            let (s, fill) = (b.stmts(), b.matrix("mass", n, n, &eq.mass));
            (quote!(#s #fill mass), b.len())
        }
    }
}
