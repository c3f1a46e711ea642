//! Time integration: shared options, statistics, dense output and the solution record.
//!
//! Every method advances an [`OdeSystem`] of fixed dimension `D` and
//! returns a [`Solution`]: the states [`Record`] asks for (by default every accepted
//! step), the dense output between them (one [`Segment`] per step when `dense`), the events
//! found, the final state, and the work done ([`Stats`]). An [`Observer`] sees every
//! accepted step as it is taken ([`Integrator::solve_observed`]).
//!
//! Memory is bounded by what is kept: `Record::Final` (or `Every(k)`, or `Times`) with
//! `dense = false` holds a few states whatever the number of steps.

pub mod ali3;
pub mod auto;
pub mod control;
pub mod dense;
pub mod dop853;
pub mod dop853_tableau;
pub mod dopri5;
pub mod events;
mod explicit;
pub mod gauss;
pub mod generalized_alpha;
pub mod radau5;
pub mod rk4;
pub mod solution;
mod stack;
pub mod tableau;
pub mod vern9;
pub mod vern9_tableau;

pub use ali3::Ali3;
pub use auto::Auto;
pub use dense::Segment;
pub use dop853::Dop853;
pub use dopri5::Dopri5;
pub use events::{Direction, Event, EventHit};
pub use gauss::Gauss;
pub use generalized_alpha::GeneralizedAlpha;
pub use radau5::Radau5;
pub use rk4::Rk4;
pub use solution::{Flow, Observer, Record, Recorder, Solution, Step};
pub use vern9::Vern9;

use crate::error::{Error, Num, Result};
use crate::model::{OdeSystem, Vector};

/// A time-integration method: advance `sys` from `(t0, y0)` to `t1`, locating `events`.
pub trait Integrator {
    /// Short name for reports ("DOPRI5", "RK4", ...).
    fn name(&self) -> &'static str;

    /// Integrate `y' = f(t, y)` from `t0` to `t1 >= t0`. The solution ends at `t1`, or at
    /// the first terminal event. A system with modes ([`OdeSystem::hybrid`]: a model with
    /// Coulomb friction) is integrated one mode at a time, exactly as
    /// [`crate::hybrid::solve`] with its default settings does (stuck contacts held
    /// exactly, every switch located; they are in `Solution::switches`). A closed loop
    /// ([`OdeSystem::passage`]) is integrated through its bridge over singular positions
    /// as [`Self::passages`] asks ([`crate::passage`]; the passages are in
    /// `Solution::passages`). A closed loop with friction runs by modes, each mode raw: a
    /// singular position inside a mode stops it with the typed error, not a bridge.
    fn solve<S: OdeSystem<D>, const D: usize>(
        &self,
        sys: &S,
        t0: f64,
        y0: Vector<D>,
        t1: f64,
        events: &[Event<'_, D>],
    ) -> Result<Solution<D>>
    where
        Self: Sized,
    {
        if let Some(modes) = sys.hybrid() {
            let settings = crate::hybrid::Settings::default();
            return modes.drive(self, (t0, y0, t1), events, &settings);
        }
        let run = match (sys.passage(), self.passages()) {
            (Some(bridge), Some(settings)) => {
                bridge.pass((t0, y0, t1), events, &settings, &mut |t, y, observer| {
                    self.solve_observed(sys, t, y, t1, events, Some(observer))
                })
            }
            _ => self.solve_observed(sys, t0, y0, t1, events, None),
        };
        match run {
            Err(e) if S::HYBRID => Err(crate::hybrid::hint(e)),
            run => run,
        }
    }

    /// How [`Self::solve`] bridges the singular positions of a closed loop; `None` runs
    /// it as one raw run. The default bridges to `1e-8`, every step kept; the adaptive
    /// methods use their `rtol` and recording ([`crate::passage::Settings::of`]).
    fn passages(&self) -> Option<crate::passage::Settings> {
        Some(crate::passage::Settings::new(1e-8))
    }

    /// One raw run of [`Self::solve`] (no bridge over singular positions), calling
    /// `observer` after every accepted step (after its events are located); the run ends
    /// where the observer returns [`Flow::Stop`].
    fn solve_observed<S: OdeSystem<D>, const D: usize>(
        &self,
        sys: &S,
        t0: f64,
        y0: Vector<D>,
        t1: f64,
        events: &[Event<'_, D>],
        observer: Option<&mut Observer<'_, D>>,
    ) -> Result<Solution<D>>;

    /// The same method with its first step set to `h` (`Options::h0`), or `None` for a
    /// method without that setting. [`crate::hybrid`] restarts a mode with the step the
    /// method last took in that mode rather than a fresh guess: the dynamics on both sides
    /// of a switch are smooth, and a guess from rest (a stuck state) starts at `1e-6`.
    fn with_first_step(&self, _h: f64) -> Option<Self>
    where
        Self: Sized,
    {
        None
    }
}

/// Step size, tolerance and recording settings shared by the adaptive methods. `Default`
/// gives Hairer's defaults, and records every step with dense output.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Relative tolerance (adaptive methods).
    pub rtol: f64,
    /// Absolute tolerance (adaptive methods), positive: with `atol = 0` a component's error
    /// weight `atol + rtol |y|` vanishes where it passes through zero.
    pub atol: f64,
    /// Initial step; `None` lets the method choose (Hairer's `HINIT`).
    pub h0: Option<f64>,
    /// Fixed step for fixed-step methods; largest step for adaptive ones (`None`: `t1 - t0`).
    pub h_max: Option<f64>,
    /// Steps allowed before [`Error::TooManySteps`].
    pub max_steps: usize,
    /// Keep one dense-output [`Segment`] per accepted step in the [`Solution`] (memory grows
    /// with the steps; `Solution::at` needs it).
    pub dense: bool,
    /// Which states the [`Solution`] keeps (default: every accepted step).
    pub record: Record,
    /// Call [`OdeSystem::project`] after each accepted step.
    pub project: bool,
    /// Explicit adaptive methods (DOPRI5, DOP853): test for stiffness every this many
    /// accepted steps (Hairer's `NSTIFF`, default 1000) and stop with [`Error::Stiff`] when
    /// 15 tests in a row find it; `None` never tests, so a stiff problem runs on (slowly,
    /// with the step held at the stability limit) to whatever accuracy it reaches.
    pub stiffness_check: Option<usize>,
    /// A closed loop's ordinary `solve` bridges its singular positions
    /// ([`crate::passage`]; default `true`); `false` runs it raw, stopping with the typed
    /// error where the index-1 accelerations are refused.
    pub passages: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            rtol: 1e-6,
            atol: 1e-6,
            h0: None,
            h_max: None,
            max_steps: 100_000,
            dense: true,
            record: Record::Steps,
            project: true,
            stiffness_check: Some(1000),
            passages: true,
        }
    }
}

/// Work counters (Hairer's `IWORK(17..20)`), read by the work-precision report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations.
    pub n_rhs: usize,
    /// Jacobian evaluations.
    pub n_jac: usize,
    /// LU decompositions.
    pub n_lu: usize,
    /// Steps attempted (accepted + rejected).
    pub n_steps: usize,
    /// Steps accepted.
    pub n_accepted: usize,
    /// Steps rejected.
    pub n_rejected: usize,
}

/// `Ok` when a step size or tolerance `value` is positive and finite, else an
/// `InvalidInput` naming it.
pub(crate) fn positive_finite(what: &'static str, value: f64) -> Result<()> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidInput {
            what,
            detail: format!("must be positive and finite, got {}", Num(value)),
        })
    }
}

/// Whether a state or derivative has a NaN or infinite component.
pub(crate) fn non_finite<const D: usize>(v: &Vector<D>) -> bool {
    !v.iter().all(|x| x.is_finite())
}

/// `[q; qd]`, the first-order state of a second-order integrator.
pub(crate) fn stack<const N: usize, const D: usize>(q: &Vector<N>, qd: &Vector<N>) -> Vector<D> {
    Vector::<D>::from_fn(|i, _| if i < N { q[i] } else { qd[i - N] })
}

/// The end of a second-order step from `t` to `t1`: the state `[q1; qd1]` and the cubic
/// Hermite segment through both ends, or [`Error::NonFinite`] at `t1`.
pub(crate) fn second_order_end<const N: usize, const D: usize>(
    t: f64,
    t1: f64,
    start: (&Vector<N>, &Vector<N>, &Vector<N>),
    end: (&Vector<N>, &Vector<N>, &Vector<N>),
) -> Result<(Vector<D>, Segment<D>)> {
    second_order_end_packed(stack, t, t1, start, end)
}

/// [`second_order_end`] with the state packed by `pack(q, qd)` instead of [`stack`] (a
/// first-order system integrated as a second-order one in padded coordinates).
pub(crate) fn second_order_end_packed<const N: usize, const D: usize>(
    pack: impl Fn(&Vector<N>, &Vector<N>) -> Vector<D>,
    t: f64,
    t1: f64,
    (q, qd, qdd): (&Vector<N>, &Vector<N>, &Vector<N>),
    (q1, qd1, qdd1): (&Vector<N>, &Vector<N>, &Vector<N>),
) -> Result<(Vector<D>, Segment<D>)> {
    let y1 = pack(q1, qd1);
    if non_finite(&y1) || non_finite(qdd1) {
        return Err(Error::NonFinite { t: t1 });
    }
    let seg = Segment::hermite(
        t,
        t1 - t,
        &pack(q, qd),
        &pack(qd, qdd),
        &y1,
        &pack(qd1, qdd1),
    );
    Ok((y1, seg))
}

impl Options {
    /// Reject options outside their domain: `rtol > 0` and `atol > 0` finite, `h0` and
    /// `h_max` finite and positive when given, `max_steps >= 1`.
    pub fn validate(&self) -> Result<()> {
        let bad = |what: &'static str, detail: String| Err(Error::InvalidInput { what, detail });
        positive_finite("rtol", self.rtol)?;
        positive_finite("atol", self.atol)?;
        if let Some(h) = self.h0 {
            positive_finite("h0", h)?;
        }
        if let Some(h) = self.h_max {
            positive_finite("h_max", h)?;
        }
        if self.max_steps == 0 {
            return bad("max_steps", "must be at least 1".to_string());
        }
        self.record.validate()?;
        if self.stiffness_check == Some(0) {
            return bad(
                "stiffness_check",
                "must be at least 1 (None turns the test off)".to_string(),
            );
        }
        Ok(())
    }
}

/// Reject an integration interval or initial state outside the domain: `t0`, `t1` finite
/// with `t1 >= t0` and a finite span `t1 - t0`, and every component of `y0` finite.
pub fn validate_problem<const D: usize>(t0: f64, y0: &Vector<D>, t1: f64) -> Result<()> {
    if !(t0.is_finite() && t1.is_finite()) {
        return Err(Error::InvalidInput {
            what: "t0/t1",
            detail: format!("must be finite, got t0 = {}, t1 = {}", Num(t0), Num(t1)),
        });
    }
    if t1 < t0 {
        return Err(Error::InvalidInput {
            what: "t1",
            detail: format!("must not precede t0 = {}, got {}", Num(t0), Num(t1)),
        });
    }
    if !(t1 - t0).is_finite() {
        return Err(Error::InvalidInput {
            what: "t0/t1",
            detail: format!(
                "the span t1 - t0 overflows: t0 = {}, t1 = {}",
                Num(t0),
                Num(t1)
            ),
        });
    }
    if !y0.iter().all(|v| v.is_finite()) {
        return Err(Error::InvalidInput {
            what: "y0",
            detail: format!("must be finite, got {:?}", y0.as_slice()),
        });
    }
    Ok(())
}
