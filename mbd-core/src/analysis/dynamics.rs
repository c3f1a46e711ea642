//! Inverse dynamics: accelerations, Lagrange multipliers and constraint forces of a
//! constrained mechanism at a given state.
//!
//! Sign convention (that of [`Constrained`]): `M qdd + Phi_q^T lambda = f`. The generalised
//! force the constraints exert on the coordinates is therefore `Q_c = -Phi_q^T lambda`.
//! For a driving constraint `q_k - s(t) = 0` the driver's effort on `q_k` (force or torque)
//! is `-lambda_k`; for a joint relaxed by a coordinate `u` pinned by `u = 0`, the reaction
//! the joint applies along `u` is `-lambda`. The power of the constraint forces is
//! `Q_c . qd = lambda . Phi_t`: only drivers (time-dependent constraints) do work
//! (Haug 1989, ch. 6).

use crate::error::Result;
use crate::model::{Constrained, Vector};

/// What the constraints do at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reactions<const N: usize, const M: usize> {
    /// Accelerations `qdd`.
    pub qdd: Vector<N>,
    /// Lagrange multipliers `lambda` of `M qdd + Phi_q^T lambda = f`.
    pub lambda: Vector<M>,
    /// Generalised constraint forces `Q_c = -Phi_q^T lambda`.
    pub constraint_forces: Vector<N>,
}

/// `qdd`, `lambda` and `-Phi_q^T lambda` at `(t, q, qd)`, from
/// `[M Phi_q^T; Phi_q 0] [qdd; lambda] = [f; gamma]` (the model's
/// [`Constrained::acceleration_and_multipliers`]). For a zero-DOF driven mechanism at a
/// state from [`kinematics`](super::kinematics::kinematics) this is the classic inverse-dynamics
/// problem: the multipliers of the drivers are minus the driving efforts.
pub fn inverse_dynamics<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
) -> Result<Reactions<N, M>> {
    let (qdd, lambda) = sys.acceleration_and_multipliers(t, q, qd)?;
    let constraint_forces = -(sys.phi_q(t, q).transpose() * lambda);
    Ok(Reactions {
        qdd,
        lambda,
        constraint_forces,
    })
}
