//! Assembly: close the loops of a mechanism, `Phi(q, t) = 0`, moving only the coordinates
//! that are not held, and make the velocities consistent, `Phi_q qd + Phi_t = 0`.
//!
//! Haug (1989), ch. 3 (Newton–Raphson assembly) and ch. 6 (consistent initial
//! conditions). When more coordinates are free than there are constraints, the update is
//! the minimum-norm Gauss–Newton step, so the result is the assembled configuration
//! closest (to first order) to the one given.

use super::{NewtonOptions, max_norm, min_norm_solve, negligible};
use crate::error::{Error, Num, Result};
use crate::model::{Constrained, Matrix, Vector};

/// Solve `Phi(q, t) = 0` for the coordinates with `held[i] == false`, starting from `q0`
/// and keeping `q_i = q0_i` where `held[i]`.
///
/// Newton / Gauss–Newton: `dq_F = -J_F^+ Phi` with `J_F` the columns of `Phi_q` of the free
/// coordinates and `J_F^+` its minimum-norm right inverse, shortened by backtracking while
/// that reduces `|Phi|` (see `damped`). Converged by the rule of
/// [`NewtonOptions::tol`]; the step already computed at the converged point is applied too
/// (with quadratic convergence it polishes `q` to rounding). The Jacobian must then have
/// full row rank, or the configuration is a toggle (dead-centre) position or the
/// constraints are redundant.
///
/// Errors: [`Error::AssemblyFailed`] (with the residual) when the iterations run out or a
/// Newton step cannot be taken because `J_F` lost rank far from a solution (a loop that
/// cannot close ends, at best, stretched straight, where the Jacobian is singular);
/// [`Error::SingularConstraintJacobian`] when a solution is found at which `J_F` has lost rank,
/// or Newton reached it only linearly (a multiple root: the rank is lost within the tolerance);
/// [`Error::NonFinite`] when `Phi` is not finite.
pub fn assemble<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q0: &Vector<N>,
    held: &[bool; N],
    opts: &NewtonOptions,
) -> Result<Vector<N>> {
    opts.validate()?;
    let free = free_set(held);
    let mut q = *q0;
    let mut iterations = 0;
    // Size of the previous full Newton step, to tell quadratic from linear convergence.
    let mut previous: Option<f64> = None;
    loop {
        let phi = sys.phi(t, &q);
        if !phi.iter().all(|v| v.is_finite()) || !q.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFinite { t });
        }
        let residual = max_norm(&phi);
        let step = min_norm_solve(&sys.phi_q(t, &q), &free, &(-phi));
        let converged = residual <= opts.tol || step.as_ref().is_some_and(|dq| negligible(dq, &q));
        if converged {
            let singular = || Error::SingularConstraintJacobian {
                t,
                detail: where_(sys, t, &q, &free),
            };
            let dq = step.ok_or_else(singular)?;
            if singular_root(&dq, &q, previous) {
                return Err(singular());
            }
            return Ok(q + dq);
        }
        match step {
            Some(dq) if iterations < opts.max_iterations => {
                previous = Some(max_norm(&dq));
                q = damped(sys, t, &q, &dq, &phi);
            }
            _ => {
                return Err(Error::AssemblyFailed {
                    t,
                    iterations,
                    residual,
                    detail: where_(sys, t, &q, &free),
                });
            }
        }
        iterations += 1;
    }
}

/// Whether Newton reached `|Phi| <= tol` only linearly, the mark of a multiple root: the
/// step `dq` at the converged point is still more than a tenth of the step before it, and
/// well above rounding. Near a regular root the ratio of successive steps goes to zero
/// (quadratic convergence); at a root where `J_F` is singular (a toggle or dead-centre
/// position reached within the tolerance) it stays near 1/2, the residual reaches `tol`
/// while `q` is still about `sqrt(tol)` from the root, and `J_F` there is regular only by
/// that distance: velocities solved with it would be finite but meaningless (1e6 rad/s
/// where the truth is infinite). Such a root is reported as singular.
fn singular_root<const N: usize>(dq: &Vector<N>, q: &Vector<N>, previous: Option<f64>) -> bool {
    let size = max_norm(dq);
    let rounding = 1e3 * f64::EPSILON * max_norm(q).max(1.0);
    previous.is_some_and(|p| size > 0.1 * p && size > rounding)
}

/// `q + alpha dq` for the first `alpha` in `1, 1/2, ..., 1/64` that reduces `|Phi|_2`
/// (Armijo backtracking, Dennis & Schnabel, *Numerical Methods for Unconstrained
/// Optimization*, 1983, ch. 6): the Gauss–Newton direction is a descent direction of
/// `|Phi|^2` while `J_F` has full rank, so far from a solution this keeps Newton from
/// jumping to another assembly branch. When no fraction helps (at a local minimum of
/// `|Phi|`, or at the level of rounding), the full step is taken.
fn damped<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    dq: &Vector<N>,
    phi: &Vector<M>,
) -> Vector<N> {
    let norm0 = phi.norm();
    let mut alpha = 1.0;
    while alpha >= 1.0 / 64.0 {
        let trial = q + dq * alpha;
        if sys.phi(t, &trial).norm() <= (1.0 - 1e-4 * alpha) * norm0 {
            return trial;
        }
        alpha *= 0.5;
    }
    q + dq
}

/// Velocities consistent with the constraints, `Phi_q qd + Phi_t = 0`, keeping
/// `qd_i = qd0_i` where `held[i]` (the independent velocities, e.g. the crank speed).
///
/// The free components get the minimum-norm correction `dqd_F = -J_F^+ (Phi_q qd0 + Phi_t)`:
/// unique when the held components are a set of independent velocities, otherwise the
/// consistent velocity closest to `qd0`.
///
/// Errors: [`Error::SingularConstraintJacobian`] when `J_F` lacks full row rank (toggle
/// position, or the held velocities are not independent).
pub fn consistent_velocities<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd0: &Vector<N>,
    held: &[bool; N],
) -> Result<Vector<N>> {
    let jac = sys.phi_q(t, q);
    let violation = jac * qd0 + sys.phi_t(t, q);
    let free = free_set(held);
    let dqd = min_norm_solve(&jac, &free, &(-violation)).ok_or_else(|| {
        Error::SingularConstraintJacobian {
            t,
            detail: where_(sys, t, q, &free),
        }
    })?;
    Ok(qd0 + dqd)
}

/// An assembly error's detail: the configuration `q`, each coordinate by name, and the
/// constraint rows that depend on the rows before them in `Phi_q`'s columns of the free
/// coordinates (by Gram-Schmidt, at a rank tolerance of `1e-6` of the largest row: a root
/// reached within Newton's tolerance of a toggle is singular only to about that), if any.
pub(crate) fn where_<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    free: &[bool; N],
) -> String {
    let coords: Vec<String> = S::COORDINATES
        .iter()
        .zip(q.iter())
        .map(|(name, v)| format!("{name} = {}", Num(*v)))
        .collect();
    let mut out = format!("at q = [{}]", coords.join(", "));
    let rows = dependent_rows(&sys.phi_q(t, q), free);
    if !rows.is_empty() {
        let rows: Vec<String> = rows.iter().map(usize::to_string).collect();
        let rows = rows.join(", ");
        out += &format!(
            ", where constraint rows {rows} (counting from 0) of Phi_q are dependent (zero, or \
             combinations of the rows before them)"
        );
    }
    out
}

/// The rows of `J` (its free columns) within `1e-6` of the span of the rows before them.
fn dependent_rows<const N: usize, const M: usize>(
    j: &Matrix<M, N>,
    free: &[bool; N],
) -> Vec<usize> {
    let row = |k: usize| Vector::<N>::from_fn(|c, _| if free[c] { j[(k, c)] } else { 0.0 });
    let scale = (0..M).map(|k| row(k).norm()).fold(0.0, f64::max);
    let mut basis: Vec<Vector<N>> = Vec::new();
    let mut out = Vec::new();
    for k in 0..M {
        let mut v = row(k);
        for _pass in 0..2 {
            for b in &basis {
                v -= b * b.dot(&v);
            }
        }
        let norm = v.norm();
        if norm.is_nan() || norm <= 1e-6 * scale {
            out.push(k);
        } else {
            basis.push(v / norm);
        }
    }
    out
}

fn free_set<const N: usize>(held: &[bool; N]) -> [bool; N] {
    held.map(|h| !h)
}
