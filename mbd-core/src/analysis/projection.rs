//! Projection of a closed loop's state back onto the constraint manifolds after an
//! integration step of the index-1 equations, which conserve `Phi = 0` and
//! `Phi_q qd + Phi_t = 0` only up to the truncation error (drift).
//!
//! Both projections use the kinetic-energy metric `M`: the correction is the smallest in
//! `|dq|_M` (resp. `|dqd|_M`) that restores the constraint, which leaves the motion
//! allowed by the constraints untouched (Hairer, Lubich & Wanner, *Geometric Numerical
//! Integration*, 2nd ed., Sect. IV.4; Eich, SIAM J. Numer. Anal. 30, 1993).
//! Position: `q <- q - M^-1 Phi_q^T (Phi_q M^-1 Phi_q^T)^-1 Phi`, iterated (Gauss–Newton);
//! velocity: `qd <- qd - M^-1 Phi_q^T (Phi_q M^-1 Phi_q^T)^-1 (Phi_q qd + Phi_t)`.

use super::{NewtonOptions, max_norm, negligible};
use crate::augmented::AugmentedLagrangian;
use crate::error::{Error, Result};
use crate::model::{Constrained, Matrix, Vector};

/// `(max |Phi_i(q, t)|, max |(Phi_q qd + Phi_t)_i|)`: how far a state is from the position
/// and velocity constraint manifolds.
pub fn constraint_drift<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
) -> (f64, f64) {
    let position = max_norm(&sys.phi(t, q));
    let velocity = max_norm(&(sys.phi_q(t, q) * qd + sys.phi_t(t, q)));
    (position, velocity)
}

/// The `M`-orthogonal correction `dx = -M^-1 J^T (J M^-1 J^T)^-1 r` that makes `J (x + dx) = J x - r`,
/// as the saddle-point system `[M J^T; J 0] [dx; mu] = [0; -r]` solved by the augmented
/// Lagrangian: where `J` lost rank, the `M`-weighted least-squares correction.
pub(crate) fn metric_correction<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    jac: &Matrix<M, N>,
    r: &Vector<M>,
) -> Result<Vector<N>> {
    let mass = sys.mass_matrix(t, q)?;
    // A large assembly well away from a singular position: the exact correction by one
    // banded L D L^T (what the iteration below converges to there, at a fraction of its cost).
    let exact = crate::banded::saddle_point_well_conditioned(&mass, &Vector::zeros(), jac, &(-r));
    let dx = match exact {
        Some((dx, _)) => dx,
        None => {
            AugmentedLagrangian::new(t, &mass, jac)?.solve_least_squares(&Vector::zeros(), &(-r))?
        }
    };
    if dx.iter().all(|v| v.is_finite()) {
        Ok(dx)
    } else {
        Err(Error::NonFinite { t })
    }
}

/// Project `q` onto `Phi(q, t) = 0` in the mass-matrix metric, iterating the Gauss–Newton
/// step until `max |Phi_i| <= tol` or the step is at rounding level ([`NewtonOptions::tol`]).
///
/// Errors: [`Error::AssemblyFailed`] when the iterations run out,
/// [`Error::SingularConstraintJacobian`] when `Phi_q` lost rank,
/// [`Error::SingularMassMatrix`] when `M` is singular (the metric needs `M^-1`).
pub fn project_positions<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &mut Vector<N>,
    opts: &NewtonOptions,
) -> Result<()> {
    opts.validate()?;
    let mut iterations = 0;
    loop {
        let phi = sys.phi(t, q);
        let residual = max_norm(&phi);
        if !residual.is_finite() {
            return Err(Error::NonFinite { t });
        }
        if residual <= opts.tol {
            return Ok(());
        }
        if iterations == opts.max_iterations {
            return Err(Error::AssemblyFailed {
                t,
                iterations,
                residual,
                detail: super::assembly::where_(sys, t, q, &[true; N]),
            });
        }
        let dq = metric_correction(sys, t, q, &sys.phi_q(t, q), &phi)?;
        *q += dq;
        if negligible(&dq, q) {
            return Ok(());
        }
        iterations += 1;
    }
}

/// Project `qd` onto `Phi_q qd + Phi_t = 0` in the mass-matrix metric (one linear solve:
/// the velocity constraint is linear in `qd`).
pub fn project_velocities<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &mut Vector<N>,
) -> Result<()> {
    let jac = sys.phi_q(t, q);
    let violation = jac * *qd + sys.phi_t(t, q);
    *qd += metric_correction(sys, t, q, &jac, &violation)?;
    Ok(())
}

/// Project the first-order state `y = [q; qd]` (`D = 2 N`) onto both manifolds: positions
/// first, then the velocities at the projected positions. Generated closed-loop models
/// call it from [`OdeSystem::project`](crate::OdeSystem::project), with the default
/// [`NewtonOptions`].
pub fn project_state<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &mut Vector<D>,
) -> Result<()> {
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    let mut q = y.fixed_rows::<N>(0).into_owned();
    let mut qd = y.fixed_rows::<N>(N).into_owned();
    project_positions(sys, t, &mut q, &NewtonOptions::default())?;
    project_velocities(sys, t, &q, &mut qd)?;
    y.fixed_rows_mut::<N>(0).copy_from(&q);
    y.fixed_rows_mut::<N>(N).copy_from(&qd);
    Ok(())
}
