//! Minimal coordinates for closed loops: the closure solved in closed form at compile time.
//!
//! A model written with more coordinates than degrees of freedom and constraints between
//! them (`#[coords(theta, beta, x)]` with two loop equations) is, where the constraints can
//! be solved one after another in closed form, turned into an unconstrained model in the
//! remaining (independent) coordinates: each dependent coordinate becomes its closed form,
//! substituted into the kinematics exactly as if the user had written the closure by hand
//! in `at`. Three shapes are solved, each for one coordinate (or a pair) of one equation
//! (or two):
//!
//! - linear in `x` with a constant non-zero coefficient: `x = -(rest) / c`;
//! - an angle `x` only inside `sin(x)` and `cos(x)`, `P cos x + Q sin x + A = 0` with `P`,
//!   `Q`, `A` free of `x`: `asin` (only `sin`), `acos` (only `cos`) or
//!   `atan2(Q, P) ± acos(-A / hypot(P, Q))`;
//! - two angles `a`, `b` in two equations `A + P_a (cos a, sin a) + P_b (cos b, sin b) = 0`
//!   with `P_a`, `P_b` scaled rotations or reflections (a planar loop: the four-bar), the
//!   two-circle intersection: eliminating `a` leaves `w . (cos b, sin b) = K`, solved as
//!   above, then `a = atan2` of the rest.
//!
//! The independent coordinates are those the solve leaves: candidates are tried from the
//! last-listed coordinate back, so the first-listed stay independent, and the search
//! backtracks when a choice leaves an equation without a closed form. A branch (`asin` or
//! `π - asin`, the sign of `acos`, and a multiple of `2π`) is chosen so that the closed form
//! reproduces the default configuration: parameter `#[default]`s and `init` positions.
//! Without one (a parameter without default, a dependent coordinate without `init`) the
//! principal branch is taken (`asin`, `+acos`). At run time every `asin`/`acos` argument is
//! checked to lie strictly inside `(-1, 1)`: outside, the loop cannot assemble, and at `±1`
//! the two branches meet (a toggle or limit position), so the generated code returns
//! `Error::SingularPosition` rather than a NaN or a silent change of branch.

use crate::sym::{Expr, Func, Graph, Node, Sym};
use std::collections::HashMap;
use std::f64::consts::PI;

/// Most equations the closed-form search takes on (it backtracks, so it is bounded).
const MAX_EQUATIONS: usize = 8;
/// Most search nodes before the closure is declared to have no closed form.
const MAX_NODES: usize = 400;

/// A coordinate the closure may solve for.
pub struct Unknown {
    /// Index into the model's coordinates.
    pub index: usize,
    pub sym: Sym,
    pub name: String,
    /// Its value in the default configuration, when there is one.
    pub default: Option<f64>,
}

/// A run-time condition of the closed form: `-1 < arg < 1` (an `asin` or `acos` argument).
pub struct Domain {
    pub arg: Expr,
    /// The coordinate whose closed form needs it.
    pub coord: String,
}

/// A dependent coordinate's closed form: its value and, for an angle, its `sin` and `cos`
/// without trigonometric calls (`sin(asin(u)) = u`, `cos(asin(u)) = sqrt(1 - u^2)`, valid
/// where the domain is checked), which replace `sin(x)` and `cos(x)` in the kinematics.
#[derive(Clone, Copy)]
pub struct Form {
    pub value: Expr,
    pub trig: Option<[Expr; 2]>,
}

/// The closure in closed form.
pub struct Solution {
    /// `(coordinate index, closed form)` in the independent coordinates (and parameters,
    /// driven coordinates, `t`), in the order solved.
    pub solved: Vec<(usize, Form)>,
    pub domain: Vec<Domain>,
    /// The solve's steps in order: the constraint rows each used and the coordinates (model
    /// indices) it fixed; the pivots of the implicit-function rule ([`rates`]).
    pub pivots: Vec<(Vec<usize>, Vec<usize>)>,
}

/// One search state: equations left, coordinates not yet solved (indices into the
/// unknowns), closed forms so far (in terms of the unsolved ones).
#[derive(Clone)]
struct State {
    eqs: Vec<Expr>,
    /// The original constraint row of each of `eqs`.
    rows: Vec<usize>,
    /// `(rows, unknowns)` of each step so far.
    pivots: Vec<(Vec<usize>, Vec<usize>)>,
    open: Vec<usize>,
    solved: Vec<(usize, Form)>,
    domain: Vec<(Expr, usize)>,
}

/// One step: closed forms for one or two unknowns, the equations they use, new conditions.
struct Step {
    forms: Vec<(usize, Form)>,
    used: Vec<usize>,
    domain: Vec<(Expr, usize)>,
}

/// Solve `phi = 0` for as many of `unknowns` as there are equations, in closed form; `None`
/// when no sequence of the shapes above solves every equation. `env` gives default values
/// (parameters and coordinates) for the choice of branch.
pub fn solve(
    g: &mut Graph,
    phi: &[Expr],
    unknowns: &[Unknown],
    env: &HashMap<Sym, f64>,
) -> Option<Solution> {
    if phi.is_empty() || phi.len() > MAX_EQUATIONS || phi.len() >= unknowns.len() {
        return None;
    }
    let start = State {
        eqs: phi.to_vec(),
        rows: (0..phi.len()).collect(),
        pivots: Vec::new(),
        open: (0..unknowns.len()).collect(),
        solved: Vec::new(),
        domain: Vec::new(),
    };
    let mut budget = MAX_NODES;
    let done = search(g, start, unknowns, env, &mut budget)?;
    Some(Solution {
        solved: done
            .solved
            .into_iter()
            .map(|(u, h)| (unknowns[u].index, h))
            .collect(),
        domain: done
            .domain
            .into_iter()
            .map(|(arg, u)| Domain {
                arg,
                coord: unknowns[u].name.clone(),
            })
            .collect(),
        pivots: done
            .pivots
            .into_iter()
            .map(|(rows, us)| (rows, us.into_iter().map(|u| unknowns[u].index).collect()))
            .collect(),
    })
}

/// Depth-first over the steps, last-listed coordinates first.
fn search(
    g: &mut Graph,
    st: State,
    unknowns: &[Unknown],
    env: &HashMap<Sym, f64>,
    budget: &mut usize,
) -> Option<State> {
    if st.eqs.is_empty() {
        return Some(st);
    }
    if *budget == 0 {
        return None;
    }
    *budget -= 1;
    for step in steps(g, &st, unknowns, env) {
        let next = apply(g, &st, step, unknowns);
        if let Some(done) = search(g, next, unknowns, env, budget) {
            return Some(done);
        }
    }
    None
}

/// The possible next steps, in order of preference: single equations first, then pairs.
fn steps(g: &mut Graph, st: &State, unknowns: &[Unknown], env: &HashMap<Sym, f64>) -> Vec<Step> {
    let mut out = Vec::new();
    let order: Vec<usize> = st.open.iter().rev().copied().collect();
    for &u in &order {
        for (k, &e) in st.eqs.iter().enumerate() {
            if !g.depends_on(e, unknowns[u].sym) {
                continue;
            }
            if let Some((h, domain)) = single(g, e, &unknowns[u], env) {
                out.push(Step {
                    forms: vec![(u, h)],
                    used: vec![k],
                    domain: domain.into_iter().map(|d| (d, u)).collect(),
                });
            }
        }
    }
    for (i, &b) in order.iter().enumerate() {
        for &a in &order[i + 1..] {
            for k1 in 0..st.eqs.len() {
                for k2 in k1 + 1..st.eqs.len() {
                    let (e1, e2) = (st.eqs[k1], st.eqs[k2]);
                    if let Some((ha, hb, arg)) = pair(g, [e1, e2], &unknowns[a], &unknowns[b], env)
                    {
                        out.push(Step {
                            forms: vec![(a, ha), (b, hb)],
                            used: vec![k1, k2],
                            domain: vec![(arg, b)],
                        });
                    }
                }
            }
        }
    }
    out
}

/// The state after `step`: its closed forms substituted into everything left, one by one
/// (a pair's first form names the second coordinate).
fn apply(g: &mut Graph, st: &State, step: Step, unknowns: &[Unknown]) -> State {
    let mut next = st.clone();
    let kept = |k: &usize| !step.used.contains(k);
    next.eqs = (0..st.eqs.len()).filter(kept).map(|k| st.eqs[k]).collect();
    next.rows = (0..st.eqs.len()).filter(kept).map(|k| st.rows[k]).collect();
    next.pivots.push((
        step.used.iter().map(|&k| st.rows[k]).collect(),
        step.forms.iter().map(|f| f.0).collect(),
    ));
    next.domain.extend(step.domain);
    for (u, form) in step.forms {
        next.solved.push((u, form));
        next.open.retain(|&o| o != u);
        let mut memo = HashMap::new();
        let x = unknowns[u].sym;
        let mut elim = |g: &mut Graph, e: Expr| eliminate(g, e, x, form, &mut memo);
        for e in next.eqs.iter_mut() {
            *e = elim(g, *e);
        }
        for s in next.solved.iter_mut() {
            s.1.value = elim(g, s.1.value);
            if let Some([sn, cs]) = s.1.trig {
                s.1.trig = Some([elim(g, sn), elim(g, cs)]);
            }
        }
        for d in next.domain.iter_mut() {
            d.0 = elim(g, d.0);
        }
    }
    next
}

/// `e` with coordinate `x` replaced by its closed form: `sin(x)`, `cos(x)` by the form's
/// trigonometric values first, then `x` itself. `memo` is per coordinate and form.
pub fn eliminate(
    g: &mut Graph,
    e: Expr,
    x: Sym,
    form: Form,
    memo: &mut HashMap<Expr, Expr>,
) -> Expr {
    let e = match form.trig {
        Some([sn, cs]) => replace_trig(g, e, x, sn, cs, memo),
        None => e,
    };
    g.substitute(e, &[(x, form.value)].into())
}

/// `e = 0` solved for `x` alone: the closed form and its `asin`/`acos` arguments.
fn single(
    g: &mut Graph,
    e: Expr,
    x: &Unknown,
    env: &HashMap<Sym, f64>,
) -> Option<(Form, Vec<Expr>)> {
    let d = g.diff(e, x.sym);
    if let Some(c) = g.as_const(d) {
        if c == 0.0 || !c.is_finite() {
            return None;
        }
        let zero = g.zero();
        let rest = g.substitute(e, &[(x.sym, zero)].into());
        let c = g.constant(c);
        let h = g.div(rest, c);
        let value = g.neg(h);
        return Some((Form { value, trig: None }, Vec::new()));
    }
    let [s, c] = placeholders(g, x);
    let r = replace_trig(g, e, x.sym, s, c, &mut HashMap::new());
    if g.depends_on(r, x.sym) {
        return None;
    }
    let (cs, ss) = (sym(g, c), sym(g, s));
    let (p, q, a) = trig_linear(g, r, cs, ss)?;
    let minus_a = g.neg(a);
    let (u, cands) = angle_from(g, p, q, minus_a)?;
    Some((choose(g, &cands, x, env), vec![u]))
}

/// `(P, Q, A)` with `r = P c + Q s + A` on the circle `c^2 + s^2 = 1`, `P`, `Q`, `A` free of
/// `c` and `s`: `r` linear in them, or quadratic with `k (c^2 + s^2)` as its only quadratic
/// part (a distance closure `|A - C|^2 = b^2` written out, the spatial four-bar's), which
/// is the constant `k` there.
fn trig_linear(g: &mut Graph, r: Expr, cs: Sym, ss: Sym) -> Option<(Expr, Expr, Expr)> {
    let free = |g: &Graph, k: Expr| !g.depends_on(k, cs) && !g.depends_on(k, ss);
    let (p, q) = (g.diff(r, cs), g.diff(r, ss));
    let zero = g.zero();
    let at_zero: HashMap<Sym, Expr> = [(cs, zero), (ss, zero)].into();
    let a = g.substitute(r, &at_zero);
    if free(g, p) && free(g, q) {
        return Some((p, q, a));
    }
    let (pcc, qss, pcs) = (g.diff(p, cs), g.diff(q, ss), g.diff(p, ss));
    let same = g.sub(pcc, qss);
    if !(free(g, pcc) && free(g, qss) && g.is_zero(pcs) && g.is_zero(same)) {
        return None;
    }
    let (p0, q0) = (g.substitute(p, &at_zero), g.substitute(q, &at_zero));
    let half = g.constant(0.5);
    let k = g.mul(half, pcc);
    let a = g.add(a, k);
    Some((p0, q0, a))
}

/// `sqrt(1 - u^2)`, built as the derivative of `asin` builds it (so the two share it).
pub(crate) fn cofactor(g: &mut Graph, u: Expr) -> Expr {
    let one = g.one();
    let u2 = g.powi(u, 2);
    let r = g.sub(one, u2);
    g.call(Func::Sqrt, r)
}

/// `P cos x + Q sin x = K`: the `asin`/`acos` argument and the two branches, each with
/// its `sin` and `cos` written without trigonometric calls.
fn angle_from(g: &mut Graph, p: Expr, q: Expr, k: Expr) -> Option<(Expr, [Form; 2])> {
    let pi = g.constant(PI);
    let form = |value, sn, cs| Form {
        value,
        trig: Some([sn, cs]),
    };
    match (g.is_zero(p), g.is_zero(q)) {
        (true, true) => None,
        (true, false) => {
            let u = g.div(k, q);
            let s = g.call(Func::Asin, u);
            let w = cofactor(g, u);
            let (other, minus_w) = (g.sub(pi, s), g.neg(w));
            Some((u, [form(s, u, w), form(other, u, minus_w)]))
        }
        (false, true) => {
            let u = g.div(k, p);
            let c = g.call(Func::Acos, u);
            let w = cofactor(g, u);
            let (other, minus_w) = (g.neg(c), g.neg(w));
            Some((u, [form(c, w, u), form(other, minus_w, u)]))
        }
        (false, false) => {
            // x = base ± acos(u), cos(base) = P / n, sin(base) = Q / n.
            let (p2, q2) = (g.mul(p, p), g.mul(q, q));
            let n2 = g.add(p2, q2);
            let n = g.call(Func::Sqrt, n2);
            let u = g.div(k, n);
            let base = g.atan2(q, p);
            let c = g.call(Func::Acos, u);
            let w = cofactor(g, u);
            let (pu, qu, pw, qw) = (g.mul(p, u), g.mul(q, u), g.mul(p, w), g.mul(q, w));
            let mut branch = |sign: bool| {
                let value = if sign { g.add(base, c) } else { g.sub(base, c) };
                let (cn, sn) = if sign {
                    (g.sub(pu, qw), g.add(qu, pw))
                } else {
                    (g.add(pu, qw), g.sub(qu, pw))
                };
                let (cs, sn) = (g.div(cn, n), g.div(sn, n));
                form(value, sn, cs)
            };
            Some((u, [branch(true), branch(false)]))
        }
    }
}

/// Two angles from two equations (the two-circle intersection): `(h_a in b, h_b, the acos
/// argument)`.
fn pair(
    g: &mut Graph,
    eqs: [Expr; 2],
    a: &Unknown,
    b: &Unknown,
    env: &HashMap<Sym, f64>,
) -> Option<(Form, Form, Expr)> {
    let [sa, ca] = placeholders(g, a);
    let [sb, cb] = placeholders(g, b);
    let places = [ca, sa, cb, sb].map(|p| sym(g, p));
    let mut coef = [[g.zero(); 4]; 2];
    let mut rest = [g.zero(); 2];
    for (k, &e) in eqs.iter().enumerate() {
        let r = replace_trig(g, e, a.sym, sa, ca, &mut HashMap::new());
        let r = replace_trig(g, r, b.sym, sb, cb, &mut HashMap::new());
        if g.depends_on(r, a.sym) || g.depends_on(r, b.sym) {
            return None;
        }
        for (j, &p) in places.iter().enumerate() {
            coef[k][j] = g.diff(r, p);
            if places.iter().any(|&p| g.depends_on(coef[k][j], p)) {
                return None;
            }
        }
        let zero = g.zero();
        let map: HashMap<Sym, Expr> = places.iter().map(|&p| (p, zero)).collect();
        rest[k] = g.substitute(r, &map);
    }
    let col = |j: usize| [coef[0][j], coef[1][j]];
    let (a0, a1, b0, b1) = (col(0), col(1), col(2), col(3));
    let ka2 = scaled_orthogonal(g, a0, a1)?;
    let kb2 = scaled_orthogonal(g, b0, b1)?;
    // |P_a u_a|^2 = ka^2 = |A + P_b u_b|^2, so (P_b^T A) . u_b = (ka^2 - kb^2 - A . A) / 2.
    let w = [g.dot(&b0, &rest), g.dot(&b1, &rest)];
    let aa = g.dot(&rest, &rest);
    let diff = g.sub(ka2, kb2);
    let num = g.sub(diff, aa);
    let half = g.constant(0.5);
    let k = g.mul(half, num);
    let (arg, cands) = angle_from(g, w[0], w[1], k)?;
    let hb = choose(g, &cands, b, env);
    // u_a = -P_a^T (A + P_b u_b) / ka^2; atan2 needs no positive scale.
    let (cos_b, sin_b) = (
        g.call(Func::Cos, b.sym_expr(g)),
        g.call(Func::Sin, b.sym_expr(g)),
    );
    let v: Vec<Expr> = (0..2)
        .map(|i| {
            let pc = g.mul(b0[i], cos_b);
            let ps = g.mul(b1[i], sin_b);
            let sum = g.add(pc, ps);
            g.add(rest[i], sum)
        })
        .collect();
    let (x, y) = (g.dot(&a0, &v), g.dot(&a1, &v));
    let (nx, ny) = (g.neg(x), g.neg(y));
    let base = g.atan2(ny, nx);
    let (x2, y2) = (g.mul(nx, nx), g.mul(ny, ny));
    let n2 = g.add(x2, y2);
    let n = g.call(Func::Sqrt, n2);
    let (cs, sn) = (g.div(nx, n), g.div(ny, n));
    let fa = Form {
        value: base,
        trig: Some([sn, cs]),
    };
    let ha = choose(g, &[fa, fa], a, env);
    Some((ha, hb, arg))
}

/// `|c0|^2` when `[c0 c1]` is a scaled rotation or reflection (`c0 . c1 = 0`,
/// `|c0| = |c1|`, not zero), as the simplifier can tell.
fn scaled_orthogonal(g: &mut Graph, c0: [Expr; 2], c1: [Expr; 2]) -> Option<Expr> {
    let cross = g.dot(&c0, &c1);
    let n0 = g.dot(&c0, &c0);
    let n1 = g.dot(&c1, &c1);
    let d = g.sub(n0, n1);
    (g.is_zero(cross) && g.is_zero(d) && !g.is_zero(n0)).then_some(n0)
}

/// The branch (and multiple of `2π`) that reproduces the default value of `x`; the first
/// candidate when there is no default configuration.
fn choose(g: &mut Graph, cands: &[Form], x: &Unknown, env: &HashMap<Sym, f64>) -> Form {
    let Some(x0) = x.default else {
        return cands[0];
    };
    let mut best: Option<(f64, usize, f64)> = None;
    for (i, c) in cands.iter().enumerate() {
        let v = g.eval(c.value, &|s| env.get(&s).copied().unwrap_or(f64::NAN));
        if !v.is_finite() {
            continue;
        }
        let turns = ((x0 - v) / (2.0 * PI)).round();
        let miss = (x0 - v - 2.0 * PI * turns).abs();
        if best.is_none_or(|(m, _, _)| miss < m) {
            best = Some((miss, i, turns));
        }
    }
    match best {
        Some((_, i, turns)) if turns != 0.0 => {
            let shift = g.constant(2.0 * PI * turns);
            Form {
                value: g.add(cands[i].value, shift),
                trig: cands[i].trig,
            }
        }
        Some((_, i, _)) => cands[i],
        None => cands[0],
    }
}

/// Placeholder symbols for `sin(x)` and `cos(x)`.
fn placeholders(g: &mut Graph, x: &Unknown) -> [Expr; 2] {
    [
        g.symbol(&format!("closure:sin:{}", x.name)),
        g.symbol(&format!("closure:cos:{}", x.name)),
    ]
}

fn sym(g: &Graph, e: Expr) -> Sym {
    g.as_sym(e).expect("a placeholder symbol")
}

impl Unknown {
    fn sym_expr(&self, g: &Graph) -> Expr {
        g.sym(self.sym)
    }
}

/// `e` with `sin(x)` replaced by `s` and `cos(x)` by `c` (memoised over the DAG).
fn replace_trig(
    g: &mut Graph,
    e: Expr,
    x: Sym,
    s: Expr,
    c: Expr,
    memo: &mut HashMap<Expr, Expr>,
) -> Expr {
    if !g.depends_on(e, x) {
        return e;
    }
    if let Some(&r) = memo.get(&e) {
        return r;
    }
    let node = g.node(e);
    let r = match node {
        Node::Call(Func::Sin, a) if g.as_sym(a) == Some(x) => s,
        Node::Call(Func::Cos, a) if g.as_sym(a) == Some(x) => c,
        Node::Sym(_) | Node::Const(_) => e,
        _ => {
            let kids: Vec<Expr> = node.children().collect();
            let mapped: Vec<Expr> = kids
                .iter()
                .map(|&k| replace_trig(g, k, x, s, c, memo))
                .collect();
            let mut it = mapped.into_iter();
            let rebuilt = node.with_children(|_| it.next().expect("one image per child"));
            g.build(rebuilt)
        }
    };
    memo.insert(e, r);
    r
}

/// How a constraint depends on earlier ones with constant coefficients.
pub enum Dependence {
    /// A combination of them, constants included: it adds nothing.
    Redundant,
    /// Its coordinate part is a combination of theirs, its constant part differs by this.
    Contradictory(f64),
    /// Its coordinate part is a combination of theirs; the constant parts (parameters,
    /// `t`) agree only for some values.
    Dependent,
    /// Its coordinate terms cancel (`x == x + 1.0`): it holds always or never.
    NoCoordinate,
}

/// Constraints affine in the coordinates with constant coefficients (`x == y`,
/// `2.0 * x == 2.0 * y`, `x == 1.0`) whose coordinate parts are linearly dependent on earlier
/// such constraints: their Jacobian rows are dependent everywhere, so each is a compile
/// error (the index of the constraint and how it depends).
pub fn constant_dependence(g: &mut Graph, phi: &[Expr], q: &[Sym]) -> Vec<(usize, Dependence)> {
    // Reduced rows (coefficients, constant part) kept in echelon form with their pivots.
    let mut basis: Vec<(Vec<f64>, Expr, usize)> = Vec::new();
    let mut out = Vec::new();
    for (k, &p) in phi.iter().enumerate() {
        let coefs: Option<Vec<f64>> = q
            .iter()
            .map(|&s| {
                let d = g.diff(p, s);
                g.as_const(d)
            })
            .collect();
        let Some(mut row) = coefs else { continue };
        let zero = g.zero();
        let map: HashMap<Sym, Expr> = q.iter().map(|&s| (s, zero)).collect();
        let mut rest = g.substitute(p, &map);
        let scale = row.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
        if scale == 0.0 {
            // Structurally free of coordinates: reported by the caller's own check.
            if q.iter().any(|&s| g.depends_on(p, s)) {
                out.push((k, Dependence::NoCoordinate));
            }
            continue;
        }
        for (b, b_rest, pivot) in &basis {
            let f = row[*pivot] / b[*pivot];
            if f != 0.0 {
                for (r, c) in row.iter_mut().zip(b) {
                    *r -= f * c;
                }
                let fc = g.constant(f);
                let scaled = g.mul(fc, *b_rest);
                rest = g.sub(rest, scaled);
            }
        }
        let left = row.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
        if left > 1e-12 * scale {
            let pivot = (0..row.len())
                .max_by(|&i, &j| row[i].abs().total_cmp(&row[j].abs()))
                .expect("a coordinate");
            basis.push((row, rest, pivot));
            continue;
        }
        let dependence = match g.as_const(rest) {
            Some(v) if v.abs() <= 1e-12 * (1.0 + scale) => Dependence::Redundant,
            Some(v) => Dependence::Contradictory(v),
            None if g.is_zero(rest) => Dependence::Redundant,
            None => Dependence::Dependent,
        };
        out.push((k, dependence));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unknown(g: &mut Graph, index: usize, name: &str, default: Option<f64>) -> (Unknown, Expr) {
        let e = g.symbol(name);
        let u = Unknown {
            index,
            sym: g.as_sym(e).unwrap(),
            name: name.into(),
            default,
        };
        (u, e)
    }

    /// The slider-crank: `x` is linear, `beta` only in a `sin`; `theta` stays independent.
    #[test]
    fn slider_crank_closes_in_x_and_beta() {
        let mut g = Graph::new();
        let (t, te) = unknown(&mut g, 0, "theta", None);
        let (b, be) = unknown(&mut g, 1, "beta", None);
        let (x, xe) = unknown(&mut g, 2, "x", None);
        let (r, l) = (g.constant(0.3), g.constant(1.0));
        let (cb, ct) = (g.call(Func::Cos, be), g.call(Func::Cos, te));
        let (sb, st) = (g.call(Func::Sin, be), g.call(Func::Sin, te));
        let (lcb, rct) = (g.mul(l, cb), g.mul(r, ct));
        let rhs = g.add(lcb, rct);
        let e1 = g.sub(xe, rhs);
        let (lsb, rst) = (g.mul(l, sb), g.mul(r, st));
        let e2 = g.sub(lsb, rst);
        let sol = solve(&mut g, &[e1, e2], &[t, b, x], &HashMap::new()).expect("closed form");
        assert_eq!(sol.domain.len(), 1);
        let th = 0.7;
        let env = |s: Sym| {
            if g.sym_name(s) == "theta" {
                th
            } else {
                f64::NAN
            }
        };
        let value = |i: usize| {
            let h = sol.solved.iter().find(|(k, _)| *k == i).unwrap().1;
            g.eval(h.value, &env)
        };
        let beta = (0.3 * th.sin()).asin();
        assert!((value(1) - beta).abs() < 1e-15);
        assert!((value(2) - (beta.cos() + 0.3 * th.cos())).abs() < 1e-15);
    }

    /// A four-bar `d + a e(phi) + b e(psi) = c e(chi)` closes in `psi` and `chi` on the
    /// branch of the default configuration, both elbow signs.
    #[test]
    fn four_bar_closes_on_the_default_branch() {
        let (a_, b_, c_, d_) = (1.0, 2.0, 2.5, 3.0);
        for elbow in [1.0, -1.0] {
            let phi0: f64 = 0.8;
            let mut g = Graph::new();
            let reference = four_bar_reference(a_, b_, c_, d_, phi0, elbow);
            let (u0, pe) = unknown(&mut g, 0, "phi", Some(phi0));
            let (u1, se) = unknown(&mut g, 1, "psi", Some(reference.0));
            let (u2, ce) = unknown(&mut g, 2, "chi", Some(reference.1));
            let mut env = HashMap::new();
            env.insert(u0.sym, phi0);
            env.insert(u1.sym, reference.0);
            env.insert(u2.sym, reference.1);
            let k = |g: &mut Graph, v: f64| g.constant(v);
            let mut eqs = Vec::new();
            for f in [Func::Cos, Func::Sin] {
                let (fp, fs, fc) = (g.call(f, pe), g.call(f, se), g.call(f, ce));
                let (ka, kb, kc) = (k(&mut g, a_), k(&mut g, b_), k(&mut g, c_));
                let terms = [g.mul(ka, fp), g.mul(kb, fs)];
                let lhs = g.sum(terms);
                let cc = g.mul(kc, fc);
                let mut rhs = cc;
                if f == Func::Cos {
                    let kd = k(&mut g, d_);
                    rhs = g.add(kd, cc);
                }
                eqs.push(g.sub(lhs, rhs));
            }
            let sol = solve(&mut g, &eqs, &[u0, u1, u2], &env).expect("closed form");
            let at = |s: Sym| {
                if g.sym_name(s) == "phi" {
                    phi0
                } else {
                    f64::NAN
                }
            };
            for (i, want) in [(1, reference.0), (2, reference.1)] {
                let h = sol.solved.iter().find(|(k, _)| *k == i).unwrap().1;
                let got = g.eval(h.value, &at);
                let [sn, cs] = h.trig.expect("an angle");
                assert!((g.eval(sn, &at) - want.sin()).abs() < 1e-12);
                assert!((g.eval(cs, &at) - want.cos()).abs() < 1e-12);
                assert!((got - want).abs() < 1e-12, "elbow {elbow}: {got} vs {want}");
            }
        }
    }

    /// `(psi, chi)` of the four-bar by Newton's method from a start on the elbow's side.
    fn four_bar_reference(a: f64, b: f64, c: f64, d: f64, phi: f64, elbow: f64) -> (f64, f64) {
        let (mut psi, mut chi) = (0.3 * elbow, 1.5 * elbow);
        for _ in 0..100 {
            let f1 = a * phi.cos() + b * psi.cos() - d - c * chi.cos();
            let f2 = a * phi.sin() + b * psi.sin() - c * chi.sin();
            let (j11, j12) = (-b * psi.sin(), c * chi.sin());
            let (j21, j22) = (b * psi.cos(), -c * chi.cos());
            let det = j11 * j22 - j12 * j21;
            psi -= (f1 * j22 - j12 * f2) / det;
            chi -= (j11 * f2 - j21 * f1) / det;
        }
        (psi, chi)
    }
}
