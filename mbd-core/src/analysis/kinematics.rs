//! Kinematic analysis of a driven mechanism with zero degrees of freedom: as many
//! constraints (loop closures plus drivers) as coordinates, so the motion follows from the
//! constraints alone (Haug 1989, ch. 3):
//! positions from `Phi(q, t) = 0` (Newton), velocities from `Phi_q qd = -Phi_t`,
//! accelerations from `Phi_q qdd = gamma`.

use super::{NewtonOptions, assemble, max_norm, min_norm_solve};
use crate::error::{Error, Num, Result};
use crate::linalg::Lu;
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
/// The model must be `Constrained<N, N>`: as many constraint rows (closures and drives) as
/// coordinates. One with free coordinates (`Constrained<N, M>`, `M < N`) is refused by
/// `cargo check` (the trait bound is not met, and the note says what to use instead: such a
/// mechanism is integrated, its state assembled with [`assemble`](super::assemble)).
///
/// Errors: [`Error::AssemblyFailed`] when Newton does not converge,
/// [`Error::SingularConstraintJacobian`] at a toggle (dead-centre) position, where the
/// drivers no longer determine the motion.
pub fn kinematics<S: Constrained<N, N>, const N: usize>(
    sys: &S,
    t: f64,
    q_guess: &Vector<N>,
    opts: &NewtonOptions,
) -> Result<KinematicState<N>> {
    let q = assemble(sys, t, q_guess, &[false; N], opts)?;
    let all = [true; N];
    let jac = sys.phi_q(t, &q);
    let singular = || Error::SingularConstraintJacobian {
        t,
        detail: super::assembly::where_(sys, t, &q, &all),
    };
    let qd = min_norm_solve(&jac, &all, &(-sys.phi_t(t, &q))).ok_or_else(singular)?;
    let qdd = min_norm_solve(&jac, &all, &sys.gamma(t, &q, &qd)).ok_or_else(singular)?;
    Ok(KinematicState { t, q, qd, qdd })
}

/// The kinematic state at each of `times` (in order), each assembly starting from the
/// previous state's second-order Taylor prediction `q + qd dt + qdd dt^2 / 2`, which keeps
/// Newton on the same branch (assembly mode) of the mechanism. Where the samples are too
/// far apart for that prediction (Newton corrects it by more than a quarter of the predicted
/// move), the interval is marched in halved sub-steps (not returned), so a coarse sampling
/// cannot land Newton on another branch: a crank-rocker sampled 5 times a turn switched
/// elbows. The model is `Constrained<N, N>`, as for [`kinematics`].
///
/// Errors as [`kinematics`], and [`Error::SingularConstraintJacobian`] when the sweep passes
/// a singular position between two of its states (`det Phi_q` changes sign): there the
/// drivers do not determine the motion (a fold or change point, where another branch
/// meets), so continuing on either would choose a branch silently.
pub fn kinematic_sweep<S: Constrained<N, N>, const N: usize>(
    sys: &S,
    times: &[f64],
    q_guess: &Vector<N>,
    opts: &NewtonOptions,
) -> Result<Vec<KinematicState<N>>> {
    let mut out: Vec<KinematicState<N>> = Vec::with_capacity(times.len());
    for &t in times {
        let next = match out.last() {
            Some(s) => continued(sys, s, t, opts)?,
            None => kinematics(sys, t, q_guess, opts)?,
        };
        out.push(next);
    }
    Ok(out)
}

/// `SingularConstraintJacobian` when `det Phi_q` changes sign from `a` to `b`: the path
/// between them crossed a configuration where `Phi_q` is singular.
fn passes_no_singular_position<S: Constrained<N, N>, const N: usize>(
    sys: &S,
    a: &KinematicState<N>,
    b: &KinematicState<N>,
) -> Result<()> {
    let det =
        |s: &KinematicState<N>| Lu::factor(sys.phi_q(s.t, &s.q)).map_or(0.0, |lu| lu.determinant());
    let (da, db) = (det(a), det(b));
    if da * db < 0.0 {
        let at = |s: &KinematicState<N>| {
            let q: Vec<String> = (S::COORDINATES.iter().zip(s.q.iter()))
                .map(|(name, v)| format!("{name} = {}", Num(*v)))
                .collect();
            format!("t = {} (q = [{}])", Num(s.t), q.join(", "))
        };
        return Err(Error::SingularConstraintJacobian {
            t: b.t,
            detail: format!(
                "passed between {} and {}: det Phi_q changed sign, so another branch of the \
                 motion meets this one in between and the drivers do not choose",
                at(a),
                at(b)
            ),
        });
    }
    Ok(())
}

/// Most halvings of a sub-step in [`continued`]; past them the step is taken as Newton
/// gives it (at a toggle position no sub-step predicts well, and the error is Newton's).
const MAX_HALVINGS: u32 = 24;

/// The state at `t` continued from `from` by Taylor-predicted sub-steps, each halved until
/// Newton moves its prediction by at most a quarter of the predicted move (plus rounding).
fn continued<S: Constrained<N, N>, const N: usize>(
    sys: &S,
    from: &KinematicState<N>,
    t: f64,
    opts: &NewtonOptions,
) -> Result<KinematicState<N>> {
    let mut s = *from;
    let mut h = t - s.t;
    let mut halvings = 0;
    loop {
        let last = (t - s.t).abs() <= h.abs();
        let tn = if last { t } else { s.t + h };
        let dt = tn - s.t;
        let guess = s.q + s.qd * dt + s.qdd * (0.5 * dt * dt);
        let next = kinematics(sys, tn, &guess, opts);
        let slack = 1e-9 * (1.0 + max_norm(&s.q));
        let predicted = next
            .as_ref()
            .is_ok_and(|n| max_norm(&(n.q - guess)) <= 0.25 * max_norm(&(guess - s.q)) + slack);
        if !predicted && halvings < MAX_HALVINGS {
            h = 0.5 * dt;
            halvings += 1;
            continue;
        }
        let next = next?;
        passes_no_singular_position(sys, &s, &next)?;
        s = next;
        if last {
            return Ok(s);
        }
        h = 2.0 * dt;
        halvings = halvings.saturating_sub(1);
    }
}
