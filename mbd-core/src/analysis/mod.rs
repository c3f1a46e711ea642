//! Analyses of a mechanism at given instants, as opposed to time integration: assembly
//! (closing the loops), kinematic analysis of a driven zero-DOF system, inverse dynamics
//! (multipliers and constraint forces), static equilibrium, and projection onto the
//! constraint manifolds after an integration step.
//!
//! Everything follows Haug, *Computer-Aided Kinematics and Dynamics of Mechanical Systems*
//! (1989), ch. 3 and 6, with the sign convention of [`Constrained`](crate::Constrained):
//! `M qdd + Phi_q^T lambda = f`.

pub mod assembly;
pub mod dynamics;
pub mod kinematics;
pub mod linear;
pub mod projection;
pub mod redundancy;
pub mod sensitivity;
pub mod singular;
pub mod statics;

pub use assembly::{assemble, consistent_velocities};
pub use dynamics::{Reactions, inverse_dynamics};
pub use kinematics::{KinematicState, kinematic_sweep, kinematics};
pub use linear::{
    Mode, ModeKind, NormalMode, StateSpace, constrained_modes, constrained_state_space,
    constrained_undamped_modes, linearize, mode_sensitivity, modes, state_space, undamped_modes,
};
pub use projection::{constraint_drift, project_positions, project_state, project_velocities};
pub use redundancy::{rank_and_redundant, redundant_constraints};
pub use sensitivity::{LinearParts, Parametric, Sensitivity, equilibrium_sensitivity};
pub use singular::check_passages;
pub use statics::{static_equilibrium, static_equilibrium_constrained};

use crate::model::{Matrix, Vector};

/// Stopping rule of the Newton iterations of the analyses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Assembly, kinematics and projection converge when `max |Phi_i| <= tol` (in the
    /// model's units), or when the Newton update has shrunk to rounding,
    /// `|dq_i| <= 8 eps max(1, |q_i|)`, for a model so large that rounding keeps `Phi` above
    /// `tol`. Statics converges when every component of the Newton step is
    /// `|dz_i| <= tol (1 + |z_i|)`.
    pub tol: f64,
    /// Iterations allowed before [`Error::AssemblyFailed`](crate::Error::AssemblyFailed).
    pub max_iterations: usize,
}

impl Default for NewtonOptions {
    /// `tol = 1e-12`, `max_iterations = 50`.
    fn default() -> Self {
        NewtonOptions {
            tol: 1e-12,
            max_iterations: 50,
        }
    }
}

impl NewtonOptions {
    /// Reject a tolerance that is not positive and finite, or zero iterations.
    pub fn validate(&self) -> crate::Result<()> {
        if !(self.tol > 0.0 && self.tol.is_finite()) {
            return Err(crate::Error::InvalidInput {
                what: "tol",
                detail: format!(
                    "must be positive and finite, got {}",
                    crate::error::Num(self.tol)
                ),
            });
        }
        if self.max_iterations == 0 {
            return Err(crate::Error::InvalidInput {
                what: "max_iterations",
                detail: "must be at least 1".to_string(),
            });
        }
        Ok(())
    }
}

/// Relative size below which a row of a constraint Jacobian counts as dependent on the
/// rows before it (rank loss): `|r_kk| <= RANK_TOL max_i |row_i|` in the QR factorisation.
pub const RANK_TOL: f64 = 1e-10;

/// The minimum-norm solution `x` of `J_F x_F = b` over the free columns `F` (`x_i = 0` for
/// the columns not in `F`), or `None` when `J_F` lacks full row rank.
///
/// `J_F^T = Q R` by modified Gram–Schmidt with one re-orthogonalisation (Giraud, Langou &
/// Rozložník, Comput. Math. Appl. 50, 2005: twice is enough for orthogonality to rounding);
/// then `J_F = R^T Q^T`, and `x = Q z` with `R^T z = b` is the minimum-norm solution
/// (Golub & Van Loan, *Matrix Computations*, 4th ed., Sect. 5.6). Unlike the normal
/// equations `J J^T` this does not square the condition number, and a small `r_kk` reveals
/// rank loss directly. For a square `J_F` it is the unique solution.
pub(crate) fn min_norm_solve<const N: usize, const M: usize>(
    j: &Matrix<M, N>,
    free: &[bool; N],
    b: &Vector<M>,
) -> Option<Vector<N>> {
    let mut q = j.transpose();
    for (c, &is_free) in free.iter().enumerate() {
        if !is_free {
            q.row_mut(c).fill(0.0);
        }
    }
    let scale = (0..M).map(|k| q.column(k).norm()).fold(0.0, f64::max);
    if !scale.is_finite() || !b.iter().all(|v| v.is_finite()) {
        return None;
    }
    let mut r = Matrix::<M, M>::zeros();
    for k in 0..M {
        for _pass in 0..2 {
            for i in 0..k {
                let qi = q.column(i).into_owned();
                let c = qi.dot(&q.column(k));
                r[(i, k)] += c;
                let mut qk = q.column_mut(k);
                qk -= qi * c;
            }
        }
        let norm = q.column(k).norm();
        if norm.is_nan() || norm <= RANK_TOL * scale {
            return None;
        }
        r[(k, k)] = norm;
        let mut qk = q.column_mut(k);
        qk /= norm;
    }
    let mut z = Vector::<M>::zeros();
    for k in 0..M {
        let s: f64 = (0..k).map(|i| r[(i, k)] * z[i]).sum();
        z[k] = (b[k] - s) / r[(k, k)];
    }
    let x = q * z;
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Whether the update `dq` of `q` is at the level of rounding: `|dq_i| <= 8 eps max(1, |q_i|)`.
pub(crate) fn negligible<const N: usize>(dq: &Vector<N>, q: &Vector<N>) -> bool {
    dq.iter()
        .zip(q.iter())
        .all(|(d, v)| d.abs() <= 8.0 * f64::EPSILON * v.abs().max(1.0))
}

/// `max_i |v_i|`.
pub(crate) fn max_norm<const N: usize>(v: &Vector<N>) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One equation `x + y = 2` in two unknowns: the minimum-norm solution is `(1, 1)`;
    /// with `y` held it is `(2, 0)`.
    #[test]
    fn minimum_norm_solution_of_an_underdetermined_system() {
        let j = Matrix::<1, 2>::new(1.0, 1.0);
        let b = Vector::<1>::new(2.0);
        let x = min_norm_solve(&j, &[true, true], &b).unwrap();
        assert!((x - Vector::<2>::new(1.0, 1.0)).norm() < 1e-15);
        let x = min_norm_solve(&j, &[true, false], &b).unwrap();
        assert!((x - Vector::<2>::new(2.0, 0.0)).norm() < 1e-15);
    }

    /// A square system with a known solution, and a rank-deficient one.
    #[test]
    fn square_solve_and_rank_loss() {
        let j = Matrix::<2, 2>::new(0.0, 2.0, 3.0, 1.0);
        let x = Vector::<2>::new(-1.5, 0.25);
        let got = min_norm_solve(&j, &[true, true], &(j * x)).unwrap();
        assert!((got - x).norm() < 1e-15);
        let singular = Matrix::<2, 2>::new(1.0, 2.0, 2.0, 4.0);
        assert!(min_norm_solve(&singular, &[true, true], &x).is_none());
        // Holding the only column that the second row depends on loses rank too.
        let j = Matrix::<2, 2>::new(1.0, 1.0, 0.0, 1.0);
        assert!(min_norm_solve(&j, &[true, false], &x).is_none());
    }
}
