//! Dormand–Prince 5(4) with Hairer's step control, dense output and stiffness detection.

use super::control::{PiController, StiffnessDetector, error_norm_sq};
use super::non_finite;
use super::tableau::{DOPRI5, DOPRI5_DENSE, Erk};
use super::{
    Event, Flow, Integrator, Observer, Options, Recorder, Segment, Solution, Stats,
    validate_problem,
};
use crate::error::{Error, Result};
use crate::model::{OdeSystem, Vector};

/// The explicit Dormand–Prince 5(4) pair run as Hairer's `dopri5.f` runs it (Hairer–Nørsett–
/// Wanner I, Sect. II.5 and II.6): FSAL, local extrapolation, the scaled RMS
/// [`error_norm`](super::control::error_norm) (taken squared, [`error_norm_sq`]), the
/// [`PiController`], Hairer's initial step guess ([`initial_step`]), Shampine's
/// fourth-order dense output, and stiffness detection every [`Options::stiffness_check`]
/// accepted steps ([`StiffnessDetector`]).
///
/// Counters: `n_rhs` is every call of `rhs` (one at `t0`, one more for the initial step
/// guess when `h0` is `None`, six per attempted step, and one more after a projection that
/// moved the state); `n_steps = n_accepted + n_rejected` (unlike `dopri5.f`, rejections
/// before the first accepted step are counted too).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Dopri5 {
    /// Tolerances and step settings.
    pub opts: Options,
}

impl Dopri5 {
    /// Hairer's default number of accepted steps between stiffness tests (`NSTIFF`), the
    /// default of [`Options::stiffness_check`].
    pub const NSTIFF: usize = 1000;
    /// `h |lambda|` above which a step counts as stiff: the boundary of DOPRI5's stability
    /// region on the negative real axis is near `-3.3` (`dopri5.f` uses 3.25).
    pub const STIFF_HLAMBDA: f64 = 3.25;
    /// Consecutive stiff tests that stop the integration with [`Error::Stiff`].
    pub const STIFF_COUNT: usize = StiffnessDetector::STIFF_COUNT;
    /// Consecutive non-stiff tests that clear the count.
    pub const NONSTIFF_COUNT: usize = StiffnessDetector::NONSTIFF_COUNT;

    /// DOPRI5 with the given options.
    pub fn new(opts: Options) -> Self {
        Dopri5 { opts }
    }
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
pub(super) fn first_stage<S: OdeSystem<D>, const D: usize>(
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

/// Hairer's continuous extension of a DOPRI5 step (`dopri5.f` `CONTD5`),
/// `y0 + theta (r2 + (1-theta) (r3 + theta (r4 + (1-theta) r5)))` with `r2 = y1 - y0`,
/// `r3 = h k1 - r2`, `r4 = r2 - h k7 - r3`, `r5 = h sum d_i k_i`, expanded into monomials:
/// `[y0, r2 + r3, r4 + r5 - r3, -r4 - 2 r5, r5, 0]`.
pub(crate) fn dense_segment<const D: usize>(
    t0: f64,
    h: f64,
    y0: &Vector<D>,
    y1: &Vector<D>,
    k: &[Vector<D>; 7],
) -> Segment<D> {
    let r2 = y1 - y0;
    let r3 = k[0] * h - r2;
    let r4 = r2 - k[6] * h - r3;
    let r5 = Erk::<7>::combine(&DOPRI5_DENSE, k, h);
    Segment::polynomial(t0, h, &[*y0, r2 + r3, r4 + r5 - r3, -(r4 + r5 * 2.0), r5])
}

impl Integrator for Dopri5 {
    fn passages(&self) -> Option<crate::passage::Settings> {
        crate::passage::Settings::of(&self.opts)
    }

    fn name(&self) -> &'static str {
        "DOPRI5"
    }

    fn with_first_step(&self, h: f64) -> Option<Self> {
        let mut opts = self.opts.clone();
        opts.h0 = Some(h);
        Some(Dopri5 { opts })
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
        let opts = &self.opts;
        opts.validate()?;
        validate_problem(t0, &y0, t1)?;
        let mut rec = Recorder::new(events, t0, y0, opts).observed(observer);
        let mut stats = Stats::default();
        if t1 == t0 {
            return rec.finish(stats);
        }
        let (rtol, atol) = (opts.rtol, opts.atol);
        let h_max = opts.h_max.unwrap_or(t1 - t0);

        let mut k = [Vector::<D>::zeros(); 7];
        let mut z = [Vector::<D>::zeros(); 7];
        let mut h;
        (k[0], h) = first_stage(sys, t0, &y0, 5, opts, h_max, &mut stats)?;

        let mut control = PiController::new();
        let (mut t, mut y) = (t0, y0);
        let mut last = false;
        let mut stiff = StiffnessDetector::new(opts.stiffness_check, Self::STIFF_HLAMBDA);
        loop {
            if stats.n_steps >= opts.max_steps {
                return Err(Error::TooManySteps {
                    t,
                    steps: stats.n_steps,
                });
            }
            if h < 16.0 * f64::EPSILON * t.abs() || h.is_nan() {
                return Err(Error::StepSizeUnderflow { t, h });
            }
            if t + 1.01 * h - t1 > 0.0 {
                h = t1 - t;
                last = true;
            }
            stats.n_steps += 1;
            DOPRI5.stages(sys, t, &y, h, &mut k, &mut z)?;
            stats.n_rhs += 6;
            let y1 = z[6];
            let t_new = if last { t1 } else { t + h };
            let err2 = error_norm_sq(&Erk::combine(&DOPRI5.e, &k, 1.0), h, &y, &y1, rtol, atol);
            if !err2.is_finite() || non_finite(&y1) {
                return Err(Error::NonFinite { t: t_new });
            }
            let ln_err = 0.5 * err2.ln();
            if err2 > 1.0 {
                h = control.reject_ln(h, ln_err);
                last = false;
                stats.n_rejected += 1;
                continue;
            }
            let h_new = control.accept_ln(h, ln_err).min(h_max);
            stats.n_accepted += 1;

            // h |lambda| ~ h ||f(y1) - f(z6)|| / ||y1 - z6||: both are at t + h.
            if stiff.due(stats.n_accepted) && stiff.stiff_after(h, &k[6], &k[5], &y1, &z[5]) {
                return Err(Error::Stiff { t });
            }

            let mut y_acc = y1;
            let mut f_acc = None;
            if opts.project {
                sys.project(t_new, &mut y_acc)?;
                if non_finite(&y_acc) {
                    return Err(Error::NonFinite { t: t_new });
                }
                if y_acc != y1 {
                    let f = sys.rhs(t_new, &y_acc)?;
                    stats.n_rhs += 1;
                    if non_finite(&f) {
                        return Err(Error::NonFinite { t: t_new });
                    }
                    f_acc = Some(f);
                }
            }
            // The segment interpolates the step as computed (before any projection).
            let flow = rec.accept_with(t_new, &y_acc, || dense_segment(t, h, &y, &y1, &k));
            k[0] = f_acc.unwrap_or(k[6]);
            (t, y) = (t_new, y_acc);
            if flow == Flow::Stop || last {
                break;
            }
            h = h_new;
        }
        rec.finish(stats)
    }
}
