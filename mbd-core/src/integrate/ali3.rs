//! The index-3 augmented Lagrangian integrator with mass-orthogonal projections (ALI3-P) for
//! closed loops, `M qdd + Phi_q^T lambda = f`, `Phi(q, t) = 0`: the IFToMM benchmark's own
//! method for loops that pass singular positions (Bayo & Ledesma, "Augmented Lagrangian and
//! mass-orthogonal projection methods for constrained multibody dynamics", Nonlinear Dyn. 9,
//! 1996; Cuadrado, Cardenal, Morer & Bayo, Multibody Syst. Dyn. 4, 2000).
//!
//! One step of the trapezoidal rule, written for the new positions `q1`:
//!
//! ```text
//! qd1  = 2/h q1 - (2/h q + qd),   qdd1 = 4/h^2 q1 - (4/h^2 q + 4/h qd + qdd)
//! h^2/4 [M qdd1 + Phi_q^T (lambda* + alpha Phi) - f] = 0        (alpha = 4 w / h^2)
//! ```
//!
//! solved by Newton with the approximate tangent `T = M + w Phi_q^T Phi_q` (the force
//! derivatives, `O(h)` and `O(h^2)` beside `M`, are left out), updating the multipliers
//! after each iteration, `lambda* <- lambda* + alpha Phi(q1)`. `T` stays positive definite
//! where `Phi_q` loses rank, so the iteration has no singular matrix at a singular
//! position. The velocities and accelerations the rule gives are then projected onto
//! `Phi_q qd + Phi_t = 0` and `Phi_q qdd = gamma` in the mass metric (rank-robust, see
//! [`crate::augmented`]): the projected accelerations are the ones nearest the rule's, not
//! a minimum-norm solution that jumps at the singular instant.

use super::{
    Options, Recorder, Solution, Stats, positive_finite, second_order_end, stack, validate_problem,
};
use crate::augmented::PenaltyMatrix;
use crate::error::{Error, Result};
use crate::integrate::events::Event;
use crate::integrate::solution::Flow;
use crate::model::{Constrained, Matrix, Vector};

/// Fixed-step index-3 augmented Lagrangian integrator (trapezoidal rule).
#[derive(Debug, Clone, PartialEq)]
pub struct Ali3 {
    /// Step size; the interval is split into `ceil((t1 - t0) / h)` equal steps.
    pub h: f64,
    /// Penalty weight `w` of `T = M + w Phi_q^T Phi_q`, relative to
    /// `max M_ii / max |row of Phi_q|^2`.
    pub weight: f64,
    /// Newton converges when `max |Phi_i| <= tol` and `|dq_i| <= tol (1 + |q_i|)`, or the
    /// error left estimated from the contraction `theta` of the updates,
    /// `theta / (1 - theta) max |dq_i|`, is at most `tol`.
    pub tol: f64,
    /// Newton iterations per step before [`Error::NewtonFailed`].
    pub max_iterations: usize,
    /// Steps allowed before [`Error::TooManySteps`].
    pub max_steps: usize,
}

impl Ali3 {
    /// Step `h`, weight `1e6`, `tol = 1e-9`, 400 iterations, `1e7` steps. Near a singular
    /// position the updates in the directions `Phi_q` lost shrink only sublinearly (the
    /// constraint is quadratic there), so `tol` bounds what is left, not rounding.
    pub fn new(h: f64) -> Self {
        Ali3 {
            h,
            weight: 1e6,
            tol: 1e-9,
            max_iterations: 400,
            max_steps: 10_000_000,
        }
    }

    /// Integrate from a state `(q0, qd0)` that satisfies the position and velocity
    /// constraints (else [`Error::InvalidInput`], as the ordinary solve); the solution's
    /// states are `y = [q; qd]` (`D = 2 N`).
    pub fn solve<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
        &self,
        sys: &S,
        t0: f64,
        q0: Vector<N>,
        qd0: Vector<N>,
        t1: f64,
        events: &[Event<'_, D>],
    ) -> Result<Solution<D>> {
        const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
        positive_finite("h", self.h)?;
        positive_finite("weight", self.weight)?;
        positive_finite("tol", self.tol)?;
        let y0 = stack(&q0, &qd0);
        validate_problem(t0, &y0, t1)?;
        // Its projections would move a start off the constraints unseen: refused instead.
        crate::passage::check_start::<S, N, M, D>(sys, t0, &y0)?;
        let steps = ((t1 - t0) / self.h).ceil().max(1.0);
        if steps > self.max_steps as f64 {
            return Err(Error::TooManySteps {
                t: t0,
                steps: self.max_steps,
            });
        }
        let steps = steps as usize;
        let h = (t1 - t0) / steps as f64;
        let mut recorder = Recorder::new(events, t0, y0, &Options::default());
        let mut stats = Stats::default();
        if h == 0.0 {
            return recorder.finish(stats);
        }
        let (mut qdd, mut lambda) = sys.acceleration_and_multipliers(t0, &q0, &qd0)?;
        let (mut q, mut qd) = (q0, qd0);
        for k in 0..steps {
            let t = t0 + k as f64 * h;
            let t_next = if k + 1 == steps {
                t1
            } else {
                t0 + (k + 1) as f64 * h
            };
            let (q1, qd1, qdd1) =
                self.step(sys, t_next, h, (&q, &qd, &qdd), &mut lambda, &mut stats)?;
            let (y1, seg) = second_order_end(t, t_next, (&q, &qd, &qdd), (&q1, &qd1, &qdd1))?;
            stats.n_steps += 1;
            stats.n_accepted += 1;
            (q, qd, qdd) = (q1, qd1, qdd1);
            if recorder.accept(seg, &y1) == Flow::Stop {
                break;
            }
        }
        recorder.finish(stats)
    }

    /// One step to `t1`: Newton on `q1` with multiplier updates, then the velocity and
    /// acceleration projections. Returns `(q1, qd1, qdd1)`.
    #[allow(clippy::type_complexity, reason = "the state of one step")]
    fn step<S: Constrained<N, M>, const N: usize, const M: usize>(
        &self,
        sys: &S,
        t1: f64,
        h: f64,
        (q, qd, qdd): (&Vector<N>, &Vector<N>, &Vector<N>),
        lambda: &mut Vector<M>,
        stats: &mut Stats,
    ) -> Result<(Vector<N>, Vector<N>, Vector<N>)> {
        let hat_d = q * (2.0 / h) + qd;
        let hat_dd = q * (4.0 / (h * h)) + qd * (4.0 / h) + qdd;
        let rates = |q1: &Vector<N>| (q1 * (2.0 / h) - hat_d, q1 * (4.0 / (h * h)) - hat_dd);
        // Predictor: constant acceleration.
        let mut q1 = q + qd * h + qdd * (0.5 * h * h);
        let factor = |q1: &Vector<N>, stats: &mut Stats| {
            stats.n_jac += 1;
            stats.n_lu += 1;
            PenaltyMatrix::new(
                t1,
                &sys.mass_matrix(t1, q1)?,
                &sys.phi_q(t1, q1),
                self.weight,
            )
        };
        let mut tangent = factor(&q1, stats)?;
        let alpha = 4.0 * tangent.w / (h * h);
        let mut phi = sys.phi(t1, &q1);
        let mut converged = false;
        let mut last = f64::INFINITY;
        for _ in 0..self.max_iterations {
            let (qd1, qdd1) = rates(&q1);
            let residual = sys.mass_matrix(t1, &q1)? * qdd1
                + sys.phi_q(t1, &q1).transpose() * (*lambda + phi * alpha)
                - sys.forces(t1, &q1, &qd1)?;
            stats.n_rhs += 1;
            let dq = tangent.solve(&(residual * (-0.25 * h * h)));
            if !dq.iter().all(|v| v.is_finite()) {
                return Err(Error::NonFinite { t: t1 });
            }
            q1 += dq;
            phi = sys.phi(t1, &q1);
            *lambda += phi * alpha;
            let small = (0..N).all(|i| dq[i].abs() <= self.tol * (1.0 + q1[i].abs()));
            // Near a singular position the multiplier updates contract slowly (by
            // `1 / (1 + w s^2)` for a vanishing singular value `s`): the error left is
            // about `theta / (1 - theta)` times the last update.
            let size = dq.amax();
            let theta = size / last;
            last = size;
            if theta > 0.25 {
                // Slow: the tangent at the predictor is too far off; take it here.
                tangent = factor(&q1, stats)?;
            }
            let small = small || (theta < 1.0 && size * theta / (1.0 - theta) <= self.tol);
            if small && phi.amax() <= self.tol {
                converged = true;
                break;
            }
        }
        if !converged {
            return Err(Error::NewtonFailed { t: t1, h });
        }
        let (qd1, qdd1) = rates(&q1);
        let (mass, jac) = (sys.mass_matrix(t1, &q1)?, sys.phi_q(t1, &q1));
        let phi_t = sys.phi_t(t1, &q1);
        let qd1 = project(&tangent, &mass, &jac, &qd1, &(-phi_t));
        let gamma = sys.gamma(t1, &q1, &qd1);
        let qdd1 = project(&tangent, &mass, &jac, &qdd1, &gamma);
        Ok((q1, qd1, qdd1))
    }
}

/// The mass-orthogonal projection of `x*` onto `Phi_q x = b` in penalty form,
/// `min |x - x*|_M^2 + w |Phi_q x - b|^2`, i.e. `T x = M x* + w Phi_q^T b`, refined by
/// three augmented-Lagrangian corrections so that well-conditioned rows hold to rounding
/// while the rows a singular position made vanish stay soft (bounded, no division by a
/// vanishing singular value).
fn project<const N: usize, const M: usize>(
    tangent: &PenaltyMatrix<N>,
    mass: &Matrix<N, N>,
    jac: &Matrix<M, N>,
    x_star: &Vector<N>,
    b: &Vector<M>,
) -> Vector<N> {
    let mut x = *x_star;
    let mut mu = Vector::<M>::zeros();
    for _ in 0..3 {
        let s = jac * x - b;
        let r = mass * (x_star - x) - jac.transpose() * (mu + s * tangent.w);
        x += tangent.solve(&r);
        mu += (jac * x - b) * tangent.w;
    }
    x
}
