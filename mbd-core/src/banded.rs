//! The saddle-point system of closed loops, `[M Phi_q^T; Phi_q 0] [x; lambda] = [u; b]`, by
//! one banded LU with partial pivoting, for large well-conditioned systems.
//!
//! A loop-closed assembly whose coordinates are numbered along its loops (a joint tree
//! closed loop by loop) has a block-banded `M` and a banded `Phi_q`. Placing each multiplier
//! just after the last coordinate its constraint row touches makes the whole saddle-point
//! matrix banded too, with a half-bandwidth of a few loops' coordinates, so one LU costs
//! `O((N + M) b^2)` and one solve `O((N + M) b)`: linear in the loops, no iteration. It
//! answers only while its pivots stay within [`PIVOT_RATIO`] (as the small dense LU of
//! `solve::solve_augmented` does); near a singular position or with redundant rows the
//! caller falls back to the rank-robust augmented Lagrangian of `crate::augmented`.

use crate::model::{Matrix, Vector};
use std::borrow::Cow;

/// The LU answers only while `min |pivot| / max |pivot|` stays above this.
pub const PIVOT_RATIO: f64 = 1e-8;
/// The banded LU is tried only while its half-bandwidth is below this fraction of the order
/// (past it a band is no cheaper than the augmented Lagrangian's profile).
const MAX_BAND_FRACTION: usize = 3;

/// The non-zeros of `M` (lower triangle and diagonal) and `Phi_q`, read once column by
/// column (the storage order), and an order of the saddle-point unknowns: coordinates in
/// turn, each multiplier right after the last coordinate of its row.
struct Pattern<'a> {
    /// `(i, j, M_ij)` with `i >= j`.
    mass: Cow<'a, [(usize, usize, f64)]>,
    /// `(k, j, Phi_q[k, j])`.
    phi_q: Cow<'a, [(usize, usize, f64)]>,
    /// Position in the band of coordinate `i` (`0..N`) and multiplier `k` (`N..N + M`).
    pos: Vec<usize>,
    /// Half-bandwidth in that order.
    kl: usize,
}

impl<'a> Pattern<'a> {
    /// From the non-zeros of dense matrices, read column by column (the storage order).
    fn dense<const N: usize, const M: usize>(mass: &Matrix<N, N>, phi_q: &Matrix<M, N>) -> Self {
        let mut m = Vec::with_capacity(3 * N);
        for (j, col) in mass.as_slice().chunks_exact(N).enumerate() {
            nonzeros(&col[j..], |i, v| m.push((j + i, j, v)));
        }
        let mut p = Vec::with_capacity(4 * M);
        for (j, col) in phi_q.as_slice().chunks_exact(M.max(1)).enumerate() {
            nonzeros(col, |k, v| p.push((k, j, v)));
        }
        Self::new::<N, M>(Cow::Owned(m), Cow::Owned(p))
    }

    fn new<const N: usize, const M: usize>(
        mass: Cow<'a, [(usize, usize, f64)]>,
        phi_q: Cow<'a, [(usize, usize, f64)]>,
    ) -> Self {
        let mut last = vec![0_usize; M];
        for &(k, j, _) in phi_q.iter() {
            last[k] = last[k].max(j);
        }
        let mut rows: Vec<usize> = (0..M).collect();
        rows.sort_by_key(|&k| last[k]);
        let mut pos = vec![0_usize; N + M];
        let (mut next, mut r) = (0, 0);
        for j in 0..N {
            pos[j] = next;
            next += 1;
            while r < M && last[rows[r]] == j {
                pos[N + rows[r]] = next;
                next += 1;
                r += 1;
            }
        }
        let kl = mass
            .iter()
            .map(|&(i, j, _)| pos[i].abs_diff(pos[j]))
            .chain(phi_q.iter().map(|&(k, j, _)| pos[N + k].abs_diff(pos[j])))
            .max()
            .unwrap_or(0);
        Pattern {
            mass,
            phi_q,
            pos,
            kl,
        }
    }
}

/// `each(i, v)` for the non-zeros `v = x[i]`, skipping all-zero blocks of 8 at once (the
/// matrices of a large assembly are mostly zero).
#[inline]
fn nonzeros(x: &[f64], mut each: impl FnMut(usize, f64)) {
    for (b, block) in x.chunks(8).enumerate() {
        if block.iter().all(|&v| v == 0.0) {
            continue;
        }
        for (i, &v) in block.iter().enumerate() {
            if v != 0.0 {
                each(8 * b + i, v);
            }
        }
    }
}

/// `L U` of a banded matrix with partial pivoting (row interchanges), rows stored as windows
/// of columns `i - kl ..= i + ku + kl` (the fill of pivoting stays inside).
#[derive(Debug)]
struct BandLu {
    n: usize,
    kl: usize,
    /// Upper bandwidth of `U`: `ku + kl`.
    ku2: usize,
    w: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
}

impl BandLu {
    fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        let w = 2 * kl + ku + 1;
        BandLu {
            n,
            kl,
            ku2: kl + ku,
            w,
            a: vec![0.0; n * w],
            piv: vec![0; n],
        }
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        i * self.w + j + self.kl - i
    }

    /// Factor in place; `None` when a pivot vanishes or the pivots' ratio falls below
    /// [`PIVOT_RATIO`].
    fn factor(&mut self) -> Option<()> {
        let n = self.n;
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for k in 0..n {
            let last = (k + self.kl).min(n - 1);
            let right = (k + self.ku2).min(n - 1);
            let p = (k..=last).max_by(|&i, &j| {
                let (x, y) = (self.a[self.at(i, k)].abs(), self.a[self.at(j, k)].abs());
                x.total_cmp(&y)
            })?;
            if p != k {
                for j in k..=right {
                    let (x, y) = (self.at(k, j), self.at(p, j));
                    self.a.swap(x, y);
                }
            }
            self.piv[k] = p;
            let d = self.a[self.at(k, k)];
            if !(d.abs() > 0.0 && d.is_finite()) {
                return None;
            }
            lo = lo.min(d.abs());
            hi = hi.max(d.abs());
            for i in k + 1..=last {
                let ik = self.at(i, k);
                let l = self.a[ik] / d;
                self.a[ik] = l;
                if l != 0.0 {
                    // Column j of row r is at `at(r, 0) + j`; row k's stretch lies before
                    // row i's.
                    let (ri, rk) = (self.at(i, 0), self.at(k, 0));
                    let (head, tail) = self.a.split_at_mut(ri + k + 1);
                    let src = &head[rk + k + 1..=rk + right];
                    for (dst, &v) in tail[..right - k].iter_mut().zip(src) {
                        *dst -= l * v;
                    }
                }
            }
        }
        (lo >= PIVOT_RATIO * hi).then_some(())
    }

    fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        for k in 0..n {
            b.swap(k, self.piv[k]);
            let bk = b[k];
            if bk != 0.0 {
                let last = (k + self.kl).min(n - 1);
                for (i, bi) in b.iter_mut().enumerate().take(last + 1).skip(k + 1) {
                    *bi -= self.a[self.at(i, k)] * bk;
                }
            }
        }
        for k in (0..n).rev() {
            let right = (k + self.ku2).min(n - 1);
            let rk = self.at(k, 0);
            let row = &self.a[rk + k + 1..=rk + right];
            let s: f64 = row.iter().zip(&b[k + 1..=right]).map(|(u, x)| u * x).sum();
            b[k] = (b[k] - s) / self.a[rk + k];
        }
    }
}

/// `(x, lambda)` of the saddle-point system by one banded LU, when its bandwidth is small
/// against its order and its pivots stay within [`PIVOT_RATIO`]; `None` otherwise (the
/// caller then takes the augmented Lagrangian).
pub fn saddle_point<const N: usize, const M: usize>(
    mass: &Matrix<N, N>,
    u: &Vector<N>,
    phi_q: &Matrix<M, N>,
    b: &Vector<M>,
) -> Option<(Vector<N>, Vector<M>)> {
    solve::<N, M>(Pattern::dense(mass, phi_q), u, b)
}

/// As [`saddle_point`], by the symmetric `L D L^T` alone (no pivoted LU behind it): it
/// answers only where `Phi_q` is well away from losing rank (its multiplier pivots scale
/// with the squares of `Phi_q`'s singular values), the case in which a mass-orthogonal
/// projection may take the exact correction instead of the augmented Lagrangian's
/// least-squares one. `None` for small systems (`N + M <= `[`MIN_ORDER`]).
pub fn saddle_point_well_conditioned<const N: usize, const M: usize>(
    mass: &Matrix<N, N>,
    u: &Vector<N>,
    phi_q: &Matrix<M, N>,
    b: &Vector<M>,
) -> Option<(Vector<N>, Vector<M>)> {
    if N + M <= MIN_ORDER {
        return None;
    }
    let pattern = Pattern::dense(mass, phi_q);
    if pattern.kl * MAX_BAND_FRACTION >= N + M {
        return None;
    }
    let z = ldl_solve::<N>(&pattern, &ordered(&pattern, u, b))?;
    unordered(&pattern, &z)
}

/// Systems up to this order are left to the dense solves (as `solve::solve_augmented`
/// does): the band pays off on large assemblies.
const MIN_ORDER: usize = 24;

/// The right-hand side `[u; b]` in the band's order.
fn ordered<const N: usize, const M: usize>(
    pattern: &Pattern<'_>,
    u: &Vector<N>,
    b: &Vector<M>,
) -> Vec<f64> {
    let mut z = vec![0.0; N + M];
    for (i, &p) in pattern.pos.iter().enumerate() {
        z[p] = if i < N { u[i] } else { b[i - N] };
    }
    z
}

/// `(x, lambda)` from the solution in the band's order, when finite.
fn unordered<const N: usize, const M: usize>(
    pattern: &Pattern<'_>,
    z: &[f64],
) -> Option<(Vector<N>, Vector<M>)> {
    let pos = &pattern.pos;
    let x = Vector::<N>::from_fn(|i, _| z[pos[i]]);
    let lambda = Vector::<M>::from_fn(|k, _| z[pos[N + k]]);
    x.iter()
        .chain(lambda.iter())
        .all(|v| v.is_finite())
        .then_some((x, lambda))
}

/// As [`saddle_point`], with `M` and `Phi_q` given by their non-zeros `(row, column, value)`
/// (`M` by its lower triangle and diagonal, each entry once): the form generated code emits
/// for a large assembly, whose dense matrices are mostly zeros.
pub fn saddle_point_sparse<const N: usize, const M: usize>(
    mass: &[(usize, usize, f64)],
    u: &Vector<N>,
    phi_q: &[(usize, usize, f64)],
    b: &Vector<M>,
) -> Option<(Vector<N>, Vector<M>)> {
    solve::<N, M>(
        Pattern::new::<N, M>(Cow::Borrowed(mass), Cow::Borrowed(phi_q)),
        u,
        b,
    )
}

fn solve<const N: usize, const M: usize>(
    pattern: Pattern<'_>,
    u: &Vector<N>,
    b: &Vector<M>,
) -> Option<(Vector<N>, Vector<M>)> {
    if pattern.kl * MAX_BAND_FRACTION >= N + M {
        return None;
    }
    let z = ordered(&pattern, u, b);
    let z = ldl_solve::<N>(&pattern, &z).or_else(|| lu_solve::<N>(&pattern, z))?;
    unordered(&pattern, &z)
}

/// The banded LU with partial pivoting of the permuted system, `rhs` in the band's order.
fn lu_solve<const N: usize>(pattern: &Pattern<'_>, mut rhs: Vec<f64>) -> Option<Vec<f64>> {
    let (kl, pos) = (pattern.kl, &pattern.pos);
    let mut lu = BandLu::zeros(rhs.len(), kl, kl);
    for &(i, j, v) in pattern.mass.iter() {
        let (e1, e2) = (lu.at(pos[i], pos[j]), lu.at(pos[j], pos[i]));
        lu.a[e1] = v;
        lu.a[e2] = v;
    }
    for &(k, j, v) in pattern.phi_q.iter() {
        let (r, c) = (pos[N + k], pos[j]);
        let (e1, e2) = (lu.at(r, c), lu.at(c, r));
        lu.a[e1] = v;
        lu.a[e2] = v;
    }
    lu.factor()?;
    lu.solve(&mut rhs);
    Some(rhs)
}

/// The symmetric `L D L^T` of the permuted system without pivoting, `rhs` in the band's
/// order: a quarter of the pivoted LU's work (no row interchanges, so no fill past the band,
/// and one triangle). In this order it exists whenever `Phi_q` has full row rank (each
/// multiplier follows every coordinate its row touches: its pivot is minus a positive
/// quadratic form; each coordinate's, the energy left on the coordinates not yet
/// eliminated, positive), but without pivoting its growth is not bounded a priori: the
/// answer is kept only if its pivots stay within [`PIVOT_RATIO`] and its residual is at
/// rounding level ([`RESIDUAL_TOL`]); else `None` and the pivoted LU answers.
fn ldl_solve<const N: usize>(pattern: &Pattern<'_>, rhs: &[f64]) -> Option<Vec<f64>> {
    let (kl, pos) = (pattern.kl, &pattern.pos);
    if kl > MAX_LDL_BAND {
        return None;
    }
    let mut ldl = BandLdl::zeros(rhs.len(), kl);
    for &(i, j, v) in pattern.mass.iter() {
        let e = ldl.at(pos[i], pos[j]);
        ldl.a[e] = v;
    }
    for &(k, j, v) in pattern.phi_q.iter() {
        let e = ldl.at(pos[N + k], pos[j]);
        ldl.a[e] = v;
    }
    ldl.factor()?;
    // One buffer: the solution after `kl` zeros (the padding rows' unknowns), then the
    // residual `rhs - K x` and the magnitudes of its terms, from the triplets (`K`
    // symmetric: each off-diagonal entry twice).
    let n = rhs.len();
    let mut work = vec![0.0; kl + 3 * n];
    work[kl..kl + n].copy_from_slice(rhs);
    ldl.solve(&mut work[..kl + n]);
    let (x, rest) = work[kl..].split_at_mut(n);
    let (r, scale) = rest.split_at_mut(n);
    r.copy_from_slice(rhs);
    let mut apply = |a: usize, b: usize, v: f64| {
        let (va, vb) = (v * x[b], v * x[a]);
        r[a] -= va;
        scale[a] += va.abs();
        if a != b {
            r[b] -= vb;
            scale[b] += vb.abs();
        }
    };
    for &(i, j, v) in pattern.mass.iter() {
        apply(pos[i], pos[j], v);
    }
    for &(k, j, v) in pattern.phi_q.iter() {
        apply(pos[N + k], pos[j], v);
    }
    let ok = (r.iter().zip(scale.iter()).zip(rhs))
        .all(|((r, s), b)| r.abs() <= RESIDUAL_TOL * (s + b.abs()));
    work.truncate(kl + n);
    work.drain(..kl);
    ok.then_some(work)
}

/// The `L D L^T` answer is kept while every residual component stays below this times the
/// sum of the magnitudes of its terms (componentwise backward error; the pivoted LU reaches
/// a few units of rounding).
const RESIDUAL_TOL: f64 = 1e-12;

/// `L D L^T` of a symmetric banded matrix of half-bandwidth `kl`, row `i` of the lower
/// triangle stored as the window of columns `i - kl ..= i` (`L` below the diagonal, `D` on
/// it), after `kl` rows of padding (`D = 1`, `L = 0`), so that every row has a full window:
/// the kernels then run fixed-length loops ([`factor_k`], [`solve_k`], monomorphised for
/// each bandwidth up to [`MAX_LDL_BAND`]).
struct BandLdl {
    n: usize,
    kl: usize,
    a: Vec<f64>,
}

/// The widest band the `L D L^T` kernels are instantiated for; wider ones take the LU.
const MAX_LDL_BAND: usize = 8;

impl BandLdl {
    fn zeros(n: usize, kl: usize) -> Self {
        let w = kl + 1;
        let mut a = vec![0.0; (n + kl) * w];
        for p in 0..kl {
            a[p * w + kl] = 1.0;
        }
        BandLdl { n, kl, a }
    }

    /// Index of `(i, j)`, `i - kl <= j <= i`.
    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        (i + self.kl) * (self.kl + 1) + j + self.kl - i
    }

    /// Factor in place; `None` when a pivot vanishes, is not finite, or the pivots' ratio
    /// falls below [`PIVOT_RATIO`].
    fn factor(&mut self) -> Option<()> {
        macro_rules! by_band {
            ($($k:literal)*) => {
                match self.kl {
                    $($k => factor_k::<$k>(&mut self.a, self.n),)*
                    _ => None,
                }
            };
        }
        let (lo, hi) = by_band!(0 1 2 3 4 5 6 7 8)?;
        (lo >= PIVOT_RATIO * hi).then_some(())
    }

    /// `x`: `kl` zeros, then the right-hand side; the solution in its place.
    fn solve(&self, x: &mut [f64]) {
        macro_rules! by_band {
            ($($k:literal)*) => {
                match self.kl {
                    $($k => solve_k::<$k>(&self.a, x),)*
                    _ => unreachable!("factor refused the band"),
                }
            };
        }
        by_band!(0 1 2 3 4 5 6 7 8)
    }
}

/// [`BandLdl::factor`] for half-bandwidth `K`: row by row, `u_c = L_ic d_c` formed first
/// and then scaled by `1 / d_c`; the least and largest `|d|`, or `None` at a zero or
/// non-finite pivot.
fn factor_k<const K: usize>(a: &mut [f64], n: usize) -> Option<(f64, f64)> {
    let w = K + 1;
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for p in K..K + n {
        let (done, rest) = a.split_at_mut(p * w);
        let row = &mut rest[..w];
        let mut u = [0.0; K];
        for c in 0..K {
            // Row `p - K + c` shares columns `c' < c` of row p at `c' + K - c` of its own.
            let rj = &done[(p - K + c) * w..(p - K + c + 1) * w];
            let mut v = row[c];
            for k in 0..c {
                v -= u[k] * rj[k + K - c];
            }
            u[c] = v;
            row[c] = v / rj[K];
        }
        let mut d = row[K];
        for c in 0..K {
            d -= u[c] * row[c];
        }
        if !(d.abs() > 0.0 && d.is_finite()) {
            return None;
        }
        lo = lo.min(d.abs());
        hi = hi.max(d.abs());
        row[K] = d;
    }
    Some((lo, hi))
}

/// `L D L^T x = b` in place with the factors of [`factor_k`]; `x` holds `K` zeros (the
/// padding rows' unknowns) and then `b`.
fn solve_k<const K: usize>(a: &[f64], x: &mut [f64]) {
    let w = K + 1;
    let n = x.len() - K;
    for p in K..K + n {
        let row = &a[p * w..(p + 1) * w];
        let mut s = x[p];
        for c in 0..K {
            s -= row[c] * x[p - K + c];
        }
        x[p] = s;
    }
    for p in K..K + n {
        x[p] /= a[p * w + K];
    }
    for p in (K..K + n).rev() {
        let row = &a[p * w..(p + 1) * w];
        let xp = x[p];
        for c in 0..K {
            x[p - K + c] -= row[c] * xp;
        }
    }
}

/// The banded LU of a saddle-point matrix `[M Phi_q^T; Phi_q 0]`, kept to solve many
/// right-hand sides: the iteration matrix of an implicit method (generalized-α), factored
/// once and reused over the Newton iterations of several steps.
#[derive(Debug)]
pub struct SaddleLu {
    lu: BandLu,
    /// Position in the band of unknown `i` (coordinates, then multipliers).
    pos: Vec<usize>,
}

impl SaddleLu {
    /// Factor, when the bandwidth is small against the order and the pivots stay within
    /// [`PIVOT_RATIO`]; `None` otherwise.
    pub fn factor<const N: usize, const M: usize>(
        mass: &Matrix<N, N>,
        phi_q: &Matrix<M, N>,
    ) -> Option<Self> {
        let pattern = Pattern::dense(mass, phi_q);
        let (kl, pos) = (pattern.kl, &pattern.pos);
        if kl * MAX_BAND_FRACTION >= N + M {
            return None;
        }
        let mut lu = BandLu::zeros(N + M, kl, kl);
        for &(i, j, v) in pattern.mass.iter() {
            let (e1, e2) = (lu.at(pos[i], pos[j]), lu.at(pos[j], pos[i]));
            lu.a[e1] = v;
            lu.a[e2] = v;
        }
        for &(k, j, v) in pattern.phi_q.iter() {
            let (r, c) = (pos[N + k], pos[j]);
            let (e1, e2) = (lu.at(r, c), lu.at(c, r));
            lu.a[e1] = v;
            lu.a[e2] = v;
        }
        lu.factor()?;
        Some(SaddleLu {
            lu,
            pos: pattern.pos,
        })
    }

    /// Solve in place: `z = [u; b]` in, `[x; lambda]` out.
    pub fn solve(&self, z: &mut [f64]) {
        let mut w = vec![0.0; z.len()];
        for (i, &v) in z.iter().enumerate() {
            w[self.pos[i]] = v;
        }
        self.lu.solve(&mut w);
        for (i, v) in z.iter_mut().enumerate() {
            *v = w[self.pos[i]];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::Lu;

    const N: usize = 21;
    const M: usize = 16;
    const A: usize = N + M;

    /// A chain of loops: block-diagonal `M` (pairs), row `k` of `Phi_q` on coordinates
    /// `k, k + 1, k + 3` (a loop closing on the next one); zero pivots on the natural diagonal.
    fn chain() -> (Matrix<N, N>, Matrix<M, N>, Vector<N>, Vector<M>) {
        let mass = Matrix::<N, N>::from_fn(|i, j| match (i.abs_diff(j), i / 2 == j / 2) {
            (0, _) => 1.0 + 0.1 * i as f64,
            (1, true) => 0.3,
            _ => 0.0,
        });
        let p = Matrix::<M, N>::from_fn(|k, j| {
            if j == k || j == k + 1 || j == k + 3 {
                ((k + 2 * j) as f64).sin() + 1.5
            } else {
                0.0
            }
        });
        let u = Vector::<N>::from_fn(|i, _| (i as f64).cos());
        let b = Vector::<M>::from_fn(|k, _| 0.5 - k as f64 * 0.2);
        (mass, p, u, b)
    }

    /// Against the dense LU of the whole saddle-point matrix.
    #[test]
    fn matches_the_dense_lu_on_a_banded_saddle_point_system() {
        let (mass, p, u, b) = chain();
        let (x, lambda) = saddle_point(&mass, &u, &p, &b).expect("banded, well conditioned");
        let mut k = Matrix::<A, A>::zeros();
        k.fixed_view_mut::<N, N>(0, 0).copy_from(&mass);
        k.fixed_view_mut::<M, N>(N, 0).copy_from(&p);
        k.fixed_view_mut::<N, M>(0, N).copy_from(&p.transpose());
        let rhs = Vector::<A>::from_fn(|i, _| if i < N { u[i] } else { b[i - N] });
        let z = Lu::factor(k).unwrap().solve(&rhs);
        assert!((x - z.fixed_rows::<N>(0)).norm() < 1e-12, "{x} vs {z}");
        assert!(
            (lambda - z.fixed_rows::<M>(N)).norm() < 1e-12,
            "{lambda} vs {z}"
        );
    }

    /// The sparse form (as generated code passes it) gives the same solution.
    #[test]
    fn sparse_form_matches_the_dense_one() {
        let (mass, p, u, b) = chain();
        let lower: Vec<(usize, usize, f64)> = (0..N)
            .flat_map(|j| (j..N).map(move |i| (i, j)))
            .filter(|&(i, j)| mass[(i, j)] != 0.0)
            .map(|(i, j)| (i, j, mass[(i, j)]))
            .collect();
        let rows: Vec<(usize, usize, f64)> = (0..M)
            .flat_map(|k| (0..N).map(move |j| (k, j)))
            .filter(|&(k, j)| p[(k, j)] != 0.0)
            .map(|(k, j)| (k, j, p[(k, j)]))
            .collect();
        let dense = saddle_point(&mass, &u, &p, &b).unwrap();
        let sparse = saddle_point_sparse::<N, M>(&lower, &u, &rows, &b).unwrap();
        assert_eq!(dense, sparse);
    }

    /// The symmetric `L D L^T` answers a well-conditioned chain of loops (the fast path, not
    /// the fallback) and agrees with the pivoted LU to rounding.
    #[test]
    fn ldl_answers_and_agrees_with_the_pivoted_lu() {
        let (mass, p, u, b) = chain();
        let pattern = Pattern::dense(&mass, &p);
        let pos = pattern.pos.clone();
        let mut rhs = vec![0.0; A];
        for i in 0..N {
            rhs[pos[i]] = u[i];
        }
        for k in 0..M {
            rhs[pos[N + k]] = b[k];
        }
        let ldl = ldl_solve::<N>(&pattern, &rhs).expect("full row rank: L D L^T exists");
        let lu = lu_solve::<N>(&pattern, rhs).expect("banded, well conditioned");
        let diff = ldl
            .iter()
            .zip(&lu)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(diff < 1e-12, "L D L^T and LU differ by {diff}");
    }

    /// A repeated constraint row makes the system singular: no answer (the caller falls
    /// back to the rank-robust solve).
    #[test]
    fn refuses_a_redundant_row() {
        let (mass, mut p, u, b) = chain();
        let last = p.row(M - 2).into_owned();
        p.set_row(M - 1, &last);
        assert!(saddle_point(&mass, &u, &p, &b).is_none());
    }

    /// One factorisation kept for several right-hand sides (a Newton iteration's) gives
    /// what the one-shot solve gives for each.
    #[test]
    fn kept_factor_solves_many_right_hand_sides() {
        let (mass, p, u, b) = chain();
        let lu = SaddleLu::factor(&mass, &p).expect("banded, well conditioned");
        for scale in [1.0, -3.0] {
            let (x, lambda) = saddle_point(&mass, &(u * scale), &p, &(b * scale)).unwrap();
            let mut z: Vec<f64> = (u * scale)
                .iter()
                .chain((b * scale).iter())
                .copied()
                .collect();
            lu.solve(&mut z);
            let (zx, zl) = z.split_at(N);
            assert!(
                x.iter().zip(zx).all(|(a, b)| (a - b).abs() < 1e-13),
                "{x} vs {zx:?}"
            );
            assert!(
                lambda.iter().zip(zl).all(|(a, b)| (a - b).abs() < 1e-13),
                "{lambda} vs {zl:?}"
            );
        }
    }
}
