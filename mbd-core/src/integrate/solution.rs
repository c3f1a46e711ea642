//! The record of an integration, and the bookkeeping every method shares to build it.

use super::dense::Segment;
use super::events::{Event, EventHit, locate};
use super::{Options, Stats};
use crate::model::Vector;
use std::fmt;

/// What an integration produced.
#[derive(Debug, Clone)]
pub struct Solution<const D: usize> {
    /// `t0` and the end of every accepted step (the last one is the terminal event's time
    /// when one fired).
    pub t: Vec<f64>,
    /// The states at `t`.
    pub y: Vec<Vector<D>>,
    /// One dense-output segment per step when `Options::dense`, else empty.
    pub segments: Vec<Segment<D>>,
    /// The events found, in time order.
    pub events: Vec<EventHit<D>>,
    /// Work counters.
    pub stats: Stats,
    /// Index of the terminal event that ended the run, if one did.
    pub stopped_by: Option<usize>,
}

impl<const D: usize> Solution<D> {
    /// The final time and state.
    pub fn last(&self) -> (f64, &Vector<D>) {
        let k = self.t.len() - 1;
        (self.t[k], &self.y[k])
    }

    /// The state at `t` from the dense output: `None` outside `[t0, t_end]` or when no
    /// segments were kept. At a step's end time it returns that step's accepted state exactly
    /// (after any projection), elsewhere the segment's polynomial.
    pub fn at(&self, t: f64) -> Option<Vector<D>> {
        let (t_first, t_last) = (self.t[0], *self.t.last()?);
        if self.segments.is_empty() || !(t >= t_first && t <= t_last) {
            return None;
        }
        if let Ok(k) = self
            .t
            .binary_search_by(|probe| probe.partial_cmp(&t).unwrap_or(std::cmp::Ordering::Less))
        {
            return Some(self.y[k]);
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
    /// A terminal event fired: the solution ends there.
    Stop,
}

/// Bookkeeping every method shares: records accepted steps, locates events on the step's
/// dense segment (a sign change of `g` between the segment's ends, refined by
/// [`locate`] to `|dt| <= 1e-12 (|t| + 1)`), and stops at terminal
/// events. Event functions are evaluated once per step at the step's end; a step in which
/// `g` crosses zero twice shows no sign change and reports nothing.
pub struct Recorder<'r, 'e, const D: usize> {
    events: &'r [Event<'e, D>],
    g_prev: Vec<f64>,
    g_next: Vec<f64>,
    dense: bool,
    sol: Solution<D>,
}

impl<'r, 'e, const D: usize> Recorder<'r, 'e, D> {
    /// Start a record at `(t0, y0)`; evaluates every event function there.
    pub fn new(events: &'r [Event<'e, D>], t0: f64, y0: Vector<D>, opts: &Options) -> Self {
        let g_prev: Vec<f64> = events.iter().map(|e| (e.g)(t0, &y0)).collect();
        Recorder {
            events,
            g_next: vec![0.0; events.len()],
            g_prev,
            dense: opts.dense,
            sol: Solution {
                t: vec![t0],
                y: vec![y0],
                segments: Vec::new(),
                events: Vec::new(),
                stats: Stats::default(),
                stopped_by: None,
            },
        }
    }

    /// Record an accepted step: `seg` covers it and `y1` is the accepted (projected) state
    /// at `seg.t1()`. Returns [`Flow::Stop`] when a terminal event fired inside the step;
    /// the record then ends at that event (its segment truncated there).
    pub fn accept(&mut self, seg: Segment<D>, y1: &Vector<D>) -> Flow {
        self.accept_with(seg.t1(), y1, || seg)
    }

    /// Whether [`Self::accept_with`] will build the step's segment: it is kept
    /// (`Options::dense`) or needed to locate events.
    pub fn needs_segment(&self) -> bool {
        self.dense || !self.events.is_empty()
    }

    /// [`Self::accept`] for a step ending at `(t1, y1)` whose segment is built only when
    /// [`Self::needs_segment`]: a run without dense output and events pays nothing for it.
    pub fn accept_with(
        &mut self,
        t1: f64,
        y1: &Vector<D>,
        segment: impl FnOnce() -> Segment<D>,
    ) -> Flow {
        if !self.needs_segment() {
            self.sol.t.push(t1);
            self.sol.y.push(*y1);
            return Flow::Continue;
        }
        let seg = segment();
        let mut crossings: Vec<(f64, usize)> = Vec::new();
        for (i, ev) in self.events.iter().enumerate() {
            let g1 = (ev.g)(t1, y1);
            self.g_next[i] = g1;
            if ev.direction.crossed(self.g_prev[i], g1) {
                crossings.push((locate(&*ev.g, &seg, self.g_prev[i], g1), i));
            }
        }
        std::mem::swap(&mut self.g_prev, &mut self.g_next);
        if crossings.is_empty() {
            self.push_step(seg, t1, *y1);
            return Flow::Continue;
        }
        crossings.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let state_at = |t: f64| if t == t1 { *y1 } else { seg.eval(t) };
        let stop = crossings
            .iter()
            .find(|&&(_, i)| self.events[i].terminal)
            .copied();
        for &(t, i) in &crossings {
            if stop.is_some_and(|(ts, _)| t > ts) {
                break;
            }
            self.sol.events.push(EventHit {
                event: i,
                t,
                y: state_at(t),
            });
        }
        match stop {
            None => {
                self.push_step(seg, t1, *y1);
                Flow::Continue
            }
            Some((ts, i)) => {
                let ys = state_at(ts);
                let cut = if ts == t1 { seg } else { seg.truncated(ts) };
                self.push_step(cut, ts, ys);
                self.sol.stopped_by = Some(i);
                Flow::Stop
            }
        }
    }

    /// Record an accepted step ending at `(t1, y1)` when [`Self::needs_segment`] is false
    /// (nothing kept or located needs the step's polynomial).
    pub(crate) fn accept_point(&mut self, t1: f64, y1: &Vector<D>) -> Flow {
        debug_assert!(!self.needs_segment());
        self.sol.t.push(t1);
        self.sol.y.push(*y1);
        Flow::Continue
    }

    #[inline]
    fn push_step(&mut self, seg: Segment<D>, t1: f64, y1: Vector<D>) {
        self.sol.t.push(t1);
        self.sol.y.push(y1);
        if self.dense {
            self.sol.segments.push(seg);
        }
    }

    /// The finished record with the method's work counters.
    pub fn finish(self, stats: Stats) -> Solution<D> {
        Solution { stats, ..self.sol }
    }
}

impl<const D: usize> fmt::Debug for Recorder<'_, '_, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Recorder")
            .field("events", &self.events)
            .field("steps", &(self.sol.t.len() - 1))
            .finish_non_exhaustive()
    }
}
