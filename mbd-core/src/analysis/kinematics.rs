//! Kinematic analysis of a driven mechanism with zero degrees of freedom: as many
//! constraints (loop closures plus drivers) as coordinates, so the motion follows from the
//! constraints alone (Haug 1989, ch. 3):
//! positions from `Phi(q, t) = 0` (Newton), velocities from `Phi_q qd = -Phi_t`,
//! accelerations from `Phi_q qdd = gamma`.

use super::{NewtonOptions, assemble, min_norm_solve};
use crate::error::{Error, Result};
use crate::model::{Constrained, Vector};

/// Positions, velocities and accelerations of a zero-DOF mechanism at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KinematicState<const N: usize> {
    /// Time.
    pub t: f64,
    /// Coordinates `q(t)`.
    pub q: Vector<N>,
    /// Velocities `qd(t)`.
    pub qd: Vector<N>,
    /// Accelerations `qdd(t)`.
    pub qdd: Vector<N>,
}

/// The kinematic state at `t`, assembling from the position guess `q_guess`.
///
/// Errors: [`Error::AssemblyFailed`] when Newton does not converge,
/// [`Error::SingularConstraintJacobian`] at a toggle (dead-centre) position, where the
/// drivers no longer determine the motion.
pub fn kinematics<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q_guess: &Vector<N>,
    opts: &NewtonOptions,
) -> Result<KinematicState<N>> {
    const {
        assert!(
            N == M,
            "kinematic analysis needs as many constraints (closures and drives) as coordinates: \
             a mechanism with free coordinates is integrated, its state assembled with \
             analysis::assemble"
        )
    };
    let q = assemble(sys, t, q_guess, &[false; N], opts)?;
    let all = [true; N];
    let jac = sys.phi_q(t, &q);
    let singular = Error::SingularConstraintJacobian { t };
    let qd = min_norm_solve(&jac, &all, &(-sys.phi_t(t, &q))).ok_or(singular.clone())?;
    let qdd = min_norm_solve(&jac, &all, &sys.gamma(t, &q, &qd)).ok_or(singular)?;
    Ok(KinematicState { t, q, qd, qdd })
}

/// The kinematic state at each of `times` (in order), each assembly starting from the
/// previous state's second-order Taylor prediction `q + qd dt + qdd dt^2 / 2`, which keeps
/// Newton on the same branch (assembly mode) of the mechanism.
pub fn kinematic_sweep<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    times: &[f64],
    q_guess: &Vector<N>,
    opts: &NewtonOptions,
) -> Result<Vec<KinematicState<N>>> {
    let mut out: Vec<KinematicState<N>> = Vec::with_capacity(times.len());
    for &t in times {
        let guess = match out.last() {
            Some(s) => {
                let dt = t - s.t;
                s.q + s.qd * dt + s.qdd * (0.5 * dt * dt)
            }
            None => *q_guess,
        };
        out.push(kinematics(sys, t, &guess, opts)?);
    }
    Ok(out)
}
