//! The one step loop of the explicit embedded Runge–Kutta pairs (DOPRI5, DOP853, Vern9).
//!
//! A pair is a [`Pair`]: its tableau and the few things that differ between pairs (error
//! measure, controller, stiffness limit, continuous extension). [`solve`] is generic over
//! it and monomorphised per pair, so the step loop has no runtime dispatch and each pair
//! runs exactly the operations its own loop ran.

use super::control::{PiController, StiffnessDetector, as_time_takes, error_norm_sq};
use super::non_finite;
use super::tableau::Erk;
use super::{Event, Flow, Observer, Options, Recorder, Segment, Solution, Stats, validate_problem};
use crate::closure::{ChartWatch, stalled, watch_step};
use crate::error::{Error, Result};
use crate::model::{OdeSystem, Vector};

/// An explicit embedded pair of `S` stages run by [`solve`], with `K >= S` stage slots:
/// `k[0..S]` the step's stages, then (for a pair that is not FSAL) `k[S] = f(t + h, y1)`,
/// then the extra stages of the continuous extension.
pub(crate) trait Pair<const S: usize, const K: usize> {
    /// Stages, weights, error weights `e`, and whether the last stage is `f(t + h, y1)`.
    const TABLEAU: &'static Erk<S>;
    /// Order for Hairer's initial step guess ([`initial_step`]).
    const ORDER: i32;
    /// `h |lambda|` above which a step counts as stiff ([`StiffnessDetector`]).
    const STIFF_LIMIT: f64;
    /// The stiffness estimate compares `f(t + h, y1)` with the last stage (DOP853), not
    /// the last two stages (both at `t + h`: DOPRI5, whose last is `f(t + h, y1)`, Vern9).
    const STIFF_FROM_END: bool = false;
    /// `rhs` calls made by [`Self::segment`].
    const DENSE_CALLS: usize = 0;
    /// [`Self::error`] is the square of the error (its `ln` is halved), not the error.
    const ERROR_SQUARED: bool = true;
    /// Whether a step may end on an output time instead of interpolating there
    /// ([`lands_on`]), where only output times need the continuous extension. Off for the
    /// pairs whose extension is cheap, and for those checked count for count (whose step
    /// sequence does not depend on what is recorded).
    const LANDS_ON_TIMES: bool = false;

    /// The step-size controller, fresh.
    fn controller() -> PiController;

    /// Whether the step `h` at `t` is too small to advance `t` (then
    /// [`Error::StepSizeUnderflow`]).
    fn underflow(h: f64, t: f64) -> bool;

    /// The error measure of a step from `y` to `y1` (accepted when `<= 1`): by default the
    /// square of the scaled RMS norm of `h sum_i e_i k_i` ([`error_norm_sq`]).
    #[inline]
    fn error<const D: usize>(
        k: &[Vector<D>; S],
        y: &Vector<D>,
        y1: &Vector<D>,
        h: f64,
        rtol: f64,
        atol: f64,
    ) -> f64 {
        error_norm_sq(
            &Erk::combine(&Self::TABLEAU.e, k, 1.0),
            h,
            y,
            y1,
            rtol,
            atol,
        )
    }

    /// The continuous extension of an accepted step from `(t, y)` to `y1` of size `h`,
    /// making [`Self::DENSE_CALLS`] more `rhs` calls into `k`'s extra slots.
    fn segment<F: OdeSystem<D>, const D: usize>(
        sys: &F,
        t: f64,
        h: f64,
        y: &Vector<D>,
        y1: &Vector<D>,
        k: &mut [Vector<D>; K],
    ) -> Result<Segment<D>>;

    /// The continuous extension as [`Self::segment`] makes it, handed to `take` as
    /// `t -> y(t)` for a record that needs only its values at output times. By default
    /// the segment's; a pair may evaluate its weights at each time instead of forming the
    /// polynomial's coefficients.
    #[inline]
    fn values<F: OdeSystem<D>, const D: usize>(
        (sys, t, h, y, y1): (&F, f64, f64, &Vector<D>, &Vector<D>),
        k: &mut [Vector<D>; K],
        take: impl FnOnce(&mut dyn FnMut(f64) -> Vector<D>) -> Flow,
    ) -> Result<Flow> {
        let seg = Self::segment(sys, t, h, y, y1, k)?;
        Ok(take(&mut |ts| seg.eval(ts)))
    }
}

/// Whether a step of `h` from `t` that would hold the next output time `ts` (the one
/// after it at `after`) should end on `ts` instead, for a pair whose accepted step costs
/// `step` calls and whose continuous extension `dense` more. Two conditions:
///
/// - the step: ending at `theta = (ts - t) / h` gives up `step (1 - theta)` calls of
///   progress, fewer than the extension's `dense` from `theta >= 1 - dense / step` (Vern9:
///   7/16);
/// - the run: steps that all end on output times `delta = after - ts` apart cost `step /
///   delta` per unit time, steps of `h` that all interpolate `(step + dense) / h`; so
///   `h <= delta (step + dense) / step` (Vern9: `25/16 delta`). Without it, longer steps
///   would be cut down to the spacing (the pendulum at 3.2e-6 with an output time every
///   0.1 s: 1618 calls, against 1084 interpolating).
///
/// Both together imply that `ts` is the only output time in the step.
#[inline]
fn lands_on(t: f64, h: f64, (ts, after): (f64, f64), step: usize, dense: usize) -> bool {
    let (s, d) = (step as f64, dense as f64);
    let theta = (ts - t) / h;
    theta < 1.0 && theta * s >= s - d && h * s <= (after - ts) * (s + d)
}

/// Hairer's initial step guess `HINIT` (Hairer–Nørsett–Wanner I, Sect. II.4, p. 169;
/// `dopri5.f`), for a method of order `order`, with `sk = atol + rtol |y0_i|`:
///
/// 1. `d0 = ||y0 / sk||`, `d1 = ||f0 / sk||` (2-norms); `h = 0.01 d0 / d1`, or `1e-6` when
///    either is below `1e-5`; `h = min(h, h_max)`.
/// 2. One explicit Euler step gives `f1 = f(t0 + h, y0 + h f0)` and `d2 = ||(f1 - f0) / sk|| / h`.
/// 3. `h1 = (0.01 / max(d1, d2))^(1/order)`, or `max(1e-6, 1e-3 h)` when that max is below
///    `1e-15`; the guess is `min(100 h, h1, h_max)`, raised to `1024 eps |t0|` (a state
///    that is nearly zero against `atol`, such as a position left at 1e-13 by a stop, would
///    otherwise give a guess below the `16 eps |t|` at which the methods stop with
///    `StepSizeUnderflow`; the step control takes it from there).
///
/// Makes one `rhs` call.
#[allow(
    clippy::too_many_arguments,
    reason = "the arguments of HINIT, all needed"
)]
pub fn initial_step<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    t0: f64,
    y0: &Vector<D>,
    f0: &Vector<D>,
    order: i32,
    h_max: f64,
    rtol: f64,
    atol: f64,
) -> Result<f64> {
    let (mut dnf, mut dny) = (0.0, 0.0);
    for i in 0..D {
        let sk = atol + rtol * y0[i].abs();
        dnf += (f0[i] / sk).powi(2);
        dny += (y0[i] / sk).powi(2);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(h_max);
    let y1 = y0 + f0 * h;
    let f1 = sys.rhs(t0 + h, &y1)?;
    if non_finite(&f1) {
        return Err(Error::NonFinite { t: t0 + h });
    }
    let mut der2 = 0.0;
    for i in 0..D {
        let sk = atol + rtol * y0[i].abs();
        der2 += ((f1[i] - f0[i]) / sk).powi(2);
    }
    let der2 = der2.sqrt() / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / order as f64)
    };
    let floor = (1024.0 * f64::EPSILON * t0.abs()).min(h_max);
    Ok((100.0 * h).min(h1).min(h_max).max(floor))
}

/// The first stage `f(t0, y0)` of an explicit pair of order `order`, and its first step:
/// `Options::h0` where given, else [`initial_step`]. Counts its `rhs` calls in `stats`.
fn first_stage<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    t0: f64,
    y0: &Vector<D>,
    order: i32,
    opts: &Options,
    h_max: f64,
    stats: &mut Stats,
) -> Result<(Vector<D>, f64)> {
    let f0 = sys.rhs(t0, y0)?;
    stats.n_rhs += 1;
    if non_finite(&f0) {
        return Err(Error::NonFinite { t: t0 });
    }
    let h = match opts.h0 {
        Some(h0) => h0.min(h_max),
        None => {
            stats.n_rhs += 1;
            initial_step(sys, t0, y0, &f0, order, h_max, opts.rtol, opts.atol)?
        }
    };
    Ok((f0, h))
}

/// `f(t, y)`, or [`Error::NonFinite`] at `t_err` when it is not finite.
#[inline]
fn rhs_finite<F: OdeSystem<D>, const D: usize>(
    sys: &F,
    t: f64,
    y: &Vector<D>,
    t_err: f64,
) -> Result<Vector<D>> {
    let f = sys.rhs(t, y)?;
    if non_finite(&f) {
        return Err(Error::NonFinite { t: t_err });
    }
    Ok(f)
}

/// The extra stages of a continuous extension: `k[first + j] = f(t + c_j h, y + h sum_i
/// a_ji k_i)` over `i < first + j`, for each row `a_j` (Hairer–Nørsett–Wanner I,
/// Sect. II.6). Makes `R` calls of `rhs`.
#[inline]
pub(crate) fn extra_stages<
    F: OdeSystem<D>,
    const D: usize,
    const K: usize,
    const R: usize,
    const L: usize,
>(
    (sys, t, h, y): (&F, f64, f64, &Vector<D>),
    k: &mut [Vector<D>; K],
    first: usize,
    a: &[[f64; L]; R],
    c: &[f64; R],
) -> Result<()> {
    for (j, (a, c)) in a.iter().zip(c).enumerate() {
        let s = first + j;
        let mut acc = Vector::<D>::zeros();
        for (aj, kj) in a[..s].iter().zip(k.iter()) {
            if *aj != 0.0 {
                acc += kj * *aj;
            }
        }
        let ts = t + c * h;
        k[s] = rhs_finite(sys, ts, &(y + acc * h), ts)?;
    }
    Ok(())
}

/// The length of the step from `t` proposed as `h`, with whether it lands on an output
/// time (`(that time, h)`, for the controller) and whether it is the last: cut to end on
/// `t1`, on the next output time where [`lands_on`] says so, else [`as_time_takes`].
#[inline]
fn step_to<M: Pair<S, K>, const S: usize, const K: usize>(
    t: f64,
    h: f64,
    t1: f64,
    next_time: impl FnOnce() -> Option<(f64, f64)>,
    rtol: f64,
) -> (f64, Option<(f64, f64)>, bool) {
    if t + 1.01 * h - t1 > 0.0 {
        return (t1 - t, None, true);
    }
    let calls = S - usize::from(M::TABLEAU.fsal);
    if let Some((ts, _)) =
        next_time().filter(|&next| M::LANDS_ON_TIMES && lands_on(t, h, next, calls, M::DENSE_CALLS))
    {
        return (ts - t, Some((ts, h)), false);
    }
    (as_time_takes(t, h, rtol), None, false)
}

/// The accepted state `y1` projected at `t_new`, with its derivative: `f1` where the
/// projection left it unmoved, else `f` evaluated again.
#[inline]
fn projected<F: OdeSystem<D>, const D: usize>(
    sys: &F,
    t_new: f64,
    y1: Vector<D>,
    f1: Vector<D>,
    stats: &mut Stats,
) -> Result<(Vector<D>, Vector<D>)> {
    let mut y = y1;
    sys.project(t_new, &mut y)?;
    if non_finite(&y) {
        return Err(Error::NonFinite { t: t_new });
    }
    if y == y1 {
        return Ok((y1, f1));
    }
    stats.n_rhs += 1;
    Ok((y, rhs_finite(sys, t_new, &y, t_new)?))
}

/// Record the step of `h` from `(t, y)` to `y1`, accepted as `(t_new, y_acc)`. Its
/// continuous extension (which interpolates the step as computed, before any projection)
/// is built only where the record needs it, and only its values where output times alone do.
#[inline]
fn record<M, F, const D: usize, const S: usize, const K: usize>(
    rec: &mut Recorder<'_, '_, D>,
    stats: &mut Stats,
    sys: &F,
    (t, h, y, y1): (f64, f64, &Vector<D>, &Vector<D>),
    (t_new, y_acc): (f64, &Vector<D>),
    k: &mut [Vector<D>; K],
) -> Result<Flow>
where
    M: Pair<S, K>,
    F: OdeSystem<D>,
{
    if !rec.needs_segment_to(t_new) {
        return Ok(rec.accept_point(t_new, y_acc));
    }
    stats.n_rhs += M::DENSE_CALLS;
    if rec.next_times_only().is_some() {
        return M::values((sys, t, h, y, y1), k, |value| {
            rec.accept_values(t_new, y_acc, value)
        });
    }
    let seg = M::segment(sys, t, h, y, y1, k)?;
    Ok(rec.accept_with(t_new, y_acc, || seg))
}

/// One raw run of the pair `M` (as `dopri5.f` and `dop853.f` run theirs; Hairer–Nørsett–
/// Wanner I, Sect. II.4-II.6): FSAL or `f(t + h, y1)` after acceptance as the next step's
/// first stage, local extrapolation, `M`'s error measure and [`PiController`], Hairer's
/// initial step, stiffness detection every [`Options::stiffness_check`] accepted steps,
/// projection after each accepted step (`f` evaluated again where it moved the state), and
/// the continuous extension built only when the [`Recorder`] needs the step's segment
/// (dense output, events, an output time inside the step). Stage storage is fixed arrays:
/// a step allocates nothing.
#[inline]
pub(crate) fn solve<M, F, const D: usize, const S: usize, const K: usize>(
    opts: &Options,
    sys: &F,
    (t0, y0, t1): (f64, Vector<D>, f64),
    events: &[Event<'_, D>],
    observer: Option<&mut Observer<'_, D>>,
) -> Result<Solution<D>>
where
    M: Pair<S, K>,
    F: OdeSystem<D>,
{
    const { assert!(S >= 2 && K >= S) };
    opts.validate()?;
    validate_problem(t0, &y0, t1)?;
    let mut rec = Recorder::new(events, t0, y0, opts).observed(observer);
    let mut stats = Stats::default();
    if t1 == t0 {
        return rec.finish(stats);
    }
    let (rtol, atol) = (opts.rtol, opts.atol);
    let h_max = opts.h_max.unwrap_or(t1 - t0);
    let tab = M::TABLEAU;

    let mut k = [Vector::<D>::zeros(); K];
    let mut z = [Vector::<D>::zeros(); S];
    let mut h;
    (k[0], h) = first_stage(sys, t0, &y0, M::ORDER, opts, h_max, &mut stats)?;

    let mut control = M::controller();
    let (mut t, mut y) = (t0, y0);
    let mut stiff = StiffnessDetector::new(opts.stiffness_check, M::STIFF_LIMIT);
    // A change point of a loop's closed forms stepped over or stalled at (`closure::stalled`).
    let mut chart = ChartWatch::<D>::default();
    // The end of the last trial step that met a non-finite value, while its cuts last.
    let mut blown: Option<f64> = None;
    loop {
        if stats.n_steps >= opts.max_steps {
            let e = Error::TooManySteps {
                t,
                steps: stats.n_steps,
            };
            return Err(stalled(sys, &chart, e));
        }
        let cut_out = blown.is_some() && h <= f64::EPSILON * (t1 - t0);
        if M::underflow(h, t) || h.is_nan() || cut_out {
            return Err(match blown {
                Some(t_bad) => Error::NonFinite { t: t_bad },
                None => stalled(sys, &chart, Error::StepSizeUnderflow { t, h }),
            });
        }
        let (step, land, last) = step_to::<M, S, K>(t, h, t1, || rec.next_times_only(), rtol);
        h = step;
        stats.n_steps += 1;
        let stages: &mut [Vector<D>; S] = (&mut k[..S]).try_into().expect("S <= K");
        let trial = tab.stages(sys, t, &y, h, stages, &mut z);
        stats.n_rhs += S - 1;
        let t_new = match land {
            _ if last => t1,
            Some((ts, _)) => ts,
            None => t + h,
        };
        let (y1, err) = match trial {
            Ok(()) => {
                let y1 = if tab.fsal {
                    z[S - 1]
                } else {
                    tab.advance(&y, stages, h)
                };
                (y1, M::error(stages, &y, &y1, h, rtol, atol))
            }
            Err(Error::NonFinite { .. }) => (y, f64::INFINITY),
            Err(e) => return Err(e),
        };
        // A trial step too long for a fast or stiff mode can overflow before its error is
        // estimated: it is rejected with the largest cut, as Radau5 does; a non-finite value
        // that persists until the step underflows is the model's (`NonFinite` there).
        if !err.is_finite() || non_finite(&y1) {
            blown = Some(t_new);
            h *= control.reject_ln(1.0, f64::INFINITY);
            stats.n_rejected += 1;
            continue;
        }
        blown = None;
        // ln err, taken where it is needed: after f(t + h, y1) on acceptance, so the
        // call does not wait for it.
        let ln_err = || {
            if M::ERROR_SQUARED {
                0.5 * err.ln()
            } else {
                err.ln()
            }
        };
        if err > 1.0 {
            h = control.reject_ln(h, ln_err());
            stats.n_rejected += 1;
            continue;
        }
        stats.n_accepted += 1;
        // h |lambda| ~ h ||f(ya) - f(yb)|| / ||ya - yb|| for two arguments at t + h.
        let test = stiff.due(stats.n_accepted);
        if test
            && !M::STIFF_FROM_END
            && stiff.stiff_after(h, &k[S - 1], &k[S - 2], &z[S - 1], &z[S - 2])
        {
            return Err(Error::Stiff { t });
        }
        // f(t + h, y1) before the controller: the call overlaps its `ln` and `exp`.
        if !tab.fsal {
            stats.n_rhs += 1;
            k[S] = rhs_finite(sys, t + h, &y1, t_new)?;
        }
        let f1 = k[if tab.fsal { S - 1 } else { S }];
        // After a step cut short onto an output time, the step it replaced stands unless
        // the short step's error lets it grow; that error is not remembered: as the last
        // error, its small one would shrink the steps after it. (Measured on the 8-link
        // chain, the pendulum and the oscillator: the short step's proposal alone took
        // 194 steps where this takes 129 (pendulum, 1e-10); remembering its error, 41
        // where this takes 33 (oscillator, 1e-9, an output time every 0.5).)
        let h_new = match land {
            Some((_, planned)) => control.accept_short_ln(h, ln_err()).max(planned),
            None => control.accept_ln(h, ln_err()),
        }
        .min(h_max);
        if test && M::STIFF_FROM_END && stiff.stiff_after(h, &f1, &k[S - 1], &y1, &z[S - 1]) {
            return Err(Error::Stiff { t });
        }

        let (y_acc, f_acc) = if opts.project {
            projected(sys, t_new, y1, f1, &mut stats)?
        } else {
            (y1, f1)
        };
        watch_step(sys, &mut chart, t_new, &y_acc)?;
        let taken = (t, h, &y, &y1);
        let flow =
            record::<M, F, D, S, K>(&mut rec, &mut stats, sys, taken, (t_new, &y_acc), &mut k)?;
        k[0] = f_acc;
        (t, y) = (t_new, y_acc);
        if flow == Flow::Stop || last {
            break;
        }
        h = h_new;
    }
    rec.finish(stats)
}
