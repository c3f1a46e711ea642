//! The classic fourth-order Runge–Kutta method with fixed steps.

use super::tableau::{Erk, RK4};
use super::{
    Event, Integrator, Observer, Record, Recorder, Segment, Solution, Stats, validate_problem,
};
use super::{non_finite, positive_finite};
use crate::error::{Error, Result};
use crate::model::{OdeSystem, Vector};

/// Classic RK4 with a fixed step `h` (the last step is shortened to end exactly at `t1`)
/// and cubic Hermite dense output ([`Segment::hermite`]). The end derivative of one step is
/// the first stage of the next, so the dense output costs one extra `rhs` call per run.
/// [`OdeSystem::project`] is called after every step (its default does nothing); a limit
/// position of a loop's closed forms stepped over stops the run ([`crate::closure::ChartWatch`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Rk4 {
    /// Step size.
    pub h: f64,
    /// Steps allowed before [`Error::TooManySteps`].
    pub max_steps: usize,
    /// Keep one Hermite segment per step (`Solution::at` needs it).
    pub dense: bool,
    /// Which states the solution keeps.
    pub record: Record,
}

impl Rk4 {
    /// RK4 with step `h`, at most a million steps, every step and its segment kept.
    pub fn new(h: f64) -> Self {
        Rk4 {
            h,
            max_steps: 1_000_000,
            dense: true,
            record: Record::Steps,
        }
    }

    /// The same method keeping only what `record` asks, with dense output `dense`.
    pub fn recording(self, record: Record, dense: bool) -> Self {
        Rk4 {
            record,
            dense,
            ..self
        }
    }
}

impl Integrator for Rk4 {
    fn passages(&self) -> Option<crate::passage::Settings> {
        Some(crate::passage::Settings::fixed(
            self.h,
            4,
            self.dense,
            &self.record,
        ))
    }

    fn name(&self) -> &'static str {
        "RK4"
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
        positive_finite("h", self.h)?;
        self.record.validate()?;
        validate_problem(t0, &y0, t1)?;
        let mut rec =
            Recorder::with(events, t0, y0, self.dense, self.record.clone()).observed(observer);
        let mut stats = Stats::default();
        // Number of steps: the last one may be shorter, but not by a rounding sliver.
        let n = ((t1 - t0) / self.h * (1.0 - 1e-12)).ceil() as usize;
        let (mut t, mut y) = (t0, y0);
        let mut k = [Vector::<D>::zeros(); 4];
        let mut z = [Vector::<D>::zeros(); 4];
        let mut chart = crate::closure::ChartWatch::<D>::default();
        let mut unstable = 0;
        if n > 0 {
            k[0] = sys.rhs(t0, &y0)?;
            stats.n_rhs += 1;
            if non_finite(&k[0]) {
                return Err(Error::NonFinite { t: t0 });
            }
        }
        for step in 1..=n {
            if stats.n_steps >= self.max_steps {
                return Err(Error::TooManySteps {
                    t,
                    steps: stats.n_steps,
                });
            }
            let t_new = if step == n {
                t1
            } else {
                t0 + step as f64 * self.h
            };
            let h = t_new - t;
            RK4.stages(sys, t, &y, h, &mut k, &mut z)?;
            unstable = match beyond_stability(h, &y, &k) {
                Some(hl) if unstable + 1 >= n.min(PERSIST) => return Err(too_long(t, h, hl)),
                Some(_) => unstable + 1,
                None => 0,
            };
            stats.n_rhs += 3;
            stats.n_steps += 1;
            stats.n_accepted += 1;
            let mut y1 = y + Erk::combine(&RK4.b, &k, h);
            sys.project(t_new, &mut y1)?;
            if non_finite(&y1) {
                return Err(Error::NonFinite { t: t_new });
            }
            let f1 = sys.rhs(t_new, &y1)?;
            stats.n_rhs += 1;
            if non_finite(&f1) {
                return Err(Error::NonFinite { t: t_new });
            }
            // A limit position stepped over (stages inside the domain) stops the run.
            if let Some((ts, yb)) = chart.accept(t_new, &y1, |y| sys.chart_margin(t_new, y)) {
                return Err(crate::closure::passed_limit(
                    ts,
                    &yb,
                    sys.rhs(ts, &yb).err(),
                ));
            }
            let flow = rec.accept_with(t_new, &y1, || Segment::hermite(t, h, &y, &k[0], &y1, &f1));
            (t, y, k[0]) = (t_new, y1, f1);
            if flow == super::Flow::Stop {
                break;
            }
        }
        rec.finish(stats)
    }
}

/// `h |lambda|` above which RK4 amplifies an undamped oscillation: `2 sqrt(2)`, where its
/// stability region meets the imaginary axis (a mechanism's fast modes lie near it).
const LIMIT: f64 = 2.0 * std::f64::consts::SQRT_2;

/// Steps in a row beyond [`LIMIT`] that stop a run (fewer in a shorter run): one step
/// across a kink of the right-hand side (`abs`, `min` in a load) may show a large estimate.
const PERSIST: usize = 3;

/// The step's `h |lambda|` when it exceeds [`LIMIT`], from its stages: `k2 - k1` is
/// `(h/2)^2 J^2 k0` to second order, so `h |lambda| = 2 sqrt(|k2 - k1| / |k0|)`, exact for
/// `y' = lambda y`. `J^2` maps positions to positions and rates to rates, so the mixed
/// units of `[q; qd]` cancel (`|k1 - k0| / |k0|` would swing from 1 to `w^2` over an
/// oscillation of `w`). A state whose change is at rounding level is not judged.
fn beyond_stability<const D: usize>(h: f64, y: &Vector<D>, k: &[Vector<D>; 4]) -> Option<f64> {
    let (d0, d21) = (k[0].norm(), (k[2] - k[1]).norm());
    let moving = h * d0 > 1e-10 * (1.0 + y.norm());
    let hl = 2.0 * (d21 / d0).sqrt();
    (moving && hl > LIMIT).then_some(hl)
}

/// The error of a run whose steps resolve no motion of its fastest mode: the state would
/// grow by `|R(h lambda)| > 1` a step and the run return a finite, wrong answer.
fn too_long(t: f64, h: f64, hl: f64) -> Error {
    Error::InvalidInput {
        what: "h",
        detail: format!(
            "at t = {} the step is beyond RK4's stability limit: h |lambda| = {hl:.3} > {LIMIT:.3} \
             (|lambda| estimated from the stages), so the run would diverge and return a wrong \
             answer; take h below {:.3e}, or an adaptive or implicit method (Radau5 for a stiff \
             model)",
            crate::error::Num(t),
            h * LIMIT / hl
        ),
    }
}
