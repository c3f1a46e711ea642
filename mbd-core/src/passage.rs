//! Singular passages of closed loops: any integrator of the index-1 equations, bridged
//! across the singular positions of a mobile mechanism in its independent coordinates.
//!
//! Where a closed loop passes a singular position (the 40-loop assembly lying flat: the
//! closure Jacobian loses rank), the accelerations of the index-1 form `[M Phi_q^T;
//! Phi_q 0] [qdd; lambda] = [f; gamma]` are only the *limit* of the solutions around the
//! instant: there the rows that vanished leave the acceleration problem with other
//! solutions, and near it the drift of an integrated state is divided by the vanishing
//! singular values. The right-hand side then stops with [`Error::SingularPosition`] rather
//! than return accelerations that are not the mechanism's; a solver's Newton iteration may
//! fail there too. The ordinary `solve` of every integrator on a closed loop (and
//! [`solve`], with settings given) runs the integrator, and when it stops at a singular
//! position bridges the window from the last accepted step: the mechanism is integrated in the
//! independent coordinates chosen there ([`Partitioned`]: the dependent positions are
//! re-solved on the branch from a Taylor prediction before every evaluation, which is what
//! keeps the branch), by DOPRI5 at the integrator's tolerance (at most `1e-10`) to just
//! before the singular instant, then by one step placed across it so that no evaluation
//! comes nearer than a quarter of the step (the step is halved until its error estimate
//! meets the tolerance), then on to the far side, where the integrator restarts. Every
//! bridge is reported ([`Passage`]). Index-3 steps (the
//! augmented Lagrangian of `Ali3`) were measured as the bridge first and dropped: two step
//! sizes never agreed better than about `1e-6`.
//!
//! A mechanism without degrees of freedom (driven, `Phi_q` of rank `N` at the start) has
//! no inertia of its own to carry it: at a singular position (a change point or a toggle)
//! two continuations satisfy the equations and the drive does not choose. There the run
//! ends with [`Error::SingularPosition`] naming the time and the configuration, whichever
//! integrator was asked, also when it stepped across without noticing
//! ([`crate::analysis::check_passages`]).

use crate::analysis::projection::metric_correction;
use crate::analysis::redundancy::rank_with;
use crate::analysis::{check_passages, max_norm, rank_and_redundant};
use crate::error::{Error, Num, Result};
use crate::integrate::{
    Dopri5, Event, Flow, GeneralizedAlpha, Integrator, Options, Record, Recorder, Segment,
    Solution, Stats, Step,
};
use crate::model::{Constrained, OdeSystem, Vector};
use crate::partition::Partitioned;
use std::collections::VecDeque;

/// How singular positions are bridged ([`solve`], and the ordinary `solve` of every
/// integrator on a closed loop: [`crate::integrate::Integrator::passages`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Tolerance of a bridge (say the integrator's `rtol`): its DOPRI5 runs use it, and the
    /// step across the singular instant is halved until its relative error estimate meets
    /// it (or reaches the floor of about `1e-10` that rounding leaves there).
    pub tol: f64,
    /// Bridges allowed before [`Error::TooManySteps`].
    pub max_passages: usize,
    /// Halvings of the step across the instant; if none keeps its error estimate below
    /// `1e-6`, the passage counts as not determined.
    pub max_halvings: usize,
    /// What the solution of a bridged run keeps (a run that meets no singular position
    /// returns the integrator's own solution): the integrator's settings, passed on.
    pub record: Record,
    /// Keep the dense output of a bridged run.
    pub dense: bool,
    /// Bridge at all: `false` ([`Options::passages`] off, [`Unbridged`]) is one raw run
    /// that stops with the typed error at a singular position, after the same check of the
    /// start against the constraints.
    pub bridge: bool,
}

impl Settings {
    /// Bridges to `tol`, at most 10 000 of them, 14 halvings of the step across; every
    /// step and its dense output kept.
    pub fn new(tol: f64) -> Self {
        Settings {
            tol,
            max_passages: 10_000,
            max_halvings: 14,
            record: Record::Steps,
            dense: true,
            bridge: true,
        }
    }

    /// The settings of a fixed-step method of order `p` with step `h`'s ordinary `solve`:
    /// bridges to `h^p`, the method's own error over a unit of time, with its recording.
    pub fn fixed(h: f64, p: i32, dense: bool, record: &Record) -> Self {
        Settings {
            record: record.clone(),
            dense,
            ..Settings::new(h.powi(p))
        }
    }

    /// The settings of an adaptive method's ordinary `solve`: its `rtol` and recording;
    /// no bridge when [`Options::passages`] is off (the start is still checked).
    pub fn of(opts: &Options) -> Option<Self> {
        Some(Settings {
            record: opts.record.clone(),
            dense: opts.dense,
            bridge: opts.passages,
            ..Settings::new(opts.rtol)
        })
    }
}

/// A model whose ordinary `solve` bridges singular positions: a closed loop in `y = [q;
/// qd]` ([`crate::model::OdeSystem::passage`] returns it; `#[derive(Mechanism)]` implements
/// it for every model with constraints, by [`pass`]).
pub trait Bridge<const D: usize> {
    /// [`solve`] from `start = (t0, y0, t1)` with the integrator given as `run(t, y,
    /// observer)`, a raw run from `(t, y)`
    /// to `t1` that calls `observer` after every accepted step.
    fn pass(
        &self,
        start: (f64, Vector<D>, f64),
        events: &[Event<'_, D>],
        settings: &Settings,
        run: &mut Run<'_, D>,
    ) -> Result<Solution<D>>;
}

/// A raw run of an integrator from `(t, y)` to the end, observed step by step.
pub type Run<'r, const D: usize> =
    dyn FnMut(f64, Vector<D>, &mut dyn FnMut(&Step<'_, D>) -> Flow) -> Result<Solution<D>> + 'r;

/// [`Bridge::pass`] for the closed loop `sys` (what generated code calls).
pub fn pass<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    start: (f64, Vector<D>, f64),
    events: &[Event<'_, D>],
    settings: &Settings,
    run: &mut Run<'_, D>,
) -> Result<Solution<D>> {
    drive::<S, N, M, D>(sys, start, events, settings, run)
}

/// `sys` with its singular positions left unbridged: `Dopri5::new(opts).solve(&Unbridged(&sys),
/// ..)` is one raw run that stops with the typed error at a singular position (the opt-out
/// for methods without [`Options`]; those with it have [`Options::passages`]).
#[derive(Debug, Clone, Copy)]
pub struct Unbridged<'a, S>(pub &'a S);

impl<S: OdeSystem<D>, const D: usize> OdeSystem<D> for Unbridged<'_, S> {
    /// Itself: no bridge, but the closed loop's start is checked ([`Settings::bridge`]).
    fn passage(&self) -> Option<&dyn Bridge<D>> {
        Some(self)
    }
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        self.0.rhs(t, y)
    }
    fn jacobian(&self, t: f64, y: &Vector<D>) -> Result<crate::model::Matrix<D, D>> {
        self.0.jacobian(t, y)
    }
    const EXACT_JACOBIAN: bool = S::EXACT_JACOBIAN;
    fn project(&self, t: f64, y: &mut Vector<D>) -> Result<()> {
        self.0.project(t, y)
    }
}

impl<S: OdeSystem<D>, const D: usize> Bridge<D> for Unbridged<'_, S> {
    fn pass(
        &self,
        start: (f64, Vector<D>, f64),
        events: &[Event<'_, D>],
        settings: &Settings,
        run: &mut Run<'_, D>,
    ) -> Result<Solution<D>> {
        match self.0.passage() {
            Some(inner) => {
                let raw = Settings {
                    bridge: false,
                    ..settings.clone()
                };
                inner.pass(start, events, &raw, run)
            }
            None => run(start.0, start.1, &mut |_| Flow::Continue),
        }
    }
}

/// One bridged passage.
#[derive(Debug, Clone, PartialEq)]
pub struct Passage {
    /// Where the integrator stopped, and why.
    pub t: f64,
    pub cause: Error,
    /// The bridge: from the last accepted step to the restart.
    pub from: f64,
    pub to: f64,
    /// Steps of the bridge, and the relative error estimate of its step over the
    /// singular instant (NaN when the run ended before it).
    pub steps: usize,
    pub error: f64,
    /// The configuration at `t` (from the bridge's dense output).
    pub q: Vec<f64>,
    /// The constraint rows that lost rank at `q`: dependent on the others to `1e-3` of the
    /// largest row, beyond those redundant at the start.
    pub rows: Vec<usize>,
}

/// A run with its passages (also in `solution.passages`).
#[derive(Debug, Clone)]
pub struct Passed<const D: usize> {
    pub solution: Solution<D>,
    pub passages: Vec<Passage>,
}

/// Integrate the closed loop `sys` (states `y = [q; qd]`) from `(t0, y0)` to `t1` with
/// `integrator`, bridging its singular positions (module docs) as `settings` ask. `events`
/// are located in the integrator's steps and in the bridges'. (The ordinary
/// `integrator.solve(&sys, ..)` of a generated closed loop does the same with the
/// integrator's own settings.)
pub fn solve<I, S, const N: usize, const M: usize, const D: usize>(
    integrator: &I,
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'_, D>],
    settings: &Settings,
) -> Result<Passed<D>>
where
    I: Integrator,
    S: Constrained<N, M> + OdeSystem<D>,
{
    let solution = drive::<S, N, M, D>(sys, (t0, y0, t1), events, settings, &mut |t, y, obs| {
        integrator.solve_observed(sys, t, y, t1, events, Some(obs))
    })?;
    Ok(Passed {
        passages: solution.passages.clone(),
        solution,
    })
}

/// [`solve`] with the generalized-α method in index-3 form (`A = N + M`); what
/// `GeneralizedAlpha::solve_constrained` runs.
pub fn solve_generalized_alpha<S, const N: usize, const M: usize, const A: usize, const D: usize>(
    method: &GeneralizedAlpha,
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'_, D>],
    settings: &Settings,
) -> Result<Passed<D>>
where
    S: Constrained<N, M>,
{
    let solution = drive::<S, N, M, D>(sys, (t0, y0, t1), events, settings, &mut |t, y, obs| {
        let (q, qd) = split::<N, D>(&y);
        method.solve_constrained_observed::<S, N, M, A, D>(sys, t, q, qd, t1, events, Some(obs))
    })?;
    Ok(Passed {
        passages: solution.passages.clone(),
        solution,
    })
}

/// One accepted step as the observer saw it.
type Kept<const D: usize> = (f64, Vector<D>, Option<Segment<D>>);

/// The last steps of a run kept whole until it ends (a stop at a singular position restarts
/// from the last of them clear of it); older ones go to the record as they come, so memory
/// is what the record keeps plus this many steps. An adaptive method may creep up to the
/// instant in hundreds of steps that are all near it: with only 64 kept, DOPRI5 at 1e-11
/// on the 40-loop assembly restarted its bridges too near the instant and crawled.
const TAIL: usize = 2048;

/// The loop of [`solve`]: `run(t, y, observer)` integrates from `(t, y)` to the end. A run
/// that meets no singular position returns the integrator's own solution.
fn drive<S, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    (t0, y0, t1): (f64, Vector<D>, f64),
    events: &[Event<'_, D>],
    settings: &Settings,
    run: &mut Run<'_, D>,
) -> Result<Solution<D>>
where
    S: Constrained<N, M>,
{
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    crate::integrate::positive_finite("tol", settings.tol)?;
    crate::integrate::validate_problem(t0, &y0, t1)?;
    check_start::<S, N, M, D>(sys, t0, &y0)?;
    if !settings.bridge {
        return run(t0, y0, &mut |_| Flow::Continue);
    }
    let (rank0, redundant0) = rank_and_redundant(&sys.phi_q(t0, &split::<N, D>(&y0).0));
    let mut out: Option<Solution<D>> = None;
    let mut passages: Vec<Passage> = Vec::new();
    let (mut t, mut y) = (t0, y0);
    loop {
        let mut record = Recorder::with(events, t, y, settings.dense, settings.record.clone());
        let mut tail: VecDeque<Kept<D>> = VecDeque::new();
        let (mut fed, mut steps) = ((t, y), 0);
        let result = run(t, y, &mut |s: &Step<'_, D>| {
            if tail.len() == TAIL
                && let Some(old) = tail.pop_front()
            {
                fed = (old.0, old.1);
                keep(&mut record, old);
            }
            tail.push_back((s.t, *s.y, s.segment.cloned()));
            steps += 1;
            Flow::Continue
        });
        let cause = match result {
            Ok(part) => {
                let Some(mut whole) = out else {
                    if rank0 >= N {
                        check_passages::<S, N, M, D>(sys, &part)?;
                    }
                    return Ok(part);
                };
                append(&mut whole, part);
                out = Some(whole);
                break;
            }
            Err(e) => e,
        };
        let kept: Vec<Kept<D>> = tail.into();
        let Some(tf) = singular_at::<S, N, M, D>(sys, &cause, rank0, &kept, (t, &y)) else {
            return Err(cause);
        };
        // Restart where the integrator's steps were still clear of the singular position.
        let clear = kept
            .iter()
            .rposition(|(tk, yk, _)| !near::<S, N, M, D>(sys, *tk, yk, rank0))
            .map_or(0, |k| k + 1);
        let before = match clear {
            0 => None,
            1 => Some(fed),
            k => Some((kept[k - 2].0, kept[k - 2].1)),
        };
        kept.into_iter().take(clear).for_each(|k| {
            keep(&mut record, k);
        });
        // The failed run's own counters are lost with it: its accepted steps at least.
        let work = Stats {
            n_steps: steps,
            n_accepted: steps,
            ..Stats::default()
        };
        let mut whole = out.take().unwrap_or_else(|| Solution::start(t0, y0));
        append(&mut whole, record.finish(work)?);
        let (ta, ya) = (whole.t_end, whole.y_end);
        if rank0 >= N {
            return Err(undetermined(tf, &split::<N, D>(&ya).0, &cause));
        }
        if passages.len() >= settings.max_passages {
            return Err(Error::TooManySteps {
                t: ta,
                steps: passages.len(),
            });
        }
        let (mut bridge, t_star, error) = bridge::<S, N, M, D>(
            sys,
            before,
            (ta, ya),
            (tf, t1),
            &cause,
            events,
            settings,
            rank0,
        )?;
        // A restart that meets the singular instant the last bridge carried it across is
        // no progress (it would bridge again and again, up to `max_passages`).
        if let Some(last) = passages.last().filter(|p| t_star <= p.to) {
            return Err(Error::SingularPosition {
                t: t_star,
                detail: format!(
                    "the singular position bridged over [{}, {}] was met again at t = {}: \
                     the bridge did not carry the motion across it",
                    Num(last.from),
                    Num(last.to),
                    Num(t_star)
                ),
            });
        }
        let q = split::<N, D>(
            &bridge
                .at(t_star.clamp(ta, bridge.t_end))
                .unwrap_or(bridge.y_end),
        )
        .0;
        if !settings.dense {
            bridge.segments.clear();
        }
        let steps = bridge.stats.n_accepted;
        append(&mut whole, bridge);
        passages.push(Passage {
            t: t_star,
            cause,
            from: ta,
            to: whole.t_end,
            steps,
            error,
            q: q.iter().copied().collect(),
            rows: rank_with(&sys.phi_q(tf, &q), NEAR)
                .1
                .into_iter()
                .filter(|r| !redundant0.contains(r))
                .collect(),
        });
        (t, y) = (whole.t_end, whole.y_end);
        let done = whole.stopped_by.is_some() || t >= t1;
        out = Some(whole);
        if done {
            break;
        }
    }
    let mut out = out.unwrap_or_else(|| Solution::start(t0, y0));
    out.passages = passages;
    if rank0 >= N {
        check_passages::<S, N, M, D>(sys, &out)?;
    }
    Ok(out)
}

/// Record one observed step.
fn keep<const D: usize>(record: &mut Recorder<'_, '_, D>, (t1, y1, seg): Kept<D>) -> Flow {
    match seg {
        Some(seg) if record.needs_segment() => record.accept(seg, &y1),
        _ => record.accept_point(t1, &y1),
    }
}

/// The time of a stop at (or near) a singular position: `cause` is
/// [`Error::SingularPosition`], or a solver's failure (Newton, step size, a singular
/// matrix) where `Phi_q` has lost rank against the start (rows dependent to `1e-2` of
/// the largest) at the configuration extrapolated from the last accepted state. `None`
/// for any other stop.
fn singular_at<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    cause: &Error,
    rank0: usize,
    kept: &[Kept<D>],
    (t, y): (f64, &Vector<D>),
) -> Option<f64> {
    let (tk, yk) = kept.last().map_or((t, y), |(tk, yk, _)| (*tk, yk));
    let tf = match *cause {
        Error::SingularPosition { t, .. } => return Some(t.max(tk)),
        Error::NewtonFailed { t, .. }
        | Error::StepSizeUnderflow { t, .. }
        | Error::SingularConstraintJacobian { t, .. }
        | Error::SingularMassMatrix { t } => t.max(tk),
        _ => return None,
    };
    let (q, qd) = split::<N, D>(yk);
    let y = crate::integrate::stack::<N, D>(&(q + qd * (tf - tk)), &qd);
    near::<S, N, M, D>(sys, tf, &y, rank0).then_some(tf)
}

/// Rows of `Phi_q` dependent on the others to this fraction of the largest row count as
/// lost: the window around a singular position that the index-3 steps bridge.
const NEAR: f64 = 1e-2;

/// Whether `Phi_q` at `y` has lost rank against `rank0` to [`NEAR`].
fn near<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    rank0: usize,
) -> bool {
    rank_with(&sys.phi_q(t, &split::<N, D>(y).0), NEAR).0 < rank0
}

/// The typed error of a mechanism without degrees of freedom at a singular position.
fn undetermined<const N: usize>(t: f64, q: &Vector<N>, cause: &Error) -> Error {
    Error::SingularPosition {
        t,
        detail: format!(
            "the constraint Jacobian of a mechanism without degrees of freedom lost rank \
             ({cause}): a bifurcation, where the motion may continue on another assembly \
             branch and the drives do not choose; q = {:?}",
            q.as_slice()
        ),
    }
}

/// How far from a singular position `q` is: the `rank0`-th singular value of `Phi_q`,
/// relative to the largest (zero there, and proportional to the distance near a simple
/// passage). A singular value is smooth along the motion where the pivoted Gram–Schmidt
/// remainder (the rank test of [`near`]) is not: its pivot order changes as the vanishing rows
/// shrink together (40 of them on the 40-loop assembly), so its slope jumped by half from one
/// point to the next and the instant located from it moved by 5e-3 s.
fn measure<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    rank0: usize,
) -> f64 {
    measure_q::<S, N, M>(sys, t, &split::<N, D>(y).0, rank0)
}

/// [`measure`] at the configuration `q` (zero where `Phi_q` is not finite).
fn measure_q<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    rank0: usize,
) -> f64 {
    let j = sys.phi_q(t, q);
    if M == 0 || N == 0 || j.iter().any(|x| !x.is_finite()) {
        return 0.0;
    }
    let dense = nalgebra::DMatrix::from_column_slice(M, N, j.as_slice());
    let Some(svd) = nalgebra::SVD::try_new(dense, false, false, f64::EPSILON, 1000) else {
        return 0.0;
    };
    let mut s: Vec<f64> = svd.singular_values.iter().copied().collect();
    s.sort_by(|a, b| b.total_cmp(a));
    match (s.first(), s.get(rank0.max(1) - 1)) {
        (Some(&top), Some(&r)) if top > 0.0 => r / top,
        _ => 0.0,
    }
}

/// The time where [`measure`] extrapolates linearly to zero from two states, if it falls.
fn extrapolate<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    (t0, y0): (f64, &Vector<D>),
    (t1, y1): (f64, &Vector<D>),
    rank0: usize,
) -> Option<f64> {
    let (m0, m1) = (
        measure::<S, N, M, D>(sys, t0, y0, rank0),
        measure::<S, N, M, D>(sys, t1, y1, rank0),
    );
    let t = t1 + m1 * (t1 - t0) / (m0 - m1);
    (m1 < m0 && t.is_finite() && t > t1).then_some(t)
}

/// Carry `(ta, ya)` across the singular position met at about `tf` in the independent
/// coordinates chosen at `ta` ([`Partitioned`]), by DOPRI5 at `settings.tol`: to just
/// before the singular instant `t*` (where [`measure`] extrapolates to zero), then one
/// step of length `H` with `t*` at `0.55 H`, between its nodes `0.3` and `0.8` (no
/// evaluation nearer than `H / 4`: accelerations there carry rounding divided by the
/// square of the vanishing singular value), halved until its error estimate meets the
/// tolerance (or as far as rounding allows), then on to as far past `t*` as `ta` was
/// before it. The run, `t*`, and the step's error estimate.
#[allow(
    clippy::too_many_arguments,
    reason = "the states and times of one bridge"
)]
fn bridge<S, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    before: Option<(f64, Vector<D>)>,
    (ta, ya): (f64, Vector<D>),
    (tf, t1): (f64, f64),
    cause: &Error,
    events: &[Event<'_, D>],
    settings: &Settings,
    rank0: usize,
) -> Result<(Solution<D>, f64, f64)>
where
    S: Constrained<N, M>,
{
    let view = Partitioned::<S, N, M>::new(sys, ta, &split::<N, D>(&ya).0, rank0)?;
    let tol = settings.tol.max(FLOOR);
    let opts = Options {
        rtol: tol,
        atol: tol,
        record: settings.record.clone(),
        max_steps: LEG_STEPS,
        ..Options::default()
    };
    let dopri = Dopri5::new(opts);
    // The index-1 solve stops within a few 1e-5 s of the instant: its time is the best
    // guess; other stops are located by the measure's trend.
    let guess = match cause {
        Error::SingularPosition { .. } => None,
        _ => {
            before.and_then(|(tp, yp)| extrapolate::<S, N, M, D>(sys, (tp, &yp), (ta, &ya), rank0))
        }
    };
    let mut t_star = guess
        .filter(|&t| t < tf + 4.0 * (tf - ta))
        .unwrap_or(tf)
        .max(ta);
    let mut h = (t_star - ta) / 0.6;
    let far = (t_star + (t_star - ta).max(tf - ta)).min(t1);
    if t_star + 0.45 * h >= t1 || h <= 0.0 {
        let sol = leg(&view, &dopri, (ta, ya), far.max(tf).min(t1), events, t_star)?;
        return Ok((sol, t_star, f64::NAN));
    }
    // The step over the instant with the smallest error estimate: halving `h` lowers the
    // truncation error and raises the rounding of the evaluations nearer the instant.
    let mut best: Option<(f64, Solution<D>, Vector<D>, Segment<D>)> = None;
    for _ in 0..settings.max_halvings {
        let (s0, part) =
            approach::<S, N, M, D>(&view, &dopri, (ta, ya), &mut t_star, h, events, rank0)?;
        if part.stopped_by.is_some() {
            return Ok((part, t_star, f64::NAN));
        }
        // The instant inside the step, between its nodes 0.3 and 0.8, else no evaluation
        // is sure to stay clear of it (a leg that could not end before `t* - 0.55 h`).
        let inside = (0.25 * h..=0.85 * h).contains(&(t_star - s0));
        let jumped = match inside {
            true => jump::<S, N, M, D>(&view, s0, &part.y_end, h)?,
            false => None,
        };
        if let Some((y1, seg, err)) = jumped
            && best.as_ref().is_none_or(|b| err < b.0)
        {
            best = Some((err, part, y1, seg));
        }
        if best.as_ref().is_some_and(|b| b.0 <= tol) {
            break;
        }
        h *= 0.5;
    }
    let worst = WORST.min(ACCEPT * tol);
    let Some((err, mut part, y1, seg)) = best.filter(|b| b.0 <= worst) else {
        return Err(Error::SingularPosition {
            t: t_star,
            detail: format!(
                "the motion across the singular position near t = {} is not determined: \
                 no step over it keeps its error estimate below {}; q = {:?}",
                Num(t_star),
                Num(worst),
                split::<N, D>(&ya).0.as_slice()
            ),
        });
    };
    let mut record = Recorder::with(
        events,
        part.t_end,
        part.y_end,
        true,
        settings.record.clone(),
    );
    let stopped = record.accept(seg, &y1) == Flow::Stop;
    let work = Stats {
        n_rhs: 8,
        n_steps: 1,
        n_accepted: 1,
        ..Stats::default()
    };
    append(&mut part, record.finish(work)?);
    if !stopped && part.t_end < t1 {
        let end = far.max(part.t_end);
        let rest = leg(&view, &dopri, (part.t_end, part.y_end), end, events, t_star)?;
        append(&mut part, rest);
    }
    Ok((part, t_star, err))
}

/// The leg of a bridge from `(ta, ya)` to `s0 = t* - 0.55 h`, with the singular instant
/// `t*` relocated from the leg's end ([`locate`]) and the leg run again while it moved by
/// more than `h / 20`: the index-1 solve may stop `1e-5` s short of the instant, so its time
/// is no guide for a step across of that size. The leg starts from `ya` itself (not from a
/// prediction out of an earlier attempt, which may lie past the instant).
#[allow(
    clippy::too_many_arguments,
    reason = "the leg's start, the instant and the step across"
)]
fn approach<S, const N: usize, const M: usize, const D: usize>(
    view: &Partitioned<'_, S, N, M>,
    dopri: &Dopri5,
    (ta, ya): (f64, Vector<D>),
    t_star: &mut f64,
    h: f64,
    events: &[Event<'_, D>],
    rank0: usize,
) -> Result<(f64, Solution<D>)>
where
    S: Constrained<N, M>,
{
    let mut tries = 0;
    loop {
        let s0 = (*t_star - 0.55 * h).max(ta);
        view.forget();
        let part = leg(view, dopri, (ta, ya), s0, events, *t_star)?;
        tries += 1;
        if part.stopped_by.is_some() || tries == RELOCATE {
            return Ok((s0, part));
        }
        match locate::<S, N, M, D>(view, s0, &part.y_end, h, rank0)? {
            Some(t) if (t - *t_star).abs() > 0.05 * h => *t_star = t,
            _ => return Ok((s0, part)),
        }
    }
}

/// Steps a leg of a bridge may take: in the independent coordinates, clear of the instant,
/// the legs of the 40-loop assembly take 1 to 9. A leg that meets the singular instant
/// itself (misplaced) has evaluations nearer it than the step and its error estimate
/// follows their rounding down: DOPRI5 at 1e-10 crawled there for 100 000 steps (120 s).
const LEG_STEPS: usize = 1000;

/// A DOPRI5 leg of a bridge from `(t, y)` to `to`: one that cannot make progress (more
/// than [`LEG_STEPS`] steps) is the singular position near `t_star` not passed, a typed error.
fn leg<S, const N: usize, const M: usize, const D: usize>(
    view: &Partitioned<'_, S, N, M>,
    dopri: &Dopri5,
    (t, y): (f64, Vector<D>),
    to: f64,
    events: &[Event<'_, D>],
    t_star: f64,
) -> Result<Solution<D>>
where
    S: Constrained<N, M>,
{
    dopri.solve(view, t, y, to, events).map_err(|e| match e {
        Error::TooManySteps { t, steps } => Error::SingularPosition {
            t,
            detail: format!(
                "the bridge across the singular position near t = {} made no progress: \
                 its run in the independent coordinates took {steps} steps to t = {}",
                Num(t_star),
                Num(t)
            ),
        },
        e => e,
    })
}

/// Legs run per step across at most (a relocation converges in one or two).
const RELOCATE: usize = 4;

/// The singular instant ahead of the consistent state `(s0, y0)`: the zero of [`measure`]
/// along the Taylor expansion `q + qd s + qdd s^2 / 2` there, by two Newton steps from the
/// side it approaches (the measure is a distance, `|s - t*|` to first order); `None` when
/// it does not fall. `h` sets the difference quotient's scale.
fn locate<S, const N: usize, const M: usize, const D: usize>(
    view: &Partitioned<'_, S, N, M>,
    s0: f64,
    y0: &Vector<D>,
    h: f64,
    rank0: usize,
) -> Result<Option<f64>>
where
    S: Constrained<N, M>,
{
    let f = view.rhs(s0, y0)?;
    let (q, qd) = split::<N, D>(y0);
    let qdd = f.fixed_rows::<N>(N).into_owned();
    let m = |s: f64| {
        let d = s - s0;
        measure_q::<S, N, M>(view.system(), s, &(q + qd * d + qdd * (0.5 * d * d)), rank0)
    };
    let newton = |s: f64, scale: f64| {
        let d = 1e-3 * scale;
        let slope = (m(s + d) - m(s - d)) / (2.0 * d);
        let t = s - m(s) / slope;
        (slope < 0.0 && t.is_finite() && t > s).then_some(t)
    };
    let Some(t1) = newton(s0, h) else {
        return Ok(None);
    };
    let s1 = s0 + 0.8 * (t1 - s0);
    Ok(Some(
        newton(s1, t1 - s0)
            .filter(|&t| t < t1 + (t1 - s0))
            .unwrap_or(t1),
    ))
}

/// The tightest tolerance a bridge is run to. Near the instant the evaluations carry
/// rounding divided by the square of the vanishing singular value, so the step across has
/// a smallest error estimate: on the 40-loop assembly at t = 0.72 it falls 31-fold a
/// halving to 2.7e-11 at `h = 1.1e-2`, then rises about fourfold a halving (1.1e-10 at
/// `h = 2.7e-3`, 7.7e-6 at `2.1e-5`). Bridges run at 1e-12 with the instant relocated
/// ([`approach`]) spent minutes in legs at that tolerance over 3 s.
const FLOOR: f64 = 1e-10;

/// The largest relative error estimate a step over a singular instant may have: past it
/// the motion across counts as not determined (a bifurcation, or evaluations too near
/// the instant to resolve it).
const WORST: f64 = 1e-6;

/// A step across whose estimate, at its smallest over the halvings, stays above this many
/// times the bridge's tolerance ends the run with [`Error::SingularPosition`] rather than
/// carry an error the tolerance did not allow (at most [`WORST`]).
const ACCEPT: f64 = 100.0;

/// A step across whose end moved by more than this fraction of `h |qd|` when its dependent
/// coordinates were rebuilt is refused: its stages met the instant too closely and
/// continued on another assembly branch (measured: `1e-10` relative at `h = 1e-2` on the
/// 40-loop assembly, `2e-4` at `h = 2e-5`, where the branches are `h |qd|` apart).
const BRANCH: f64 = 1e-2;

/// One DOPRI5 step of `view` from `(s0, y0)` over `h`: the projected end, its continuous
/// extension, and the relative error estimate; `None` when a stage met the singular
/// position itself, or when rebuilding the end moved it by more than [`BRANCH`] (the
/// stages continued on another branch).
#[allow(clippy::type_complexity, reason = "the end of one step")]
fn jump<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    view: &Partitioned<'_, S, N, M>,
    s0: f64,
    y0: &Vector<D>,
    h: f64,
) -> Result<Option<(Vector<D>, Segment<D>, f64)>> {
    let tab = &crate::integrate::tableau::DOPRI5;
    let mut k = [Vector::<D>::zeros(); 7];
    let mut z = [Vector::<D>::zeros(); 7];
    k[0] = view.rhs(s0, y0)?;
    match tab.stages(view, s0, y0, h, &mut k, &mut z) {
        Ok(()) => {}
        Err(Error::SingularPosition { .. }) => return Ok(None),
        Err(e) => return Err(e),
    }
    let mut y1 = y0 + crate::integrate::tableau::Erk::<7>::combine(&tab.b, &k, h);
    let e = crate::integrate::tableau::Erk::<7>::combine(&tab.e, &k, h);
    let err = (0..D)
        .map(|i| e[i].abs() / (1.0 + y0[i].abs().max(y1[i].abs())))
        .fold(0.0, f64::max);
    // The segment is the step's continuous extension, as computed (before the projection):
    // a cubic Hermite one was 1e-8 off inside the step at DOPRI5 1e-12.
    let seg = crate::integrate::dopri5::dense_segment(s0, h, y0, &y1, &k);
    let raw = y1;
    view.project(s0 + h, &mut y1)?;
    view.rhs(s0 + h, &y1)?;
    let moved = (0..D)
        .map(|i| (y1[i] - raw[i]).abs() / (1.0 + y1[i].abs()))
        .fold(0.0, f64::max);
    let speed = max_norm(&split::<N, D>(y0).1).max(1.0);
    Ok((moved <= BRANCH * h * speed).then_some((y1, seg, err)))
}

/// Add a run to the whole: its states after the first, segments, events and work.
fn append<const D: usize>(out: &mut Solution<D>, part: Solution<D>) {
    out.t.extend_from_slice(&part.t[1..]);
    out.y.extend_from_slice(&part.y[1..]);
    out.segments.extend(part.segments);
    out.events.extend(part.events);
    add(&mut out.stats, part.stats);
    out.stopped_by = part.stopped_by;
    (out.t_end, out.y_end) = (part.t_end, part.y_end);
}

fn add(s: &mut Stats, p: Stats) {
    s.n_rhs += p.n_rhs;
    s.n_jac += p.n_jac;
    s.n_lu += p.n_lu;
    s.n_steps += p.n_steps;
    s.n_accepted += p.n_accepted;
    s.n_rejected += p.n_rejected;
}

/// How far off its constraints a start may be, relative to its size: a start further off is
/// refused rather than projected after the first step, out of sight of the caller.
const START_TOL: f64 = 1e-8;

/// The start must lie on the position and velocity constraints: the least `M`-norm
/// correction that would put it there is at most [`START_TOL`] of its size, and it must
/// leave no residual the Jacobian cannot reach. (Where `Phi_q` loses rank, a residual
/// outside its range has a zero least-norm correction: a Cartesian pendulum started at its
/// pivot, `x^2 + y^2 = l^2` at `(0, 0)`, passed and ran as a free fall or was projected
/// onto the circle after the first step, unseen.)
pub(crate) fn check_start<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
) -> Result<()> {
    let (q, qd) = split::<N, D>(y);
    let jac = sys.phi_q(t, &q);
    let position = sys.phi(t, &q);
    let velocity = jac * qd + sys.phi_t(t, &q);
    for (what, r, x) in [("positions", position, q), ("velocities", velocity, qd)] {
        let dx = metric_correction(sys, t, &q, &jac, &r)?;
        let (off, size) = (max_norm(&dx), max_norm(&x));
        let slope = jac.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let unreached = max_norm(&(r + jac * dx));
        let stuck = unreached > START_TOL * (1.0 + slope * (1.0 + size));
        if off > START_TOL * (1.0 + size) || stuck {
            let row = r.iamax();
            let why = if stuck {
                "the constraint Jacobian has lost rank there: no correction reaches it".to_string()
            } else {
                format!("a correction of {off:.3e} against a size of {size:.3e}")
            };
            return Err(Error::InvalidInput {
                what: "initial state",
                detail: format!(
                    "its {what} are off the constraints (row {row} by {:.3e}; {why}): assemble \
                     the start first (`mbd::analysis::assemble`, or the model's `initial_state`)",
                    r[row]
                ),
            });
        }
    }
    Ok(())
}

fn split<const N: usize, const D: usize>(y: &Vector<D>) -> (Vector<N>, Vector<N>) {
    (
        y.fixed_rows::<N>(0).into_owned(),
        y.fixed_rows::<N>(N).into_owned(),
    )
}
