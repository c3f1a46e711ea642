//! Rank-robust solves of the saddle-point systems of closed loops,
//! `[M Phi_q^T; Phi_q 0] [x; lambda] = [u; b]`: accelerations (`u = f`, `b = gamma`),
//! mass-orthogonal projections (`u = 0`, `b = -Phi` or the velocity violation) and the
//! columns of the acceleration Jacobian.
//!
//! The augmented Lagrangian (Bayo, García de Jalón & Serna, Comput. Methods Appl. Mech. Eng.
//! 71, 1988; Bayo & Ledesma, Nonlinear Dyn. 9, 1996) replaces the indefinite matrix by
//! `A = M + alpha Phi_q^T Phi_q`, symmetric positive definite whenever `M` is positive definite
//! on the motions the constraints allow, also where `Phi_q` loses rank (singular positions,
//! redundant constraints), and iterates the multipliers:
//! `x_{k+1} = x_k + A^-1 (r_k + alpha Phi_q^T s_k)`, `lambda_{k+1} = lambda_k + alpha (Phi_q x_{k+1} - b)`,
//! with the true residuals `r = u - M x - Phi_q^T lambda`, `s = b - Phi_q x`. Written as
//! corrections, the iteration is also an iterative refinement of the solve with `A` (whose
//! condition grows with `alpha`), so it converges to the rounding level of the saddle-point
//! system. Started from `lambda = 0`, every multiplier update lies in the range of `Phi_q`,
//! so redundant constraints get the minimum-norm multipliers.
//!
//! `A` is factored by `L D L^T` in its envelope (profile), found from the non-zero pattern of
//! `M` and `Phi_q`: a loop-closed assembly whose coordinates are numbered along the loops has
//! a banded `A`, and the factorisation costs `O(N b^2)` for half-bandwidth `b`, not `O(N^3)`.

use crate::error::{Error, Result};
use crate::model::{Matrix, Vector};

/// The weights `alpha` relative to `max M_ii / max |row of Phi_q|^2`. The fine one leaves
/// the multipliers accurate to about `FINE * eps` (each update adds `alpha` times the rounding
/// of `Phi_q x`) and converges in a few iterations where `Phi_q` is well conditioned; the
/// coarse one contracts the iteration by `1 / (1 + COARSE s^2)` for a normalised singular
/// value `s` of `Phi_q M^-1/2`, so near singular positions too (the 40-loop assembly needs
/// `>= 1e6`, measured), at multipliers accurate to about `COARSE * eps`.
const FINE: f64 = 1e4;
const COARSE: f64 = 1e8;
/// The largest relative constraint residual a penalty-regularised solution may keep
/// ([`AugmentedLagrangian::solve_regularized`]); past it the solve is an error, never a wrong
/// `Ok`. Measured on the 40-loop assembly (20 s): with `1e-3` allowed, Radau5 at 1e-9 kept
/// its residuals below it and still ended 0.13 m off; with `1e-6`, every run that ends is
/// within its tolerance's error of the reference and the others stop with a typed error.
const REGULARIZED_RESIDUAL: f64 = 1e-6;
/// Iterations with the fine weight before the coarse one takes over, and with the coarse one
/// before the system counts as inconsistent.
const FINE_ITERATIONS: usize = 12;
const MAX_ITERATIONS: usize = 60;

/// `Phi_q` by rows, non-zeros only.
#[derive(Debug)]
struct SparseRows {
    ptr: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl SparseRows {
    fn new<const M: usize, const N: usize>(p: &Matrix<M, N>) -> Self {
        let mut s = SparseRows {
            ptr: Vec::with_capacity(M + 1),
            col: Vec::new(),
            val: Vec::new(),
        };
        s.ptr.push(0);
        for k in 0..M {
            for j in 0..N {
                let v = p[(k, j)];
                if v != 0.0 {
                    s.col.push(j);
                    s.val.push(v);
                }
            }
            s.ptr.push(s.col.len());
        }
        s
    }

    fn row(&self, k: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let r = self.ptr[k]..self.ptr[k + 1];
        self.col[r.clone()]
            .iter()
            .copied()
            .zip(self.val[r].iter().copied())
    }

    /// `Phi_q x`.
    fn mul<const M: usize, const N: usize>(&self, x: &Vector<N>) -> Vector<M> {
        Vector::<M>::from_fn(|k, _| self.row(k).map(|(j, v)| v * x[j]).sum())
    }

    /// `y += c Phi_q^T z`.
    fn add_transpose_mul<const M: usize, const N: usize>(
        &self,
        c: f64,
        z: &Vector<M>,
        y: &mut Vector<N>,
    ) {
        for k in 0..M {
            let ck = c * z[k];
            for (j, v) in self.row(k) {
                y[j] += v * ck;
            }
        }
    }
}

/// `L D L^T` of a symmetric positive definite matrix in skyline storage: row `i` holds the
/// columns `first[i] ..= i` (unit `L` below the diagonal, `D` on it).
#[derive(Debug)]
struct Envelope {
    first: Vec<usize>,
    start: Vec<usize>,
    v: Vec<f64>,
}

impl Envelope {
    fn at(&self, i: usize, j: usize) -> f64 {
        self.v[self.start[i] + j - self.first[i]]
    }

    /// Factor in place; `false` when a pivot is not positive (relative to `scale`) or not finite.
    fn factor(&mut self, scale: f64) -> bool {
        let n = self.first.len();
        for i in 0..n {
            let (fi, si) = (self.first[i], self.start[i]);
            for j in fi..i {
                let (fj, sj) = (self.first[j], self.start[j]);
                let lo = fi.max(fj);
                let mut s = self.v[si + j - fi];
                for k in lo..j {
                    s -= self.v[si + k - fi] * self.v[sj + k - fj];
                }
                // Row i keeps `L_ij D_j` until the diagonal is formed.
                self.v[si + j - fi] = s;
            }
            let mut d = self.v[si + i - fi];
            for j in fi..i {
                let dj = self.at(j, j);
                let lij_dj = self.v[si + j - fi];
                let lij = lij_dj / dj;
                d -= lij * lij_dj;
                self.v[si + j - fi] = lij;
            }
            if d.is_nan() || d <= scale * 1e-14 || !d.is_finite() {
                return false;
            }
            self.v[si + i - fi] = d;
        }
        true
    }

    fn solve<const N: usize>(&self, b: &Vector<N>) -> Vector<N> {
        let mut x = *b;
        for i in 0..N {
            let (fi, si) = (self.first[i], self.start[i]);
            let mut s = x[i];
            for k in fi..i {
                s -= self.v[si + k - fi] * x[k];
            }
            x[i] = s;
        }
        for i in 0..N {
            x[i] /= self.at(i, i);
        }
        for i in (0..N).rev() {
            let (fi, si) = (self.first[i], self.start[i]);
            let xi = x[i];
            for k in fi..i {
                x[k] -= self.v[si + k - fi] * xi;
            }
        }
        x
    }
}

/// The factored augmented-Lagrangian operator of one `(M, Phi_q)`: solves any number of
/// saddle-point systems with them.
#[derive(Debug)]
pub struct AugmentedLagrangian<'a, const N: usize, const M: usize> {
    mass: &'a Matrix<N, N>,
    /// Envelope of `M` alone: `M x` costs its profile.
    mass_first: Vec<usize>,
    /// Envelope of `M + Phi_q^T Phi_q`.
    first: Vec<usize>,
    rows: SparseRows,
    /// `max M_ii` and `max |row of Phi_q|^2`: `alpha = weight * m_scale / p_scale`.
    m_scale: f64,
    p_scale: f64,
    /// Row-sum norms of `M` and `Phi_q`, the scales of the residuals.
    m_norm: f64,
    p_norm: f64,
    /// `A` with the fine weight, and with the coarse one once needed.
    fine: Envelope,
    coarse: std::cell::OnceCell<Option<Envelope>>,
    t: f64,
}

/// A solution of `[M Phi_q^T; Phi_q 0] [x; lambda] = [u; b]` and how it was reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SaddleSolution<const N: usize, const M: usize> {
    pub x: Vector<N>,
    /// The multipliers; the minimum-norm ones when `Phi_q` lacks full row rank.
    pub lambda: Vector<M>,
    /// Multiplier updates taken.
    pub iterations: usize,
    /// Whether the coarse (large) weight was needed: a near-singular position, where the
    /// multipliers carry only about `COARSE * eps` relative accuracy (`x` keeps full accuracy).
    pub coarse: bool,
    /// Whether the iteration stopped before the constraint rows were met to rounding (see
    /// [`AugmentedLagrangian::solve_regularized`]): `x` is then the penalty-regularised
    /// solution and `lambda` the penalty forces, not exact multipliers.
    pub regularized: bool,
}

/// Where an iteration ended: converged, or not (with the last iterate).
type Iterate<const N: usize, const M: usize> =
    std::result::Result<SaddleSolution<N, M>, (Vector<N>, Vector<M>)>;

impl<'a, const N: usize, const M: usize> AugmentedLagrangian<'a, N, M> {
    /// Factor `A = M + alpha Phi_q^T Phi_q`. [`Error::SingularMassMatrix`] when `A` is not
    /// positive definite: `M` does not move mass in some motion the constraints allow.
    pub fn new(t: f64, mass: &'a Matrix<N, N>, phi_q: &Matrix<M, N>) -> Result<Self> {
        let mut al = Self::unfactored(t, mass, phi_q)?;
        al.fine = al.factor(FINE).ok_or(Error::SingularMassMatrix { t })?;
        Ok(al)
    }

    /// The profile and scales of `(M, Phi_q)`, before any factorisation.
    fn unfactored(t: f64, mass: &'a Matrix<N, N>, phi_q: &Matrix<M, N>) -> Result<Self> {
        let rows = SparseRows::new(phi_q);
        let mass_first: Vec<usize> = (0..N)
            .map(|i| (0..i).find(|&j| mass[(j, i)] != 0.0).unwrap_or(i))
            .collect();
        let mut first = mass_first.clone();
        for k in 0..M {
            if let Some(lo) = rows.row(k).map(|(j, _)| j).min() {
                for (j, _) in rows.row(k) {
                    first[j] = first[j].min(lo);
                }
            }
        }
        let m_scale = (0..N).map(|i| mass[(i, i)].abs()).fold(0.0, f64::max);
        let p_scale = (0..M)
            .map(|k| rows.row(k).map(|(_, v)| v * v).sum::<f64>())
            .fold(0.0, f64::max);
        let m_norm = (0..N)
            .map(|i| mass.column(i).iter().map(|v| v.abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let p_norm = (0..M)
            .map(|k| rows.row(k).map(|(_, v)| v.abs()).sum::<f64>())
            .fold(0.0, f64::max);
        if !(m_norm.is_finite() && p_norm.is_finite()) {
            return Err(Error::NonFinite { t });
        }
        Ok(AugmentedLagrangian {
            mass,
            mass_first,
            first,
            rows,
            m_scale,
            p_scale,
            m_norm,
            p_norm,
            fine: Envelope {
                first: vec![],
                start: vec![],
                v: vec![],
            },
            coarse: std::cell::OnceCell::new(),
            t,
        })
    }

    fn alpha(&self, weight: f64) -> f64 {
        if self.p_scale > 0.0 {
            weight * self.m_scale.max(f64::MIN_POSITIVE) / self.p_scale
        } else {
            0.0
        }
    }

    /// `L D L^T` of `M + alpha Phi_q^T Phi_q` in its envelope; `None` if not positive definite.
    fn factor(&self, weight: f64) -> Option<Envelope> {
        let (first, mass) = (&self.first, self.mass);
        let alpha = self.alpha(weight);
        let mut start = Vec::with_capacity(N);
        let mut len = 0;
        for (i, f) in first.iter().enumerate() {
            start.push(len);
            len += i + 1 - f;
        }
        let mut v = vec![0.0; len];
        for i in 0..N {
            for j in self.mass_first[i]..=i {
                v[start[i] + j - first[i]] = mass[(j, i)];
            }
        }
        for k in 0..M {
            for (i, pi) in self.rows.row(k) {
                for (j, pj) in self.rows.row(k) {
                    if j <= i {
                        v[start[i] + j - first[i]] += alpha * pi * pj;
                    }
                }
            }
        }
        let mut a = Envelope {
            first: first.clone(),
            start,
            v,
        };
        a.factor(self.m_scale.max(alpha * self.p_scale))
            .then_some(a)
    }

    /// `M x` over the profile of `M`.
    fn mass_mul(&self, x: &Vector<N>) -> Vector<N> {
        let mut y = Vector::<N>::zeros();
        for i in 0..N {
            let mut s = self.mass[(i, i)] * x[i];
            for j in self.mass_first[i]..i {
                let mij = self.mass[(j, i)];
                s += mij * x[j];
                y[j] += mij * x[i];
            }
            y[i] += s;
        }
        y
    }

    /// Solve `[M Phi_q^T; Phi_q 0] [x; lambda] = [u; b]`: with the fine weight (multipliers
    /// to rounding) while it converges quickly, then with the coarse one, whose iteration
    /// contracts also where `Phi_q` is nearly rank-deficient.
    /// [`Error::SingularConstraintJacobian`] when the residuals do not shrink to rounding:
    /// the equations are inconsistent (`b` outside the range of a rank-deficient `Phi_q`, a
    /// locked position needing unbounded constraint forces).
    pub fn solve(&self, u: &Vector<N>, b: &Vector<M>) -> Result<SaddleSolution<N, M>> {
        self.both(u, b)
            .map_err(|_| Error::SingularConstraintJacobian {
                t: self.t,
                detail: String::new(),
            })
    }

    /// As [`Self::solve`], but where the iteration does not meet the constraint rows to
    /// rounding (`Phi_q` nearly rank-deficient and `b` carrying the drift of an integrated
    /// state in its vanishing directions), the last iterate: the solution of the penalty
    /// formulation `(M + alpha Phi_q^T Phi_q) x = u + alpha Phi_q^T b - Phi_q^T lambda`,
    /// which stays bounded and continuous through a singular position, where the exact
    /// solve divides the drift by a vanishing singular value, as long as it meets the
    /// constraint rows to `REGULARIZED_RESIDUAL` relative; past that,
    /// [`Error::SingularPosition`] (its accelerations would not be the mechanism's). The
    /// right-hand side of a closed loop uses it; the result says `regularized`.
    pub fn solve_regularized(&self, u: &Vector<N>, b: &Vector<M>) -> Result<SaddleSolution<N, M>> {
        match self.both(u, b) {
            Ok(s) => Ok(s),
            Err((x, lambda)) if x.iter().chain(lambda.iter()).all(|v| v.is_finite()) => {
                let s = b - self.rows.mul::<M, N>(&x);
                let scale = max_abs(b) + self.p_norm * max_abs(&x);
                let residual = max_abs(&s) / scale.max(f64::MIN_POSITIVE);
                if residual > REGULARIZED_RESIDUAL {
                    return Err(Error::SingularPosition {
                        t: self.t,
                        detail: format!(
                            "near a singular position of the closed loops the constraint \
                             equations are met only to {} relative; the accelerations there \
                             would not be the mechanism's (a looser tolerance steps over the \
                             position; the index-3 integrator `Ali3` passes it)",
                            crate::error::Num(residual)
                        ),
                    });
                }
                Ok(SaddleSolution {
                    x,
                    lambda,
                    iterations: FINE_ITERATIONS + MAX_ITERATIONS,
                    coarse: true,
                    regularized: true,
                })
            }
            Err(_) => Err(Error::NonFinite { t: self.t }),
        }
    }

    /// As [`Self::solve`], but when `b` lies outside the range of a rank-deficient `Phi_q`,
    /// the `x` the iteration reached (it tends to the `M`-weighted least-squares solution
    /// while the multipliers grow): a Gauss–Newton projection step at a singular position.
    pub fn solve_least_squares(&self, u: &Vector<N>, b: &Vector<M>) -> Result<Vector<N>> {
        match self.both(u, b) {
            Ok(s) => Ok(s.x),
            Err((x, _)) if x.iter().all(|v| v.is_finite()) => Ok(x),
            Err(_) => Err(Error::NonFinite { t: self.t }),
        }
    }

    fn both(&self, u: &Vector<N>, b: &Vector<M>) -> Iterate<N, M> {
        let start = (Vector::<N>::zeros(), Vector::<M>::zeros());
        let (x, lambda) = match self.iterate(&self.fine, FINE, FINE_ITERATIONS, u, b, start) {
            Ok(s) => return Ok(s),
            Err(last) => last,
        };
        match self.coarse.get_or_init(|| self.factor(COARSE)) {
            Some(a) => self
                .iterate(a, COARSE, MAX_ITERATIONS, u, b, (x, lambda))
                .map(|s| SaddleSolution {
                    coarse: true,
                    iterations: s.iterations + FINE_ITERATIONS,
                    ..s
                }),
            None => Err((x, lambda)),
        }
    }

    /// The multiplier iteration with `A` factored for `weight`, from `(x, lambda)`.
    fn iterate(
        &self,
        a: &Envelope,
        weight: f64,
        max_iterations: usize,
        u: &Vector<N>,
        b: &Vector<M>,
        (mut x, mut lambda): (Vector<N>, Vector<M>),
    ) -> Iterate<N, M> {
        let alpha = self.alpha(weight);
        let mut best = f64::INFINITY;
        let mut stalled = 0;
        for iterations in 0..=max_iterations {
            let mx = self.mass_mul(&x);
            let px: Vector<M> = self.rows.mul(&x);
            let mut ptl = Vector::<N>::zeros();
            self.rows.add_transpose_mul(1.0, &lambda, &mut ptl);
            let r = u - mx - ptl;
            let s = b - px;
            // Norm-wise: the residuals against the sizes of the terms that form them.
            let (xn, ln) = (max_abs(&x), max_abs(&lambda));
            let r_scale = max_abs(u) + self.m_norm * xn + self.p_norm * ln;
            let s_scale = max_abs(b) + self.p_norm * xn;
            let scale = r_scale.max(s_scale);
            let size = max_abs(&r).max(max_abs(&s)) / scale.max(f64::MIN_POSITIVE);
            // Growing multipliers must not hide a constraint residual of the size of its own
            // terms: that is an inconsistent system, not convergence.
            let consistent = max_abs(&s) <= 1e-6 * s_scale;
            if !size.is_finite() {
                return Err((x, lambda));
            }
            let done = SaddleSolution {
                x,
                lambda,
                iterations,
                coarse: false,
                regularized: false,
            };
            // Rounding level of an `N`-term sum; or stopped shrinking near the weight's floor.
            if (size <= 4.0 * f64::EPSILON * (N as f64).sqrt() && consistent) || scale == 0.0 {
                return Ok(done);
            }
            if size < 0.5 * best {
                best = size;
                stalled = 0;
            } else {
                stalled += 1;
                if stalled >= 3 && best <= 1e3 * weight * f64::EPSILON && consistent {
                    return Ok(done);
                }
            }
            if iterations == max_iterations {
                break;
            }
            let mut rhs = r;
            self.rows.add_transpose_mul(alpha, &s, &mut rhs);
            x += a.solve(&rhs);
            let viol: Vector<M> = self.rows.mul(&x);
            lambda += (viol - b) * alpha;
        }
        Err((x, lambda))
    }
}

/// The factored penalty matrix `T = M + w Phi_q^T Phi_q` with `w = weight max M_ii /
/// max |row of Phi_q|^2`: the (approximate) Newton matrix of the index-3 augmented
/// Lagrangian integrator, positive definite also where `Phi_q` loses rank.
#[derive(Debug)]
pub struct PenaltyMatrix<const N: usize> {
    env: Envelope,
    /// The absolute `w`.
    pub w: f64,
}

impl<const N: usize> PenaltyMatrix<N> {
    /// Factor `T` in its envelope; [`Error::SingularMassMatrix`] when it is not positive
    /// definite.
    pub fn new<const M: usize>(
        t: f64,
        mass: &Matrix<N, N>,
        phi_q: &Matrix<M, N>,
        weight: f64,
    ) -> Result<Self> {
        let al = AugmentedLagrangian::unfactored(t, mass, phi_q)?;
        let env = al.factor(weight).ok_or(Error::SingularMassMatrix { t })?;
        Ok(PenaltyMatrix {
            env,
            w: al.alpha(weight),
        })
    }

    /// `T^-1 b`.
    pub fn solve(&self, b: &Vector<N>) -> Vector<N> {
        self.env.solve(b)
    }
}

fn max_abs<const K: usize>(v: &Vector<K>) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit mass in the plane held on `x = 1` by two equal constraints (one redundant):
    /// `x'' = 1 - ...` is fixed, `y'' = f_y`, and the multipliers are the minimum-norm split
    /// `lambda_1 = lambda_2 = f_x / 2` of the one reaction.
    #[test]
    fn redundant_constraints_get_minimum_norm_multipliers() {
        let mass = Matrix::<2, 2>::identity();
        let p = Matrix::<2, 2>::new(1.0, 0.0, 1.0, 0.0);
        let al = AugmentedLagrangian::new(0.0, &mass, &p).unwrap();
        let s = al
            .solve(&Vector::<2>::new(3.0, -2.0), &Vector::<2>::zeros())
            .unwrap();
        assert!(
            (s.x - Vector::<2>::new(0.0, -2.0)).norm() < 1e-14,
            "{}",
            s.x
        );
        assert!(
            (s.lambda - Vector::<2>::new(1.5, 1.5)).norm() < 1e-10,
            "{}",
            s.lambda
        );
        // Contradictory accelerations of the same two rows: inconsistent, a typed error.
        let err = al
            .solve(&Vector::<2>::zeros(), &Vector::<2>::new(0.0, 1.0))
            .unwrap_err();
        assert!(matches!(err, Error::SingularConstraintJacobian { t, .. } if t == 0.0));
    }

    /// A banded system against the dense LU of the whole saddle-point matrix.
    #[test]
    fn matches_the_dense_saddle_point_solve() {
        const N: usize = 5;
        let mass = Matrix::<N, N>::from_fn(|i, j| match i.abs_diff(j) {
            0 => 2.0 + i as f64,
            1 => 0.3,
            _ => 0.0,
        });
        let p = Matrix::<2, N>::from_fn(|k, j| {
            if j == k + 1 || j == k + 2 {
                1.0 + (k + j) as f64 * 0.1
            } else {
                0.0
            }
        });
        let (u, b) = (
            Vector::<N>::from_fn(|i, _| (i as f64).sin()),
            Vector::<2>::new(0.5, -1.0),
        );
        let s = AugmentedLagrangian::new(0.0, &mass, &p)
            .unwrap()
            .solve(&u, &b)
            .unwrap();
        let mut k = Matrix::<7, 7>::zeros();
        k.fixed_view_mut::<N, N>(0, 0).copy_from(&mass);
        k.fixed_view_mut::<2, N>(N, 0).copy_from(&p);
        k.fixed_view_mut::<N, 2>(0, N).copy_from(&p.transpose());
        let rhs = Vector::<7>::from_fn(|i, _| if i < N { u[i] } else { b[i - N] });
        let z = crate::linalg::Lu::factor(k).unwrap().solve(&rhs);
        assert!(
            (s.x - z.fixed_rows::<N>(0)).norm() < 1e-14,
            "{} vs {}",
            s.x,
            z
        );
        // Multipliers to about `FINE * eps` relative (module docs).
        let dl = (s.lambda - z.fixed_rows::<2>(N)).norm();
        assert!(
            dl < 1e-11 * s.lambda.norm(),
            "{dl:e} at |lambda| = {}",
            s.lambda.norm()
        );
    }
}
