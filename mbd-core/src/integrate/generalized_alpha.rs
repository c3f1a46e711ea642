//! The generalized-α method for mechanisms, `M(q, t) qdd = f(q, qd, t)`, and for closed
//! loops in index-3 form, `M qdd + Phi_q^T lambda = f`, `Phi(q, t) = 0`.
//!
//! Chung & Hulbert, "A time integration algorithm for structural dynamics with improved
//! numerical dissipation: the generalized-α method", J. Appl. Mech. 60 (1993) 371–375;
//! for constraints, Arnold & Brüls, "Convergence of the generalized-α scheme for
//! constrained mechanical systems", Multibody Syst. Dyn. 18 (2007) 185–202.
//! With the acceleration-like variable `a` (not the acceleration itself), one step is
//!
//! ```text
//! q1  = q + h qd + h^2 (1/2 - beta) a + h^2 beta a1
//! qd1 = qd + h (1 - gamma) a + h gamma a1
//! (1 - alpha_m) a1 + alpha_m a = (1 - alpha_f) qdd1 + alpha_f qdd
//! M(q1) qdd1 + Phi_q(q1)^T lambda1 = f(q1, qd1, t1),   Phi(q1, t1) = 0
//! ```
//!
//! solved by Newton for `q1` (and `lambda1`). The constraint rows are divided by
//! `beta h^2` and the unknown multipliers are `beta h^2 lambda1`, so that both scale like
//! the force rows and the positions (whose derivative is about `M / (beta h^2)`) and the
//! iteration matrix stays well conditioned as `h -> 0`
//! (Bottasso, Bauchau & Cardona, SIAM J. Sci. Comput. 29, 2007). For closed loops the
//! iteration matrix is built from the model's own `M` and `Phi_q`, the simplified-Newton
//! matrix `[c1 M, Phi_q^T; Phi_q, 0]` (see [`Factor`]), banded for a large assembly, kept
//! over steps and refactored only when Newton slows; where it does not contract (stiff
//! forces), and for unconstrained models, the matrix is the forward-difference Jacobian of
//! the residual, formed once per step. Positions and velocities converge with order 2; the
//! position constraints hold to the Newton tolerance at every step (no drift), also through
//! singular positions of a mobile loop, where Newton's increments stall at the rounding
//! that the lost ranks amplify and the iterate there is accepted.

use super::{Integrator, positive_finite, second_order_end_packed, stack};
use super::{Observer, Record, Recorder, Solution, Stats, validate_problem};
use crate::banded::SaddleLu;
use crate::chart::shadow_motion;
use crate::closure::{ChartWatch, passed_limit};
use crate::error::{Error, Result};
use crate::integrate::events::Event;
use crate::integrate::solution::Flow;
use crate::jacobian::forward_difference;
use crate::linalg::Lu;
use crate::model::{Constrained, Matrix, Mechanism, OdeSystem, Vector};

/// The initial state of a run: time, positions, velocities, accelerations, and the first
/// unknowns `z0 = [q0; extra]`.
#[derive(Debug, Clone, Copy)]
struct Start<const N: usize, const K: usize> {
    t0: f64,
    q0: Vector<N>,
    qd0: Vector<N>,
    qdd0: Vector<N>,
    z0: Vector<K>,
}

/// Fixed-step generalized-α integrator.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralizedAlpha {
    /// Spectral radius at infinite frequency, in `[0, 1]`: 1 is no numerical damping (the
    /// trapezoidal rule), 0 annihilates the highest frequencies in one step.
    pub rho_inf: f64,
    /// Step size. The interval is split into `ceil((t1 - t0) / h)` equal steps.
    pub h: f64,
    /// Steps allowed before [`Error::TooManySteps`].
    pub max_steps: usize,
    /// Newton converges when every component of the last position increment (or the error
    /// left estimated from the contraction `theta`, `theta / (1 - theta)` times it) moves
    /// the step's positions and velocities by at most `tol` relative to them:
    /// `|dq_i| <= tol (1 + |q_i|)` and `gamma / (beta h) |dq_i| <= tol (1 + |qd_i|)`; or
    /// when the increments stop contracting (rounding) within `1e3 tol (1 + |q_i|)`.
    pub tol: f64,
    /// Newton iterations per step before [`Error::NewtonFailed`].
    pub max_iterations: usize,
    /// Keep one Hermite segment per step (`Solution::at` needs it).
    pub dense: bool,
    /// Which states the solution keeps.
    pub record: Record,
}

/// The four parameters of the method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// `alpha_m = (2 rho - 1) / (rho + 1)`.
    pub alpha_m: f64,
    /// `alpha_f = rho / (rho + 1)`.
    pub alpha_f: f64,
    /// `gamma = 1/2 - alpha_m + alpha_f` (second order).
    pub gamma: f64,
    /// `beta = (gamma + 1/2)^2 / 4` (unconditional stability, maximal high-frequency damping).
    pub beta: f64,
}

impl Coefficients {
    /// Chung & Hulbert (1993): the parameters for the spectral
    /// radius `rho` at infinity.
    pub fn from_rho_inf(rho: f64) -> Result<Self> {
        if !(0.0..=1.0).contains(&rho) {
            return Err(Error::InvalidInput {
                what: "rho_inf",
                detail: format!("must be in [0, 1], got {}", crate::error::Num(rho)),
            });
        }
        let alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
        let alpha_f = rho / (rho + 1.0);
        let gamma = 0.5 - alpha_m + alpha_f;
        let beta = 0.25 * (gamma + 0.5).powi(2);
        Ok(Coefficients {
            alpha_m,
            alpha_f,
            gamma,
            beta,
        })
    }
}

impl GeneralizedAlpha {
    /// Step `h` with `rho_inf` (0.9 is a common choice), `tol = 1e-12`, 20 iterations,
    /// `max_steps = 10_000_000`.
    pub fn new(rho_inf: f64, h: f64) -> Self {
        GeneralizedAlpha {
            rho_inf,
            h,
            max_steps: 10_000_000,
            tol: 1e-12,
            max_iterations: 20,
            dense: true,
            record: Record::Steps,
        }
    }

    /// The same method keeping only what `record` asks, with dense output `dense`.
    pub fn recording(self, record: Record, dense: bool) -> Self {
        GeneralizedAlpha {
            record,
            dense,
            ..self
        }
    }

    /// Integrate an unconstrained mechanism from `(t0, q0, qd0)` to `t1`; the solution's
    /// state is `y = [q; qd]` (`D = 2 N`), with cubic Hermite dense output. A model with
    /// constraint rows ([`Mechanism::CONSTRAINTS`]) is refused with [`Error::InvalidInput`]:
    /// it runs through [`Self::solve_constrained`].
    pub fn solve<S: Mechanism<N>, const N: usize, const D: usize>(
        &self,
        sys: &S,
        t0: f64,
        q0: Vector<N>,
        qd0: Vector<N>,
        t1: f64,
        events: &[Event<'_, D>],
    ) -> Result<Solution<D>> {
        self.solve_observed(sys, t0, q0, qd0, t1, events, None)
    }

    /// [`Self::solve`], calling `observer` after every step; it ends the run by returning
    /// [`Flow::Stop`].
    #[allow(
        clippy::too_many_arguments,
        reason = "solve's arguments and the observer"
    )]
    pub fn solve_observed<S: Mechanism<N>, const N: usize, const D: usize>(
        &self,
        sys: &S,
        t0: f64,
        q0: Vector<N>,
        qd0: Vector<N>,
        t1: f64,
        events: &[Event<'_, D>],
        observer: Option<&mut Observer<'_, D>>,
    ) -> Result<Solution<D>> {
        crate::model::unconstrained::<S, N>("GeneralizedAlpha::solve", "solve_constrained")?;
        let qdd0 = sys.acceleration(t0, &q0, &qd0)?;
        let residual = |_, t, z: &Vector<N>, qd1: &Vector<N>, qdd1: &Vector<N>| {
            Ok(sys.mass_matrix(t, z)? * qdd1 - sys.forces(t, z, qd1)?)
        };
        let start = Start {
            t0,
            q0,
            qd0,
            qdd0,
            z0: q0,
        };
        const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
        let chart = Chart {
            margin: |t: f64, y: &Vector<D>| sys.chart_margin(t, &y.fixed_rows::<N>(0).into_owned()),
            explain: |t: f64, y: &Vector<D>| {
                let (q, qd) = (
                    y.fixed_rows::<N>(0).into_owned(),
                    y.fixed_rows::<N>(N).into_owned(),
                );
                sys.acceleration(t, &q, &qd).err()
            },
            rotations: sys.rotation_charts(),
        };
        self.run::<N, N, D>(
            start,
            t1,
            events,
            observer,
            stack,
            residual,
            no_structure(),
            chart,
        )
    }

    /// Integrate a closed loop in index-3 form (`A = N + M` unknowns `(q1, lambda1)` per
    /// step). `(q0, qd0)` should satisfy the position and velocity constraints
    /// (see [`analysis::assemble`](crate::analysis::assemble)).
    pub fn solve_constrained<
        S: Constrained<N, M>,
        const N: usize,
        const M: usize,
        const A: usize,
        const D: usize,
    >(
        &self,
        sys: &S,
        t0: f64,
        q0: Vector<N>,
        qd0: Vector<N>,
        t1: f64,
        events: &[Event<'_, D>],
    ) -> Result<Solution<D>> {
        // Through the bridge over singular positions (`crate::passage`), to `h^2`;
        // `solve_constrained_observed` is one raw run.
        let settings = crate::passage::Settings::fixed(self.h, 2, self.dense, &self.record);
        let y0 = super::stack::<N, D>(&q0, &qd0);
        crate::passage::solve_generalized_alpha::<S, N, M, A, D>(
            self, sys, t0, y0, t1, events, &settings,
        )
        .map(|run| run.solution)
    }

    /// [`Self::solve_constrained`], calling `observer` after every step.
    #[allow(
        clippy::too_many_arguments,
        reason = "solve's arguments and the observer"
    )]
    pub fn solve_constrained_observed<
        S: Constrained<N, M>,
        const N: usize,
        const M: usize,
        const A: usize,
        const D: usize,
    >(
        &self,
        sys: &S,
        t0: f64,
        q0: Vector<N>,
        qd0: Vector<N>,
        t1: f64,
        events: &[Event<'_, D>],
        observer: Option<&mut Observer<'_, D>>,
    ) -> Result<Solution<D>> {
        const { assert!(A == N + M, "the unknowns are (q, lambda): A = N + M") };
        const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
        let (qdd0, lambda0) = sys.acceleration_and_multipliers(t0, &q0, &qd0)?;
        // Redundant rows (found once, at `q0`: a redundant row stays redundant; a rank lost
        // at a singular position is the bridge's business) make the saddle matrix singular
        // and the multipliers not unique. They leave Newton's system: the equation of such a
        // row is `lambda_i = 0` (a basic choice of the multipliers; `q` is unique).
        let redundant = crate::analysis::rank_and_redundant(&sys.phi_q(t0, &q0)).1;
        let kept = |mut phi_q: Matrix<M, N>| {
            for &i in &redundant {
                phi_q.row_mut(i).fill(0.0);
            }
            phi_q
        };
        let mut z0 = Vector::<A>::zeros();
        z0.fixed_rows_mut::<N>(0).copy_from(&q0);
        z0.fixed_rows_mut::<M>(N).copy_from(&lambda0);
        for &i in &redundant {
            z0[N + i] = 0.0;
        }
        let start = Start {
            t0,
            q0,
            qd0,
            qdd0,
            z0,
        };
        // The iteration matrix from structure: `M` and `Phi_q` at the iterate (see `Factor`).
        let structure = |t: f64, q1: &Vector<N>, c1: f64| {
            Ok(Factor::saddle(
                &(sys.mass_matrix(t, q1)? * c1),
                &kept(sys.phi_q(t, q1)),
                &redundant,
            ))
        };
        self.run::<N, A, D>(
            start,
            t1,
            events,
            observer,
            stack,
            |scale, t, z: &Vector<A>, qd1, qdd1| {
                let q1 = z.fixed_rows::<N>(0).into_owned();
                // The unknowns carry beta h^2 lambda (see `run`).
                let lambda = z.fixed_rows::<M>(N) * scale;
                let mut r = Vector::<A>::zeros();
                r.fixed_rows_mut::<N>(0).copy_from(
                    &(sys.inverse_dynamics(t, &q1, qd1, qdd1)?
                        + kept(sys.phi_q(t, &q1)).transpose() * lambda),
                );
                r.fixed_rows_mut::<M>(N)
                    .copy_from(&(sys.phi(t, &q1) * scale));
                for &i in &redundant {
                    r[N + i] = z[N + i] * scale;
                }
                Ok(r)
            },
            Some(structure),
            no_chart(),
        )
    }

    /// The stepping loop. The unknowns of a step are `z = [q1; extra]` (`K >= N`);
    /// `residual(1 / (beta h^2), t1, z, qd1, qdd1)` gets the velocities and accelerations
    /// that the generalized-α formulas give for `q1`; `pack(q, qd)` is the state recorded.
    /// `structure(t1, q1, c1)`, where given, factors the iteration matrix from the model's
    /// own matrices (see [`Factor`]); without it (or where it fails to converge) the matrix is
    /// the forward-difference Jacobian of the residual.
    #[allow(
        clippy::too_many_arguments,
        reason = "the run's start, end, events, observer, state packing, residual and matrix"
    )]
    fn run<const N: usize, const K: usize, const D: usize>(
        &self,
        start: Start<N, K>,
        t1: f64,
        events: &[Event<'_, D>],
        observer: Option<&mut Observer<'_, D>>,
        pack: impl Fn(&Vector<N>, &Vector<N>) -> Vector<D>,
        residual: impl Fn(f64, f64, &Vector<K>, &Vector<N>, &Vector<N>) -> Result<Vector<K>>,
        structure: Option<impl Fn(f64, &Vector<N>, f64) -> Result<Option<Factor<K>>>>,
        chart: Chart<
            '_,
            impl Fn(f64, &Vector<D>) -> Option<f64>,
            impl Fn(f64, &Vector<D>) -> Option<Error>,
        >,
    ) -> Result<Solution<D>> {
        let Start {
            t0,
            q0,
            qd0,
            qdd0,
            z0,
        } = start;
        const { assert!(K >= N, "the unknowns start with q1") };
        let c = Coefficients::from_rho_inf(self.rho_inf)?;
        self.validate()?;
        let y0 = pack(&q0, &qd0);
        validate_problem(t0, &y0, t1)?;
        let steps = ((t1 - t0) / self.h).ceil().max(1.0);
        if steps > self.max_steps as f64 {
            return Err(Error::TooManySteps {
                t: t0,
                steps: self.max_steps,
            });
        }
        let steps = steps as usize;
        let h = (t1 - t0) / steps as f64;
        self.record.validate()?;
        let mut recorder =
            Recorder::with(events, t0, y0, self.dense, self.record.clone()).observed(observer);
        let mut stats = Stats::default();
        if h == 0.0 {
            return recorder.finish(stats);
        }
        let (mut q, mut qd, mut qdd, mut a, mut z) = (q0, qd0, qdd0, qdd0, z0);
        let bh2 = c.beta * h * h;
        // The unknowns after q1 (the multipliers) are carried scaled by beta h^2, like the
        // constraint rows: unscaled, a multiplier of 1e7 N next to positions of 0.1 m gave
        // the forward-difference Jacobian a column below the residual's rounding (a zero
        // column for a multiplier that starts at 0), and Newton a singular matrix.
        for i in N..K {
            z[i] *= bh2;
        }
        let mut newton = Newton {
            factor: None,
            structure,
            structured: true,
        };
        let mut watch = ChartWatch::<D>::default();
        for k in 0..steps {
            let t = t0 + k as f64 * h;
            let t_next = if k + 1 == steps {
                t1
            } else {
                t0 + (k + 1) as f64 * h
            };
            // Everything at t_next follows from q1.
            let base = q + qd * h + a * (h * h * (0.5 - c.beta));
            // Newton's unknowns are the position increment d = q1 - base = beta h^2 a1 (and
            // the multipliers): a1 = d / (beta h^2) carries d's full relative precision,
            // where (q1 - base) / (beta h^2) lost eps |q| / (beta h^2) to cancellation, a
            // velocity error of eps |q| gamma / (beta h) that grew as h shrank.
            let kinematics = |d: &Vector<N>| {
                let a1 = d / bh2;
                let qd1 = qd + (a * (1.0 - c.gamma) + a1 * c.gamma) * h;
                let qdd1 =
                    (a1 * (1.0 - c.alpha_m) + a * c.alpha_m - qdd * c.alpha_f) / (1.0 - c.alpha_f);
                (base + d, a1, qd1, qdd1)
            };
            // Predictor: the acceleration stays what it was (qdd1 = qdd).
            let a_pred = (qdd - a * c.alpha_m) / (1.0 - c.alpha_m);
            z.fixed_rows_mut::<N>(0).copy_from(&(a_pred * bh2));
            let step = Step {
                t1: t_next,
                h,
                bh2,
                c1: (1.0 - c.alpha_m) / (1.0 - c.alpha_f),
                v_gain: c.gamma / (c.beta * h),
            };
            let solved = self.newton(
                &mut newton,
                &step,
                z,
                |d| kinematics(d),
                &residual,
                &mut stats,
            );
            // Newton failing on its way to a limit position (within the next step): the
            // position, not the solver.
            z = solved.map_err(|e| {
                let margin = |y: &Vector<D>| (chart.margin)(t_next, y);
                match watch.passed(t_next + h, &margin) {
                    Some((ts, yb)) => passed_limit(ts, &yb, (chart.explain)(ts, &yb)),
                    None => e,
                }
            })?;
            let (mut q1, mut a1, mut qd1, mut qdd1) =
                kinematics(&z.fixed_rows::<N>(0).into_owned());
            let (mut y1, seg) =
                second_order_end_packed(&pack, t, t_next, (&q, &qd, &qdd), (&q1, &qd1, &qdd1))?;
            // Past a half turn a ball joint's parameters switch to their shadow set after the
            // step's segment (which interpolates the step as computed), with the rates and
            // both accelerations mapped along; the predictor starts there. `z`'s position
            // part is only the next predictor's slot, refilled below.
            let rotations = chart.rotations;
            if shadow_motion(&mut q1, &mut qd1, &mut [&mut qdd1, &mut a1], rotations) {
                y1 = pack(&q1, &qd1);
            }
            stats.n_steps += 1;
            stats.n_accepted += 1;
            if let Some((ts, yb)) = watch.accept(t_next, &y1, |y| (chart.margin)(t_next, y)) {
                return Err(passed_limit(ts, &yb, (chart.explain)(ts, &yb)));
            }
            (q, qd, qdd, a) = (q1, qd1, qdd1, a1);
            if recorder.accept(seg, &y1) == Flow::Stop {
                break;
            }
        }
        recorder.finish(stats)
    }

    /// Newton's iteration for one step from `z` (the predictor). The matrix from structure
    /// is kept over steps and refactored at the iterate only when the iteration slows
    /// (contraction above [`SLOW`]), as Radau5 keeps its Jacobian; the forward-difference
    /// matrix is formed at every step's predictor and once more at the fifth iteration.
    /// Converged when the last increment, or the error left estimated from the contraction
    /// `theta` (`theta / (1 - theta)` times it), passes [`Self::tol`]'s test; or when the
    /// increments stall within [`STALL`] times the positions' test (rounding).
    fn newton<const N: usize, const K: usize, F>(
        &self,
        newton: &mut Newton<K, F>,
        step: &Step,
        z0: Vector<K>,
        kinematics: impl Fn(&Vector<N>) -> (Vector<N>, Vector<N>, Vector<N>, Vector<N>),
        residual: &impl Fn(f64, f64, &Vector<K>, &Vector<N>, &Vector<N>) -> Result<Vector<K>>,
        stats: &mut Stats,
    ) -> Result<Vector<K>>
    where
        F: Fn(f64, &Vector<N>, f64) -> Result<Option<Factor<K>>>,
    {
        let Step {
            t1, h, bh2, v_gain, ..
        } = *step;
        let r = |z: &Vector<K>| {
            let (q1, _, qd1, qdd1) = kinematics(&z.fixed_rows::<N>(0).into_owned());
            let mut zq = *z;
            zq.fixed_rows_mut::<N>(0).copy_from(&q1);
            residual(1.0 / bh2, t1, &zq, &qd1, &qdd1)
        };
        let failed = Error::NewtonFailed { t: t1, h };
        let mut z = z0;
        // The forward-difference matrix depends on the step: formed at every step. Each
        // step tries the matrix from structure first, where there is one.
        if !newton.structured() {
            newton.factor = None;
        }
        newton.structured = true;
        let (mut fresh, mut last, mut last_theta) = (false, f64::INFINITY, 0.0);
        for iteration in 0..self.max_iterations {
            if newton.factor.is_none() || (!newton.structured() && iteration == 4) {
                let q1 = kinematics(&z.fixed_rows::<N>(0).into_owned()).0;
                newton.form(&r, step, (&z, &q1), stats)?;
                fresh = true;
            }
            let rz = r(&z)?;
            stats.n_rhs += 1;
            let dz = newton.solve(&rz).ok_or(failed.clone())?;
            if !dz.iter().all(|v| v.is_finite()) {
                return Err(Error::NonFinite { t: t1 });
            }
            z += dz;
            let (q1, _, qd1, _) = kinematics(&z.fixed_rows::<N>(0).into_owned());
            let size = dz.fixed_rows::<N>(0).amax();
            let theta = if iteration == 0 { 0.0 } else { size / last };
            // `passes(f)`: the increment scaled by `f` meets the positions' and the
            // velocities' tests.
            let passes = |f: f64, velocities: bool| {
                (0..N).all(|i| {
                    let d = f * dz[i].abs();
                    d <= self.tol * (1.0 + q1[i].abs())
                        && (!velocities || v_gain * d <= self.tol * (1.0 + qd1[i].abs()))
                })
            };
            let left = if iteration > 0 && theta < 1.0 {
                theta / (1.0 - theta)
            } else {
                1.0
            };
            if passes(1.0, true) || passes(left, true) {
                return Ok(z);
            }
            // Increments that stop contracting (with a matrix formed in this step, or right
            // after contracting fast) within `STALL` times the positions' tolerance: the
            // residual's rounding, amplified by a stiff model or an ill-conditioned matrix
            // (near a singular position, along the motions the constraints stop fixing). As
            // converged as it gets: the better of the last two iterates.
            let stalled = theta > 0.5 && (fresh || last_theta <= SLOW);
            if stalled && passes(1.0 / STALL, false) {
                return Ok(if theta > 1.0 { z - dz } else { z });
            }
            if theta > SLOW && !fresh {
                // A matrix from earlier steps: refactor, at the predictor if diverging.
                newton.factor = None;
                if theta >= 1.0 {
                    z = z0;
                }
            } else if theta >= 1.0 && newton.structured() && fresh {
                // The matrix from structure lacks what dominates here (stiff forces, or
                // the curvature of the constraints near a singular position): the
                // forward-difference Jacobian for this step, from the predictor.
                newton.structured = false;
                newton.factor = None;
                z = z0;
            }
            (last, last_theta) = (size, theta);
        }
        Err(failed)
    }

    fn validate(&self) -> Result<()> {
        let bad = |what: &'static str, detail: String| Err(Error::InvalidInput { what, detail });
        positive_finite("h", self.h)?;
        positive_finite("tol", self.tol)?;
        if self.max_iterations == 0 || self.max_steps == 0 {
            return bad("max_iterations/max_steps", "must be at least 1".to_string());
        }
        Ok(())
    }
}

/// Contraction of Newton's increments above which a matrix kept from earlier steps is
/// refactored at the iterate.
const SLOW: f64 = 0.2;

/// Newton's increments that stall (a matrix formed in the step no longer contracts them)
/// within this many times the positions' tolerance end the iteration.
const STALL: f64 = 1e3;

/// Saddle-point systems larger than this (`N + M`) are factored banded
/// ([`crate::banded::SaddleLu`]), smaller ones dense.
const BANDED_FROM: usize = 24;

/// A minimal loop's closed-form chart, watched for a limit position stepped over
/// ([`ChartWatch`]): its margin at a state `y = [q; qd]`, and the model's own error there;
/// and the ball joints' rotation charts, switched after each step ([`crate::chart`]).
struct Chart<'r, M, E> {
    margin: M,
    explain: E,
    rotations: &'r [[usize; 3]],
}

/// No chart: constrained (index-3) loops keep all their coordinates.
#[allow(clippy::type_complexity, reason = "the two closures' types")]
fn no_chart<const D: usize>() -> Chart<
    'static,
    impl Fn(f64, &Vector<D>) -> Option<f64>,
    impl Fn(f64, &Vector<D>) -> Option<Error>,
> {
    Chart {
        margin: |_: f64, _: &Vector<D>| None,
        explain: |_: f64, _: &Vector<D>| None,
        rotations: &[],
    }
}

/// No structure: the forward-difference matrix.
#[allow(clippy::type_complexity, reason = "the structure argument's type")]
fn no_structure<const N: usize, const K: usize>()
-> Option<fn(f64, &Vector<N>, f64) -> Result<Option<Factor<K>>>> {
    None
}

/// What one step's Newton iteration needs to know of the step.
#[derive(Debug, Clone, Copy)]
struct Step {
    t1: f64,
    h: f64,
    /// `beta h^2`.
    bh2: f64,
    /// `(1 - alpha_m) / (1 - alpha_f)`: `d qdd1 / d q1` times `beta h^2`.
    c1: f64,
    /// `gamma / (beta h)`: `d qd1 / d q1`.
    v_gain: f64,
}

/// A factored iteration matrix. From structure (closed loops, unknowns `[d; beta h^2
/// lambda]`): the residual's derivative times `beta h^2`,
///
/// ```text
/// [c1 M + gamma h C + beta h^2 K,  Phi_q^T]      c1 = (1 - alpha_m) / (1 - alpha_f),
/// [Phi_q,                          0      ]      C = -df/dqd,  K = d(M qdd + Phi_q^T lambda - f)/dq,
/// ```
///
/// taken as the simplified-Newton matrix `[c1 M, Phi_q^T; Phi_q, 0]`: `C` and `K` are
/// `O(h)` and `O(h^2)` beside `c1 M` (their absence only slows the contraction, which the
/// convergence test measures; the answer is the residual's root either way). Banded for a
/// large assembly, dense LU below [`BANDED_FROM`] or where the band refuses (a pivot ratio
/// below `1e-8`, near a singular position). Otherwise the forward-difference Jacobian of
/// the residual.
pub(crate) enum Factor<const K: usize> {
    Saddle(SaddleLu),
    Dense(Box<Lu<f64, K>>),
}

impl<const K: usize> Factor<K> {
    /// `[c1 M, Phi_q^T; Phi_q, 0]` factored (`mass` is `c1 M`); `None` when singular. The
    /// `redundant` rows of `phi_q` are zero and their equations `lambda_i = 0` (dense).
    fn saddle<const N: usize, const M: usize>(
        mass: &Matrix<N, N>,
        phi_q: &Matrix<M, N>,
        redundant: &[usize],
    ) -> Option<Self> {
        const { assert!(K == N + M, "the unknowns are (q, lambda)") };
        if K > BANDED_FROM
            && redundant.is_empty()
            && let Some(lu) = SaddleLu::factor(mass, phi_q)
        {
            return Some(Factor::Saddle(lu));
        }
        let mut j = Box::new(Matrix::<K, K>::zeros());
        j.fixed_view_mut::<N, N>(0, 0).copy_from(mass);
        j.fixed_view_mut::<M, N>(N, 0).copy_from(phi_q);
        j.fixed_view_mut::<N, M>(0, N).copy_from(&phi_q.transpose());
        for &i in redundant {
            j[(N + i, N + i)] = 1.0;
        }
        Lu::factor(*j).map(|lu| Factor::Dense(Box::new(lu)))
    }

    /// `J^-1 r`.
    fn solve(&self, r: &Vector<K>) -> Vector<K> {
        match self {
            Factor::Saddle(lu) => {
                let mut z = *r;
                lu.solve(z.as_mut_slice());
                z
            }
            Factor::Dense(lu) => lu.solve(r),
        }
    }
}

/// Newton's matrix over a run: the factor kept (with the factor its right-hand side is
/// scaled by: `beta h^2` from structure, 1 for forward differences), how to form it from
/// structure, and whether structure serves this step (where the matrix from structure does
/// not contract, the step turns to forward differences).
struct Newton<const K: usize, F> {
    factor: Option<(Factor<K>, f64)>,
    structure: Option<F>,
    structured: bool,
}

impl<const K: usize, F> Newton<K, F> {
    fn structured(&self) -> bool {
        self.structured && self.structure.is_some()
    }

    /// The increment `-J^-1 r`.
    fn solve(&self, r: &Vector<K>) -> Option<Vector<K>> {
        let (factor, scale) = self.factor.as_ref()?;
        Some(factor.solve(&(r * -*scale)))
    }

    /// Form and factor the matrix at the iterate `z` (positions `q1`).
    fn form<const N: usize>(
        &mut self,
        r: &impl Fn(&Vector<K>) -> Result<Vector<K>>,
        step: &Step,
        (z, q1): (&Vector<K>, &Vector<N>),
        stats: &mut Stats,
    ) -> Result<()>
    where
        F: Fn(f64, &Vector<N>, f64) -> Result<Option<Factor<K>>>,
    {
        let Step { t1, h, bh2, c1, .. } = *step;
        stats.n_jac += 1;
        stats.n_lu += 1;
        let failed = Error::NewtonFailed { t: t1, h };
        if self.structured()
            && let Some(structure) = &self.structure
        {
            self.factor = Some((structure(t1, q1, c1)?.ok_or(failed)?, bh2));
            return Ok(());
        }
        // A residual's own error (a singular position) as it is; a column that overflowed at `t1`.
        let jac = forward_difference(r, z).map_err(|e| match e {
            Error::NonFinite { .. } => Error::NonFinite { t: t1 },
            e => e,
        })?;
        stats.n_rhs += K + 1;
        let lu = Lu::factor(jac).ok_or(failed)?;
        self.factor = Some((Factor::Dense(Box::new(lu)), 1.0));
        Ok(())
    }
}

/// A first-order system `y = [q; qd]`, `y' = [qd; a(t, q, qd)]` (what a mechanism's `rhs`
/// is, and a hybrid system's in each of its modes) integrated as the second-order
/// `qdd = a(t, q, qd)`, i.e. with `M = I`: this is how [`crate::hybrid::solve`] drives
/// generalized-α mode by mode. The const generics cannot name `N = D / 2`, so the positions
/// are padded to `D` coordinates whose last `D / 2` stay exactly zero (`qdd = 0` there,
/// decoupled in the Newton matrix). Refused with [`Error::InvalidInput`] unless `D` is even
/// and the upper half of `f(t0, y0)` is the lower half of `y0`. No projection is applied.
impl Integrator for GeneralizedAlpha {
    fn passages(&self) -> Option<crate::passage::Settings> {
        Some(crate::passage::Settings::fixed(
            self.h,
            2,
            self.dense,
            &self.record,
        ))
    }

    fn name(&self) -> &'static str {
        "generalized-alpha"
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
        validate_problem(t0, &y0, t1)?;
        let n = D / 2;
        let f0 = sys.rhs(t0, &y0)?;
        if !D.is_multiple_of(2) || (0..n).any(|i| f0[i] != y0[n + i]) {
            return Err(Error::InvalidInput {
                what: "system",
                detail: "generalized-alpha integrates second-order systems, y = [q; qd] with \
                         y' = [qd; qdd]"
                    .to_string(),
            });
        }
        let pad = |v: &Vector<D>| Vector::<D>::from_fn(|i, _| if i < n { v[n + i] } else { 0.0 });
        let q0 = Vector::<D>::from_fn(|i, _| if i < n { y0[i] } else { 0.0 });
        let (qd0, qdd0) = (pad(&y0), pad(&f0));
        let pack = |q: &Vector<D>, qd: &Vector<D>| {
            Vector::<D>::from_fn(|i, _| if i < n { q[i] } else { qd[i - n] })
        };
        let residual = |_, t, z: &Vector<D>, qd1: &Vector<D>, qdd1: &Vector<D>| {
            let f = sys.rhs(t, &pack(z, qd1))?;
            Ok(Vector::<D>::from_fn(|i, _| {
                if i < n { qdd1[i] - f[n + i] } else { qdd1[i] }
            }))
        };
        let start = Start {
            t0,
            q0,
            qd0,
            qdd0,
            z0: q0,
        };
        let chart = Chart {
            margin: |t: f64, y: &Vector<D>| sys.chart_margin(t, y),
            explain: |t: f64, y: &Vector<D>| sys.rhs(t, y).err(),
            rotations: sys.rotation_charts(),
        };
        self.run::<D, D, D>(
            start,
            t1,
            events,
            observer,
            pack,
            residual,
            no_structure(),
            chart,
        )
        .map(|mut s| {
            s.stats.n_rhs += 1;
            s
        })
    }
}
