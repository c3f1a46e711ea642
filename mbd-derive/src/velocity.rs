//! Minimal coordinates by the velocity transformation, as an expert writes them.
//!
//! The closure's closed form (closure.rs) gives each dependent coordinate's *value*; its
//! rate and acceleration come from the implicit-function rule instead of differentiating
//! the closed form through `asin`/`sqrt`: with the constraint Jacobian split into the
//! dependent columns `Phi_d` and the others `Phi_o`,
//!
//! `zd_d = -Phi_d^-1 (Phi_o zd_o + Phi_t)`, `zdd_d = -Phi_d^-1 (Phi_o zdd_o + (dPhi/dt)' |zdd_d=0)`,
//!
//! solved symbolically by block elimination in the order the closed form was found (one
//! coordinate or an angle pair per step, so `Phi_d` is block triangular after elimination
//! and every pivot is the step's own `1x1` or `2x2` block). The dependent coordinates stay
//! symbols through the whole derivation, which runs in all coordinates as for the augmented
//! form (short kinematics, short `M` and `f`), and the equations are then projected on the
//! independent coordinates by `zd = R qd`: `R^T M R qdd = R^T (f - M a0)`, `a0` the
//! dependents' accelerations at `qdd = 0` (`R^T Phi_z^T = 0`, so no multipliers remain).
//! Last, each dependent coordinate's `sin`/`cos` and value are replaced by its closed form
//! (computed once and shared), as the expert computes `beta` once.

use crate::closure::{Domain, Form, eliminate};
use crate::sym::{Expr, Graph, Node, Sym};
use std::collections::HashMap;

/// A model in minimal coordinates: what the generated code checks and how each dependent
/// coordinate's symbol is replaced at the end.
pub struct Minimal {
    /// The `asin`/`acos` arguments checked at run time.
    pub domain: Vec<Domain>,
    /// Each dependent coordinate's position symbol and closed form.
    pub forms: Vec<(Sym, Form)>,
}

impl Minimal {
    /// The closed forms and domain arguments with `map` applied: a closed form may name
    /// relaxed and driven coordinates, which the reduction replaces.
    pub fn reduced(&self, g: &mut Graph, map: &HashMap<Sym, Expr>) -> Minimal {
        let domain = (self.domain.iter())
            .map(|d| Domain {
                arg: g.substitute(d.arg, map),
                coord: d.coord.clone(),
            })
            .collect();
        let forms = (self.forms.iter())
            .map(|&(x, form)| {
                let value = g.substitute(form.value, map);
                let trig = form.trig.map(|t| t.map(|e| g.substitute(e, map)));
                (x, Form { value, trig })
            })
            .collect();
        Minimal { domain, forms }
    }

    /// `rows` with every dependent coordinate replaced by its closed form, then [`tidy`].
    pub fn close(&self, g: &mut Graph, rows: &[Expr]) -> Vec<Expr> {
        let mut out = rows.to_vec();
        for &(x, form) in &self.forms {
            let mut memo = HashMap::new();
            for e in out.iter_mut() {
                *e = eliminate(g, *e, x, form, &mut memo);
            }
        }
        let nonzero = self.nonzero(g);
        tidy(g, &out, &nonzero)
    }

    /// What is non-zero wherever the domain check passes (`-1 < u < 1`, `u` finite): each
    /// `asin`/`acos` argument's denominator (else `u` is infinite or NaN) and `sqrt(1 - u^2)`.
    fn nonzero(&self, g: &mut Graph) -> Vec<Expr> {
        let mut out = Vec::new();
        for d in &self.domain {
            if let Node::Div(_, den) = g.node(d.arg) {
                out.push(den);
            }
            out.push(crate::closure::cofactor(g, d.arg));
        }
        out
    }
}

/// `roots` rebuilt bottom-up with rewrites the constructors do not make, for the shapes the
/// closed forms leave (their terms meet only after the substitution):
/// - a monomial of symbols in one order (`r (r m)` and `m (r r)` become one node: the
///   inertia written `m r r / 12` and the kinematics' `m r^2` share it);
/// - a sum of two terms with one power-of-two coefficient `k` up to sign as
///   `k (x ± y)`, exact in binary (`0.5 a - 0.5 b`, `2 a + 2 b`): the constants then float
///   outwards and cancel (`0.5 (qd^2 (2 x))`); with other coefficients and a shared
///   operand, `a x p + b x r = (a p + b r) x` (a few ulps);
/// - `d (n / d) = n` and `(x (1 / d)) (d y) = x y` for `d` in `nonzero` (non-zero wherever the
///   closed form is valid, checked at run time): `l sin(beta)` is `r sin(theta)` again.
pub fn tidy(g: &mut Graph, roots: &[Expr], nonzero: &[Expr]) -> Vec<Expr> {
    let mut map: HashMap<Expr, Expr> = HashMap::new();
    for e in crate::sym::schedule(g, roots) {
        let node = g
            .node(e)
            .with_children(|c| map.get(&c).copied().unwrap_or(c));
        let rebuilt = match node {
            Node::Mul(a, b) => cancelled(g, a, b, nonzero).or_else(|| monomial(g, node)),
            Node::Add(a, b) => common_power_of_two(g, a, b).or_else(|| common_operand(g, a, b)),
            _ => None,
        };
        let new = rebuilt.unwrap_or_else(|| g.build(node));
        map.insert(e, new);
    }
    roots
        .iter()
        .map(|r| map.get(r).copied().unwrap_or(*r))
        .collect()
}

/// A product of symbols, their positive powers and constants (`node`'s operands rebuilt
/// already), in the order of the symbols' ids; `None` for any other product.
fn monomial(g: &mut Graph, node: Node) -> Option<Expr> {
    let (mut k, mut factors) = (1.0, Vec::<(Expr, i32)>::new());
    let mut stack: Vec<Expr> = node.children().collect();
    while let Some(x) = stack.pop() {
        match g.node(x) {
            Node::Mul(a, b) => stack.extend([a, b]),
            Node::Const(c) => k *= c.value(),
            Node::Sym(_) => factors.push((x, 1)),
            Node::Powi(b, n) if n > 0 && g.as_sym(b).is_some() => factors.push((b, n)),
            _ => return None,
        }
    }
    factors.sort_unstable();
    let mut merged: Vec<(Expr, i32)> = Vec::new();
    for (b, n) in factors {
        match merged.last_mut() {
            Some((last, m)) if *last == b => *m += n,
            _ => merged.push((b, n)),
        }
    }
    let mut p = g.constant(k);
    for (b, n) in merged {
        let f = g.powi(b, n);
        p = g.mul(p, f);
    }
    Some(p)
}

/// `k (x ± y)` for `a = k x`, `b = ±k y` with `|k|` a power of two other than 1 (then
/// `k x ± k y` and `k (x ± y)` round alike); `None` otherwise.
fn common_power_of_two(g: &mut Graph, a: Expr, b: Expr) -> Option<Expr> {
    let split = |g: &Graph, e: Expr| match g.node(e) {
        Node::Mul(c, r) => g.as_const(c).map(|k| (k, r)),
        _ => None,
    };
    let ((ka, x), (kb, y)) = (split(g, a)?, split(g, b)?);
    let power_of_two = |k: f64| k.is_normal() && k.to_bits() & ((1 << 52) - 1) == 0;
    if ka.abs() != kb.abs() || ka.abs() == 1.0 || !power_of_two(ka) {
        return None;
    }
    let sum = if ka == kb { g.add(x, y) } else { g.sub(x, y) };
    let k = g.constant(ka);
    Some(g.mul(k, sum))
}

/// The dependent coordinates' rates, each in the other coordinates' rates and the
/// coordinates themselves (dependent ones as symbols).
pub struct Rates {
    /// `zd_d`, linear in the other coordinates' `zd`.
    pub velocity: Vec<Expr>,
    /// `zdd_d`, linear in the other coordinates' `zdd`, with `zd_d` replaced by `velocity`.
    pub acceleration: Vec<Expr>,
}

/// A model's coordinate symbols (all of them, in model order).
pub struct Symbols<'a> {
    pub z: &'a [Expr],
    pub zd: &'a [Expr],
    pub zdd: &'a [Expr],
}

/// The rates of the coordinates `dep` (model indices) fixed by `phi = 0` through the steps
/// `pivots` (`(rows, coordinates)` in the order solved). `tder` is the total time derivative.
pub fn rates(
    g: &mut Graph,
    phi: &[Expr],
    dep: &[usize],
    pivots: &[(Vec<usize>, Vec<usize>)],
    s: &Symbols<'_>,
    tder: &dyn Fn(&mut Graph, Expr) -> Expr,
) -> Rates {
    let sym = |g: &Graph, e: Expr| g.as_sym(e).expect("coordinate symbol");
    let jac: Vec<Vec<Expr>> = phi
        .iter()
        .map(|&p| dep.iter().map(|&i| g.diff(p, sym(g, s.z[i]))).collect())
        .collect();
    let zero = g.zero();
    let drop = |g: &mut Graph, e: Expr, of: &[Expr]| {
        let map: HashMap<Sym, Expr> = dep.iter().map(|&i| (sym(g, of[i]), zero)).collect();
        let rest = g.substitute(e, &map);
        g.neg(rest)
    };
    let mut rhs = Vec::with_capacity(phi.len());
    for &p in phi {
        let v = tder(g, p);
        let a = tder(g, v);
        rhs.push(vec![drop(g, v, s.zd), drop(g, a, s.zdd)]);
    }
    let at = |i: usize| {
        dep.iter()
            .position(|&d| d == i)
            .expect("a dependent coordinate")
    };
    let steps: Vec<(Vec<usize>, Vec<usize>)> = pivots
        .iter()
        .map(|(rows, cs)| (rows.clone(), cs.iter().map(|&c| at(c)).collect()))
        .collect();
    let x = block_solve(g, jac, rhs, &steps);
    // zd_d = R zd_o + v0: the coefficients R (the projection's too) shared, not re-formed.
    let others: Vec<Sym> = (0..s.zd.len())
        .filter(|i| !dep.contains(i))
        .map(|i| sym(g, s.zd[i]))
        .collect();
    let velocity: Vec<Expr> = x.iter().map(|r| linear_in(g, r[0], &others)).collect();
    let map: HashMap<Sym, Expr> = dep
        .iter()
        .zip(&velocity)
        .map(|(&i, &v)| (sym(g, s.zd[i]), v))
        .collect();
    let acceleration = x.iter().map(|r| g.substitute(r[1], &map)).collect();
    Rates {
        velocity,
        acceleration,
    }
}

/// `e`, linear in the symbols `by`, rebuilt as `sum_j (de/d by_j) by_j + e|by=0`.
fn linear_in(g: &mut Graph, e: Expr, by: &[Sym]) -> Expr {
    let zero = g.zero();
    let map: HashMap<Sym, Expr> = by.iter().map(|&v| (v, zero)).collect();
    let mut out = g.substitute(e, &map);
    for &v in by {
        let c = g.diff(e, v);
        if !g.is_zero(c) {
            let term = g.mul(c, g.sym(v));
            out = g.add(out, term);
        }
    }
    out
}

/// `a x = b` for square `a` by block elimination with the given pivots (`(rows, columns)`,
/// `1x1` or `2x2`, each non-singular once the earlier ones are eliminated); `x` by column.
fn block_solve(
    g: &mut Graph,
    mut a: Vec<Vec<Expr>>,
    mut b: Vec<Vec<Expr>>,
    pivots: &[(Vec<usize>, Vec<usize>)],
) -> Vec<Vec<Expr>> {
    let m = a.len();
    let k = b.first().map_or(0, Vec::len);
    let mut done = vec![false; m];
    let mut inverses = Vec::with_capacity(pivots.len());
    for (rows, cols) in pivots {
        let block: Vec<Vec<Expr>> = rows
            .iter()
            .map(|&r| cols.iter().map(|&c| a[r][c]).collect())
            .collect();
        let inv = inverse(g, &block);
        for &r in rows {
            done[r] = true;
        }
        for i in (0..m).filter(|&i| !done[i]) {
            let lead: Vec<Expr> = cols.iter().map(|&c| a[i][c]).collect();
            if lead.iter().all(|&e| g.is_zero(e)) {
                continue;
            }
            // Row i -= (lead inv) rows; its pivot columns become zero exactly.
            let f: Vec<Expr> = (0..cols.len())
                .map(|j| {
                    let col: Vec<Expr> = inv.iter().map(|r| r[j]).collect();
                    g.dot(&lead, &col)
                })
                .collect();
            a[i] = minus_rows(g, &a, i, rows, &f);
            for &c in cols {
                a[i][c] = g.zero();
            }
            b[i] = minus_rows(g, &b, i, rows, &f);
        }
        inverses.push(inv);
    }
    let zero = g.zero();
    let mut x = vec![vec![zero; k]; m];
    let mut solved = vec![false; m];
    for ((rows, cols), inv) in pivots.iter().zip(&inverses).rev() {
        for c in 0..k {
            let rhs: Vec<Expr> = rows
                .iter()
                .map(|&r| {
                    let mut e = b[r][c];
                    for l in 0..m {
                        if !solved[l] || g.is_zero(a[r][l]) {
                            continue;
                        }
                        let t = g.mul(a[r][l], x[l][c]);
                        e = g.sub(e, t);
                    }
                    e
                })
                .collect();
            for (j, &col) in cols.iter().enumerate() {
                x[col][c] = g.dot(&inv[j], &rhs);
            }
        }
        for &col in cols {
            solved[col] = true;
        }
    }
    x
}

/// Row `i` of `mat` minus `sum_j f_j` times row `rows[j]`.
fn minus_rows(g: &mut Graph, mat: &[Vec<Expr>], i: usize, rows: &[usize], f: &[Expr]) -> Vec<Expr> {
    (0..mat[i].len())
        .map(|c| {
            let sub: Vec<Expr> = rows.iter().map(|&r| mat[r][c]).collect();
            let d = g.dot(f, &sub);
            g.sub(mat[i][c], d)
        })
        .collect()
}

/// The inverse of a `1x1` or `2x2` block (Cramer's rule: one reciprocal of the determinant).
fn inverse(g: &mut Graph, a: &[Vec<Expr>]) -> Vec<Vec<Expr>> {
    let one = g.one();
    match a.len() {
        1 => vec![vec![g.div(one, a[0][0])]],
        2 => {
            let (p, q) = (g.mul(a[0][0], a[1][1]), g.mul(a[0][1], a[1][0]));
            let det = g.sub(p, q);
            let r = g.div(one, det);
            let (n01, n10) = (g.neg(a[0][1]), g.neg(a[1][0]));
            vec![
                vec![g.mul(a[1][1], r), g.mul(n01, r)],
                vec![g.mul(n10, r), g.mul(a[0][0], r)],
            ]
        }
        n => unreachable!("closed-form steps fix one or two coordinates, not {n}"),
    }
}

/// The coordinates' roles in the projection.
pub struct Split<'a> {
    /// The independent (free) coordinates.
    pub free: &'a [usize],
    /// Driven coordinates: their accelerations are known, their columns stay.
    pub driven: &'a [usize],
    /// `(index, velocity, acceleration)` of each dependent coordinate.
    pub dependent: &'a [(usize, Expr, Expr)],
}

/// `M zdd = f` in all coordinates projected on the free ones by `zd = R qd`: the free rows
/// of `m` become `R^T M R` (free columns) and `R^T M` (driven columns), and of `f`
/// `R^T (f - M a0)`, `a0` the dependents' accelerations with the free `qdd` at zero.
pub fn project(
    g: &mut Graph,
    m: &mut [Vec<Expr>],
    f: &mut [Expr],
    split: &Split<'_>,
    s: &Symbols<'_>,
) {
    let nz = m.len();
    let zero = g.zero();
    let sym = |g: &Graph, e: Expr| g.as_sym(e).expect("coordinate symbol");
    // R by column (free coordinate j): e_j on the free rows, d velocity / d zd_j on the dependent ones.
    let r: Vec<Vec<Expr>> = split
        .free
        .iter()
        .map(|&j| {
            let mut col = vec![zero; nz];
            col[j] = g.one();
            for &(i, v, _) in split.dependent {
                col[i] = g.diff(v, sym(g, s.zd[j]));
            }
            col
        })
        .collect();
    let rest: HashMap<Sym, Expr> = split
        .free
        .iter()
        .map(|&j| (sym(g, s.zdd[j]), zero))
        .collect();
    let mut a0 = vec![zero; nz];
    for &(i, _, acc) in split.dependent {
        a0[i] = g.substitute(acc, &rest);
    }
    let rows: Vec<usize> = split
        .free
        .iter()
        .copied()
        .chain(split.dependent.iter().map(|d| d.0))
        .collect();
    let mr: Vec<Vec<Expr>> = r
        .iter()
        .map(|col| {
            (0..nz)
                .map(|a| {
                    let terms: Vec<Expr> = rows.iter().map(|&b| g.mul(m[a][b], col[b])).collect();
                    g.sum(terms)
                })
                .collect()
        })
        .collect();
    let proj = |g: &mut Graph, col: &[Expr], v: &dyn Fn(usize) -> Expr| {
        let terms: Vec<Expr> = rows.iter().map(|&a| g.mul(col[a], v(a))).collect();
        g.sum(terms)
    };
    let mut out_m = Vec::new();
    let mut out_f = Vec::new();
    for (ci, &i) in split.free.iter().enumerate() {
        let row: Vec<Expr> = split
            .free
            .iter()
            .enumerate()
            .map(|(cj, _)| proj(g, &r[ci], &|a| mr[cj][a]))
            .collect();
        let driven: Vec<Expr> = split
            .driven
            .iter()
            .map(|&d| proj(g, &r[ci], &|a| m[a][d]))
            .collect();
        out_m.push((i, row, driven));
        // R^T (f - M a0) = R^T f - (M R)^T a0 (M symmetric), reusing M R.
        let rf = proj(g, &r[ci], &|a| f[a]);
        let inertial = g.dot(&mr[ci], &a0);
        out_f.push((i, g.sub(rf, inertial)));
    }
    for (i, row, driven) in out_m {
        for (&j, e) in split.free.iter().zip(row) {
            m[i][j] = e;
        }
        for (&d, e) in split.driven.iter().zip(driven) {
            m[i][d] = e;
        }
    }
    let rates: Vec<(Sym, Expr)> = split
        .dependent
        .iter()
        .map(|&(i, v, _)| (sym(g, s.zd[i]), v))
        .collect();
    let qd: Vec<Sym> = split.free.iter().map(|&j| sym(g, s.zd[j])).collect();
    for (i, e) in out_f {
        f[i] = collected(g, e, &rates, &qd).unwrap_or(e);
    }
}

/// `f`, with the dependents' rates substituted, rebuilt as a polynomial of degree two in the
/// free rates `qd` (`f0 + sum f_j qd_j + sum_{j<=k} f_jk qd_j qd_k`, as an expert writes the
/// velocity terms: coefficients times one product of rates) when it is one and the rebuilt
/// form is shorter; `None` otherwise.
fn collected(g: &mut Graph, f: Expr, rates: &[(Sym, Expr)], qd: &[Sym]) -> Option<Expr> {
    let map: HashMap<Sym, Expr> = rates.iter().copied().collect();
    let e = g.substitute(f, &map);
    // `|qd|`, `signum`, `min`/`max` are flat in places: no Taylor form is exact for them.
    if !g.nonsmooth_calls(e).is_empty() {
        return None;
    }
    let zero = g.zero();
    let at_rest: HashMap<Sym, Expr> = qd.iter().map(|&v| (v, zero)).collect();
    let mut out = g.substitute(e, &at_rest);
    for (a, &j) in qd.iter().enumerate() {
        let dj = g.diff(e, j);
        let lin = g.substitute(dj, &at_rest);
        if !g.is_zero(lin) {
            let t = g.mul(lin, g.sym(j));
            out = g.add(out, t);
        }
        for &k in &qd[a..] {
            let djk = g.diff(dj, k);
            if qd.iter().any(|&v| g.depends_on(djk, v)) {
                return None;
            }
            let c = if j == k {
                let half = g.constant(0.5);
                g.mul(half, djk)
            } else {
                djk
            };
            if !g.is_zero(c) {
                let pair = g.mul(g.sym(j), g.sym(k));
                let t = g.mul(c, pair);
                out = g.add(out, t);
            }
        }
    }
    let cost = |g: &Graph, r: Expr| crate::sym::schedule(g, &[r]).len();
    (cost(g, out) < cost(g, e)).then_some(out)
}

/// The product `a b` with one factor `n / d` and one factor `d` cancelled to `n` (factors
/// read two levels deep: `(x (1 / d)) (d y)` is `x y`), `d` non-zero.
fn cancelled(g: &mut Graph, a: Expr, b: Expr, nonzero: &[Expr]) -> Option<Expr> {
    let mut fs = Vec::with_capacity(4);
    for x in [a, b] {
        match g.node(x) {
            Node::Mul(p, q) => fs.extend([p, q]),
            _ => fs.push(x),
        }
    }
    let (i, j, n) = (0..fs.len()).find_map(|i| {
        let Node::Div(n, d) = g.node(fs[i]) else {
            return None;
        };
        let j = (0..fs.len()).find(|&j| j != i && fs[j] == d)?;
        is_nonzero(g, d, nonzero).then_some((i, j, n))
    })?;
    fs[i] = n;
    fs.remove(j);
    let one = g.one();
    Some(fs.into_iter().fold(one, |p, f| g.mul(p, f)))
}

/// Whether `e` is one of `nonzero`, or a product, power or negation of such.
fn is_nonzero(g: &Graph, e: Expr, nonzero: &[Expr]) -> bool {
    nonzero.contains(&e)
        || match g.node(e) {
            Node::Mul(a, b) => is_nonzero(g, a, nonzero) && is_nonzero(g, b, nonzero),
            Node::Neg(a) | Node::Powi(a, _) => is_nonzero(g, a, nonzero),
            _ => false,
        }
}

/// `(k_a p + k_b r) x` for `a = k_a (x p)`, `b = k_b (x r)` (one shared operand `x`, the
/// coefficients of different size: equal ones the constructors factor already).
fn common_operand(g: &mut Graph, a: Expr, b: Expr) -> Option<Expr> {
    let split = |g: &Graph, e: Expr| match g.node(e) {
        Node::Neg(t) => (-1.0, t),
        Node::Mul(c, r) if g.as_const(c).is_some() => (g.as_const(c).unwrap_or(1.0), r),
        _ => (1.0, e),
    };
    let ((ka, ta), (kb, tb)) = (split(g, a), split(g, b));
    let (Node::Mul(a0, a1), Node::Mul(b0, b1)) = (g.node(ta), g.node(tb)) else {
        return None;
    };
    if ka.abs() == kb.abs() || [a0, a1, b0, b1].iter().any(|&e| g.as_const(e).is_some()) {
        return None;
    }
    let (x, p, r) = [
        (a0, a1, b0, b1),
        (a0, a1, b1, b0),
        (a1, a0, b0, b1),
        (a1, a0, b1, b0),
    ]
    .into_iter()
    .find(|&(x, _, y, _)| x == y)
    .map(|(x, p, _, r)| (x, p, r))?;
    let (ka, kb) = (g.constant(ka), g.constant(kb));
    let (kp, kr) = (g.mul(ka, p), g.mul(kb, r));
    let sum = g.add(kp, kr);
    Some(g.mul(sum, x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sym::Func;

    /// `e` at one set of values of its symbols (by name).
    fn at(g: &Graph, e: Expr) -> f64 {
        g.eval(e, &|s| match g.sym_name(s) {
            "x" => 0.7,
            "y" | "r" => -1.3,
            "l" | "m" => 0.35,
            "p" => 2.9,
            _ => -0.45,
        })
    }

    #[test]
    fn power_of_two_coefficients_come_out_of_a_sum_exactly() {
        let mut g = Graph::new();
        let (x, y) = (g.symbol("x"), g.symbol("y"));
        let (sx, cy) = (g.call(Func::Sin, x), g.call(Func::Cos, y));
        let (half, minus_half) = (g.constant(0.5), g.constant(-0.5));
        let (a, b) = (g.mul(half, sx), g.mul(minus_half, cy));
        let sum = g.add(a, b);
        let [t] = tidy(&mut g, &[sum], &[])[..] else {
            panic!("one root")
        };
        let Node::Mul(k, rest) = g.node(t) else {
            panic!("{}", g.display(t))
        };
        assert_eq!(g.as_const(k), Some(0.5));
        assert!(matches!(g.node(rest), Node::Add(..)));
        assert_eq!(at(&g, t).to_bits(), at(&g, sum).to_bits());
    }

    #[test]
    fn monomials_of_one_set_of_symbols_become_one_node() {
        let mut g = Graph::new();
        let (m, r) = (g.symbol("m"), g.symbol("r"));
        let rm = g.mul(r, m);
        let r_rm = g.mul(r, rm);
        let rr = g.mul(r, r);
        let m_rr = g.mul(m, rr);
        assert_ne!(r_rm, m_rr);
        let out = tidy(&mut g, &[r_rm, m_rr], &[]);
        assert_eq!(out[0], out[1]);
        assert!((at(&g, out[0]) - at(&g, r_rm)).abs() < 1e-15);
    }

    #[test]
    fn a_factor_cancels_only_where_it_is_known_non_zero() {
        let mut g = Graph::new();
        let (l, x, c) = (g.symbol("l"), g.symbol("x"), g.symbol("c"));
        let sx = g.call(Func::Sin, x);
        let u = g.div(sx, l);
        let lu = g.mul(l, u);
        let one = g.one();
        let inv = g.div(one, l);
        let c_inv = g.mul(c, inv);
        let l_c_inv = g.mul(l, c_inv);
        // Unknown sign of `l`: kept (`l = 0` must stay NaN).
        assert_eq!(tidy(&mut g, &[lu, l_c_inv], &[]), vec![lu, l_c_inv]);
        // `l` non-zero (the domain check's denominator), and a product of non-zeros.
        assert_eq!(tidy(&mut g, &[lu, l_c_inv], &[l]), vec![sx, c]);
        let ll = g.mul(l, l);
        let over_ll = g.div(sx, ll);
        let cancelled = g.mul(ll, over_ll);
        assert_eq!(tidy(&mut g, &[cancelled], &[l]), vec![sx]);
    }

    #[test]
    fn a_shared_operand_comes_out_with_unequal_coefficients() {
        let mut g = Graph::new();
        let (x, p, r) = (g.symbol("x"), g.symbol("p"), g.symbol("r"));
        let cx = g.call(Func::Cos, x);
        let (cp, cr) = (g.mul(cx, p), g.mul(cx, r));
        let k = g.constant(-0.5);
        let a = g.mul(k, cp);
        let b = g.neg(cr);
        let sum = g.add(a, b);
        let [t] = tidy(&mut g, &[sum], &[])[..] else {
            panic!("one root")
        };
        let Node::Mul(f, h) = g.node(t) else {
            panic!("{}", g.display(t))
        };
        assert!(f == cx || h == cx, "{}", g.display(t));
        let (new, old) = (at(&g, t), at(&g, sum));
        assert!((new - old).abs() <= 4.0 * f64::EPSILON * old.abs());
    }
}
