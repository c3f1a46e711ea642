//! Linear analysis about an operating point: the state matrix `A = d(y')/dy`, exact from the
//! generated derivatives ([`OdeSystem::jacobian`] of a model derived with
//! `#[mechanism(jacobian)]`), and its modes.
//!
//! Two eigen-analyses: [`modes`] decomposes the real non-symmetric `A` (damped, gyroscopic
//! or unstable operating points alike) by nalgebra's real Schur form, with mode shapes by
//! one inverse iteration each; [`undamped_modes`] solves the symmetric generalised problem
//! `K v = w^2 M v` at an equilibrium of an undamped conservative model, with
//! `K = -df/dq = -M dqdd/dq` (at rest in equilibrium `f = 0`, so `dqdd/dq = M^-1 df/dq`).
//! Both convert to `DMatrix`: nalgebra's fixed-size decompositions need typenum bounds that
//! a bare `const D: usize` does not meet.
//!
//! At a state that is neither an equilibrium nor a steady motion, [`linearize`] is still the
//! Jacobian there and [`modes`] its eigen-decomposition (local rates, which depend on the
//! coordinates); [`undamped_modes`] refuses such a point. [`StateSpace::frequency_response`]
//! evaluates a linear model's transfer matrix on the imaginary axis.
//!
//! Closed loops in the augmented form: `A` of the index-1 equations also has the directions
//! that leave the constraint manifold (a double zero per constraint, the drift).
//! [`constrained_modes`] restricts `A` to the constraints' tangent space (independent
//! coordinates) at a rest state with time-independent constraints; elsewhere (moving
//! points, drives) the tangent space needs `(Phi_q qd)_q`, which is not generated yet.

use super::sensitivity::Parametric;
use crate::error::{Error, Result};
use crate::model::{Constrained, Matrix, Mechanism, OdeSystem, Vector};
use nalgebra::{Complex, DMatrix, DVector, Schur, SymmetricEigen};

/// Eigenvalues with `|lambda| <= NEUTRAL_TOL |A_b|` (`|A_b|` the largest row sum of `A`
/// balanced, see [`modes_of`]) may be neutral: rigid-body motion, a cyclic coordinate. A
/// double zero (a free coordinate's Jordan block) is computed `O(sqrt(eps) |A_b|)` away
/// from zero, so this bound sits above `sqrt(eps)`; below it an eigenvalue is neutral only
/// when its condition number says rounding could have made it. The same bound decides
/// stability of the fast modes: unstable when `Re lambda > NEUTRAL_TOL |A_b|`.
pub const NEUTRAL_TOL: f64 = 1e-7;

/// `A = d(y')/dy` at `(t, y)` from the model's exact Jacobian.
///
/// Errors: [`Error::InvalidInput`] when the model has no generated Jacobian (derive it with
/// `#[mechanism(jacobian)]`: a finite difference is not a linearisation this module vouches
/// for); the model's own errors; [`Error::NonFinite`] for a non-finite entry.
pub fn linearize<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
) -> Result<Matrix<D, D>> {
    if !S::EXACT_JACOBIAN {
        return Err(Error::InvalidInput {
            what: "linearize",
            detail: "the model has no generated Jacobian: derive it with #[mechanism(jacobian)]"
                .into(),
        });
    }
    let a = sys.jacobian(t, y)?;
    if a.iter().all(|v| v.is_finite()) {
        Ok(a)
    } else {
        Err(Error::NonFinite { t })
    }
}

/// `df/dy` by central differences with steps `h_j = h (1 + |y_j|)`: truncation error
/// `O(h^2 |f'''|)`, rounding `O(eps |f| / h)`. The check of [`linearize`] and the cost it is
/// compared with; not used by the analysis.
pub fn central_difference<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    h: f64,
) -> Result<Matrix<D, D>> {
    let mut jac = Matrix::<D, D>::zeros();
    let mut yj = *y;
    for j in 0..D {
        let hj = h * (1.0 + y[j].abs());
        yj[j] = y[j] + hj;
        let plus = sys.rhs(t, &yj)?;
        yj[j] = y[j] - hj;
        let minus = sys.rhs(t, &yj)?;
        yj[j] = y[j];
        jac.set_column(j, &((plus - minus) / (2.0 * hj)));
    }
    Ok(jac)
}

/// What kind of motion an eigenvalue stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeKind {
    /// A complex pair `lambda = -zeta w_n +- i w_d` (reported once, `Im lambda > 0`).
    Oscillatory,
    /// A real eigenvalue: overdamped decay (`lambda < 0`) or divergence (`lambda > 0`).
    Real,
    /// `|lambda|` below [`NEUTRAL_TOL`]: rigid-body motion or drift.
    Neutral,
}

/// One mode of `A`.
#[derive(Debug, Clone, PartialEq)]
pub struct Mode {
    pub eigenvalue: Complex<f64>,
    pub kind: ModeKind,
    /// Natural frequency `w_n = |lambda|` in rad/s (near 0 for a neutral mode).
    pub omega_n: f64,
    /// Damped frequency `w_d = Im lambda` in rad/s (0 unless oscillatory).
    pub omega_d: f64,
    /// `zeta = -Re lambda / |lambda|`: 1 for a real decaying mode, -1 for a diverging one;
    /// `None` for a neutral mode.
    pub damping_ratio: Option<f64>,
    /// `Re lambda > NEUTRAL_TOL |A|`.
    pub unstable: bool,
    /// The eigenvector over the state, scaled so that its largest entry is 1.
    pub shape: DVector<Complex<f64>>,
}

impl Mode {
    /// `w_n / 2 pi`.
    pub fn frequency_hz(&self) -> f64 {
        self.omega_n / std::f64::consts::TAU
    }
    /// `w_d / 2 pi`.
    pub fn damped_hz(&self) -> f64 {
        self.omega_d / std::f64::consts::TAU
    }
}

/// The modes of `A`, slowest first: each complex pair once, each real or neutral eigenvalue
/// once.
///
/// Errors: [`Error::NonFinite`] for a non-finite `A`; [`Error::InvalidInput`] when the Schur
/// iteration does not converge.
pub fn modes<const D: usize>(a: &Matrix<D, D>) -> Result<Vec<Mode>> {
    modes_of(DMatrix::from_iterator(D, D, a.iter().copied()))
}

/// [`modes`] of a matrix of any size.
///
/// The eigenvalues come from `A` balanced (`D^-1 A D`, `D` diagonal powers of 2: Parlett &
/// Reinsch, as LAPACK's `dgeev` does), whose norm `|A_b|` is in the units of the
/// eigenvalues (1/s) where `|A|` mixes `1/s` with `1/s^2` (a stiffness `w^2`). An
/// eigenvalue is neutral when `|lambda| <= NEUTRAL_TOL |A_b|` *and* it cannot be told from
/// zero: `|lambda| <= RESOLVED eps |A_b| kappa`, `kappa` its condition number
/// (`|x| |y| / |y^H x|`, right and left eigenvectors of `A_b`). A double zero split by
/// rounding is ill-conditioned (`kappa ~ |A_b| / |lambda|`) and stays neutral; a slow
/// oscillator beside a fast one is well conditioned and is reported at its frequency.
pub fn modes_of(a: DMatrix<f64>) -> Result<Vec<Mode>> {
    if !a.iter().all(|v| v.is_finite()) {
        return Err(Error::NonFinite { t: f64::NAN });
    }
    let row_norm = |m: &DMatrix<f64>| {
        m.row_iter()
            .map(|r| r.iter().map(|v| v.abs()).sum::<f64>())
            .fold(0.0, f64::max)
    };
    let norm = row_norm(&a);
    let ab = balance(&a);
    let norm_b = row_norm(&ab).max(f64::MIN_POSITIVE);
    let tol = NEUTRAL_TOL * norm_b;
    let eigenvalues = eigenvalues(&ab).ok_or_else(|| Error::InvalidInput {
        what: "modes",
        detail: "the Schur iteration did not converge".into(),
    })?;
    let mut out: Vec<Mode> = Vec::new();
    for lambda in eigenvalues.iter().copied() {
        let modulus = lambda.norm();
        // The rounding `lambda` could carry (`tol` for the fast ones, never neutral).
        let floor = if modulus <= tol {
            RESOLVED * f64::EPSILON * norm_b * condition(&ab, lambda, norm_b)
        } else {
            tol
        };
        let neutral = modulus <= tol && modulus <= floor;
        // A pair once; neutral eigenvalues each (a double zero may come out as `+-i eps`).
        if lambda.im < 0.0 && !neutral {
            continue;
        }
        let lambda = if !neutral && modulus <= tol {
            refine(&a, lambda, norm)
        } else {
            lambda
        };
        let modulus = lambda.norm();
        let kind = if neutral {
            ModeKind::Neutral
        } else if lambda.im > 0.0 {
            ModeKind::Oscillatory
        } else {
            ModeKind::Real
        };
        out.push(Mode {
            eigenvalue: lambda,
            kind,
            omega_n: modulus,
            omega_d: if kind == ModeKind::Oscillatory {
                lambda.im
            } else {
                0.0
            },
            damping_ratio: (!neutral).then(|| -lambda.re / modulus),
            unstable: !neutral && lambda.re > floor,
            // Repeated within the eigenvalue's own resolution: a resolved slow one is not
            // a copy of a neutral zero beside it.
            shape: shape(
                &a,
                lambda,
                norm,
                &repeated(&out, lambda, if neutral { tol } else { floor }),
            ),
        });
    }
    out.sort_by(|x, y| x.omega_n.total_cmp(&y.omega_n));
    Ok(out)
}

/// A small eigenvalue is resolved (not neutral) above `RESOLVED eps |A_b| kappa`: the
/// first-order bound of its rounding error, `eps |A_b| kappa`, with a margin for the
/// Schur iteration's backward error. A double zero `[[0, s], [0, 0]]` perturbed by
/// `delta` splits into `+-sqrt(s delta)` with `kappa = s / (2 |lambda|)`, so the bound is
/// `RESOLVED (eps |A_b| / delta) |lambda| / 2`: it stays neutral for a backward error up
/// to `delta = 50 eps |A_b|`, while a creep at `1e-3` 1/s beside a 1 MHz mode
/// (`kappa ~ 1e3`) is resolved.
const RESOLVED: f64 = 100.0;

/// A slow eigenvalue beside fast ones, refined: Schur's carries rounding of the fastest
/// (`eps |A_b| kappa`); the two-sided Rayleigh quotient `w^T A x / w^T x` of its right and
/// left eigenvectors (`A x = lambda x`, `A^T w = lambda w`) has an error quadratic in
/// theirs, and `A x` rounds with the entries it meets, not with the largest. Kept only
/// when it moves `lambda` by less than 1% (rounding is below 0.1% of a resolved one);
/// a real eigenvalue stays real.
fn refine(a: &DMatrix<f64>, lambda: Complex<f64>, norm: f64) -> Complex<f64> {
    let quotient = two_sided_quotient(a, lambda, norm, a);
    let refined = if lambda.im == 0.0 {
        Complex::new(quotient.re, 0.0)
    } else {
        quotient
    };
    if refined.re.is_finite()
        && refined.im.is_finite()
        && (refined - lambda).norm() <= 1e-2 * lambda.norm()
    {
        refined
    } else {
        lambda
    }
}

/// `D^-1 A D` with `D` diagonal powers of 2 that bring each row's and column's
/// off-diagonal sums together (Parlett & Reinsch, Numer. Math. 13, 1969; exact in
/// floating point, a similarity). A stiffness row `-w^2` and a velocity row `1` become
/// `-w` and `w`: the norm then measures the eigenvalues.
fn balance(a: &DMatrix<f64>) -> DMatrix<f64> {
    let n = a.nrows();
    let mut b = a.clone();
    for _sweep in 0..64 {
        let mut done = true;
        for i in 0..n {
            let off = |v: f64, j: usize| if j == i { 0.0 } else { v.abs() };
            let mut c: f64 = (0..n).map(|j| off(b[(j, i)], j)).sum();
            let r: f64 = (0..n).map(|j| off(b[(i, j)], j)).sum();
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            while c < r / 2.0 {
                f *= 2.0;
                c *= 4.0;
            }
            while c >= r * 2.0 {
                f /= 2.0;
                c /= 4.0;
            }
            if (c + r) / f < 0.95 * s {
                done = false;
                b.row_mut(i).scale_mut(1.0 / f);
                b.column_mut(i).scale_mut(f);
            }
        }
        if done {
            break;
        }
    }
    b
}

/// The condition number `|x| |y| / |y^H x|` of the eigenvalue `lambda` of `a` (infinite at
/// a defective one), its right and left eigenvectors by inverse iteration.
fn condition(a: &DMatrix<f64>, lambda: Complex<f64>, norm: f64) -> f64 {
    if lambda.norm() == 0.0 {
        return f64::INFINITY;
    }
    let (x, w) = eigenvectors(a, lambda, norm);
    x.norm() * w.norm() / left_dot(&w, &x).norm()
}

/// The right and left eigenvectors of `lambda`, `A x = lambda x` and `A^T w = lambda w`,
/// by inverse iteration. For a real `A` the left eigenvector is `y = conj(w)`, so
/// `y^H u = w^T u` ([`left_dot`]).
fn eigenvectors(
    a: &DMatrix<f64>,
    lambda: Complex<f64>,
    norm: f64,
) -> (DVector<Complex<f64>>, DVector<Complex<f64>>) {
    let x = inverse_iteration(a, lambda, norm, &[]);
    let w = inverse_iteration(&a.transpose(), lambda, norm, &[]);
    (x, w)
}

/// `w^T u`, unconjugated: `y^H u` for the left eigenvector `y = conj(w)`.
fn left_dot(w: &DVector<Complex<f64>>, u: &DVector<Complex<f64>>) -> Complex<f64> {
    w.iter().zip(u.iter()).map(|(p, q)| p * q).sum()
}

/// `w^T B x / w^T x` with the right and left eigenvectors of `lambda` of `a`: for
/// `B = A` the two-sided Rayleigh quotient ([`refine`]), for `B = dA/dp` the first-order
/// change of a simple eigenvalue ([`mode_sensitivity`]).
fn two_sided_quotient(
    a: &DMatrix<f64>,
    lambda: Complex<f64>,
    norm: f64,
    b: &DMatrix<f64>,
) -> Complex<f64> {
    let (x, w) = eigenvectors(a, lambda, norm);
    let bx = b.map(|v| Complex::new(v, 0.0)) * &x;
    left_dot(&w, &bx) / left_dot(&w, &x)
}

/// The eigenvalues of `a` from its real Schur form. nalgebra's shifted QR iteration can
/// cycle without converging on a matrix with a symmetric pattern of eigenvalues (an
/// unstable gyroscopic pair `+-a +-ib`: a sleeping top spun below its stability limit);
/// then it is run again on `H a H`, `H` a fixed reflection that breaks the pattern
/// (a similarity: the same eigenvalues).
fn eigenvalues(a: &DMatrix<f64>) -> Option<DVector<Complex<f64>>> {
    let schur = |m: DMatrix<f64>| Schur::try_new(m, f64::EPSILON, 10_000);
    if let Some(s) = schur(a.clone()) {
        return Some(s.complex_eigenvalues());
    }
    let n = a.nrows();
    let v = DVector::from_fn(n, |i, _| 1.0 + 0.618_033_988_749_895 * i as f64);
    let h = DMatrix::<f64>::identity(n, n) - &v * v.transpose() * (2.0 / v.norm_squared());
    schur(&h * a * &h).map(|s| s.complex_eigenvalues())
}

/// The shapes already found for eigenvalues within `tol` of `lambda` (a repeated one).
fn repeated(found: &[Mode], lambda: Complex<f64>, tol: f64) -> Vec<DVector<Complex<f64>>> {
    found
        .iter()
        .filter(|m| (m.eigenvalue - lambda).norm() <= tol)
        .map(|m| m.shape.clone())
        .collect()
}

/// The eigenvector of `lambda` by inverse iteration with a shift a relative `1e-10` off it
/// (of `|lambda|`, at least of `eps |A|`; three solves; an exactly singular shift
/// is moved further). A repeated eigenvalue's
/// later shapes are kept orthogonal to its earlier ones (`others`), so a semisimple one
/// (two identical uncoupled oscillators) gets independent shapes spanning its eigenspace;
/// a defective one (a Jordan block: a free coordinate's double zero) has a single
/// eigenvector, which is then repeated.
fn shape(
    a: &DMatrix<f64>,
    lambda: Complex<f64>,
    norm: f64,
    others: &[DVector<Complex<f64>>],
) -> DVector<Complex<f64>> {
    let plain = inverse_iteration(a, lambda, norm, &[]);
    if others.is_empty() {
        return plain;
    }
    let v = inverse_iteration(a, lambda, norm, others);
    let ac = a.map(|x| Complex::new(x, 0.0));
    let residual = (&ac * &v - &v * lambda).norm();
    if residual <= 1e-6 * norm.max(f64::MIN_POSITIVE) * v.norm() {
        v
    } else {
        plain
    }
}

/// Inverse iteration on `lambda` with each iterate made orthogonal to `others`.
fn inverse_iteration(
    a: &DMatrix<f64>,
    lambda: Complex<f64>,
    norm: f64,
    others: &[DVector<Complex<f64>>],
) -> DVector<Complex<f64>> {
    let n = a.nrows();
    let ac = a.map(|v| Complex::new(v, 0.0));
    let mut v = DVector::from_fn(n, |i, _| Complex::new(1.0, 0.1 * i as f64));
    orthogonalise(&mut v, others);
    // Relative to `lambda` itself: a slow mode's shift must stay far nearer to it than to
    // its conjugate (`2 |lambda|` away), however fast the other modes are.
    let scale = lambda
        .norm()
        .max(f64::EPSILON * norm)
        .max(f64::MIN_POSITIVE);
    for k in 0..4 {
        let shift = lambda + Complex::new(1.0, 1.0) * 1e-10 * 10f64.powi(k) * scale;
        let lu = (&ac - DMatrix::<Complex<f64>>::identity(n, n) * shift).lu();
        if !lu.is_invertible() {
            continue;
        }
        for _ in 0..3 {
            match lu.solve(&v) {
                Some(w) if w.iter().all(|x| x.re.is_finite() && x.im.is_finite()) => v = w,
                _ => break,
            }
            orthogonalise(&mut v, others);
            let big = largest(&v);
            v /= big;
        }
        return v;
    }
    v
}

/// Gram-Schmidt (twice, for rounding) of `v` against `others`.
fn orthogonalise(v: &mut DVector<Complex<f64>>, others: &[DVector<Complex<f64>>]) {
    for _ in 0..2 {
        for u in others {
            let uu = u.dotc(u);
            if uu.norm() > 0.0 {
                *v -= u * (u.dotc(v) / uu);
            }
        }
    }
}

/// The entry of largest modulus (1 for a zero vector).
fn largest(v: &DVector<Complex<f64>>) -> Complex<f64> {
    v.iter()
        .copied()
        .max_by(|x, y| x.norm().total_cmp(&y.norm()))
        .filter(|x| x.norm() > 0.0)
        .unwrap_or(Complex::new(1.0, 0.0))
}

/// Eigenvalues of `K v = w^2 M v` with `|w^2| <= NEUTRAL_W2 max |w^2|` carry the rounding
/// of the fastest mode (`O(eps cond(M) |K|)`, of either sign): they are recomputed as the
/// Rayleigh quotient of `K` and `M`, and returned as exactly `w^2 = 0` (a rigid-body mode)
/// when that is within its own rounding (a negative rounding would read as unstable).
pub const NEUTRAL_W2: f64 = 1e-10;

/// A mode of `K v = w^2 M v`.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalMode<const N: usize> {
    /// `w^2` in (rad/s)^2; negative at an unstable equilibrium, exactly 0 for a rigid-body
    /// mode (see [`NEUTRAL_W2`]).
    pub omega_squared: f64,
    /// `v`, mass-normalised (`v^T M v = 1`).
    pub shape: Vector<N>,
}

impl<const N: usize> NormalMode<N> {
    /// `sqrt(w^2) / 2 pi`, `None` at an unstable equilibrium (`w^2 < 0`).
    pub fn frequency_hz(&self) -> Option<f64> {
        (self.omega_squared >= 0.0).then(|| self.omega_squared.sqrt() / std::f64::consts::TAU)
    }
}

/// The modes of an undamped conservative model at its equilibrium `q` (at rest), slowest
/// first: `K v = w^2 M v` with `K = -M dqdd/dq` from the exact Jacobian, reduced by the
/// Cholesky factor of `M` to a symmetric eigenproblem. Rigid-body modes have `w^2 = 0`
/// ([`NEUTRAL_W2`]).
///
/// Errors ([`Error::InvalidInput`]) when `q` is not an equilibrium (`|qdd| > 1e-9 |A|`),
/// when the model is damped or gyroscopic (`dqdd/dqd != 0` at rest; the message says
/// which), when `K` is not symmetric (to
/// `1e-9 |K|`: non-conservative forces), when `M` is not positive definite, or for a
/// generated closed loop in the augmented form (its constraint directions would read as
/// rigid-body modes: [`constrained_undamped_modes`] restricts to the loop); plus the
/// errors of [`linearize`].
pub fn undamped_modes<S, const N: usize, const D: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
) -> Result<Vec<NormalMode<N>>>
where
    S: Mechanism<N> + OdeSystem<D>,
{
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    // Generated models with constraint rows are their own passage bridge.
    if sys.passage().is_some() {
        return Err(Error::InvalidInput {
            what: "undamped_modes",
            detail: "a closed loop in the augmented form: its constraint directions would \
                     read as rigid-body modes; use `constrained_undamped_modes`"
                .into(),
        });
    }
    normal_modes(sys, t, q, DMatrix::identity(N, N), "undamped_modes")
}

/// [`undamped_modes`] of a closed loop in the augmented form at its equilibrium `q` (at
/// rest, time-independent constraints), in the loop's independent motions `dq = Z u` (`Z`
/// an orthonormal null basis of `Phi_q`, as in [`constrained_modes`]):
/// `Z^T K Z u = w^2 Z^T M Z u`. At an equilibrium this is the reduced stiffness, the
/// multipliers' geometric stiffness included: differentiating `M qdd + Phi_q^T lambda = f`
/// with `qdd = 0` and `Phi_q dqdd = 0` gives `Z^T M dqdd = Z^T (f_q - (Phi_q^T lambda)_q)
/// dq`. Shapes are `v = Z u` over all coordinates, mass-normalised (`v^T M v = 1`).
///
/// Errors: those of [`constrained_modes`] (not assembled, time-dependent constraints, rank
/// loss) and of [`undamped_modes`].
pub fn constrained_undamped_modes<S, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
) -> Result<Vec<NormalMode<N>>>
where
    S: Constrained<N, M> + OdeSystem<D>,
{
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    let what = "constrained_undamped_modes";
    let tm = tangent_basis::<S, N, M, D>(sys, t, q, what)?;
    let z = tm.view((0, 0), (N, tm.ncols() / 2)).into_owned();
    normal_modes(sys, t, q, z, what)
}

/// `Z^T K Z u = w^2 Z^T M Z u` with the checks of [`undamped_modes`]; shapes `Z u`.
fn normal_modes<S, const N: usize, const D: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    z: DMatrix<f64>,
    what: &'static str,
) -> Result<Vec<NormalMode<N>>>
where
    S: Mechanism<N> + OdeSystem<D>,
{
    let bad = |detail: String| Error::InvalidInput { what, detail };
    let y = Vector::<D>::from_fn(|i, _| if i < N { q[i] } else { 0.0 });
    let a = linearize(sys, t, &y)?;
    let scale = a.abs().max().max(1.0);
    let qdd = sys.rhs(t, &y)?.fixed_rows::<N>(N).abs().max();
    if qdd > 1e-9 * scale {
        return Err(bad(format!("not an equilibrium: |qdd| = {qdd:.3e}")));
    }
    let mass = sys.mass_matrix(t, q)?;
    let damping = a.fixed_view::<N, N>(N, N).abs().max();
    if damping > 1e-12 * scale {
        // `M dqdd/dqd = -(C + G)`: a skew `G` is gyroscopic (Coriolis of a spin or a turning
        // frame), which conserves energy but still couples the velocities.
        let c = mass * a.fixed_view::<N, N>(N, N);
        let kind = if (c + c.transpose()).abs().max() <= 1e-9 * c.abs().max() {
            "gyroscopic (skew velocity terms: a spin or a turning frame)"
        } else {
            "damped"
        };
        return Err(bad(format!(
            "{kind}: |dqdd/dqd| = {damping:.3e}; use `modes`"
        )));
    }
    let dyn_n = |m: Matrix<N, N>| DMatrix::from_iterator(N, N, m.iter().copied());
    let k = z.transpose() * dyn_n(-(mass * a.fixed_view::<N, N>(N, 0))) * &z;
    let asym = (&k - k.transpose()).amax();
    if asym > 1e-9 * k.amax() {
        return Err(bad(format!("K is not symmetric (|K - K^T| = {asym:.3e})")));
    }
    let dm = z.transpose() * dyn_n(mass) * &z;
    let l = dm
        .clone()
        .cholesky()
        .ok_or_else(|| bad("M is not positive definite".into()))?
        .l();
    let linv = l.try_inverse().ok_or_else(|| bad("M is singular".into()))?;
    let ks = (&k + k.transpose()) * 0.5;
    let c = &linv * &ks * linv.transpose();
    let eig = SymmetricEigen::try_new(c, f64::EPSILON, 10_000)
        .ok_or_else(|| bad("the symmetric eigen-iteration did not converge".into()))?;
    let top = eig.eigenvalues.amax();
    let mut out: Vec<NormalMode<N>> = (0..z.ncols())
        .map(|i| {
            let u = linv.transpose() * eig.eigenvectors.column(i);
            let v = &z * &u;
            let w2 = eig.eigenvalues[i];
            NormalMode {
                omega_squared: if w2.abs() <= NEUTRAL_W2 * top {
                    small_omega_squared(&ks, &dm, &u)
                } else {
                    w2
                },
                shape: Vector::<N>::from_fn(|r, _| v[r]),
            }
        })
        .collect();
    out.sort_by(|x, y| x.omega_squared.total_cmp(&y.omega_squared));
    Ok(out)
}

/// `w^2` of a slow or rigid-body mode `v`, whose eigenvalue of the reduced problem carries
/// rounding of the fastest (`eps max |w^2|`, more than a slow `w^2` beside a very stiff
/// one): the Rayleigh quotient `v^T K v / v^T M v` of the original `K`, `M` (error
/// quadratic in the shape's), exactly 0 (a rigid-body mode) when it lies within its own
/// rounding, `64 n eps sum |v_i| |K_ij| |v_j| / v^T M v`.
fn small_omega_squared(k: &DMatrix<f64>, mass: &DMatrix<f64>, v: &DVector<f64>) -> f64 {
    let vmv = v.dot(&(mass * v));
    let quotient = v.dot(&(k * v)) / vmv;
    let va = v.abs();
    let rounding = 64.0 * v.len() as f64 * f64::EPSILON * va.dot(&(k.abs() * &va)) / vmv;
    if quotient.abs() <= rounding {
        0.0
    } else {
        quotient
    }
}

/// The modes of a closed loop at rest on its constraints, in independent coordinates: `A`
/// of the augmented (index-1) equations restricted to the tangent space of `Phi = 0`,
/// `Phi_q qd = 0`. At rest that space is spanned by `T = diag(Z, Z)`, `Z` an orthonormal
/// basis of the null space of `Phi_q` (from the eigenvectors of `Phi_q^T Phi_q`); the
/// equations keep it invariant (`d^2 Phi / dt^2 = 0`), so `A T = T A_r` with
/// `A_r = T^T A T` of size `2 (N - M)`. Shapes are mapped back to the full state (`T v`).
/// Without the restriction `A` also has a double zero per constraint: the drift off it.
///
/// Errors: [`Error::InvalidInput`] when `q` is not assembled (`|Phi| > 1e-9`) or the
/// constraints depend on time (`Phi_t != 0`: the tangent space then moves);
/// [`Error::SingularConstraintJacobian`] when `Phi_q` lacks full row rank; plus those of
/// [`linearize`] and [`modes`].
pub fn constrained_modes<S, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
) -> Result<Vec<Mode>>
where
    S: Constrained<N, M> + OdeSystem<D>,
{
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    let tm = tangent_basis::<S, N, M, D>(sys, t, q, "constrained_modes")?;
    let y = Vector::<D>::from_fn(|i, _| if i < N { q[i] } else { 0.0 });
    let a = linearize(sys, t, &y)?;
    let ad = DMatrix::from_iterator(D, D, a.iter().copied());
    let mut out = modes_of(tm.transpose() * ad * &tm)?;
    let tc = tm.map(|v| Complex::new(v, 0.0));
    for m in &mut out {
        m.shape = &tc * &m.shape;
        let big = largest(&m.shape);
        m.shape /= big;
    }
    Ok(out)
}

/// `T = diag(Z, Z)` (`D x 2 (N - M)`) at a rest state `q` on time-independent constraints,
/// with the checks of [`constrained_modes`].
fn tangent_basis<S, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    what: &'static str,
) -> Result<DMatrix<f64>>
where
    S: Constrained<N, M>,
{
    let bad = |detail: String| Error::InvalidInput { what, detail };
    let phi = sys.phi(t, q).abs().max();
    if phi.is_nan() || phi > 1e-9 {
        return Err(bad(format!("not assembled: |Phi| = {phi:.3e}")));
    }
    let phi_t = sys.phi_t(t, q).abs().max();
    if phi_t.is_nan() || phi_t > 0.0 {
        return Err(bad(format!(
            "time-dependent constraints: |Phi_t| = {phi_t:.3e}"
        )));
    }
    let z = null_space(&sys.phi_q(t, q)).ok_or(Error::SingularConstraintJacobian {
        t,
        detail: String::new(),
    })?;
    let r = z.ncols();
    let mut tm = DMatrix::<f64>::zeros(D, 2 * r);
    tm.view_mut((0, 0), (N, r)).copy_from(&z);
    tm.view_mut((N, r), (N, r)).copy_from(&z);
    Ok(tm)
}

/// An orthonormal basis (`N x (N - M)`) of the null space of `Phi_q`, `None` when `Phi_q`
/// lacks full row rank (eigenvalues of `Phi_q^T Phi_q` below `1e-10` of the largest count
/// as zero: rank loss shows as more of them than `N - M`).
fn null_space<const M: usize, const N: usize>(phi_q: &Matrix<M, N>) -> Option<DMatrix<f64>> {
    let g = phi_q.transpose() * phi_q;
    let eig = SymmetricEigen::try_new(
        DMatrix::from_iterator(N, N, g.iter().copied()),
        f64::EPSILON,
        10_000,
    )?;
    let top = eig.eigenvalues.amax();
    let zero: Vec<usize> = (0..N)
        .filter(|&i| eig.eigenvalues[i] <= 1e-10 * top)
        .collect();
    (top.is_finite() && zero.len() + M == N)
        .then(|| DMatrix::from_fn(N, zero.len(), |r, c| eig.eigenvectors[(r, zero[c])]))
}

/// A linear model `dx' = A dx + B du`, `dy = C dx + D du` about an operating point (`du`
/// the inputs' deviations from the struct's values), with the names of its columns/rows.
#[derive(Debug, Clone, PartialEq)]
pub struct StateSpace {
    pub a: DMatrix<f64>,
    pub b: DMatrix<f64>,
    pub c: DMatrix<f64>,
    pub d: DMatrix<f64>,
    pub inputs: Vec<&'static str>,
    pub outputs: Vec<&'static str>,
}

impl StateSpace {
    /// The frequency response `G(i w) = C (i w I - A)^-1 B + D` at `w` rad/s (outputs by
    /// inputs): the complex amplitude of each output per unit input `e^{i w t}` in steady
    /// state, meaningful where the operating point is stable.
    ///
    /// Errors: [`Error::InvalidInput`] for a non-finite `w` or where `i w` is an eigenvalue
    /// of `A` (an undamped resonance, a rigid-body mode at `w = 0`: the response is
    /// unbounded).
    pub fn frequency_response(&self, w: f64) -> Result<DMatrix<Complex<f64>>> {
        let bad = |detail: String| Error::InvalidInput {
            what: "frequency_response",
            detail,
        };
        if !w.is_finite() {
            return Err(bad(format!("w = {w}")));
        }
        let n = self.a.nrows();
        let c = |m: &DMatrix<f64>| m.map(|v| Complex::new(v, 0.0));
        let shifted = DMatrix::<Complex<f64>>::identity(n, n) * Complex::new(0.0, w) - c(&self.a);
        let x = shifted
            .lu()
            .solve(&c(&self.b))
            .filter(|x| x.iter().all(|v| v.re.is_finite() && v.im.is_finite()))
            .ok_or_else(|| bad(format!("i w is an eigenvalue of A at w = {w}")))?;
        Ok(c(&self.c) * x + c(&self.d))
    }

    /// The model as JSON, for a control design tool:
    /// `{"inputs": [..], "outputs": [..], "a": [[..], ..], "b": .., "c": .., "d": ..}`,
    /// each matrix as its rows, each number in Rust's shortest form that reads back as
    /// the same `f64`. The state is `[q; qd]` in the model's coordinate order
    /// ([`Mechanism::COORDINATES`]), or a closed loop's `x = T^T dy` from
    /// [`constrained_state_space`]. MATLAB: `s = jsondecode(fileread(f));
    /// sys = ss(s.a, s.b, s.c, s.d)`; Python: `numpy.array(json.load(f)["a"])`.
    ///
    /// Errors: [`Error::InvalidInput`] for a non-finite entry (JSON has no NaN or
    /// infinity) or matrices whose sizes do not fit together.
    pub fn to_json(&self) -> Result<String> {
        let bad = |detail: String| Error::InvalidInput {
            what: "to_json",
            detail,
        };
        let (n, m, p) = (self.a.nrows(), self.b.ncols(), self.c.nrows());
        let sizes = [
            ("a", &self.a, n, n),
            ("b", &self.b, n, m),
            ("c", &self.c, p, n),
            ("d", &self.d, p, m),
        ];
        for (name, x, r, c) in sizes {
            if x.shape() != (r, c) {
                return Err(bad(format!(
                    "{name} is {:?}, expected {:?}",
                    x.shape(),
                    (r, c)
                )));
            }
            if !x.iter().all(|v| v.is_finite()) {
                return Err(bad(format!("{name} has a non-finite entry")));
            }
        }
        if self.inputs.len() != m || self.outputs.len() != p {
            return Err(bad(
                "the names do not match the columns of B and rows of C".into()
            ));
        }
        let names = |v: &[&str]| {
            let quoted: Vec<String> = v.iter().map(|s| format!("{s:?}")).collect();
            format!("[{}]", quoted.join(", "))
        };
        let matrix = |x: &DMatrix<f64>| {
            let rows: Vec<String> = x
                .row_iter()
                .map(|r| {
                    let v: Vec<String> = r.iter().map(|v| format!("{v:?}")).collect();
                    format!("[{}]", v.join(", "))
                })
                .collect();
            format!("[{}]", rows.join(", "))
        };
        let body: Vec<String> = sizes
            .iter()
            .map(|(name, x, ..)| format!("  \"{name}\": {}", matrix(x)))
            .collect();
        Ok(format!(
            "{{\n  \"inputs\": {},\n  \"outputs\": {},\n{}\n}}\n",
            names(&self.inputs),
            names(&self.outputs),
            body.join(",\n")
        ))
    }
}

/// `A, B, C, D` at `(t, y)`, exact from one generated evaluation
/// ([`Parametric::linear_parts`]): `B = df/du`, `C = d out/dy`, `D = d out/du` for the
/// inputs `u` (`#[input(..)]`) and outputs (`#[output(..)]`).
///
/// Errors: the model's; [`Error::NonFinite`] for a non-finite entry.
pub fn state_space<S: Parametric<D>, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
) -> Result<StateSpace> {
    let lp = sys.linear_parts(t, y)?;
    Ok(StateSpace {
        b: lp.f_p.select_columns(S::INPUTS),
        d: lp.out_p.select_columns(S::INPUTS),
        a: lp.a,
        c: lp.out_y,
        inputs: S::INPUTS.iter().map(|&i| S::PARAMETERS[i]).collect(),
        outputs: S::OUTPUT_NAMES.to_vec(),
    })
}

/// How each mode's eigenvalue moves with the parameter `param` at the fixed state `y`:
/// `dlambda/dp = w^T (dA/dp) x / w^T x` (first-order perturbation of a simple eigenvalue;
/// right `A x = lambda x`, left `A^T w = lambda w`), beside the modes of [`modes`]. `dA/dp`
/// is `d(df/dp)/dy`, by central differences of the exact `df/dp`
/// ([`Parametric::linear_parts`]) with steps `1e-5 (1 + |y_j|)`: error `O(h^2)`, about
/// `1e-9` relative. The state is held: at an equilibrium that moves with `p` the total
/// derivative adds the change of `A` along `dy/dp`
/// ([`equilibrium_sensitivity`](super::equilibrium_sensitivity)). A neutral mode has `None`
/// (a zero of a Jordan block has no derivative); a repeated eigenvalue's is not defined.
///
/// Errors: [`Error::InvalidInput`] for a name that is not a parameter (the message lists
/// them); those of [`state_space`] and [`modes`].
pub fn mode_sensitivity<S: Parametric<D>, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    param: &str,
) -> Result<Vec<(Mode, Option<Complex<f64>>)>> {
    let p = S::PARAMETERS
        .iter()
        .position(|&n| n == param)
        .ok_or_else(|| Error::InvalidInput {
            what: "mode_sensitivity",
            detail: format!(
                "no parameter `{param}`; the parameters are {:?}",
                S::PARAMETERS
            ),
        })?;
    let a = sys.linear_parts(t, y)?.a;
    let mut da = DMatrix::<f64>::zeros(D, D);
    let mut yj = *y;
    for j in 0..D {
        let h = 1e-5 * (1.0 + y[j].abs());
        yj[j] = y[j] + h;
        let plus = sys.linear_parts(t, &yj)?.f_p.column(p).into_owned();
        yj[j] = y[j] - h;
        let minus = sys.linear_parts(t, &yj)?.f_p.column(p).into_owned();
        yj[j] = y[j];
        da.set_column(j, &((plus - minus) / (2.0 * h)));
    }
    let norm = a.abs().column_sum().max();
    let found = modes_of(a.clone())?;
    Ok(found
        .into_iter()
        .map(|m| {
            let d = (m.kind != ModeKind::Neutral)
                .then(|| two_sided_quotient(&a, m.eigenvalue, norm, &da));
            (m, d)
        })
        .collect())
}

/// [`state_space`] of a closed loop (augmented form) at rest on its constraints, in
/// independent coordinates `x = T^T dy` (`T = diag(Z, Z)` as in [`constrained_modes`]):
/// `A_r = T^T A T`, `B_r = T^T B`, `C_r = C T`, `D`; the map `T` back to the full state is
/// returned beside it.
///
/// Errors as [`constrained_modes`], and [`Error::InvalidInput`] when an input moves the
/// state off the tangent space (`|B - T T^T B| > 1e-9 |B|`: an input inside a constraint,
/// which this restriction does not model).
pub fn constrained_state_space<S, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
) -> Result<(StateSpace, DMatrix<f64>)>
where
    S: Constrained<N, M> + Parametric<D>,
{
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    let tm = tangent_basis::<S, N, M, D>(sys, t, q, "constrained_state_space")?;
    let y = Vector::<D>::from_fn(|i, _| if i < N { q[i] } else { 0.0 });
    let full = state_space(sys, t, &y)?;
    let b = tm.transpose() * &full.b;
    let off = (&full.b - &tm * &b).amax();
    if off > 1e-9 * full.b.amax() {
        return Err(Error::InvalidInput {
            what: "constrained_state_space",
            detail: format!("an input leaves the constraints' tangent space ({off:.3e})"),
        });
    }
    let reduced = StateSpace {
        a: tm.transpose() * &full.a * &tm,
        b,
        c: &full.c * &tm,
        d: full.d,
        inputs: full.inputs,
        outputs: full.outputs,
    };
    Ok((reduced, tm))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x'' + 6 x' + 36 x = 0`: `w_n = 6`, `zeta = 0.5`, `w_d = 3 sqrt(3)`; the shape's
    /// velocity is `lambda` times its position.
    #[test]
    fn damped_oscillator() {
        let a = Matrix::<2, 2>::new(0.0, 1.0, -36.0, -6.0);
        let m = &modes(&a).unwrap()[0];
        assert_eq!(m.kind, ModeKind::Oscillatory);
        assert!((m.omega_n - 6.0).abs() < 1e-14);
        assert!((m.damping_ratio.unwrap() - 0.5).abs() < 1e-15);
        assert!((m.omega_d - 27f64.sqrt()).abs() < 1e-14);
        assert!((m.shape[1] - m.eigenvalue * m.shape[0]).norm() < 1e-12);
        assert!(!m.unstable);
    }

    /// A null basis is orthonormal and annihilated; rank loss is refused.
    #[test]
    fn null_space_and_rank_loss() {
        let j = Matrix::<1, 3>::new(1.0, 2.0, -1.0);
        let z = null_space(&j).unwrap();
        assert_eq!(z.ncols(), 2);
        let jd = DMatrix::from_row_slice(1, 3, &[1.0, 2.0, -1.0]);
        assert!((&jd * &z).amax() < 1e-14);
        assert!((z.transpose() * &z - DMatrix::<f64>::identity(2, 2)).amax() < 1e-14);
        let dependent = Matrix::<2, 3>::new(1.0, 2.0, -1.0, 2.0, 4.0, -2.0);
        assert!(null_space(&dependent).is_none());
    }
}
