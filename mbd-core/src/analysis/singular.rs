//! Singular passages of a driven (zero-dof) closed loop along an integrated motion.
//!
//! A mechanism whose drives leave it no degree of freedom has a square, regular `Phi_q`
//! (its independent rows) on a regular motion. Where that matrix becomes singular (a
//! toggle, or a change point where two assembly branches cross) the motion is at a
//! bifurcation: the equations admit more than one continuation, and which one an
//! integrator follows depends on its drift, not on the physics. Along one branch the
//! determinant of the independent rows changes sign there (a simple zero) or touches zero
//! (a double zero, on some branches through a change point): a sign change between two
//! recorded states, or a minimum of `|det|` inside a step near zero in the cubic Hermite
//! interpolant of its values and rates at the step's ends, marks the passage — tests that
//! do not depend on how close a step came to the singular instant — or a recorded local
//! minimum of the normalised `|det|` below [`NEAR`] that it rises from tenfold: an adaptive method creeps up to a
//! change point and turns back on the reflected branch, `|det|` V-shaped.

use super::rank_and_redundant;
use crate::error::{Error, Result};
use crate::integrate::Solution;
use crate::model::Constrained;

/// The normalised `|det|` below which a local minimum counts as reaching the singular
/// position: an integrator at tolerance `tol` turns back from a change point at about
/// `tol` (measured: `4e-7` for DOPRI5 at `1e-8`).
const NEAR: f64 = 1e-4;

/// `Ok` when the motion in `sol` (states `y = [q; qd]`) never passes a singular position
/// of `sys`'s constraints, or when `sys` is mobile (`Phi_q` of rank below `N` at the start:
/// its singular positions are passed by the dynamics, see the 40-loop assembly);
/// otherwise [`Error::SingularPosition`] at the first recorded time after the passage,
/// naming the interval and the configuration there.
pub fn check_passages<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    sol: &Solution<D>,
) -> Result<()> {
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    let q_at = |k: usize| sol.y[k].fixed_rows::<N>(0).into_owned();
    let Some(&t0) = sol.t.first() else {
        return Ok(());
    };
    let (rank, redundant) = rank_and_redundant(&sys.phi_q(t0, &q_at(0)));
    if rank < N {
        return Ok(());
    }
    let rows: Vec<usize> = (0..M).filter(|k| !redundant.contains(k)).collect();
    let det_at = |t: f64, q: &crate::model::Vector<N>| {
        let p = sys.phi_q(t, q);
        // Normalised by `|rows|_F^N`: scale-free, and small exactly when the smallest
        // singular value is small against the largest (a row norm would vanish with
        // the row at a position where a whole row of `Phi_q` vanishes).
        let frobenius = rows
            .iter()
            .map(|&r| p.row(r).norm_squared())
            .sum::<f64>()
            .sqrt();
        let norms = frobenius.powi(N as i32);
        nalgebra::DMatrix::<f64>::from_fn(N, N, |i, j| p[(rows[i], j)]).determinant() / norms
    };
    // `(det, d det / dt)` at a recorded state, the rate by a central difference along
    // the motion `(t, q) + e (1, qd)`.
    let det = |k: usize| {
        let (t, q) = (sol.t[k], q_at(k));
        let qd = sol.y[k].fixed_rows::<N>(N).into_owned();
        let e = 1e-6 * (1.0 + t.abs());
        let rate = (det_at(t + e, &(q + qd * e)) - det_at(t - e, &(q - qd * e))) / (2.0 * e);
        (det_at(t, &q), rate)
    };
    let mut before = det(0);
    let mut lowest = f64::INFINITY;
    for k in 1..sol.t.len() {
        let now = det(k);
        // Came below `NEAR` and turned back (risen tenfold from the lowest value): the
        // integrator reached the singular position and left it on the reflected branch.
        if now.0.abs() <= NEAR {
            lowest = lowest.min(now.0.abs());
        }
        let dip = (now.0.abs() > 10.0 * lowest).then_some(lowest);
        if let Some(min) = dip.or_else(|| passage(before, now, sol.t[k] - sol.t[k - 1])) {
            let detail = format!(
                "the constraint Jacobian of a mechanism without degrees of freedom became \
                 singular between t = {} and t = {} (det of its independent rows {:.3e}, \
                 then {:.3e}, smallest {min:.3e}; normalised by |Phi_q|_F^N): a bifurcation, where the \
                 motion may continue on another assembly branch; q = {:?}",
                sol.t[k - 1],
                sol.t[k],
                before.0,
                now.0,
                q_at(k).as_slice()
            );
            return Err(Error::SingularPosition {
                t: sol.t[k],
                detail,
            });
        }
        before = now;
    }
    Ok(())
}

/// Whether the determinant, `(value, rate)` at both ends of a step of length `h`, vanishes
/// inside it: it changes sign, is not finite, or its cubic Hermite interpolant has an
/// interior minimum of `|det|` below `1e-3` of its end values (a double zero: along some
/// branches through a change point the determinant touches zero without changing sign).
/// Returns the interpolated minimum of `|det|`.
fn passage((d0, s0): (f64, f64), (d1, s1): (f64, f64), h: f64) -> Option<f64> {
    if !(d0.is_finite() && d1.is_finite()) || d0 == 0.0 || d1 == 0.0 || d0.signum() != d1.signum() {
        return Some(0.0);
    }
    // |det| falling at the start and rising at the end: a minimum inside.
    if !(d0 * s0 < 0.0 && d1 * s1 > 0.0) {
        return None;
    }
    let (m0, m1) = (s0 * h, s1 * h);
    let min = (1..64)
        .map(|i| {
            let x = i as f64 / 64.0;
            let (x2, x3) = (x * x, x * x * x);
            (2.0 * x3 - 3.0 * x2 + 1.0) * d0
                + (x3 - 2.0 * x2 + x) * m0
                + (-2.0 * x3 + 3.0 * x2) * d1
                + (x3 - x2) * m1
        })
        .fold(f64::INFINITY, |m, p| {
            if p.signum() != d0.signum() {
                0.0f64.min(m)
            } else {
                m.min(p.abs())
            }
        });
    (min <= 1e-3 * d0.abs().max(d1.abs())).then_some(min)
}
