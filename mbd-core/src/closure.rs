//! Run-time side of minimal coordinates for closed loops: the closed form of a dependent
//! coordinate (an `asin` or `acos` the derive wrote) is only valid strictly inside its
//! domain. Outside it the loop cannot assemble; at its edge two assembly branches meet (a
//! toggle or limit position) and the closed form could not tell which one the motion
//! continues on. Either way the generated code stops with [`Error::SingularPosition`]
//! rather than pass a NaN on or switch branch silently.

use crate::error::{Error, Result};
use crate::model::{OdeSystem, Vector};

/// `Ok` when `-1 < arg < 1`; else the error naming `coord`, the time and the configuration
/// (`names[i] = q[i]`).
#[inline]
pub fn check_domain(t: f64, arg: f64, coord: &str, names: &[&str], q: &[f64]) -> Result<()> {
    if arg > -1.0 && arg < 1.0 {
        Ok(())
    } else {
        Err(singular(t, arg, coord, names, q))
    }
}

/// `Ok(x)` when every entry of `x` is finite, else [`Error::NonFinite`] at `t`: the last
/// check of a generated `mass_matrix`, `forces`, `energy` or `inverse_dynamics`, after the
/// closed forms' domain checks, so that none of them hands out a NaN.
#[inline]
pub fn finite_value<X: Entries>(t: f64, x: X) -> Result<X> {
    if x.all_finite() {
        Ok(x)
    } else {
        Err(Error::NonFinite { t })
    }
}

/// A value [`finite_value`] checks entry by entry: a real, a vector or a matrix.
pub trait Entries {
    /// Whether no entry is NaN or infinite.
    fn all_finite(&self) -> bool;
}

impl Entries for f64 {
    #[inline]
    fn all_finite(&self) -> bool {
        self.is_finite()
    }
}

impl<const R: usize, const C: usize> Entries for crate::model::Matrix<R, C> {
    #[inline]
    fn all_finite(&self) -> bool {
        self.iter().all(|v| v.is_finite())
    }
}

/// A one-coordinate acceleration `a = f / m` of minimal coordinates with every check in one
/// branch on values the body computed anyway: `m` positive and finite, `a` finite, each
/// closed-form argument `args[k]` strictly inside `(-1, 1)`. Otherwise the error, in the
/// order the separate checks gave it: the first argument outside its domain
/// (`SingularPosition` naming `coords[k]`), then the mass, then `NonFinite`.
#[inline(always)]
pub fn one_coordinate_in_domain<const K: usize>(
    t: f64,
    m: f64,
    a: f64,
    args: [f64; K],
    coords: [&str; K],
    names: &[&str],
    q: &[f64],
) -> Result<Vector<1>> {
    // `&` on the comparisons (not `&&`): one branch; NaN fails every comparison.
    let inside = args.iter().fold(true, |ok, u| ok & (u.abs() < 1.0));
    if inside & (m > 0.0) & (m < f64::INFINITY) & (a.abs() < f64::INFINITY) {
        Ok(Vector::<1>::new(a))
    } else {
        Err(one_coordinate_failure(t, m, a, &args, &coords, names, q))
    }
}

#[cold]
#[inline(never)]
fn one_coordinate_failure(
    t: f64,
    m: f64,
    a: f64,
    args: &[f64],
    coords: &[&str],
    names: &[&str],
    q: &[f64],
) -> Error {
    for (&u, coord) in args.iter().zip(coords) {
        if let Err(e) = check_domain(t, u, coord, names, q) {
            return e;
        }
    }
    match crate::solve::one_coordinate(t, m, a) {
        Err(e) => e,
        Ok(_) => Error::NonFinite { t },
    }
}

#[cold]
fn singular(t: f64, arg: f64, coord: &str, names: &[&str], q: &[f64]) -> Error {
    let config: Vec<String> = names
        .iter()
        .zip(q)
        .map(|(n, v)| format!("{n} = {v}"))
        .collect();
    Error::SingularPosition {
        t,
        detail: format!(
            "the closed form of `{coord}` needs an asin/acos argument strictly inside (-1, 1), got {arg} at {}: the loop cannot assemble there or is at a toggle (limit) position",
            config.join(", ")
        ),
    }
}

/// Watches a fixed-step run for a limit position its stages stepped over.
///
/// Near a limit position the closed forms' margin `m` (see
/// [`crate::Mechanism::chart_margin`]) goes like `lim - th ~ (t - t*)^2`: the minimal
/// equations stay smooth there, so a step whose stages happen to stay inside the domain
/// comes back on the same branch (the reflection the physical loop does not make: it
/// passes into the other branch). A physical turning point keeps `m` bounded away from
/// zero. So after each accepted step: the quadratic `m* + c (t - t*)^2` through the last
/// three margins has its minimum inside the window (of length `w`) with `m* <= c w^2`: the
/// minimum is not resolvably positive (a step's own error in `m` near a limit is of the
/// order of `c h^2`: RK4 at `h = 1e-3` reflected the four-bar of the tests at
/// `m* = 5e-6` with `c h^2 = 4.6e-6`), so the step passed the chart's boundary. A physical
/// turn with minimum `M > 0` passes the test once `c w^2 < M`.
#[derive(Debug, Clone)]
pub struct ChartWatch<const D: usize> {
    /// The last accepted `(t, margin, y)`, oldest first; `None` once the system has no chart.
    window: Option<Vec<(f64, f64, Vector<D>)>>,
}

impl<const D: usize> Default for ChartWatch<D> {
    fn default() -> Self {
        ChartWatch {
            window: Some(Vec::with_capacity(3)),
        }
    }
}

impl<const D: usize> ChartWatch<D> {
    /// Records the accepted `(t, y)`; `Some((t*, y_b))` when the window shows the boundary
    /// passed at `t*`, with `y_b` the first state just outside the chart (see
    /// [`Self::boundary`]). `margin(y)` is called once per step, and never again once it
    /// has returned `None` (a model without closed-form closures).
    pub fn accept(
        &mut self,
        t: f64,
        y: &Vector<D>,
        margin: impl Fn(&Vector<D>) -> Option<f64>,
    ) -> Option<(f64, Vector<D>)> {
        let window = self.window.as_mut()?;
        let Some(m) = margin(y) else {
            self.window = None;
            return None;
        };
        if window.len() == 3 {
            window.remove(0);
        }
        window.push((t, m, *y));
        self.passed(t, &margin)
    }

    /// Whether the last three accepted margins' quadratic reaches the boundary before
    /// `t_end` (for a step that failed on its way there: Newton does not converge on the
    /// steps next to a limit, where the minimal equations' inertia grows without bound);
    /// as [`Self::accept`].
    pub fn passed(
        &self,
        t_end: f64,
        margin: &impl Fn(&Vector<D>) -> Option<f64>,
    ) -> Option<(f64, Vector<D>)> {
        let w = self.window.as_ref().filter(|w| w.len() == 3)?;
        let [(t0, m0, _), (t1, m1, _), (t2, m2, _)] = [w[0], w[1], w[2]];
        let (d01, d12) = ((m1 - m0) / (t1 - t0), (m2 - m1) / (t2 - t1));
        let curv = (d12 - d01) / (t2 - t0);
        if curv.is_nan() || curv <= 0.0 {
            return None;
        }
        let ts = 0.5 * (t0 + t1) - d01 / (2.0 * curv);
        if !(ts >= t0 && ts <= t_end) {
            return None;
        }
        let ms = m0 + d01 * (ts - t0) + curv * (ts - t0) * (ts - t1);
        if ms.is_nan() || ms > curv * (t2 - t0) * (t2 - t0) {
            return None;
        }
        // The state at t* (the quadratic through the three), then out along the path.
        let l = |ta: f64, tb: f64, tc: f64| (ts - tb) * (ts - tc) / ((ta - tb) * (ta - tc));
        let ys = w[0].2 * l(t0, t1, t2) + w[1].2 * l(t1, t0, t2) + w[2].2 * l(t2, t0, t1);
        let far = if m0 >= m2 { &w[0] } else { &w[2] };
        Some((ts, Self::boundary(&ys, &far.2, margin)))
    }

    /// The oldest accepted `(t, y)` in the window.
    pub fn oldest(&self) -> Option<(f64, Vector<D>)> {
        self.window.as_ref()?.first().map(|&(t, _, y)| (t, y))
    }

    /// The last accepted `(t, y)` when its margin is at most `within`: a run that fails
    /// there (its steps shrinking to nothing) is at the chart's edge, where the closed
    /// forms' rates are rounding (`sqrt` of the margin).
    pub fn at_edge(&self, within: f64) -> Option<(f64, Vector<D>)> {
        let (t, m, y) = *self.window.as_ref()?.last()?;
        (m <= within).then_some((t, y))
    }

    /// The first state outside the chart on the line from `far` through `ys` (the margin
    /// is close to linear in the coordinates there): found by doubling then bisection,
    /// keeping the outside end, so the configuration named is at or just past the limit.
    fn boundary(
        ys: &Vector<D>,
        far: &Vector<D>,
        margin: &impl Fn(&Vector<D>) -> Option<f64>,
    ) -> Vector<D> {
        let dir = ys - far;
        let at = |s: f64| ys + dir * s;
        let m = |s: f64| margin(&at(s)).unwrap_or(f64::NAN);
        let (mut inside, mut outside) = (0.0, 1e-3);
        if m(0.0).is_nan() || m(0.0) <= 0.0 {
            return *ys;
        }
        for _ in 0..60 {
            if m(outside).is_nan() || m(outside) <= 0.0 {
                break;
            }
            (inside, outside) = (outside, 2.0 * outside);
        }
        for _ in 0..60 {
            let mid = 0.5 * (inside + outside);
            if m(mid) > 0.0 {
                inside = mid
            } else {
                outside = mid
            }
        }
        at(outside)
    }
}

/// The error for a limit position passed at `t` by a step that could not resolve it: the
/// model's own (the closure check at `y`, outside the chart), else one naming `y`.
#[cold]
pub fn passed_limit<const D: usize>(t: f64, y: &Vector<D>, model: Option<Error>) -> Error {
    match model {
        Some(e @ Error::SingularPosition { .. }) => e,
        _ => Error::SingularPosition {
            t,
            detail: format!(
                "a step passed a limit position of the loop's closed forms it could not \
                 resolve, at y = {:?}: the motion continues on another assembly branch",
                y.as_slice()
            ),
        },
    }
}

/// A chart margin this small is the chart's edge to rounding (`sqrt(eps)`).
const EDGE: f64 = 1.5e-8;

/// `cause` (an adaptive run's failure to step on: too many steps, a step size underflow),
/// or the limit position of a loop's closed forms the last accepted steps were closing on,
/// or stalled at (margin below [`EDGE`]). At a change point (a parallelogram folding flat)
/// the closed form's argument touches its domain's edge and comes back, so no stage lands
/// outside it: adaptive steps passed it and went on, `Ok`, on the other assembly branch (the
/// crossed linkage), or stalled there (DOP853, Vern9) until `TooManySteps`. Both now stop
/// with [`Error::SingularPosition`], as the fixed-step methods do.
#[cold]
pub fn stalled<F: OdeSystem<D>, const D: usize>(
    sys: &F,
    chart: &ChartWatch<D>,
    cause: Error,
) -> Error {
    let t = match cause {
        Error::TooManySteps { t, .. } | Error::StepSizeUnderflow { t, .. } => t,
        _ => return cause,
    };
    let passed = chart.passed(f64::INFINITY, &|y: &Vector<D>| sys.chart_margin(t, y));
    match passed.or_else(|| chart.at_edge(EDGE)) {
        Some((ts, yb)) => passed_limit(ts, &yb, sys.rhs(ts, &yb).err()),
        None => cause,
    }
}

/// For an adaptive run whose window ([`ChartWatch::accept`]) shows a limit position passed
/// by `t_end`: the error when the window's span, stepped again by RK4 in 256 steps under the
/// same watch, stops there too; `None` for a near miss the adaptive steps were too long to
/// tell (a nearly parallelogram linkage turning past its flat positions at `tol = 1e-3`
/// was stopped: margin 0.03, steps of 0.3 rad).
#[cold]
pub fn confirmed<F: OdeSystem<D>, const D: usize>(
    sys: &F,
    chart: &ChartWatch<D>,
    t_end: f64,
) -> Option<Error> {
    use crate::integrate::{Integrator, Rk4};
    let (t0, y0) = chart.oldest()?;
    match Rk4::new((t_end - t0) / 256.0).solve(sys, t0, y0, t_end, &[]) {
        Err(e @ Error::SingularPosition { .. }) => Some(e),
        _ => None,
    }
}

/// After an adaptive run's accepted step to `(t, y)`: the step joins the watch's window
/// ([`ChartWatch::accept`]), and a limit position it shows passed is an error where it is
/// [`confirmed`].
#[inline]
pub(crate) fn watch_step<F: OdeSystem<D>, const D: usize>(
    sys: &F,
    chart: &mut ChartWatch<D>,
    t: f64,
    y: &Vector<D>,
) -> Result<()> {
    if chart.accept(t, y, |y| sys.chart_margin(t, y)).is_some()
        && let Some(e) = confirmed(sys, chart, t)
    {
        return Err(e);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_passes_and_the_edge_and_outside_fail() {
        assert!(check_domain(0.0, 0.5, "x", &["q"], &[1.0]).is_ok());
        for bad in [1.0, -1.0, 1.5, f64::NAN, f64::INFINITY] {
            match check_domain(2.5, bad, "beta", &["theta"], &[0.25]) {
                Err(Error::SingularPosition { t, detail }) => {
                    assert_eq!(t, 2.5);
                    assert!(detail.contains("`beta`") && detail.contains("theta = 0.25"));
                }
                other => panic!("{bad}: {other:?}"),
            }
        }
    }

    /// The folded check gives what the separate ones gave, in their order: the first
    /// argument outside its domain, then the mass, then a non-finite acceleration.
    #[test]
    fn folded_one_coordinate_check_keeps_the_order_of_the_errors() {
        let run = |m: f64, a: f64, args: [f64; 2]| {
            one_coordinate_in_domain(1.5, m, a, args, ["beta", "x"], &["theta"], &[0.3])
        };
        assert_eq!(run(2.0, -3.0, [0.5, -0.9]).unwrap()[0], -3.0);
        let singular_at = |r: Result<Vector<1>>| match r {
            Err(Error::SingularPosition { t, detail }) => {
                assert_eq!(t, 1.5);
                assert!(detail.contains("theta = 0.3"));
                ["`beta`", "`x`"].into_iter().find(|c| detail.contains(c))
            }
            other => panic!("{other:?}"),
        };
        // Outside the domain wins over a bad mass or a NaN acceleration.
        assert_eq!(singular_at(run(-1.0, f64::NAN, [0.5, 1.0])), Some("`x`"));
        assert_eq!(singular_at(run(2.0, 1.0, [f64::NAN, -1.0])), Some("`beta`"));
        // Inside it, the one-coordinate solve's own errors (a bad mass before a bad `a`).
        for (m, a) in [
            (0.0, 1.0),
            (-1.0, f64::NAN),
            (f64::INFINITY, 1.0),
            (f64::NAN, 1.0),
        ] {
            let separate = crate::solve::one_coordinate(1.5, m, a);
            assert!(separate.is_err());
            assert_eq!(
                format!("{:?}", run(m, a, [0.0, 0.0])),
                format!("{separate:?}")
            );
        }
        for a in [f64::NAN, f64::INFINITY] {
            assert!(matches!(run(1.0, a, [0.0, 0.0]), Err(Error::NonFinite { t }) if t == 1.5));
        }
    }

    /// A path that touches the chart's edge and reflects (`m = (t - 1)^2`, `y = 1 + m`
    /// with the margin `y - 1`) is caught at `t = 1` with the state at the edge; a turn
    /// whose margin stays at `0.5` is not, at the same steps.
    #[test]
    fn a_reflection_at_the_edge_is_caught_and_a_turn_inside_is_not() {
        let margin = |y: &Vector<1>| Some(y[0] - 1.0);
        for (floor, caught) in [(0.0, true), (0.5, false)] {
            let mut watch = ChartWatch::<1>::default();
            let mut found = None;
            for k in 0..20 {
                let t = 0.7 + 0.05 * k as f64;
                let y = Vector::<1>::new(1.0 + floor + (t - 1.0) * (t - 1.0));
                found = found.or(watch.accept(t, &y, margin));
            }
            match found {
                Some((ts, yb)) => {
                    assert!(caught && (ts - 1.0).abs() < 1e-12, "{ts}");
                    assert!(yb[0] <= 1.0 && yb[0] > 1.0 - 1e-12, "{yb}");
                }
                None => assert!(!caught),
            }
        }
        // No chart: the margin is asked once.
        let asked = std::cell::Cell::new(0);
        let mut watch = ChartWatch::<1>::default();
        for k in 0..5 {
            let none = |_: &Vector<1>| {
                asked.set(asked.get() + 1);
                None
            };
            assert!(
                watch
                    .accept(k as f64, &Vector::<1>::zeros(), none)
                    .is_none()
            );
        }
        assert_eq!(asked.get(), 1);
    }
}
