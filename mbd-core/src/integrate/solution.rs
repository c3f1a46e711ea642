//! The record of an integration, and the bookkeeping every method shares to build it.

use super::dense::Segment;
use super::events::{self, Event, EventHit};
use super::{Options, Stats};
use crate::error::{Error, Result};
use crate::model::Vector;
use std::fmt;

/// What a [`Solution`] keeps of the accepted steps (dense segments are
/// [`Options::dense`]'s business, apart). The first and the final states are always kept.
///
/// Memory: [`Record::Steps`] grows with the number of steps; [`Record::Every`] with the
/// steps divided by `k`; [`Record::Final`] and [`Record::Times`] only with what was asked
/// (with `dense = false`, a run of a million steps then holds a few states).
#[derive(Debug, Clone, Default, PartialEq)]
pub enum Record {
    /// The end of every accepted step (the default).
    #[default]
    Steps,
    /// The end of every `k`-th accepted step (`k >= 1`).
    Every(usize),
    /// Nothing between the first and the final state.
    Final,
    /// The states at these times, ascending, from each step's dense output (a time before
    /// `t0` or after the end of the run is not reached and not recorded). Vern9, whose
    /// interpolant costs nine calls, ends a step on an output time instead where that costs
    /// less (without dense output, events or an observer): its steps then depend on the times.
    Times(Vec<f64>),
}

impl Record {
    /// `Err` for `Every(0)` and for times that are not finite or not ascending.
    pub fn validate(&self) -> Result<()> {
        let bad = |detail: String| {
            Err(Error::InvalidInput {
                what: "record",
                detail,
            })
        };
        match self {
            Record::Every(0) => bad("Every(k) needs k >= 1".to_string()),
            Record::Times(ts) if !ts.iter().all(|t| t.is_finite()) => {
                bad("output times must be finite".to_string())
            }
            Record::Times(ts) if ts.windows(2).any(|w| w[1] < w[0]) => {
                bad("output times must be ascending".to_string())
            }
            _ => Ok(()),
        }
    }
}

/// One accepted step as an [`Observer`] sees it: its end `(t, y)` (after any projection),
/// and its dense segment when one was built (dense output, events, or an output time inside
/// the step).
#[derive(Debug, Clone, Copy)]
pub struct Step<'s, const D: usize> {
    /// End of the step.
    pub t: f64,
    /// Accepted state at `t`.
    pub y: &'s Vector<D>,
    /// The step's polynomial, when built.
    pub segment: Option<&'s Segment<D>>,
}

/// A callback over accepted steps (after events are located): return [`Flow::Stop`] to end
/// the integration there.
pub type Observer<'o, const D: usize> = dyn FnMut(&Step<'_, D>) -> Flow + 'o;

/// What an integration produced.
#[derive(Debug, Clone)]
pub struct Solution<const D: usize> {
    /// `t0`, the recorded times ([`Record`]), and the final time (the terminal event's
    /// when one fired).
    pub t: Vec<f64>,
    /// The states at `t`.
    pub y: Vec<Vector<D>>,
    /// One dense-output segment per accepted step when `Options::dense`, else empty.
    pub segments: Vec<Segment<D>>,
    /// The events found, in time order.
    pub events: Vec<EventHit<D>>,
    /// Work counters.
    pub stats: Stats,
    /// Index of the terminal event that ended the run, if one did.
    pub stopped_by: Option<usize>,
    /// The final time, kept apart from the record so that it exists whatever was recorded.
    pub t_end: f64,
    /// The final state.
    pub y_end: Vector<D>,
    /// The singular positions of a closed loop bridged on the way ([`crate::passage`]).
    pub passages: Vec<crate::passage::Passage>,
    /// The mode switches of a hybrid system (Coulomb friction: stops and breakaways), in
    /// time order, with the modes erased ([`crate::hybrid::AnyMode::get`] gives them back);
    /// empty for a smooth system.
    pub switches: Vec<crate::hybrid::Switch<crate::hybrid::AnyMode>>,
}

impl<const D: usize> Solution<D> {
    /// The record of a run that has not stepped yet: `(t0, y0)` only.
    pub fn start(t0: f64, y0: Vector<D>) -> Self {
        Solution {
            t: vec![t0],
            y: vec![y0],
            segments: Vec::new(),
            events: Vec::new(),
            stats: Stats::default(),
            stopped_by: None,
            t_end: t0,
            y_end: y0,
            passages: Vec::new(),
            switches: Vec::new(),
        }
    }

    /// The final time and state. Never fails: every solution has them
    /// ([`Solution::t_end`], [`Solution::y_end`]), whatever [`Record`] kept.
    pub fn last(&self) -> (f64, &Vector<D>) {
        (self.t_end, &self.y_end)
    }

    /// The state at `t` from the dense output: `None` outside the segments kept, or when
    /// none were. At a recorded time it returns that state exactly (after any projection),
    /// elsewhere the segment's polynomial.
    pub fn at(&self, t: f64) -> Option<Vector<D>> {
        // Kept segments cover every step, from t0 to the end.
        let first = self.segments.first()?;
        if !(t >= first.t0 && t <= self.t_end) {
            return None;
        }
        if t == self.t_end {
            return Some(self.y_end);
        }
        if let Ok(k) = self
            .t
            .binary_search_by(|probe| probe.partial_cmp(&t).unwrap_or(std::cmp::Ordering::Less))
        {
            return self.y.get(k).copied();
        }
        // The last segment starting at or before t.
        let k = self.segments.partition_point(|s| s.t0 <= t).max(1) - 1;
        Some(self.segments[k].eval(t))
    }
}

/// Whether a method should go on after an accepted step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Take the next step.
    Continue,
    /// A terminal event fired, or the observer asked to stop: the solution ends there.
    Stop,
}

/// Bookkeeping every method shares: records accepted steps as [`Record`] asks, locates
/// events on the step's dense segment (every sign change of `g` between samples of the
/// segment and the extrema between them, [`events::crossings`], refined by
/// [`events::locate`] to `|dt| <= 1e-12 (|t| + 1)`), stops at terminal events, and calls the
/// observer. A step in which `g` crosses zero and back is no longer silent: its crossings
/// are found between the samples (the ends alone showed no sign change).
///
/// Nothing here allocates per step unless the record grows ([`Record::Steps`],
/// [`Record::Every`], dense segments, events found).
pub struct Recorder<'r, 'e, const D: usize> {
    events: &'r [Event<'e, D>],
    g_prev: Vec<f64>,
    g_next: Vec<f64>,
    dense: bool,
    record: Record,
    /// Index of the next [`Record::Times`] entry to produce.
    next_time: usize,
    steps: usize,
    observer: Option<&'r mut Observer<'r, D>>,
    sol: Solution<D>,
    /// An event function that failed: the record ends and [`Self::finish`] returns it.
    failed: Option<Error>,
}

impl<'r, 'e, const D: usize> Recorder<'r, 'e, D> {
    /// Start a record at `(t0, y0)` with `opts.dense` and `opts.record`; evaluates every
    /// event function there. (`opts.record` is assumed valid: [`Options::validate`].)
    pub fn new(events: &'r [Event<'e, D>], t0: f64, y0: Vector<D>, opts: &Options) -> Self {
        Self::with(events, t0, y0, opts.dense, opts.record.clone())
    }

    /// [`Self::new`] with the two recording settings given apart (for methods without
    /// [`Options`]).
    pub fn with(
        events: &'r [Event<'e, D>],
        t0: f64,
        y0: Vector<D>,
        dense: bool,
        record: Record,
    ) -> Self {
        let mut failed = None;
        let g_prev: Vec<f64> = events
            .iter()
            .map(|e| {
                e.value(t0, &y0).unwrap_or_else(|err| {
                    failed.get_or_insert(err);
                    f64::NAN
                })
            })
            .collect();
        // Output times at t0 are the initial state, already kept.
        let next_time = match &record {
            Record::Times(ts) => ts.partition_point(|&t| t <= t0),
            _ => 0,
        };
        Recorder {
            failed,
            events,
            g_next: vec![0.0; events.len()],
            g_prev,
            dense,
            record,
            next_time,
            steps: 0,
            observer: None,
            sol: Solution::start(t0, y0),
        }
    }

    /// The same record, calling `observer` after every accepted step.
    pub fn observed<'o: 'r>(self, observer: Option<&'r mut Observer<'o, D>>) -> Self {
        let observer = observer.map(|o| -> &'r mut Observer<'r, D> { o });
        Recorder { observer, ..self }
    }

    /// Record an accepted step: `seg` covers it and `y1` is the accepted (projected) state
    /// at `seg.t1()`. Returns [`Flow::Stop`] when a terminal event fired inside the step
    /// (the record then ends at that event, its segment truncated there) or the observer
    /// asked to stop.
    pub fn accept(&mut self, seg: Segment<D>, y1: &Vector<D>) -> Flow {
        self.accept_with(seg.t1(), y1, || seg)
    }

    /// Whether [`Self::accept_with`] will build the step's segment: it is kept
    /// (`Options::dense`), needed to locate events or to produce output times.
    pub fn needs_segment(&self) -> bool {
        self.dense
            || !self.events.is_empty()
            || matches!(&self.record, Record::Times(ts) if self.next_time < ts.len())
    }

    /// Whether a step ending at `t1` needs its segment: [`Self::needs_segment`], narrowed
    /// for output times to a step with an output time inside it (before `t1`; one at `t1`
    /// is the step's end state). Steps between output times then cost no more than with
    /// [`Record::Final`] (DOP853 saves its three dense stages there).
    #[inline]
    pub fn needs_segment_to(&self, t1: f64) -> bool {
        self.dense
            || !self.events.is_empty()
            || matches!(&self.record, Record::Times(ts) if ts.get(self.next_time).is_some_and(|&t| t < t1))
    }

    /// [`Self::accept`] for a step ending at `(t1, y1)` whose segment is built only when
    /// [`Self::needs_segment_to`]: a run without dense output, events and output times pays
    /// nothing for it.
    #[inline]
    pub fn accept_with(
        &mut self,
        t1: f64,
        y1: &Vector<D>,
        segment: impl FnOnce() -> Segment<D>,
    ) -> Flow {
        if self.failed.is_some() {
            return Flow::Stop;
        }
        if !self.needs_segment_to(t1) {
            return self.accept_point(t1, y1);
        }
        self.accept_segment(segment(), t1, y1)
    }

    /// [`Self::accept`] with the segment built: events, then the record.
    #[inline]
    fn accept_segment(&mut self, seg: Segment<D>, t1: f64, y1: &Vector<D>) -> Flow {
        let stop = self.locate_events(&seg, t1, y1);
        if self.failed.is_some() {
            return Flow::Stop;
        }
        match stop {
            None => self.push_step(Some(seg), t1, *y1),
            Some((ts, i)) => {
                let ys = if ts == t1 { *y1 } else { seg.eval(ts) };
                let cut = if ts == t1 { seg } else { seg.truncated(ts) };
                self.sol.stopped_by = Some(i);
                self.push_step(Some(cut), ts, ys);
                Flow::Stop
            }
        }
    }

    /// The next two output times (the second `INFINITY` when there is none) when output
    /// times are all a step's polynomial is needed for (no dense output, events or
    /// observer): a method may then end a step on the next, or evaluate its continuous
    /// extension at the times alone ([`Self::accept_values`]).
    #[inline]
    pub(crate) fn next_times_only(&self) -> Option<(f64, f64)> {
        match &self.record {
            Record::Times(ts)
                if !self.dense && self.events.is_empty() && self.observer.is_none() =>
            {
                let after = ts.get(self.next_time + 1).copied();
                Some((*ts.get(self.next_time)?, after.unwrap_or(f64::INFINITY)))
            }
            _ => None,
        }
    }

    /// Record an accepted step ending at `(t1, y1)` when only output times need its
    /// polynomial ([`Self::next_times_only`] is `Some`): `value(t)` for each output time
    /// inside the step, `y1` for one at `t1`.
    #[inline]
    pub(crate) fn accept_values(
        &mut self,
        t1: f64,
        y1: &Vector<D>,
        mut value: impl FnMut(f64) -> Vector<D>,
    ) -> Flow {
        debug_assert!(self.next_times_only().is_some());
        self.steps += 1;
        if let Record::Times(ts) = &self.record {
            while let Some(&t) = ts.get(self.next_time).filter(|&&t| t <= t1) {
                self.sol.t.push(t);
                self.sol.y.push(if t == t1 { *y1 } else { value(t) });
                self.next_time += 1;
            }
        }
        (self.sol.t_end, self.sol.y_end) = (t1, *y1);
        Flow::Continue
    }

    /// Record an accepted step ending at `(t1, y1)` when [`Self::needs_segment_to`] is
    /// false (nothing kept or located needs the step's polynomial).
    #[inline]
    pub(crate) fn accept_point(&mut self, t1: f64, y1: &Vector<D>) -> Flow {
        debug_assert!(!self.needs_segment_to(t1));
        self.push_step(None, t1, *y1)
    }

    /// Evaluate the event functions at the step's end, record the crossings located on
    /// `seg` up to the first terminal one, and return that one's time and index.
    fn locate_events(&mut self, seg: &Segment<D>, t1: f64, y1: &Vector<D>) -> Option<(f64, usize)> {
        if self.events.is_empty() {
            return None;
        }
        let mut crossings: Vec<(f64, usize)> = Vec::new();
        for (i, ev) in self.events.iter().enumerate() {
            let located = ev.value(t1, y1).and_then(|g1| {
                self.g_next[i] = g1;
                let g = |t, y: &Vector<D>| ev.value(t, y);
                let mut found = |t| crossings.push((t, i));
                events::crossings(&g, seg, ev.direction, (self.g_prev[i], g1), &mut found)
            });
            match located {
                Ok(()) => {}
                Err(e) => {
                    // The caller sees `failed` and stops.
                    self.failed = Some(e);
                    return None;
                }
            }
        }
        std::mem::swap(&mut self.g_prev, &mut self.g_next);
        crossings.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let stop = crossings
            .iter()
            .find(|&&(_, i)| self.events[i].terminal)
            .copied();
        for &(t, i) in &crossings {
            if stop.is_some_and(|(ts, _)| t > ts) {
                break;
            }
            let y = if t == t1 { *y1 } else { seg.eval(t) };
            self.sol.events.push(EventHit { event: i, t, y });
        }
        stop
    }

    /// Keep what the record asks of a step ending at `(t1, y1)`, then call the observer.
    #[inline]
    fn push_step(&mut self, seg: Option<Segment<D>>, t1: f64, y1: Vector<D>) -> Flow {
        self.steps += 1;
        match &self.record {
            Record::Steps => self.keep(t1, y1),
            Record::Every(k) if self.steps.is_multiple_of(*k) => self.keep(t1, y1),
            Record::Times(ts) => {
                while let Some(&t) = ts.get(self.next_time) {
                    if t > t1 {
                        break;
                    }
                    let y = match &seg {
                        Some(s) if t != t1 => s.eval(t),
                        _ => y1,
                    };
                    self.sol.t.push(t);
                    self.sol.y.push(y);
                    self.next_time += 1;
                }
            }
            _ => {}
        }
        (self.sol.t_end, self.sol.y_end) = (t1, y1);
        let mut flow = Flow::Continue;
        if let Some(observer) = self.observer.as_mut() {
            flow = observer(&Step {
                t: t1,
                y: &y1,
                segment: seg.as_ref(),
            });
        }
        if self.dense
            && let Some(seg) = seg
        {
            self.sol.segments.push(seg);
        }
        flow
    }

    #[inline]
    fn keep(&mut self, t: f64, y: Vector<D>) {
        self.sol.t.push(t);
        self.sol.y.push(y);
    }

    /// The finished record with the method's work counters (the final state closes `t`
    /// and `y` when the record did not already end there), or the error of an event
    /// function that failed.
    pub fn finish(mut self, stats: Stats) -> Result<Solution<D>> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let (t_end, y_end) = (self.sol.t_end, self.sol.y_end);
        if self.sol.t.last() != Some(&t_end) {
            self.keep(t_end, y_end);
        }
        Ok(Solution { stats, ..self.sol })
    }
}

impl<const D: usize> fmt::Debug for Recorder<'_, '_, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Recorder")
            .field("events", &self.events)
            .field("record", &self.record)
            .field("steps", &self.steps)
            .finish_non_exhaustive()
    }
}
