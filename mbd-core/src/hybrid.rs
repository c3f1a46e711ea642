//! Integrating a [`Hybrid`] system mode by mode with any [`Integrator`].
//!
//! Within a mode the right-hand side is smooth, so the integrator runs at its own order
//! and step sizes; the mode's switching functions are terminal events, located on the
//! dense output and then refined by bisection on the same polynomial to the last bit of
//! `t`. At the switch the system picks the next mode ([`Hybrid::switch`]) and the
//! integrator restarts there. No step crosses a discontinuity, so no step size collapses at
//! one; the price is the restart (a new initial step) per switch, reported in [`Switch`].
//!
//! The ordinary `Integrator::solve` reaches this driver through object-safe hooks: the
//! system hands over its modes ([`OdeSystem::hybrid`], a `&dyn` [`Modes`]) and the
//! integrator is erased as a [`Method`] that runs each mode's [`View`] (one virtual call
//! per right-hand side). [`solve`] runs the same driver, so both give the same states.
//!
//! A sign change at step ends is not enough: in a mode where the state is constant while a
//! switching function varies (a body stuck under a time-dependent push), the method sees no
//! error and its steps grow without bound, and the function can cross zero and come back
//! within one step. So every accepted step is also sampled inside ([`hidden`]), at a
//! spacing set by the function's own slope and curvature there; no `h_max` is needed.

use crate::error::{Error, Result};
use crate::integrate::{
    Direction, Event, Flow, Integrator, Observer, Segment, Solution, Stats, Step,
};
use crate::model::{Hybrid, OdeSystem, Vector};
use std::any::Any;
use std::sync::Arc;

/// Switches allowed by default before [`Error::TooManySteps`] (an accumulation of
/// switches, say).
pub const MAX_SWITCHES: usize = 1_000_000;

/// How [`solve_with`] treats switches.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Re-integrate the step that ended at a switch from its start to the located time and
    /// take one Newton step on the switching function with that step-end state: switch
    /// times and restart states as accurate as step ends rather than as the dense output
    /// (which matters for Radau IIA, whose dense output is of degree 3), for two short
    /// integrations per switch. Off by default.
    pub polish: bool,
    /// Switches allowed before [`Error::TooManySteps`].
    pub max_switches: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            polish: false,
            max_switches: MAX_SWITCHES,
        }
    }
}

/// One mode switch.
#[derive(Debug, Clone, PartialEq)]
pub struct Switch<Mode> {
    /// Time of the switch.
    pub t: f64,
    /// Which switching function crossed zero.
    pub by: usize,
    /// The mode before and after.
    pub from: Mode,
    pub to: Mode,
    /// Steps the integrator accepted in the mode that ended here.
    pub steps: usize,
}

impl<Mode: Copy + PartialEq + std::fmt::Debug + Send + Sync + 'static> Switch<Mode> {
    /// The same switch with its modes erased, as [`Solution::switches`] keeps it.
    pub fn erased(&self) -> Switch<AnyMode> {
        Switch {
            t: self.t,
            by: self.by,
            from: AnyMode::new(self.from),
            to: AnyMode::new(self.to),
            steps: self.steps,
        }
    }
}

/// A run of a hybrid system: the whole solution (its segments, events and work across all
/// modes, as one [`Solution`], whose `switches` are these with the modes erased), the
/// switches, and the final mode.
#[derive(Debug, Clone)]
pub struct HybridSolution<const D: usize, Mode> {
    pub solution: Solution<D>,
    pub switches: Vec<Switch<Mode>>,
    pub mode: Mode,
}

/// The system frozen in one mode, as an ordinary [`OdeSystem`].
#[derive(Debug)]
pub struct InMode<'a, S, Mode> {
    pub sys: &'a S,
    pub mode: Mode,
}

impl<S: Hybrid<D>, const D: usize> OdeSystem<D> for InMode<'_, S, S::Mode> {
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        self.sys.rhs_in(t, y, &self.mode)
    }
    fn project(&self, t: f64, y: &mut Vector<D>) -> Result<()> {
        self.sys.project_in(t, y, &self.mode)
    }
}

/// The error of an ordinary solve of a system that switches modes: a step failure (the
/// steps collapsing at a switch, which no step size resolves) becomes
/// [`Error::ModeSwitch`], whose message says to use [`solve`]; any other error is kept.
pub fn hint(e: Error) -> Error {
    match e {
        Error::TooManySteps { t, .. }
        | Error::StepSizeUnderflow { t, .. }
        | Error::Stiff { t }
        | Error::NewtonFailed { t, .. } => Error::ModeSwitch {
            t,
            cause: Box::new(e),
        },
        e => e,
    }
}

/// Integrate `sys` from `(t0, y0)` to `t1` with `integrator`, switching modes where the
/// switching functions cross zero. `events` are the user's (indices in the result refer to
/// this slice); a terminal one ends the run as usual. (The ordinary `integrator.solve(&sys,
/// ..)` of a generated friction model runs this with the default [`Settings`] and returns
/// its `solution`: [`OdeSystem::hybrid`].)
///
/// Switching functions are checked for a sign change at step ends and sampled inside each
/// accepted step ([`hidden`]): a breakaway under a load that rises above the bound and falls
/// back within one long step (a stuck body's state is constant, so nothing bounds its steps)
/// is found without `Options::h_max`.
pub fn solve<I: Integrator, S: Hybrid<D>, const D: usize>(
    integrator: &I,
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'_, D>],
) -> Result<HybridSolution<D, S::Mode>> {
    solve_with(integrator, sys, t0, y0, t1, events, &Settings::default())
}

/// [`solve`] with [`Settings`].
pub fn solve_with<I: Integrator, S: Hybrid<D>, const D: usize>(
    integrator: &I,
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'_, D>],
    settings: &Settings,
) -> Result<HybridSolution<D, S::Mode>> {
    drive(integrator, sys, (t0, y0, t1), events, settings)
}

/// An integrator with its type erased, so that a hybrid system reached through the
/// object-safe [`Modes`] can run it: one raw run of one mode's [`View`] from `(t0, y0)` to
/// `t1`, starting with the step `first_step` when the method has that setting
/// ([`Integrator::with_first_step`]). Every [`Integrator`] is one.
pub trait Method<const D: usize> {
    /// [`Integrator::solve_observed`] of `view`.
    #[allow(
        clippy::too_many_arguments,
        reason = "solve_observed's arguments and the step"
    )]
    fn run(
        &self,
        view: &View<'_, D>,
        start: (f64, Vector<D>, f64),
        events: &[Event<'_, D>],
        first_step: Option<f64>,
        observer: Option<&mut Observer<'_, D>>,
    ) -> Result<Solution<D>>;
}

impl<I: Integrator, const D: usize> Method<D> for I {
    fn run(
        &self,
        view: &View<'_, D>,
        (t0, y0, t1): (f64, Vector<D>, f64),
        events: &[Event<'_, D>],
        first_step: Option<f64>,
        observer: Option<&mut Observer<'_, D>>,
    ) -> Result<Solution<D>> {
        match first_step.and_then(|h| self.with_first_step(h)) {
            Some(restarted) => restarted.solve_observed(view, t0, y0, t1, events, observer),
            None => self.solve_observed(view, t0, y0, t1, events, observer),
        }
    }
}

/// A system frozen in one mode with its type erased: what the driver hands a [`Method`].
/// Its right-hand side and projection are the mode's (`Hybrid::rhs_in`, `project_in`) one
/// virtual call away; its Jacobian is the default forward difference, as for [`InMode`].
pub struct View<'a, const D: usize>(&'a dyn Frozen<D>);

impl<'a, const D: usize> View<'a, D> {
    /// The view of `frozen` (what the driver runs in each mode).
    pub fn new<S: Hybrid<D>>(frozen: &'a InMode<'a, S, S::Mode>) -> Self {
        View(frozen)
    }
}

impl<const D: usize> std::fmt::Debug for View<'_, D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("View")
    }
}

/// The object-safe part of an [`OdeSystem`] that a mode's view needs.
trait Frozen<const D: usize> {
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>>;
    fn project(&self, t: f64, y: &mut Vector<D>) -> Result<()>;
}

impl<S: Hybrid<D>, const D: usize> Frozen<D> for InMode<'_, S, S::Mode> {
    #[inline]
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        self.sys.rhs_in(t, y, &self.mode)
    }
    fn project(&self, t: f64, y: &mut Vector<D>) -> Result<()> {
        self.sys.project_in(t, y, &self.mode)
    }
}

impl<const D: usize> OdeSystem<D> for View<'_, D> {
    #[inline]
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        self.0.rhs(t, y)
    }
    fn project(&self, t: f64, y: &mut Vector<D>) -> Result<()> {
        self.0.project(t, y)
    }
}

/// A hybrid system as the ordinary `Integrator::solve` reaches it ([`OdeSystem::hybrid`]):
/// object-safe, so a generic `S: OdeSystem` can hand itself over without naming its modes.
/// Every [`Hybrid`] system is one; generated friction models return themselves.
pub trait Modes<const D: usize> {
    /// [`solve_with`] from `start = (t0, y0, t1)` with `method`; the switches are in the
    /// solution's [`Solution::switches`].
    fn drive(
        &self,
        method: &dyn Method<D>,
        start: (f64, Vector<D>, f64),
        events: &[Event<'_, D>],
        settings: &Settings,
    ) -> Result<Solution<D>>;
}

impl<S: Hybrid<D>, const D: usize> Modes<D> for S {
    fn drive(
        &self,
        method: &dyn Method<D>,
        start: (f64, Vector<D>, f64),
        events: &[Event<'_, D>],
        settings: &Settings,
    ) -> Result<Solution<D>> {
        drive(method, self, start, events, settings).map(|run| run.solution)
    }
}

/// A mode of some [`Hybrid`] system with its type erased, as [`Solution::switches`] keeps
/// it: it prints as the mode does (`[Stick]`) and [`AnyMode::get`] gives the mode back.
#[derive(Clone)]
pub struct AnyMode(Arc<dyn ModeValue>);

impl AnyMode {
    /// Erase `mode`.
    pub fn new<M: Copy + PartialEq + std::fmt::Debug + Send + Sync + 'static>(mode: M) -> Self {
        AnyMode(Arc::new(mode))
    }

    /// The mode, when it is an `M` (for friction: `[Slip; F]`).
    pub fn get<M: 'static>(&self) -> Option<&M> {
        self.0.as_any().downcast_ref()
    }
}

trait ModeValue: std::fmt::Debug + Send + Sync {
    fn as_any(&self) -> &dyn Any;
    fn same(&self, other: &dyn ModeValue) -> bool;
}

impl<M: Copy + PartialEq + std::fmt::Debug + Send + Sync + 'static> ModeValue for M {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn same(&self, other: &dyn ModeValue) -> bool {
        other.as_any().downcast_ref::<M>() == Some(self)
    }
}

impl std::fmt::Debug for AnyMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl PartialEq for AnyMode {
    fn eq(&self, other: &Self) -> bool {
        self.0.same(&*other.0)
    }
}

/// [`solve_with`] with the integrator erased (what [`Modes::drive`] runs too).
fn drive<S: Hybrid<D>, const D: usize>(
    method: &dyn Method<D>,
    sys: &S,
    (t0, y0, t1): (f64, Vector<D>, f64),
    events: &[Event<'_, D>],
    settings: &Settings,
) -> Result<HybridSolution<D, S::Mode>> {
    crate::integrate::validate_problem(t0, &y0, t1)?;
    let mut mode = sys.mode_at(t0, &y0)?;
    let (mut t, mut y) = (t0, y0);
    let mut out = Solution::start(t0, y0);
    let mut switches = Vec::new();
    // The last full step the method took in each mode met so far.
    let mut steps_in: Vec<(S::Mode, f64)> = Vec::new();
    // The side each kink function is on (`+-1`), and the kink just restarted at.
    let mut sides = vec![1.0; S::KINKS];
    let mut crossed: Option<usize> = None;
    loop {
        let current = mode;
        kink_sides(sys, (t, &y), &current, &mut sides, crossed.take());
        let all = with_switches(sys, &current, events, &sides);
        let frozen = InMode { sys, mode };
        let view = View::new(&frozen);
        // A crossing inside a step that its ends did not show: (function, time).
        let mut inside: Option<(usize, f64)> = None;
        // The last step's segment (cut at a terminal event), also when `dense` keeps none:
        // the switch is located and the record cut on it.
        let mut last: Option<Segment<D>> = None;
        // The lengths of the last two steps, whatever the record keeps.
        let mut lengths = [f64::NAN; 2];
        let mut watch = |step: &Step<'_, D>| {
            last = step.segment.cloned();
            lengths = [lengths[1], step.segment.map_or(f64::NAN, |s| s.h)];
            match step.segment.and_then(|s| first_inside(sys, &current, s)) {
                Some(hit) => {
                    inside = Some(hit);
                    Flow::Stop
                }
                None => Flow::Continue,
            }
        };
        // Restart with the step last taken in this mode (a fresh guess from a stuck
        // state starts at 1e-6 and takes a step per tenfold growth).
        let restart = steps_in.iter().find(|(m, _)| *m == mode).map(|&(_, h)| h);
        let part = method.run(&view, (t, y, t1), &all, restart, Some(&mut watch))?;
        let steps = part.stats.n_accepted;
        if let Some(h) = restart_step(lengths) {
            match steps_in.iter_mut().find(|(m, _)| *m == mode) {
                Some(entry) => entry.1 = h,
                None => steps_in.push((mode, h)),
            }
        }
        let stopped = part.stopped_by;
        append(&mut out, part, events.len());
        // A crossing inside the step comes before any located at its (possibly cut) end.
        let (k, ts) = match (inside, stopped) {
            (Some((k, ts)), _) => {
                // User events past the switch did not happen.
                out.events.retain(|e| e.t <= ts);
                (k, Some(ts))
            }
            (None, Some(i)) if i < events.len() => {
                out.stopped_by = Some(i);
                break;
            }
            (None, Some(i)) => (i - events.len(), None),
            (None, None) => break,
        };
        // Index `k` past the switching functions is a kink: located the same way (leaving
        // its side), then the same mode restarts.
        let kink = k.checked_sub(S::SWITCHES);
        let g = |t: f64, y: &Vector<D>| match kink {
            Some(j) => sides[j] * sys.kink(t, y, &current, j),
            None => watched(sys.switching(t, y, &current, k)),
        };
        // The located time is within 1e-12 (|t| + 1) past the crossing: bisect the last
        // segment down to adjacent floating-point times.
        if let Some(mut seg) = last {
            let ts = ts.unwrap_or_else(|| refine(&g, &seg));
            if ts < seg.t1() {
                seg = seg.truncated(ts);
                // Output times inside the cut step past the switch did not happen (the
                // next mode records them).
                let n = out.t.len();
                let past = out.t[..n - 1].partition_point(|&t| t <= ts);
                out.t.drain(past..n - 1);
                out.y.drain(past..n - 1);
                *out.t.last_mut().expect("a step") = ts;
                *out.y.last_mut().expect("a step") = seg.eval(ts);
                if let Some(kept) = out.segments.last_mut() {
                    *kept = seg.clone();
                }
            }
            if settings.polish {
                polish(method, &view, &mut out, &seg, &g)?;
            } else if kink.is_some() {
                retake(method, &view, &mut out, &seg)?;
            }
        }
        t = *out.t.last().expect("a step");
        y = *out.y.last().expect("a step");
        if kink.is_some() {
            crossed = kink;
            if t >= t1 {
                break;
            }
            continue;
        }
        mode = sys.switch(t, &mut y, &current, k)?;
        // The record holds the state the next mode starts from (a stop's velocity exactly 0).
        *out.y.last_mut().expect("a step") = y;
        let switch = Switch {
            t,
            by: k,
            from: current,
            to: mode,
            steps,
        };
        out.switches.push(switch.erased());
        switches.push(switch);
        if switches.len() >= settings.max_switches {
            return Err(Error::TooManySteps {
                t,
                steps: out.stats.n_steps,
            });
        }
        if t >= t1 {
            break;
        }
    }
    // The final state is the record's last point (which a switch may have moved).
    if let (Some(&t_end), Some(&y_end)) = (out.t.last(), out.y.last()) {
        (out.t_end, out.y_end) = (t_end, y_end);
    }
    Ok(HybridSolution {
        solution: out,
        switches,
        mode,
    })
}

/// A switching function's value as the driver watches it: a crossing is a strictly
/// negative value, so an exact zero counts as still positive. A function that only touches
/// zero (a bound `mu_s |N| - |h|` met for an instant, which static friction still holds)
/// is no switch, and one that starts at zero (a mode entered on its boundary: a slide from
/// rest at `v = 0`, a stick exactly at its bound) is still seen when it goes negative;
/// before, a start at zero never counted, so a slide whose velocity then turned the wrong
/// way went on under kinetic friction that drove the body.
fn watched(g: f64) -> f64 {
    if g == 0.0 { f64::MIN_POSITIVE } else { g }
}

/// The user's `events` followed by the switching functions of `mode` as terminal events
/// (falling crossings), so that index `events.len() + k` is switching function `k`, then
/// its kink functions times their `sides` (falling crossings).
fn with_switches<'e, S: Hybrid<D>, const D: usize>(
    sys: &'e S,
    mode: &'e S::Mode,
    events: &'e [Event<'_, D>],
    sides: &[f64],
) -> Vec<Event<'e, D>> {
    let mut all: Vec<Event<'e, D>> = events
        .iter()
        .map(|e| Event {
            name: e.name.clone(),
            g: Box::new(move |t: f64, y: &Vector<D>| (e.g)(t, y)),
            direction: e.direction,
            terminal: e.terminal,
        })
        .collect();
    all.extend((0..S::SWITCHES).map(|k| {
        Event::new(
            format!("switch {k}"),
            move |t: f64, y: &Vector<D>| watched(sys.switching(t, y, mode, k)),
            Direction::Falling,
        )
        .terminal()
    }));
    // Kinks: leaving their side, at step ends only (not sampled inside steps: a kink
    // crossed and recrossed within one step costs accuracy, not a wrong mode).
    all.extend(sides.iter().enumerate().map(|(k, &side)| {
        Event::new(
            format!("kink {k}"),
            move |t: f64, y: &Vector<D>| side * sys.kink(t, y, mode, k),
            Direction::Falling,
        )
        .terminal()
    }));
    all
}

/// The side of each kink function at the start `(t, y)` of a run in `mode`: its sign there,
/// except for the kink `crossed` just restarted at, which is on its other side whatever the
/// sign (the restart state, from a step that stops at the located time, may still show the
/// old one to rounding: its crossing was that one, not a new one), and a zero keeps the last.
fn kink_sides<S: Hybrid<D>, const D: usize>(
    sys: &S,
    (t, y): (f64, &Vector<D>),
    mode: &S::Mode,
    sides: &mut [f64],
    crossed: Option<usize>,
) {
    for (k, side) in sides.iter_mut().enumerate() {
        if crossed == Some(k) {
            *side = -*side;
            continue;
        }
        let v = sys.kink(t, y, mode, k);
        if v != 0.0 && !v.is_nan() {
            *side = v.signum();
        }
    }
}

/// The switch from step ends instead of the dense output (whose degree, 3 for Radau IIA,
/// limits the located time and the restart state): integrate the last step `seg` (cut at
/// the located time) again from its start to that time, take one Newton step on the
/// switching function there (its slope from the dense output), and integrate to that time.
/// The record's last point becomes that step-end state; the work is added to the statistics.
fn polish<const D: usize>(
    method: &dyn Method<D>,
    view: &View<'_, D>,
    out: &mut Solution<D>,
    seg: &Segment<D>,
    g: &impl Fn(f64, &Vector<D>) -> f64,
) -> Result<()> {
    let n = out.t.len();
    // The polynomial's value at its start (theta = 0) is the step's initial state.
    let (ta, ya, ts) = (seg.t0, seg.coeffs[0], seg.t1());
    let dt = 1e-3 * (ts - ta);
    // A step of zero length (or NaN) has nothing to polish.
    if dt.is_nan() || dt <= 0.0 {
        return Ok(());
    }
    let mut work = Stats::default();
    let mut end = |t: f64| -> Result<Vector<D>> {
        let run = method.run(view, (ta, ya, t), &[], None, None)?;
        add(&mut work, run.stats);
        Ok(*run.last().1)
    };
    let ys = end(ts)?;
    let slope = (g(ts, &seg.eval(ts)) - g(ts - dt, &seg.eval(ts - dt))) / dt;
    let tn = ts - g(ts, &ys) / slope;
    // Newton stays within the last step and a step's length past it; else keep `ts`.
    let (t, y) = if tn.is_finite() && tn > ta && tn < ts + (ts - ta) && tn != ts {
        (tn, end(tn)?)
    } else {
        (ts, ys)
    };
    if let Some(kept) = out.segments.last_mut() {
        *kept = seg.truncated(t);
    }
    out.t[n - 1] = t;
    out.y[n - 1] = y;
    add(&mut out.stats, work);
    Ok(())
}

/// The state at a kink from a step that does not cross it: the cut step `seg` again from
/// its start to its (cut) end, in one step where the method takes one. The step that found
/// the kink evaluated its stages past it, where the mode's right-hand side is another
/// smooth function, so its polynomial is off by more than the method's local error (DOPRI5
/// at rtol 1e-12: a velocity 4e-11 off). The record's last point (and kept segments)
/// become the new step's; the work is added to the statistics.
fn retake<const D: usize>(
    method: &dyn Method<D>,
    view: &View<'_, D>,
    out: &mut Solution<D>,
    seg: &Segment<D>,
) -> Result<()> {
    let (ta, ya, ts) = (seg.t0, seg.coeffs[0], seg.t1());
    // A step within rounding of its start is below any method's smallest step (and its
    // polynomial is as good as a step there).
    let span = ts - ta;
    if span.is_nan() || span <= 64.0 * f64::EPSILON * ts.abs().max(ta.abs()) {
        return Ok(());
    }
    let run = method.run(view, (ta, ya, ts), &[], Some(ts - ta), None)?;
    let n = out.t.len();
    out.y[n - 1] = *run.last().1;
    if !run.segments.is_empty() && out.segments.pop().is_some() {
        out.segments.extend(run.segments.iter().cloned());
    }
    add(&mut out.stats, run.stats);
    Ok(())
}

/// The step size to restart a mode with: the longer of the run's last two steps (the last
/// one may have been cut short by the switch).
fn restart_step(lengths: [f64; 2]) -> Option<f64> {
    lengths
        .into_iter()
        .filter(|h| *h > 0.0 && h.is_finite())
        .reduce(f64::max)
}

fn add(s: &mut Stats, p: Stats) {
    s.n_rhs += p.n_rhs;
    s.n_jac += p.n_jac;
    s.n_lu += p.n_lu;
    s.n_steps += p.n_steps;
    s.n_accepted += p.n_accepted;
    s.n_rejected += p.n_rejected;
}

/// Add one mode's run to the whole: its steps after the first point, its segments, its
/// user events (switching events are not user events) and its work.
fn append<const D: usize>(out: &mut Solution<D>, part: Solution<D>, user: usize) {
    out.t.extend_from_slice(&part.t[1..]);
    out.y.extend_from_slice(&part.y[1..]);
    out.segments.extend(part.segments);
    out.events
        .extend(part.events.into_iter().filter(|e| e.event < user));
    add(&mut out.stats, part.stats);
}

/// The first time in the segment where `g` is no longer positive, to adjacent doubles:
/// regula falsi with the Illinois halving (as [`crate::integrate::events::locate`]) from a
/// bracket just before the segment's end (the located crossing) or, if `g` is not positive
/// there, from the segment's start; bisection where the secant leaves the bracket.
fn refine<const D: usize>(g: &impl Fn(f64, &Vector<D>) -> f64, seg: &Segment<D>) -> f64 {
    let b0 = seg.t1();
    let at = |t: f64| g(t, &seg.eval(t));
    let near = b0 - 4.0 * crate::integrate::events::EVENT_TIME_TOL * (b0.abs() + 1.0);
    let (mut a, mut ga) = (near, if near > seg.t0 { at(near) } else { f64::NAN });
    // NaN counts as not positive.
    if ga.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        (a, ga) = (seg.t0, at(seg.t0));
    }
    let (b, gb) = (b0, at(b0));
    if !(ga > 0.0 && gb <= 0.0) {
        return b0;
    }
    bracketed(g, seg, (a, ga), (b, gb))
}

/// The first time in `[a, b]` where `g` is no longer positive, given `g(a) > 0 >= g(b)`, to
/// adjacent doubles (regula falsi, Illinois, bisection where the secant leaves the bracket
/// or three steps did not halve it).
fn bracketed<const D: usize>(
    g: &impl Fn(f64, &Vector<D>) -> f64,
    seg: &Segment<D>,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
) -> f64 {
    let at = |t: f64| g(t, &seg.eval(t));
    let mut kept_a = 0u8;
    let mut kept_b = 0u8;
    // The bracket's width three steps ago: a bisection whenever three steps did not halve
    // it (an end whose value is far smaller than the function's scale, an exact zero
    // watched as the least positive double, moves the secant point by next to nothing).
    let mut width = b - a;
    for i in 0..200 {
        let mut c = (a * gb - b * ga) / (gb - ga);
        if i % 3 == 2 {
            if b - a > 0.5 * width {
                c = 0.5 * (a + b);
            }
            width = b - a;
        }
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        if c <= a || c >= b {
            break;
        }
        let gc = at(c);
        if gc > 0.0 {
            (a, ga) = (c, gc);
            kept_a = 0;
            kept_b += 1;
            if kept_b >= 2 {
                gb *= 0.5;
            }
        } else if gc <= 0.0 {
            (b, gb) = (c, gc);
            kept_b = 0;
            kept_a += 1;
            if kept_a >= 2 {
                ga *= 0.5;
            }
        } else {
            break;
        }
    }
    b
}

/// Samples of one switching function per accepted step, at most: the spacing never falls
/// below `h / MAX_SAMPLES` of the step `h`.
pub const MAX_SAMPLES: usize = 4096;

/// The earliest crossing inside `seg` of any switching function of `mode` that the step's
/// ends did not show, located to adjacent doubles: `(function, time)`.
fn first_inside<S: Hybrid<D>, const D: usize>(
    sys: &S,
    mode: &S::Mode,
    seg: &Segment<D>,
) -> Option<(usize, f64)> {
    (0..S::SWITCHES)
        .filter(|&k| {
            sys.switching_state(mode, k)
                .is_none_or(|(i, sign)| !positive_on(seg, i, sign))
        })
        .filter_map(|k| {
            let g = |t: f64, y: &Vector<D>| watched(sys.switching(t, y, mode, k));
            hidden(&g, seg).map(|(a, b)| (k, bracketed(&g, seg, a, b)))
        })
        .min_by(|x, y| x.1.total_cmp(&y.1))
}

/// Whether `sign * y[i]` stays positive over the whole segment, from its coefficients in
/// `theta` in `[0, 1]`: `p_0 + sum min(0, p_j) > 0` bounds it from below (`theta^j <= 1`).
fn positive_on<const D: usize>(seg: &Segment<D>, i: usize, sign: f64) -> bool {
    let p0 = sign * seg.coeffs[0][i];
    let low: f64 = seg.coeffs[1..].iter().map(|c| (sign * c[i]).min(0.0)).sum();
    p0 + low > 0.0
}

/// A bracket `((a, g(a) > 0), (b, g(b) <= 0))` of a zero of `g` inside `seg` (before its
/// end), or `None`.
///
/// The rule: from each sample `a` (`g > 0`), the slope `g1` and curvature `g2` are taken by
/// central differences (spacing `1e-4 h`) on the dense output, and the next sample is the
/// farthest `s` where this local model cannot reach zero, `|g1| s + |g2| s^2 / 2 <= g`;
/// where the model falls monotonically through zero at `tau`, the next sample is at
/// `1.5 tau` instead, so that a transversal crossing is reached in a few samples rather
/// than approached forever. A constant function costs three evaluations per step; a load
/// that nears the bound is sampled more densely as it nears it. Limits: the model is local,
/// so a change that begins and ends between two samples (a pulse shorter than the spacing
/// the function's derivatives allowed at the sample before it) is not seen, nor a dip below
/// zero shorter than `h / MAX_SAMPLES`; the derivatives are only as good as the dense
/// output, within the method's tolerance.
fn hidden<const D: usize>(
    g: &impl Fn(f64, &Vector<D>) -> f64,
    seg: &Segment<D>,
) -> Option<((f64, f64), (f64, f64))> {
    let (t0, t1) = (seg.t0, seg.t1());
    let h = t1 - t0;
    let at = |t: f64| g(t, &seg.eval(t));
    let (mut a, mut ga) = (t0, at(t0));
    if !(h > 0.0 && ga > 0.0 && ga.is_finite()) {
        return None;
    }
    let delta = 1e-4 * h;
    let floor = h / MAX_SAMPLES as f64;
    loop {
        let (gm, gp) = (at(a - delta), at(a + delta));
        let g1 = (gp - gm) / (2.0 * delta);
        let g2 = ((gp - ga) + (gm - ga)) / (delta * delta);
        let s = spacing(ga, g1, g2);
        // NaN: the function could not be evaluated; infinite: it is flat to the end.
        let b = a + s.max(floor);
        if s.is_nan() || b >= t1 {
            return None;
        }
        let gb = at(b);
        if gb <= 0.0 {
            return Some(((a, ga), (b, gb)));
        }
        if !gb.is_finite() {
            return None;
        }
        (a, ga) = (b, gb);
    }
}

/// How far the local model `g + g1 s + g2 s^2 / 2` (`g > 0`) may be followed ([`hidden`]).
fn spacing(g: f64, g1: f64, g2: f64) -> f64 {
    let (b, c) = (g1.abs(), g2.abs());
    let safe = if b == 0.0 && c == 0.0 {
        f64::INFINITY
    } else {
        2.0 * g / (b + (b * b + 2.0 * c * g).sqrt())
    };
    // The model's first zero, and whether it falls all the way to 1.5 times that.
    let disc = g1 * g1 - 2.0 * g2 * g;
    if g1 < 0.0 && disc >= 0.0 {
        let tau = 2.0 * g / (-g1 + disc.sqrt());
        if g1 + g2 * 1.5 * tau < 0.0 {
            return safe.max(1.5 * tau);
        }
    }
    safe
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{Dopri5, Options, Rk4};

    /// A thermostat: `y' = 1` while on, `-1` while off; off at `y = 1`, on at `y = 0`.
    /// From `y = 0` on, it switches at `t = 1, 2, 3, ...` exactly.
    struct Thermostat;

    impl Hybrid<1> for Thermostat {
        type Mode = bool;
        const SWITCHES: usize = 1;
        fn rhs_in(&self, _t: f64, _y: &Vector<1>, on: &bool) -> Result<Vector<1>> {
            Ok(Vector::<1>::new(if *on { 1.0 } else { -1.0 }))
        }
        fn switching(&self, _t: f64, y: &Vector<1>, on: &bool, _k: usize) -> f64 {
            if *on { 1.0 - y[0] } else { y[0] }
        }
        fn mode_at(&self, _t: f64, y: &Vector<1>) -> Result<bool> {
            Ok(y[0] < 1.0)
        }
        fn switch(&self, _t: f64, _y: &mut Vector<1>, on: &bool, _k: usize) -> Result<bool> {
            Ok(!*on)
        }
    }

    #[test]
    fn switches_at_the_exact_times_with_any_method() {
        let opts = Options {
            rtol: 1e-10,
            atol: 1e-10,
            ..Options::default()
        };
        let y0 = Vector::<1>::zeros();
        let runs = [
            solve(&Dopri5::new(opts), &Thermostat, 0.0, y0, 5.5, &[]).unwrap(),
            solve(&Rk4::new(0.3), &Thermostat, 0.0, y0, 5.5, &[]).unwrap(),
        ];
        for run in &runs {
            assert_eq!(run.switches.len(), 5);
            for (i, sw) in run.switches.iter().enumerate() {
                assert!((sw.t - (i + 1) as f64).abs() <= 1e-14, "{}", sw.t);
                assert_eq!(sw.to, i % 2 == 1);
            }
            let (t, y) = run.solution.last();
            assert_eq!(t, 5.5);
            assert!((y[0] - 0.5).abs() <= 1e-13);
            assert!(
                run.solution
                    .at(2.5)
                    .is_some_and(|y| (y[0] - 0.5).abs() <= 1e-13)
            );
        }
    }

    /// A hand-written hybrid system opts in to the ordinary solve by returning itself from
    /// `OdeSystem::hybrid`: the same exact switches, kept in `Solution::switches`.
    impl OdeSystem<1> for Thermostat {
        fn rhs(&self, t: f64, y: &Vector<1>) -> Result<Vector<1>> {
            self.rhs_in(t, y, &self.mode_at(t, y)?)
        }
        fn hybrid(&self) -> Option<&dyn Modes<1>> {
            Some(self)
        }
    }

    #[test]
    fn the_ordinary_solve_switches_a_hand_written_system() {
        let sol = Rk4::new(0.3)
            .solve(&Thermostat, 0.0, Vector::<1>::zeros(), 5.5, &[])
            .unwrap();
        assert_eq!(sol.switches.len(), 5);
        for (i, sw) in sol.switches.iter().enumerate() {
            assert!((sw.t - (i + 1) as f64).abs() <= 1e-14, "{}", sw.t);
            assert_eq!(sw.to.get::<bool>(), Some(&(i % 2 == 1)));
            assert_eq!(sw.to, AnyMode::new(i % 2 == 1));
            assert_ne!(sw.to, AnyMode::new(i as u8));
        }
        assert!((sol.last().1[0] - 0.5).abs() <= 1e-13);
    }

    #[test]
    fn too_many_switches_is_a_typed_error() {
        let settings = Settings {
            max_switches: 3,
            ..Settings::default()
        };
        let y0 = Vector::<1>::zeros();
        let err = solve_with(&Rk4::new(0.3), &Thermostat, 0.0, y0, 10.0, &[], &settings);
        assert!(matches!(err, Err(Error::TooManySteps { .. })));
    }

    /// Generalized-alpha integrates `y = [q; qd]` systems only: the thermostat (one state)
    /// is a typed error, not a wrong `Ok`.
    #[test]
    fn generalized_alpha_refuses_a_first_order_system() {
        let ga = crate::integrate::GeneralizedAlpha::new(0.9, 0.1);
        let err = solve(&ga, &Thermostat, 0.0, Vector::<1>::zeros(), 1.0, &[]);
        assert!(matches!(err, Err(Error::InvalidInput { .. })), "{err:?}");
    }

    /// A function of `t` alone that dips below zero many times inside one long segment:
    /// `0.5 - sin(10 t)` on `[0, 100]` first crosses at `asin(0.5) / 10`; a constant one
    /// costs three evaluations.
    #[test]
    fn hidden_crossings_are_found_inside_a_long_step() {
        let z = Vector::<1>::zeros();
        let seg = Segment::polynomial(0.0, 100.0, &[z]);
        let g = |t: f64, _y: &Vector<1>| 0.5 - (10.0 * t).sin();
        let (a, b) = hidden(&g, &seg).expect("a crossing");
        let t = bracketed(&g, &seg, a, b);
        assert!((t - 0.5f64.asin() / 10.0).abs() <= 1e-15, "{t}");
        let calls = std::cell::Cell::new(0);
        let flat = |_t: f64, _y: &Vector<1>| {
            calls.set(calls.get() + 1);
            1.0
        };
        assert!(hidden(&flat, &seg).is_none());
        assert_eq!(calls.get(), 3);
    }

    /// The refinement finds the crossing of `y - 1/3` on `y = t` to adjacent doubles.
    #[test]
    fn refine_reaches_adjacent_doubles() {
        let z = Vector::<1>::zeros();
        let seg = Segment::polynomial(0.0, 1.0, &[z, Vector::<1>::new(1.0)]);
        let g = |_t: f64, y: &Vector<1>| 1.0 / 3.0 - y[0];
        let t = refine(&g, &seg);
        assert!(g(t, &seg.eval(t)) <= 0.0);
        assert!(g(t, &seg.eval(t.next_down())) > 0.0);
    }
}
