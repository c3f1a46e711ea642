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
