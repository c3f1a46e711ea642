//! The linear solves behind accelerations: `M qdd = f` and the augmented constrained system.

use crate::augmented::AugmentedLagrangian;
use crate::error::{Error, Result};
use crate::linalg::Lu;
use crate::model::{Constrained, Matrix, Vector};

/// `qdd` from `M qdd = f` by `L D L^T`. A mass matrix is symmetric positive definite; one
/// that is not is refused, not solved: NaN or infinite entries ([`Error::NonFinite`]), a
/// singular one, or an indefinite one (a negative mass or inertia,
/// [`Error::MassMatrixNotPositiveDefinite`]).
pub fn solve_mass<const N: usize>(t: f64, mass: &Matrix<N, N>, f: &Vector<N>) -> Result<Vector<N>> {
    if N == 1 {
        // One coordinate: `f * (1 / m)`, whose reciprocal an integrator loop can hoist
        // when the mass is constant (a pendulum's `m l^2`), as hand-written code does.
        let m = mass[(0, 0)];
        if !(m > 0.0 && m.is_finite()) {
            return Err(not_positive(t, mass));
        }
        return finite(t, f * (1.0 / m));
    }
    match crate::linalg::solve_spd(mass, f) {
        Some(x) => finite(t, x),
        None => Err(not_positive(t, mass)),
    }
}

/// Why a mass matrix failed `L D L^T` (the error path only).
#[cold]
fn not_positive<const N: usize>(t: f64, mass: &Matrix<N, N>) -> Error {
    if mass.iter().any(|v| !v.is_finite()) {
        Error::NonFinite { t }
    } else if Lu::factor(*mass).is_none() {
        Error::SingularMassMatrix { t }
    } else {
        Error::MassMatrixNotPositiveDefinite { t }
    }
}

/// The acceleration `a` of a one-coordinate model, computed by generated code as `f / m`
/// with the factors they share cancelled: refused (typed error) when the mass `m` is zero or
/// not finite, or `a` is not finite.
#[inline]
pub fn one_coordinate(t: f64, m: f64, a: f64) -> Result<Vector<1>> {
    // Two plain comparisons each (`is_finite` here became integer class tests).
    if m > 0.0 && m < f64::INFINITY && a.abs() < f64::INFINITY {
        Ok(Vector::<1>::new(a))
    } else if !(m > 0.0 && m < f64::INFINITY) {
        Err(not_positive(t, &Matrix::<1, 1>::new(m)))
    } else {
        Err(Error::NonFinite { t })
    }
}

/// `(qdd, lambda)` from `[M Phi_q^T; Phi_q 0] [qdd; lambda] = [f; gamma]` (`A = N + M`), by
/// the augmented Lagrangian of [`crate::augmented`]: it stays regular where `Phi_q` loses rank
/// (singular positions, redundant constraints; `lambda` is then the minimum-norm one) and
/// where `M` alone is singular (massless coordinates fixed by constraints), and costs the
/// profile of `M + Phi_q^T Phi_q`, not `(N + M)^3`. Near a singular position, where the
/// exact solve would divide the state's drift by a vanishing singular value of `Phi_q`, the
/// penalty-regularised solution ([`AugmentedLagrangian::solve_regularized`]) while it meets
/// the constraints closely (an integrator steps through; the projection after each step
/// restores them), else [`crate::Error::SingularPosition`].
pub fn solve_augmented<const N: usize, const M: usize, const A: usize>(
    t: f64,
    mass: &Matrix<N, N>,
    f: &Vector<N>,
    phi_q: &Matrix<M, N>,
    gamma: &Vector<M>,
) -> Result<(Vector<N>, Vector<M>)> {
    const { assert!(A == N + M, "augmented size must be N + M") };
    if A <= DENSE_MAX
        && let Some(qdd_lambda) = dense_saddle_point::<N, M, A>(mass, f, phi_q, gamma)
    {
        return Ok(qdd_lambda);
    }
    // Larger ones, while banded and well conditioned: one banded LU (crate::banded).
    if A > DENSE_MAX
        && let Some(qdd_lambda) = crate::banded::saddle_point(mass, f, phi_q, gamma)
    {
        return Ok(qdd_lambda);
    }
    let s = AugmentedLagrangian::new(t, mass, phi_q)?.solve_regularized(f, gamma)?;
    Ok((finite(t, s.x)?, finite(t, s.lambda)?))
}

/// [`solve_augmented`] with `M` and `Phi_q` given by their non-zeros `(row, column, value)`
/// (`M` by its lower triangle and diagonal): what generated code passes for a large
/// assembly, whose dense matrices are mostly zeros. One banded LU (crate::banded) while it is
/// well conditioned, else [`solve_constrained`] on the dense matrices built from them.
#[allow(
    clippy::too_many_arguments,
    reason = "the state and the blocks of one system"
)]
pub fn solve_augmented_sparse<
    S: Constrained<N, M>,
    const N: usize,
    const M: usize,
    const A: usize,
>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
    mass: &[(usize, usize, f64)],
    f: &Vector<N>,
    phi_q: &[(usize, usize, f64)],
    gamma: &Vector<M>,
) -> Result<(Vector<N>, Vector<M>)> {
    if let Some(qdd_lambda) = crate::banded::saddle_point_sparse::<N, M>(mass, f, phi_q, gamma) {
        return Ok(qdd_lambda);
    }
    let mut m = Matrix::<N, N>::zeros();
    for &(i, j, v) in mass {
        m[(i, j)] = v;
        m[(j, i)] = v;
    }
    let mut p = Matrix::<M, N>::zeros();
    for &(k, j, v) in phi_q {
        p[(k, j)] = v;
    }
    solve_constrained::<S, N, M, A>(sys, t, q, qd, &m, f, &p, gamma)
}

/// [`solve_augmented`] for a closed loop's state `(q, qd)`; where it stops with
/// [`Error::SingularPosition`], the accelerations at the state projected onto the
/// constraint manifolds (mass-orthogonally, to the default tolerance) if the rows that are
/// nearly dependent at `(q, qd)` are dependent to rounding there: redundant constraints
/// (the Bricard linkage), whose rows are only nearly dependent off the manifold, so that
/// the drift of an integrated state looks like a singular position. A singular position
/// (rows that vanish only at one instant) keeps the error: its rows are independent at
/// the projected state, and its accelerations are not determined by one state there.
/// Generated closed-loop models call it.
#[allow(
    clippy::too_many_arguments,
    reason = "the state and the blocks of one system"
)]
pub fn solve_constrained<S: Constrained<N, M>, const N: usize, const M: usize, const A: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
    mass: &Matrix<N, N>,
    f: &Vector<N>,
    phi_q: &Matrix<M, N>,
    gamma: &Vector<M>,
) -> Result<(Vector<N>, Vector<M>)> {
    match solve_augmented::<N, M, A>(t, mass, f, phi_q, gamma) {
        Err(e @ Error::SingularPosition { .. }) => redundant_at_projection(sys, t, q, qd).ok_or(e),
        other => other,
    }
}

/// The accelerations and multipliers at the projection of `(q, qd)` when `Phi_q` there
/// has dependent rows to [`crate::analysis::RANK_TOL`] and the augmented solve converges
/// (consistent to rounding); `None` otherwise.
fn redundant_at_projection<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
) -> Option<(Vector<N>, Vector<M>)> {
    use crate::analysis::{
        NewtonOptions, project_positions, project_velocities, rank_and_redundant,
    };
    let (mut q, mut qd) = (*q, *qd);
    project_positions(sys, t, &mut q, &NewtonOptions::default()).ok()?;
    project_velocities(sys, t, &q, &mut qd).ok()?;
    let phi_q = sys.phi_q(t, &q);
    if rank_and_redundant(&phi_q).1.is_empty() {
        return None;
    }
    let mass = sys.mass_matrix(t, &q).ok()?;
    let s = AugmentedLagrangian::new(t, &mass, &phi_q)
        .ok()?
        .solve(&sys.forces(t, &q, &qd).ok()?, &sys.gamma(t, &q, &qd))
        .ok()?;
    Some((finite(t, s.x).ok()?, finite(t, s.lambda).ok()?))
}

/// Saddle-point systems up to this size (`N + M`) are first tried by one dense LU on the
/// stack: for a small loop (a slider-crank's 5) it costs less than the augmented
/// Lagrangian's profile setup and allocations.
const DENSE_MAX: usize = 24;
/// The LU answers only while its pivots stay within this ratio: a nearly singular
/// system (a singular position, redundant rows) goes to the rank-robust solve.
const DENSE_PIVOT_RATIO: f64 = 1e-8;

/// `(qdd, lambda)` by dense LU of `[M Phi_q^T; Phi_q 0]` when it is well conditioned
/// (pivot ratio above [`DENSE_PIVOT_RATIO`]) and the result finite; `None` otherwise.
fn dense_saddle_point<const N: usize, const M: usize, const A: usize>(
    mass: &Matrix<N, N>,
    f: &Vector<N>,
    phi_q: &Matrix<M, N>,
    gamma: &Vector<M>,
) -> Option<(Vector<N>, Vector<M>)> {
    let k = Matrix::<A, A>::from_fn(|i, j| match (i < N, j < N) {
        (true, true) => mass[(i, j)],
        (true, false) => phi_q[(j - N, i)],
        (false, true) => phi_q[(i - N, j)],
        (false, false) => 0.0,
    });
    let lu = Lu::factor(k)?;
    if lu.pivot_ratio() < DENSE_PIVOT_RATIO {
        return None;
    }
    let z = lu.solve(&Vector::<A>::from_fn(|i, _| {
        if i < N { f[i] } else { gamma[i - N] }
    }));
    let qdd = Vector::<N>::from_fn(|i, _| z[i]);
    let lambda = Vector::<M>::from_fn(|i, _| z[N + i]);
    z.iter().all(|v| v.is_finite()).then_some((qdd, lambda))
}

/// `x`, or [`Error::NonFinite`] if any entry is NaN or infinite: no NaN reaches the user.
#[inline]
pub fn finite<const N: usize>(t: f64, x: Vector<N>) -> Result<Vector<N>> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(x)
    } else {
        Err(Error::NonFinite { t })
    }
}

/// `y' = [qd; qdd]` as a model wrote it in place, or [`Error::NonFinite`] if an acceleration
/// (its lower half) is NaN or infinite.
#[inline]
pub fn finite_accelerations<const N: usize, const D: usize>(
    t: f64,
    dy: Vector<D>,
) -> Result<Vector<D>> {
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    if dy.iter().skip(N).all(|v| v.is_finite()) {
        Ok(dy)
    } else {
        Err(Error::NonFinite { t })
    }
}

/// `y' = [qd; qdd]` for a second-order model with `y = [q; qd]` (`D = 2 N`).
#[inline]
pub fn second_order_rhs<const N: usize, const D: usize>(
    y: &Vector<D>,
    acceleration: impl FnOnce(&Vector<N>, &Vector<N>) -> Result<Vector<N>>,
) -> Result<Vector<D>> {
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    let q = Vector::<N>::from_fn(|i, _| y[i]);
    let qd = Vector::<N>::from_fn(|i, _| y[N + i]);
    let qdd = acceleration(&q, &qd)?;
    Ok(Vector::<D>::from_fn(
        |i, _| if i < N { qd[i] } else { qdd[i - N] },
    ))
}

/// `df/dy = [0 I; dqdd/dq dqdd/dqd]` for `y = [q; qd]`.
pub fn second_order_jacobian<const N: usize, const D: usize>(
    dqdd_dq: &Matrix<N, N>,
    dqdd_dqd: &Matrix<N, N>,
) -> Matrix<D, D> {
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    let mut j = Matrix::<D, D>::zeros();
    j.fixed_view_mut::<N, N>(0, N).fill_with_identity();
    j.fixed_view_mut::<N, N>(N, 0).copy_from(dqdd_dq);
    j.fixed_view_mut::<N, N>(N, N).copy_from(dqdd_dqd);
    j
}

/// `(dqdd/dq, dqdd/dqd)` from the derivatives of the residuals `R = M qdd + Phi_q^T lambda - f`
/// and `C = Phi_q qdd - gamma` taken at fixed `(qdd, lambda)`: differentiating
/// `[M Phi_q^T; Phi_q 0] [qdd; lambda] = [f; gamma]` gives
/// `[M Phi_q^T; Phi_q 0] [qdd_x; lambda_x] = -[R_x; C_x]` for `x = q, qd`.
#[allow(clippy::too_many_arguments, reason = "the blocks of one linear system")]
pub fn acceleration_jacobian<const N: usize, const M: usize, const A: usize>(
    t: f64,
    mass: &Matrix<N, N>,
    phi_q: &Matrix<M, N>,
    r_q: &Matrix<N, N>,
    r_qd: &Matrix<N, N>,
    c_q: &Matrix<M, N>,
    c_qd: &Matrix<M, N>,
) -> Result<(Matrix<N, N>, Matrix<N, N>)> {
    let saddle = Saddle::<N, M, A>::new(t, mass, phi_q)?;
    let solve = |r: &Matrix<N, N>, c: &Matrix<M, N>| -> Result<Matrix<N, N>> {
        let mut out = Matrix::<N, N>::zeros();
        for j in 0..N {
            let (x, _) = saddle.solve(&(-r.column(j)), &(-c.column(j)))?;
            out.set_column(j, &x);
        }
        Ok(out)
    };
    let (a_q, a_qd) = (solve(r_q, c_q)?, solve(r_qd, c_qd)?);
    if a_q.iter().chain(a_qd.iter()).all(|v| v.is_finite()) {
        Ok((a_q, a_qd))
    } else {
        Err(Error::NonFinite { t })
    }
}

/// `[M Phi_q^T; Phi_q 0]` factored once for several right-hand sides (the columns of a
/// Jacobian): `L D L^T` of `M` without constraints; with them the dense LU of
/// [`solve_augmented`] when small and well conditioned, else the augmented Lagrangian
/// (regularised near a singular position, as there).
#[derive(Debug)]
#[allow(
    clippy::large_enum_variant,
    reason = "built once per Jacobian on the stack, never stored"
)]
pub enum Saddle<'a, const N: usize, const M: usize, const A: usize> {
    Mass(crate::linalg::Ldl<N>),
    Dense(Lu<f64, A>),
    Augmented(AugmentedLagrangian<'a, N, M>),
}

impl<'a, const N: usize, const M: usize, const A: usize> Saddle<'a, N, M, A> {
    /// Errors: [`Error::MassMatrixNotPositiveDefinite`] (and its relatives) without
    /// constraints, those of [`AugmentedLagrangian::new`] with them.
    pub fn new(t: f64, mass: &'a Matrix<N, N>, phi_q: &Matrix<M, N>) -> Result<Self> {
        const { assert!(A == N + M, "augmented size must be N + M") };
        if M == 0 {
            return crate::linalg::Ldl::factor(mass)
                .map(Saddle::Mass)
                .ok_or_else(|| not_positive(t, mass));
        }
        if A <= DENSE_MAX {
            let k = Matrix::<A, A>::from_fn(|i, j| match (i < N, j < N) {
                (true, true) => mass[(i, j)],
                (true, false) => phi_q[(j - N, i)],
                (false, true) => phi_q[(i - N, j)],
                (false, false) => 0.0,
            });
            if let Some(lu) = Lu::factor(k).filter(|lu| lu.pivot_ratio() >= DENSE_PIVOT_RATIO) {
                return Ok(Saddle::Dense(lu));
            }
        }
        AugmentedLagrangian::new(t, mass, phi_q).map(Saddle::Augmented)
    }

    /// `(x, lambda)` with `M x + Phi_q^T lambda = u`, `Phi_q x = b`.
    pub fn solve(&self, u: &Vector<N>, b: &Vector<M>) -> Result<(Vector<N>, Vector<M>)> {
        match self {
            Saddle::Mass(ldl) => Ok((ldl.solve(u), Vector::<M>::zeros())),
            Saddle::Dense(lu) => {
                let z = lu.solve(&Vector::<A>::from_fn(
                    |i, _| if i < N { u[i] } else { b[i - N] },
                ));
                Ok((
                    Vector::<N>::from_fn(|i, _| z[i]),
                    Vector::<M>::from_fn(|i, _| z[N + i]),
                ))
            }
            Saddle::Augmented(al) => al.solve_regularized(u, b).map(|s| (s.x, s.lambda)),
        }
    }
}

/// `sum x_i y_i` in twice the working precision, rounded once (Ogita, Rump and Oishi's
/// `Dot2`, SIAM J. Sci. Comput. 26, 2005: each product split exactly by a fused
/// multiply-add, each sum by Knuth's two-sum): the residuals of iterative refinement.
pub fn dot2(terms: impl IntoIterator<Item = (f64, f64)>) -> f64 {
    let (mut s, mut c) = (0.0f64, 0.0f64);
    for (x, y) in terms {
        let p = x * y;
        let pe = x.mul_add(y, -p);
        let t = s + p;
        let z = t - s;
        c += (s - (t - z)) + (p - z) + pe;
        s = t;
    }
    s + c
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `1e16 + 1 - 1e16` is 1 in twice the precision (0 summed in `f64`), and the product's
    /// low part counts: `(1 + 2^-30)^2 - 1 - 2^-29 = 2^-60`.
    #[test]
    fn dot2_sums_in_twice_the_precision() {
        assert_eq!(dot2([(1e16, 1.0), (1.0, 1.0), (-1e16, 1.0)]), 1.0);
        let x = 1.0 + 2f64.powi(-30);
        assert_eq!(
            dot2([(x, x), (-1.0, 1.0), (-(2f64.powi(-29)), 1.0)]),
            2f64.powi(-60)
        );
    }

    /// One coordinate: `f / m`, and a zero or non-finite mass is a typed error, not a NaN.
    #[test]
    fn scalar_mass_solve() {
        let f = Vector::<1>::new(-3.0);
        let x = solve_mass::<1>(0.0, &Matrix::<1, 1>::new(0.5), &f).unwrap();
        assert_eq!(x[0], -6.0);
        let err = |m: f64| solve_mass::<1>(2.0, &Matrix::<1, 1>::new(m), &f).unwrap_err();
        assert_eq!(err(0.0), Error::SingularMassMatrix { t: 2.0 });
        assert_eq!(err(-1.0), Error::MassMatrixNotPositiveDefinite { t: 2.0 });
        for m in [f64::NAN, f64::INFINITY] {
            assert_eq!(err(m), Error::NonFinite { t: 2.0 });
        }
        let err = solve_mass::<1>(1.0, &Matrix::<1, 1>::new(1.0), &Vector::<1>::new(f64::NAN));
        assert_eq!(err.unwrap_err(), Error::NonFinite { t: 1.0 });
    }

    /// An indefinite mass matrix (a negative mass) is refused, not solved by LU; a singular
    /// one and one with a NaN entry are told apart.
    #[test]
    fn mass_matrix_must_be_positive_definite() {
        let f = Vector::<2>::new(1.0, 1.0);
        let indefinite = Matrix::<2, 2>::new(2.0, 0.0, 0.0, -1.0);
        let err = solve_mass::<2>(0.5, &indefinite, &f).unwrap_err();
        assert_eq!(err, Error::MassMatrixNotPositiveDefinite { t: 0.5 });
        let singular = Matrix::<2, 2>::new(1.0, 1.0, 1.0, 1.0);
        assert_eq!(
            solve_mass::<2>(0.5, &singular, &f).unwrap_err(),
            Error::SingularMassMatrix { t: 0.5 }
        );
        let nan = Matrix::<2, 2>::new(1.0, 0.0, 0.0, f64::NAN);
        assert_eq!(
            solve_mass::<2>(0.5, &nan, &f).unwrap_err(),
            Error::NonFinite { t: 0.5 }
        );
        let x = solve_mass::<2>(0.5, &Matrix::<2, 2>::new(2.0, 1.0, 1.0, 2.0), &f).unwrap();
        assert!((x[0] - 1.0 / 3.0).abs() < 1e-15 && (x[1] - 1.0 / 3.0).abs() < 1e-15);
    }

    /// A tree's in-place `y'`: passed on when its accelerations are finite, refused when one
    /// is not; its velocity half is the caller's state and is not judged here.
    #[test]
    fn finite_accelerations_checks_the_lower_half() {
        let dy = Vector::<4>::new(1.0, 2.0, -3.0, 4.0);
        assert_eq!(finite_accelerations::<2, 4>(0.5, dy).unwrap(), dy);
        for bad in [f64::NAN, f64::INFINITY] {
            let mut dy = dy;
            dy[3] = bad;
            let err = finite_accelerations::<2, 4>(0.5, dy).unwrap_err();
            assert_eq!(err, Error::NonFinite { t: 0.5 });
        }
    }

    /// The generated one-coordinate form: the acceleration passes when the mass is usable.
    #[test]
    fn one_coordinate_checks_the_mass_and_the_result() {
        assert_eq!(one_coordinate(0.0, 2.0, -4.5).unwrap()[0], -4.5);
        assert_eq!(
            one_coordinate(3.0, 0.0, 1.0).unwrap_err(),
            Error::SingularMassMatrix { t: 3.0 }
        );
        assert_eq!(
            one_coordinate(3.0, -2.0, 1.0).unwrap_err(),
            Error::MassMatrixNotPositiveDefinite { t: 3.0 }
        );
        for m in [f64::NAN, f64::NEG_INFINITY] {
            let err = one_coordinate(3.0, m, 1.0).unwrap_err();
            assert_eq!(err, Error::NonFinite { t: 3.0 });
        }
        let err = one_coordinate(1.0, 1.0, f64::INFINITY).unwrap_err();
        assert_eq!(err, Error::NonFinite { t: 1.0 });
    }
}
