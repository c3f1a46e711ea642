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
/// bracket is shrunk until its width is at most [`EVENT_TIME_TOL`]` (|t| + 1)`; the end
/// returned is the one past the crossing, so `g` there has the new sign (or is zero).
pub fn locate<const D: usize>(
    g: &dyn Fn(f64, &Vector<D>) -> Result<f64>,
    seg: &Segment<D>,
    g0: f64,
    g1: f64,
) -> Result<f64> {
    let (mut a, mut ga) = (seg.t0, g0);
    let (mut b, mut gb) = (seg.t1(), g1);
    if gb == 0.0 {
        return Ok(b);
    }
    // -1: b moved last, +1: a moved last (for the Illinois halving).
    let mut last = 0i8;
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
            b = c;
            gb = gc;
            if last == -1 {
                ga *= 0.5;
            }
            last = -1;
        } else {
            a = c;
            ga = gc;
            if last == 1 {
                gb *= 0.5;
            }
            last = 1;
        }
    }
    Ok(b)
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
