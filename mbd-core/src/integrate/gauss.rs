//! The two-stage Gauss–Legendre collocation method: order 4, A-stable, symmetric, and
//! symplectic, with a fixed step.
//!
//! Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed. (2006), Sect. II.1.3
//! (collocation), VI.4 (symplecticity of Gauss methods), VIII.6 (implementation); Hairer &
//! Wanner, *Solving ODEs II*, Sect. IV.5 (the tableau) and IV.8 (the transformed Newton
//! iteration, which this shares with [`Radau5`](super::Radau5)).
//!
//! Why it is here: a non-symplectic method (RK4, DOPRI5, Radau IIA) run over many periods
//! of a conservative mechanism lets the energy error grow linearly in time, however tight
//! the tolerance; Radau IIA and the damped generalized-α even dissipate. A symplectic,
//! symmetric method with a fixed step keeps the energy error bounded (oscillating, no
//! drift) over exponentially long times (GNI Sect. IX.8), and conserves every quadratic
//! invariant (linear systems' energy, angular momentum) to rounding. In the first-order form
//! `y = [q; qd]` this holds exactly for a constant mass matrix (`p = M qd` is a linear map,
//! with which Runge–Kutta methods commute); for a configuration-dependent `M(q)` the method
//! is still symmetric, and reversible mechanisms keep a bounded energy error
//! (GNI Sect. XI.3) — the stress suite measures it on the double pendulum.
//!
//! One step solves the stage equations `z_i = h sum_j a_ij f(t + c_j h, y + z_j)` by the
//! simplified Newton iteration on `W = (T^-1 ⊗ I) Z`, which reduces the `2D × 2D` system to
//! one complex `D × D` system with `((α + iβ)/h) I − J`, `α ± iβ = 3 ± i√3` the eigenvalues
//! of `A^-1`. The iteration runs to rounding (a symplectic method is symplectic only for the
//! exact stage values). The Jacobian is kept across steps and refreshed when the
//! iteration slows down. Starting values extrapolate the previous step's collocation
//! polynomial. The result is `y1 = y0 + h sum_i b_i f(Y_i)` with the exact weights
//! `b = (1/2, 1/2)` and the stage derivatives of the last iteration, added with compensated
//! summation (GNI Sect. VIII.5). The shortcut `y1 = y0 + sum_i d_i z_i`, `d = b^T A^-1`,
//! would use the rounded `√3`, and the method with rounded coefficients is not exactly
//! symplectic: measured, it drifts the oscillator's energy by 4e-11 over 1e5 periods.

use super::{
    Event, Flow, Integrator, Observer, Record, Recorder, Segment, Solution, Stats, validate_problem,
};
use super::{non_finite, positive_finite};
use crate::closure::{ChartWatch, passed_limit};
use crate::error::{Error, Result};
use crate::linalg::Lu;
use crate::model::{Matrix, OdeSystem, Vector};
use nalgebra::{Complex, SMatrix, SVector};

/// Coefficients of the two-stage Gauss–Legendre method (Hairer & Wanner II, Table IV.5.1).
pub mod tableau {
    /// `√3`, correctly rounded.
    pub const SQRT3: f64 = 1.7320508075688772;
    /// Nodes `c = 1/2 ∓ √3/6`: the zeros of the shifted Legendre polynomial `6x² − 6x + 1`.
    pub const C: [f64; 2] = [0.5 - SQRT3 / 6.0, 0.5 + SQRT3 / 6.0];
    /// Runge–Kutta matrix (collocation: `sum_j a_ij c_j^(k−1) = c_i^k / k`, `k = 1, 2`).
    pub const A: [[f64; 2]; 2] = [[0.25, 0.25 - SQRT3 / 6.0], [0.25 + SQRT3 / 6.0, 0.25]];
    /// Weights.
    pub const B: [f64; 2] = [0.5, 0.5];
    /// `d = b^T A^-1`, with `A^-1 = [[3, −3 + 2√3], [−3 − 2√3, 3]]`: `y1 = y0 + d_1 z_1 + d_2 z_2`.
    pub const D: [f64; 2] = [-SQRT3, SQRT3];
    /// Real part of the eigenvalues `α ± iβ` of `A^-1` (trace 6, determinant 12).
    pub const ALPHA: f64 = 3.0;
    /// Imaginary part of the eigenvalues of `A^-1`.
    pub const BETA: f64 = SQRT3;
    /// `T` with `T^-1 A^-1 T = [[α, −β], [β, α]]`: the columns are the real part and minus
    /// the imaginary part of the eigenvector `(i(√3 − 2), 1)` of `α + iβ`.
    pub const T: [[f64; 2]; 2] = [[0.0, 2.0 - SQRT3], [1.0, 0.0]];
    /// `T^-1`.
    pub const T_INV: [[f64; 2]; 2] = [[0.0, 1.0], [2.0 + SQRT3, 0.0]];
}

use tableau::{ALPHA, B, BETA, C, T, T_INV};

/// Fixed-step two-stage Gauss–Legendre (order 4, symplectic, symmetric).
///
/// The interval is split into `ceil((t1 − t0) / h)` equal steps (equal steps keep the
/// method symplectic and its iteration matrix factored once). Dense output is the cubic
/// Hermite interpolant ([`Segment::hermite`]), which costs one `rhs` call per step when kept
/// or needed for events. [`OdeSystem::project`] is called after every step when `project`
/// is set (closed loops; it makes the method no longer exactly symplectic, but keeps the
/// constraints to the projection's tolerance).
///
/// Errors: [`Error::NewtonFailed`] when the stage equations do not converge even with a
/// fresh Jacobian (the step is too large for the problem: the method has no step control),
/// [`Error::NonFinite`] for non-finite values, [`Error::TooManySteps`] when the run would
/// need more than `max_steps` steps (checked before starting).
#[derive(Debug, Clone, PartialEq)]
pub struct Gauss {
    /// Step size.
    pub h: f64,
    /// Steps allowed before [`Error::TooManySteps`].
    pub max_steps: usize,
    /// Newton stops when the scaled increment `max_i |Δz_i| / (1 + |y_i|)` falls below `tol`,
    /// or, once below `1e-8`, stops decreasing fast (by less than half) or runs out of
    /// iterations: that is rounding, which a stiff right-hand side amplifies (k = 1e10 N/m
    /// turns `eps |x|` into a force error of 1e-7 N). An increment that stops decreasing
    /// above `1e-8` is divergence.
    pub tol: f64,
    /// Newton iterations per step (per Jacobian) before giving up.
    pub max_iterations: usize,
    /// Call [`OdeSystem::project`] after each step.
    pub project: bool,
    /// Keep one dense-output segment per step in the [`Solution`].
    pub dense: bool,
    /// Which states the solution keeps.
    pub record: Record,
}

impl Gauss {
    /// Step `h`; `max_steps = 10_000_000`, `tol = 1e-16`, 12 iterations, projection and
    /// dense output on.
    pub fn new(h: f64) -> Self {
        Gauss {
            h,
            max_steps: 10_000_000,
            tol: 1e-16,
            max_iterations: 12,
            project: true,
            dense: true,
            record: Record::Steps,
        }
    }

    fn validate(&self) -> Result<()> {
        let bad = |what: &'static str, detail: String| Err(Error::InvalidInput { what, detail });
        positive_finite("h", self.h)?;
        positive_finite("tol", self.tol)?;
        if self.max_iterations < 2 || self.max_steps == 0 {
            return bad(
                "max_iterations/max_steps",
                "need at least 2 iterations and 1 step".to_string(),
            );
        }
        Ok(())
    }
}

/// Below this scaled increment, a Newton iteration that stops decreasing has reached rounding.
const STAGNATION: f64 = 1e-8;

/// `sum_j m[k][j] v_j` for each `k`.
fn mix<const D: usize>(m: &[[f64; 2]; 2], v: &[Vector<D>; 2]) -> [Vector<D>; 2] {
    std::array::from_fn(|k| v[0] * m[k][0] + v[1] * m[k][1])
}

/// The factored iteration matrix `((α + iβ)/h) I − J`.
fn factor<const D: usize>(jac: &Matrix<D, D>, h: f64) -> Option<Lu<Complex<f64>, D>> {
    let shift = Complex::new(ALPHA / h, BETA / h);
    Lu::factor(
        SMatrix::<Complex<f64>, D, D>::from_diagonal_element(shift)
            - jac.map(|v| Complex::new(v, 0.0)),
    )
}

/// Outcome of the Newton iteration of one step.
enum Stages<const D: usize> {
    /// `z` the stage increments, `f` the derivatives at the stages of the last iteration
    /// (one rounding-sized update away from `z`); `slow` when it took five iterations or more.
    Converged {
        z: [Vector<D>; 2],
        f: [Vector<D>; 2],
        slow: bool,
    },
    /// Diverged or out of iterations; `non_finite` when it met a NaN or an infinity.
    Failed { non_finite: bool },
}

impl Gauss {
    /// Simplified Newton on the stage equations of the step `[t, t + h]` from `y`.
    #[allow(clippy::too_many_arguments, reason = "one step's full context")]
    fn stages<S: OdeSystem<D>, const D: usize>(
        &self,
        sys: &S,
        t: f64,
        y: &Vector<D>,
        h: f64,
        z0: [Vector<D>; 2],
        lu: &Lu<Complex<f64>, D>,
        stats: &mut Stats,
    ) -> Result<Stages<D>> {
        let (an, bn) = (ALPHA / h, BETA / h);
        let mut z = z0;
        let mut w = mix(&T_INV, &z);
        let mut previous = f64::INFINITY;
        for iteration in 0..self.max_iterations {
            let mut f = [Vector::<D>::zeros(); 2];
            for i in 0..2 {
                f[i] = sys.rhs(t + C[i] * h, &(y + z[i]))?;
                stats.n_rhs += 1;
                if non_finite(&f[i]) {
                    return Ok(Stages::Failed { non_finite: true });
                }
            }
            let r = mix(&T_INV, &f);
            let rhs = SVector::<Complex<f64>, D>::from_fn(|i, _| {
                Complex::new(
                    r[0][i] - an * w[0][i] + bn * w[1][i],
                    r[1][i] - bn * w[0][i] - an * w[1][i],
                )
            });
            let dw = lu.solve(&rhs);
            let dw = [dw.map(|c| c.re), dw.map(|c| c.im)];
            let dz = mix(&T, &dw);
            let norm = (0..D)
                .map(|i| dz[0][i].abs().max(dz[1][i].abs()) / (1.0 + y[i].abs()))
                .fold(0.0, f64::max);
            if !norm.is_finite() {
                return Ok(Stages::Failed { non_finite: true });
            }
            for k in 0..2 {
                w[k] += dw[k];
            }
            z = mix(&T, &w);
            let slow = iteration >= 4;
            // Converged: below `tol`, or at rounding, where the increments of a stiff system
            // only creep down (measured: 1e-13 -> 1e-14 over ten iterations at k = 1e8).
            if norm <= self.tol
                || (norm <= STAGNATION && norm > 0.5 * previous)
                || (norm <= STAGNATION && iteration + 1 == self.max_iterations)
            {
                return Ok(Stages::Converged { z, f, slow });
            }
            if norm >= previous {
                // No more progress: at rounding this is convergence, above it divergence.
                return Ok(if previous <= STAGNATION {
                    Stages::Converged { z, f, slow }
                } else {
                    Stages::Failed { non_finite: false }
                });
            }
            previous = norm;
        }
        Ok(Stages::Failed { non_finite: false })
    }
}

impl Integrator for Gauss {
    fn passages(&self) -> Option<crate::passage::Settings> {
        Some(crate::passage::Settings::fixed(
            self.h,
            4,
            self.dense,
            &self.record,
        ))
    }

    fn name(&self) -> &'static str {
        "Gauss4"
    }

    fn solve_observed<S: OdeSystem<D>, const D: usize>(
        &self,
        sys: &S,
        t0: f64,
        y0: Vector<D>,
        t1: f64,
        events: &[Event<'_, D>],
        observer: Option<&mut Observer<'_, D>>,
    ) -> Result<Solution<D>> {
        // With room for its D x D matrices (`super::stack`).
        super::stack::with_room::<D, _>(16, || self.observed(sys, t0, y0, t1, events, observer))
    }
}

impl Gauss {
    fn observed<S: OdeSystem<D>, const D: usize>(
        &self,
        sys: &S,
        t0: f64,
        y0: Vector<D>,
        t1: f64,
        events: &[Event<'_, D>],
        observer: Option<&mut Observer<'_, D>>,
    ) -> Result<Solution<D>> {
        self.validate()?;
        validate_problem(t0, &y0, t1)?;
        self.record.validate()?;
        let mut rec =
            Recorder::with(events, t0, y0, self.dense, self.record.clone()).observed(observer);
        let mut stats = Stats::default();
        if t1 == t0 {
            return rec.finish(stats);
        }
        let n = ((t1 - t0) / self.h * (1.0 - 1e-12)).ceil().max(1.0);
        if n > self.max_steps as f64 {
            return Err(Error::TooManySteps {
                t: t0,
                steps: self.max_steps,
            });
        }
        let n = n as usize;
        let h = (t1 - t0) / n as f64;
        let (mut t, mut y) = (t0, y0);
        let dense = rec.needs_segment();
        let mut f0 = if dense {
            stats.n_rhs += 1;
            let f = sys.rhs(t0, &y0)?;
            if non_finite(&f) {
                return Err(Error::NonFinite { t: t0 });
            }
            f
        } else {
            Vector::<D>::zeros()
        };
        let fresh = |t: f64, y: &Vector<D>, stats: &mut Stats| -> Result<Lu<Complex<f64>, D>> {
            let jac = sys.jacobian(t, y).map_err(|e| match e {
                Error::NonFinite { .. } => Error::NonFinite { t },
                e => e,
            })?;
            stats.n_jac += 1;
            stats.n_lu += 1;
            if !jac.iter().all(|v| v.is_finite()) {
                return Err(Error::NonFinite { t });
            }
            factor(&jac, h).ok_or(Error::NewtonFailed { t, h })
        };
        let mut lu = fresh(t0, &y0, &mut stats)?;
        let mut jac_current = true;
        // A minimal loop's limit position stepped over, or Newton failing on its way there.
        let mut chart = ChartWatch::<D>::default();
        // Collocation polynomial of the last step: u(θ) − y0 = a1 θ + a2 θ².
        let mut previous: Option<[Vector<D>; 2]> = None;
        let mut compensation = Vector::<D>::zeros();
        for step in 1..=n {
            let t_new = if step == n { t1 } else { t0 + step as f64 * h };
            let z_start = match &previous {
                Some(a) => {
                    let u = |th: f64| (a[1] * th + a[0]) * th;
                    let end = u(1.0);
                    [u(1.0 + C[0]) - end, u(1.0 + C[1]) - end]
                }
                None => [Vector::<D>::zeros(); 2],
            };
            stats.n_steps += 1;
            let (z, f, slow) = loop {
                match self.stages(sys, t, &y, h, z_start, &lu, &mut stats)? {
                    Stages::Converged { z, f, slow } => {
                        jac_current = false;
                        break (z, f, slow);
                    }
                    Stages::Failed { .. } if !jac_current => {
                        lu = fresh(t, &y, &mut stats)
                            .map_err(|e| at_limit(sys, &chart, t_new + h, e))?;
                        jac_current = true;
                    }
                    Stages::Failed { non_finite: true } => return Err(Error::NonFinite { t }),
                    Stages::Failed { non_finite: false } => {
                        return Err(at_limit(
                            sys,
                            &chart,
                            t_new + h,
                            Error::NewtonFailed { t, h },
                        ));
                    }
                }
            };
            // u(c_i) − y0 = z_i with u − y0 = a1 θ + a2 θ²: a Vandermonde solve.
            let det = C[0] * C[1] * (C[1] - C[0]);
            let a1 = (z[0] * (C[1] * C[1]) - z[1] * (C[0] * C[0])) / det;
            let a2 = (z[1] * C[0] - z[0] * C[1]) / det;
            previous = Some([a1, a2]);
            // Compensated summation (Kahan; GNI Sect. VIII.5): the increment is added with
            // the rounding error of the last addition, so that rounding does not drift.
            let delta = (f[0] * B[0] + f[1] * B[1]) * h + compensation;
            let mut y1 = y + delta;
            compensation = delta - (y1 - y);
            // The step's end as computed, when a projection moved it farther than the step
            // itself did: a ball joint's switch to its shadow set (`chart.rs`), not a
            // correction onto a loop's constraints. The step is then interpolated as
            // computed, and neither the Newton start nor the Jacobian crosses the switch.
            let mut computed = None;
            if self.project {
                let before = y1;
                sys.project(t_new, &mut y1)?;
                if y1 != before {
                    compensation = Vector::<D>::zeros();
                    if (y1 - before).amax() > (before - y).amax() {
                        computed = Some(before);
                        previous = None;
                    }
                }
            }
            if non_finite(&y1) {
                return Err(Error::NonFinite { t: t_new });
            }
            if let Some((ts, yb)) = chart.accept(t_new, &y1, |y| sys.chart_margin(t_new, y)) {
                return Err(passed_limit(ts, &yb, sys.rhs(ts, &yb).err()));
            }
            if (slow || computed.is_some()) && step < n {
                // The iteration slowed down: a fresh Jacobian for the next step.
                lu = fresh(t_new, &y1, &mut stats)?;
                jac_current = true;
            }
            stats.n_accepted += 1;
            let flow = if dense {
                stats.n_rhs += 1;
                let f1 = sys.rhs(t_new, &y1)?;
                if non_finite(&f1) {
                    return Err(Error::NonFinite { t: t_new });
                }
                let seg = match computed {
                    Some(end) => {
                        stats.n_rhs += 1;
                        let f_end = sys.rhs(t_new, &end)?;
                        Segment::hermite(t, t_new - t, &y, &f0, &end, &f_end)
                    }
                    None => Segment::hermite(t, t_new - t, &y, &f0, &y1, &f1),
                };
                f0 = f1;
                rec.accept_with(t_new, &y1, || seg)
            } else {
                let end = computed.unwrap_or(y1);
                rec.accept_with(t_new, &y1, || {
                    Segment::hermite(t, t_new - t, &y, &f0, &end, &f0)
                })
            };
            (t, y) = (t_new, y1);
            if flow == Flow::Stop {
                break;
            }
        }
        rec.finish(stats)
    }
}

/// A Newton failure (or a singular iteration matrix) whose step was on its way to a limit
/// position of a minimal loop's closed forms (the last three margins reach the boundary
/// before `t_end`): the position's [`Error::SingularPosition`], naming it, as RK4 and
/// generalized-α report it; there the minimal equations' inertia grows without bound and
/// Newton cannot converge. Any other error is returned as it is.
fn at_limit<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    chart: &ChartWatch<D>,
    t_end: f64,
    e: Error,
) -> Error {
    if !matches!(e, Error::NewtonFailed { .. }) {
        return e;
    }
    match chart.passed(t_end, &|y: &Vector<D>| sys.chart_margin(t_end, y)) {
        Some((ts, yb)) => passed_limit(ts, &yb, sys.rhs(ts, &yb).err()),
        None => e,
    }
}
