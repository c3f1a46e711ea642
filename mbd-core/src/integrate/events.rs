//! Events: zero crossings of a scalar function `g(t, y)` located on the dense output.

use super::dense::Segment;
use crate::error::{Error, Result};
use crate::model::Vector;
use std::fmt;

/// Which sign changes of `g` count as an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// `g` goes from negative to zero or positive.
    Rising,
    /// `g` goes from positive to zero or negative.
    Falling,
    /// Either.
    Either,
}

impl Direction {
    /// Whether `g` went from `g0` (start of a step) to `g1` (end) through zero in this
    /// direction. A start value of exactly zero never counts, so an event found at the end
    /// of one step is not found again at the start of the next; non-finite values never count.
    pub fn crossed(self, g0: f64, g1: f64) -> bool {
        let rising = g0 < 0.0 && g1 >= 0.0;
        let falling = g0 > 0.0 && g1 <= 0.0;
        match self {
            Direction::Rising => rising,
            Direction::Falling => falling,
            Direction::Either => rising || falling,
        }
    }
}

/// The signature of an event function `g(t, y)`: an error (a singular position where `g`
/// needs the accelerations) stops the integration with [`Error::EventFailed`].
pub type EventFn<'a, const D: usize> = dyn Fn(f64, &Vector<D>) -> Result<f64> + 'a;

/// A named event function `g(t, y)`; the event happens where `g` crosses zero in `direction`.
/// A terminal event ends the integration there.
pub struct Event<'a, const D: usize> {
    /// Name, for reports.
    pub name: String,
    /// The event function.
    pub g: Box<EventFn<'a, D>>,
    /// Which crossings count.
    pub direction: Direction,
    /// Stop the integration at the first crossing.
    pub terminal: bool,
}

impl<'a, const D: usize> Event<'a, D> {
    /// A non-terminal event: every crossing is recorded and the integration goes on.
    pub fn new(
        name: impl Into<String>,
        g: impl Fn(f64, &Vector<D>) -> f64 + 'a,
        direction: Direction,
    ) -> Self {
        Self::fallible(name, move |t, y| Ok(g(t, y)), direction)
    }

    /// An event whose function can fail (generated models' events, which may solve for the
    /// accelerations): its error, or a NaN or infinite value, ends the integration with
    /// [`Error::EventFailed`] rather than hiding a crossing.
    pub fn fallible(
        name: impl Into<String>,
        g: impl Fn(f64, &Vector<D>) -> Result<f64> + 'a,
        direction: Direction,
    ) -> Self {
        Event {
            name: name.into(),
            g: Box::new(g),
            direction,
            terminal: false,
        }
    }

    /// `g(t, y)`, finite, or why not.
    pub fn value(&self, t: f64, y: &Vector<D>) -> Result<f64> {
        let failed = |cause| Error::EventFailed {
            event: self.name.clone(),
            t,
            cause,
        };
        match (self.g)(t, y) {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(failed(None)),
            Err(e) => Err(failed(Some(Box::new(e)))),
        }
    }

    /// The same event, but stopping the integration at its first crossing.
    pub fn terminal(self) -> Self {
        Event {
            terminal: true,
            ..self
        }
    }
}

impl<const D: usize> fmt::Debug for Event<'_, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Event")
            .field("name", &self.name)
            .field("direction", &self.direction)
            .field("terminal", &self.terminal)
            .finish_non_exhaustive()
    }
}

/// One located event: which one (index into the events slice), when, and the state there.
#[derive(Debug, Clone)]
pub struct EventHit<const D: usize> {
    /// Index of the event in the slice passed to `solve`.
    pub event: usize,
    /// Time of the crossing.
    pub t: f64,
    /// State at the crossing (from the dense output).
    pub y: Vector<D>,
}

/// Time resolution of event location: `|dt| <= EVENT_TIME_TOL (|t| + 1)`.
pub const EVENT_TIME_TOL: f64 = 1e-12;

/// The time in `[seg.t0, seg.t1()]` where `g(t, seg.eval(t))` changes sign, given
/// `g0 = g` at the start and `g1` at the end with opposite signs (`g1` may be zero).
///
/// Regula falsi with the Illinois modification (Dowell & Jarratt 1971, BIT 11, 168–174):
/// when the same end is kept twice its `g` is halved, which makes convergence superlinear.
/// A secant point outside the bracket falls back to bisection; a failed or non-finite `g`
/// is the caller's error. The
/// bracket is shrunk until its width is at most [`EVENT_TIME_TOL`]` (|t| + 1)`; the time
/// returned is past the crossing, so `g` there has the new sign (or is zero): the first of
/// the final bracket's secant point and a few points from it towards the far end that is.
pub fn locate<const D: usize>(
    g: &dyn Fn(f64, &Vector<D>) -> Result<f64>,
    seg: &Segment<D>,
    g0: f64,
    g1: f64,
) -> Result<f64> {
    locate_in(g, seg, (seg.t0, g0), (seg.t1(), g1))
}

/// [`locate`] on the bracket `[a, b]` inside `seg`.
fn locate_in<const D: usize>(
    g: &dyn Fn(f64, &Vector<D>) -> Result<f64>,
    seg: &Segment<D>,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
) -> Result<f64> {
    if gb == 0.0 {
        return Ok(b);
    }
    // -1: b moved last, +1: a moved last (for the Illinois halving); `fa`, `fb` are the
    // ends' values of `g`, `ga`, `gb` their Illinois weights.
    let mut last = 0i8;
    let (mut fa, mut fb) = (ga, gb);
    for _ in 0..200 {
        if (b - a).abs() <= EVENT_TIME_TOL * (b.abs() + 1.0) {
            break;
        }
        let mut c = (a * gb - b * ga) / (gb - ga);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let gc = g(c, &seg.eval(c))?;
        if gc == 0.0 {
            return Ok(c);
        }
        if (gc > 0.0) == (gb > 0.0) {
            (b, gb, fb) = (c, gc, gc);
            if last == -1 {
                ga *= 0.5;
            }
            last = -1;
        } else {
            (a, ga, fa) = (c, gc, gc);
            if last == 1 {
                gb *= 0.5;
            }
            last = 1;
        }
    }
    // The first point past the crossing from the final bracket's secant point (true
    // values) towards `b`: for a smooth `g` far closer to the crossing than `b` (which may
    // be a whole `EVENT_TIME_TOL` past it), at a few evaluations per event.
    let c = (a * fb - b * fa) / (fb - fa);
    if c >= a && c < b {
        for x in [c, c + (b - c) / 64.0, c + (b - c) / 8.0, c + (b - c) / 2.0] {
            let gx = g(x, &seg.eval(x))?;
            if x > a && (gx == 0.0 || (gx > 0.0) == (fb > 0.0)) {
                return Ok(x);
            }
        }
    }
    Ok(b)
}

/// Samples of `g` inside a step besides its ends: a crossing and its return within one
/// step leave `g` with one sign at both ends (an oscillator's `x - 0.99 x0`, steps of half
/// a period, was found at 2 of 10 peaks by DOPRI5 at 1e-3 and 5 of 10 by DOP853 at 1e-9).
const SAMPLES: usize = 8;

/// Golden-section iterations that look for an extremum of `g` between samples that could
/// reach zero: a local maximum of negative samples or a local minimum of positive ones,
/// stopping as soon as one reaches zero.
const PEAK_ITERATIONS: usize = 40;

/// Every crossing of `g` in `direction` on `seg`, in time order, given `g0` and `g1` at its
/// ends, each passed to `found`: `g` is sampled at [`SAMPLES`] points and a local extremum
/// between samples is searched for a value past zero, so a crossing pair inside the step is
/// found unless it lies within one sample interval of a step end, or of another extremum.
/// (No allocation: a step's samples and extrema fit on the stack.)
pub fn crossings<const D: usize>(
    g: &dyn Fn(f64, &Vector<D>) -> Result<f64>,
    seg: &Segment<D>,
    direction: Direction,
    (g0, g1): (f64, f64),
    found: &mut dyn FnMut(f64),
) -> Result<()> {
    let (t0, t1) = (seg.t0, seg.t1());
    let mut pts = [(t1, g1); 2 * SAMPLES + 2];
    pts[0] = (t0, g0);
    for (j, p) in pts.iter_mut().enumerate().take(SAMPLES).skip(1) {
        let t = t0 + (t1 - t0) * j as f64 / SAMPLES as f64;
        *p = (t, g(t, &seg.eval(t))?);
    }
    // pts[..=SAMPLES] are the samples in order (pts[SAMPLES] the end); extrema go after.
    // Each window (a, m, b) whose middle is an extremum of one sign is searched; at the
    // step's ends a probe `d` inside the step tells whether the extremum is inside.
    let mut n = SAMPLES + 1;
    let d = (t1 - t0) / SAMPLES as f64 * 1e-3;
    for j in 0..=SAMPLES {
        let window = match j {
            0 => probe(g, seg, pts[0], t0 + d, pts[1])?,
            SAMPLES => probe(g, seg, pts[SAMPLES], t1 - d, pts[SAMPLES - 1])?,
            _ => Some((pts[j - 1], pts[j], pts[j + 1])),
        };
        let Some(((a, ga), (m, gm), (b, gb))) = window else {
            continue;
        };
        // Either kind of extremum, whatever the direction: a falling crossing between
        // negative ends follows a rising one.
        let top = gm < 0.0 && gm >= ga && gm >= gb;
        let bottom = gm > 0.0 && gm <= ga && gm <= gb;
        if top || bottom {
            let sign = if top { 1.0 } else { -1.0 };
            let (a, b) = (a.min(b), a.max(b));
            if let Some(p) = peak(g, seg, (a, m, b), gm, sign)? {
                pts[n] = p;
                n += 1;
            }
        }
    }
    let pts = &mut pts[..n];
    pts.sort_by(|x, y| x.0.total_cmp(&y.0));
    for w in pts.windows(2) {
        if direction.crossed(w[0].1, w[1].1) {
            found(locate_in(g, seg, w[0], w[1])?);
        }
    }
    Ok(())
}

/// At a step's end `e` (its neighbouring sample `s`): the window `(e, x, s)` with the
/// probe `x` just inside the step when `e` is no extremum but `g` turns between `e` and
/// `s` (it moves from `e` towards `x` away from `s`'s side); `None` otherwise, without
/// evaluating `g` when `e` already lies between zero and `s`.
#[allow(clippy::type_complexity, reason = "three points (t, g)")]
fn probe<const D: usize>(
    g: &dyn Fn(f64, &Vector<D>) -> Result<f64>,
    seg: &Segment<D>,
    e: (f64, f64),
    x: f64,
    s: (f64, f64),
) -> Result<Option<((f64, f64), (f64, f64), (f64, f64))>> {
    // A turn towards zero inside: e below zero and above s, or above zero and below s.
    let towards_zero = (e.1 < 0.0 && e.1 >= s.1) || (e.1 > 0.0 && e.1 <= s.1);
    if !towards_zero {
        return Ok(None);
    }
    let gx = g(x, &seg.eval(x))?;
    Ok(((gx - e.1) * e.1 < 0.0).then_some((e, (x, gx), s)))
}

/// Golden-section search of `sign g` for its maximum on `[a, b]` around `m`, `gm = g(m)`:
/// the first point where `sign g >= 0`, or `None`.
fn peak<const D: usize>(
    g: &dyn Fn(f64, &Vector<D>) -> Result<f64>,
    seg: &Segment<D>,
    (mut a, mut m, mut b): (f64, f64, f64),
    mut gm: f64,
    sign: f64,
) -> Result<Option<(f64, f64)>> {
    const R: f64 = 0.381_966_011_250_105_1; // 2 - golden ratio
    for _ in 0..PEAK_ITERATIONS {
        // Probe the larger side of the bracket.
        let left = m - a > b - m;
        let x = if left {
            m - R * (m - a)
        } else {
            m + R * (b - m)
        };
        let gx = g(x, &seg.eval(x))?;
        if sign * gx >= 0.0 {
            return Ok(Some((x, gx)));
        }
        if sign * gx > sign * gm {
            (a, b) = if left { (a, m) } else { (m, b) };
            (m, gm) = (x, gx);
        } else if left {
            a = x;
        } else {
            b = x;
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_rules() {
        assert!(Direction::Rising.crossed(-1.0, 0.0));
        assert!(Direction::Rising.crossed(-1.0, 2.0));
        assert!(!Direction::Rising.crossed(1.0, -2.0));
        assert!(Direction::Falling.crossed(1.0, -2.0));
        assert!(!Direction::Falling.crossed(0.0, -2.0));
        assert!(Direction::Either.crossed(1.0, -2.0));
        assert!(Direction::Either.crossed(-1.0, 2.0));
        assert!(!Direction::Either.crossed(f64::NAN, 2.0));
    }

    /// y = t on [0, 2]; g = y^3 - 2 has its root at 2^(1/3).
    #[test]
    fn locates_a_cubic_root() {
        let z = Vector::<1>::zeros();
        let seg = Segment::polynomial(0.0, 2.0, &[z, Vector::<1>::new(2.0)]);
        let g = |_t: f64, y: &Vector<1>| Ok(y[0].powi(3) - 2.0);
        let t = locate(&g, &seg, -2.0, 6.0).unwrap();
        let exact = 2f64.cbrt();
        assert!((t - exact).abs() <= 1e-12 * (exact + 1.0));
        assert!(t >= exact);
    }

    /// A failing or NaN event function is an error naming the event, never a silent miss.
    #[test]
    fn failed_event_functions_are_errors() {
        let y = Vector::<1>::new(1.0);
        let nan = Event::new("nan", |_t, _y: &Vector<1>| f64::NAN, Direction::Either);
        let err = nan.value(0.5, &y).unwrap_err();
        assert_eq!(
            err,
            Error::EventFailed {
                event: "nan".into(),
                t: 0.5,
                cause: None
            }
        );
        let cause = Error::SingularMassMatrix { t: 0.25 };
        let failing = Event::fallible(
            "hit",
            |_t, _y: &Vector<1>| Err(cause.clone()),
            Direction::Rising,
        );
        let err = failing.value(0.25, &y).unwrap_err();
        assert_eq!(
            err,
            Error::EventFailed {
                event: "hit".into(),
                t: 0.25,
                cause: Some(Box::new(cause.clone()))
            }
        );
        assert!(
            err.to_string().starts_with(
                "event `hit` could not be evaluated at t = 0.25: singular mass matrix"
            ),
            "{err}"
        );
    }
}
