//! Verner's "most efficient" 9(8) pair with its ninth-order interpolant.

use super::control::{PiController, StiffnessDetector, error_norm_sq};
use super::dopri5::first_stage;
use super::non_finite;
use super::tableau::Erk;
use super::vern9_tableau::{VERN9, VERN9_DENSE_A, VERN9_DENSE_C, VERN9_DENSE_R};
use super::{
    Event, Flow, Integrator, Observer, Options, Recorder, Segment, Solution, Stats,
    validate_problem,
};
use crate::error::{Error, Result};
use crate::model::{OdeSystem, Vector};

/// Verner's 9(8) pair (J. H. Verner, Numer. Algorithms 53 (2010) 383–396; the "most
/// efficient" of his published 9(8) pairs): sixteen stages, the ninth-order solution
/// propagated and the eighth-order one's difference as the error estimate (RMS norm, as
/// DOPRI5's), the controller of DOP853 with the exponent `1/9`, Hairer's initial step,
/// stiffness detection every [`Options::stiffness_check`] accepted steps, and Verner's
/// ninth-order interpolant built from nine more stages per accepted step (only when the
/// step's segment is kept, events are located or an output time falls inside it).
///
/// For tight tolerances: each step costs 16 calls against DOP853's 12 (and its interpolant
/// nine more against three), and at equal error its steps are the longer by more than that
/// on the chains from about 1e-10 and on every problem measured from about 1e-12 (see
/// [`super::Auto`]).
///
/// Counters: `n_rhs` is every call of `rhs`: one at `t0`, one for the initial step guess
/// when `h0` is `None`, fifteen per attempted step, one per accepted step
/// (`f(t + h, y1)`, the next step's first stage and the interpolant's seventeenth), nine
/// per accepted step when its dense segment is built, and one after a projection that
/// moved the state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Vern9 {
    /// Tolerances and step settings.
    pub opts: Options,
}

impl Vern9 {
    /// `h |lambda|` above which a step counts as stiff: the real stability interval of the
    /// ninth-order solution is `[-4.47, 0]` (test `vern9_real_stability_interval`); as
    /// `dop853.f`'s 6.1 for its `[-6.07, 0]`, the limit sits at the boundary.
    pub const STIFF_HLAMBDA: f64 = 4.4;

    /// Vern9 with the given options.
    pub fn new(opts: Options) -> Self {
        Vern9 { opts }
    }

    /// DOP853's controller with the exponent of an eighth-order estimate: `1/9`, no memory
    /// of the last error, ratio `h_new / h` in `[1/3, 6]`, safety 0.9.
    pub fn controller() -> PiController {
        PiController::with(1.0 / 9.0, 0.0, 0.9, 0.333, 6.0)
    }
}

/// Verner's interpolant over the step `[t0, t0 + h]`: nine more stages `k[17..26]` after
/// `k[16] = f(t0 + h, y1)`, then `y0 + h sum_i b_i(theta) k_i` with
/// `b_i(theta) = sum_m R[m-1][i] theta^m`. Makes nine `rhs` calls.
fn dense_segment<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    t0: f64,
    h: f64,
    y0: &Vector<D>,
    k: &mut [Vector<D>; 26],
) -> Result<Segment<D>> {
    for (j, (a, c)) in VERN9_DENSE_A.iter().zip(VERN9_DENSE_C).enumerate() {
        let s = 17 + j;
        let mut acc = Vector::<D>::zeros();
        for (aj, kj) in a[..s].iter().zip(k.iter()) {
            if *aj != 0.0 {
                acc += kj * *aj;
            }
        }
        let t = t0 + c * h;
        k[s] = sys.rhs(t, &(y0 + acc * h))?;
        if non_finite(&k[s]) {
            return Err(Error::NonFinite { t });
        }
    }
    let mut c = [*y0; 10];
    for (cm, r) in c[1..].iter_mut().zip(&VERN9_DENSE_R) {
        *cm = Erk::<26>::combine(r, k, h);
    }
    Ok(Segment::polynomial(t0, h, &c))
}

impl Integrator for Vern9 {
    fn name(&self) -> &'static str {
        "VERN9"
    }

    fn with_first_step(&self, h: f64) -> Option<Self> {
        let mut opts = self.opts.clone();
        opts.h0 = Some(h);
        Some(Vern9 { opts })
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

        // k[0..16] the step's stages, k[16] = f(t + h, y1), k[17..26] the dense stages.
        let mut k = [Vector::<D>::zeros(); 26];
        let mut z = [Vector::<D>::zeros(); 16];
        let mut h;
        (k[0], h) = first_stage(sys, t0, &y0, 9, opts, h_max, &mut stats)?;

        let mut control = Self::controller();
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
            if 0.1 * h <= t.abs() * f64::EPSILON || h.is_nan() {
                return Err(Error::StepSizeUnderflow { t, h });
            }
            if t + 1.01 * h - t1 > 0.0 {
                h = t1 - t;
                last = true;
            }
            stats.n_steps += 1;
            let stages: &mut [Vector<D>; 16] = (&mut k[..16]).try_into().expect("16 stages");
            VERN9.stages(sys, t, &y, h, stages, &mut z)?;
            stats.n_rhs += 15;
            let y1 = VERN9.advance(&y, stages, h);
            let t_new = if last { t1 } else { t + h };
            let err2 = error_norm_sq(&Erk::combine(&VERN9.e, stages, 1.0), h, &y, &y1, rtol, atol);
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
            stats.n_accepted += 1;
            // h |lambda| ~ h ||f(z15) - f(z14)|| / ||z15 - z14||: both at t + h.
            if stiff.due(stats.n_accepted) && stiff.stiff_after(h, &k[15], &k[14], &z[15], &z[14]) {
                return Err(Error::Stiff { t });
            }
            k[16] = sys.rhs(t + h, &y1)?;
            stats.n_rhs += 1;
            if non_finite(&k[16]) {
                return Err(Error::NonFinite { t: t_new });
            }
            let h_new = control.accept_ln(h, ln_err).min(h_max);

            let mut y_acc = y1;
            let mut f_acc = k[16];
            if opts.project {
                sys.project(t_new, &mut y_acc)?;
                if non_finite(&y_acc) {
                    return Err(Error::NonFinite { t: t_new });
                }
                if y_acc != y1 {
                    f_acc = sys.rhs(t_new, &y_acc)?;
                    stats.n_rhs += 1;
                    if non_finite(&f_acc) {
                        return Err(Error::NonFinite { t: t_new });
                    }
                }
            }
            // The segment interpolates the step as computed (before any projection).
            let flow = if rec.needs_segment_to(t_new) {
                stats.n_rhs += 9;
                let seg = dense_segment(sys, t, h, &y, &mut k)?;
                rec.accept(seg, &y_acc)
            } else {
                rec.accept_point(t_new, &y_acc)
            };
            k[0] = f_acc;
            (t, y) = (t_new, y_acc);
            if flow == Flow::Stop || last {
                break;
            }
            h = h_new;
        }
        rec.finish(stats)
    }
}
