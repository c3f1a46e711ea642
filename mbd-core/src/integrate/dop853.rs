//! Dormand–Prince 8(5,3) with Hairer's step control, dense output and stiffness detection.

use super::control::PiController;
use super::dop853_tableau::{DOP853, DOP853_BHH, DOP853_DENSE_A, DOP853_DENSE_C, DOP853_DENSE_D};
use super::explicit::{self, Pair, extra_stages};
use super::tableau::Erk;
use super::{Event, Integrator, Observer, Options, Segment, Solution};
use crate::error::Result;
use crate::model::{OdeSystem, Vector};

/// The explicit Dormand–Prince 8(5,3) pair run as Hairer's `dop853.f` runs it
/// (Hairer–Nørsett–Wanner I, Sect. II.5, II.6 and IV.2), by the shared explicit step loop:
/// twelve stages, the error of the
/// fifth-order estimate corrected by the third-order one ([`dop853_error`]), the PI
/// controller with `dop853.f`'s constants ([`Dop853::controller`]), Hairer's initial step,
/// stiffness detection every [`Options::stiffness_check`] accepted steps, and a
/// seventh-order dense output built from three more stages per accepted step (only when
/// the step's segment is kept, events are located or an output time falls inside it).
///
/// Counters: `n_rhs` is every call of `rhs`: one at `t0` (`dop853.f` counts two there even
/// when the initial step is given), one for the initial step guess when `h0` is `None`,
/// eleven per attempted step, one per accepted step (`f(t + h, y1)`, the next step's first
/// stage), three per accepted step when its dense segment is built, and one after a
/// projection that moved the state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Dop853 {
    /// Tolerances and step settings.
    pub opts: Options,
}

impl Dop853 {
    /// `h |lambda|` above which a step counts as stiff (`dop853.f`: 6.1, near the boundary
    /// of the stability region on the negative real axis).
    pub const STIFF_HLAMBDA: f64 = 6.1;
    /// DOP853 with the given options.
    pub fn new(opts: Options) -> Self {
        Dop853 { opts }
    }

    /// `dop853.f`'s controller: exponent `1/8`, no memory of the last error (`BETA = 0`),
    /// ratio `h_new / h` in `[1/3, 6]`, safety 0.9.
    pub fn controller() -> PiController {
        PiController::with(1.0 / 8.0, 0.0, 0.9, 0.333, 6.0)
    }
}

/// `dop853.f`'s error of a step (label 41): with `sk = atol + rtol max(|y0|, |y1|)`,
/// `e5 = sum (sum_i er_i k_i / sk)^2`, `e3 = sum ((sum_i (b_i - bhh_i) k_i) / sk)^2`,
/// `err = |h| e5 / sqrt(D (e5 + 0.01 e3))`: the fifth-order estimate, damped where the
/// third-order one shows the step is far from the asymptotic regime.
pub fn dop853_error<const D: usize>(
    k: &[Vector<D>; 12],
    y0: &Vector<D>,
    y1: &Vector<D>,
    h: f64,
    rtol: f64,
    atol: f64,
) -> f64 {
    if D == 0 {
        return 0.0;
    }
    let (mut e5, mut e3) = (0.0, 0.0);
    for i in 0..D {
        let sk = atol + rtol * y0[i].abs().max(y1[i].abs());
        let (mut a5, mut a3) = (0.0, 0.0);
        for (s, ks) in k.iter().enumerate() {
            a5 += DOP853.e[s] * ks[i];
            a3 += (DOP853.b[s] - DOP853_BHH[s]) * ks[i];
        }
        e5 += (a5 / sk).powi(2);
        e3 += (a3 / sk).powi(2);
    }
    let mut deno = e5 + 0.01 * e3;
    if deno <= 0.0 {
        deno = 1.0;
    }
    h.abs() * e5 * (1.0 / (D as f64 * deno)).sqrt()
}

/// The seventh-order continuous extension (`dop853.f` `CONTD8`): three more stages `k[13..16]`
/// after `k[12] = f(t + h, y1)`, then
/// `y0 + s (r1 + s1 (r2 + s (r3 + s1 (r4 + s (r5 + s1 (r6 + s r7))))))` with `s1 = 1 - s`,
/// `r1 = y1 - y0`, `r2 = h k0 - r1`, `r3 = r1 - h k12 - r2`, `r4..r7 = h sum_i d_i k_i`.
/// Makes three `rhs` calls.
fn dense_segment<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    t0: f64,
    h: f64,
    y0: &Vector<D>,
    y1: &Vector<D>,
    k: &mut [Vector<D>; 16],
) -> Result<Segment<D>> {
    extra_stages((sys, t0, h, y0), k, 13, &DOP853_DENSE_A, &DOP853_DENSE_C)?;
    let r1 = y1 - y0;
    let r2 = k[0] * h - r1;
    let r3 = r1 - k[12] * h - r2;
    let d = DOP853_DENSE_D
        .each_ref()
        .map(|w| Erk::<16>::combine(w, k, h));
    Ok(Segment::from_nested(
        t0,
        h,
        &[*y0, r1, r2, r3, d[0], d[1], d[2], d[3]],
    ))
}

impl Integrator for Dop853 {
    fn passages(&self) -> Option<crate::passage::Settings> {
        crate::passage::Settings::of(&self.opts)
    }

    fn name(&self) -> &'static str {
        "DOP853"
    }

    fn with_first_step(&self, h: f64) -> Option<Self> {
        let mut opts = self.opts.clone();
        opts.h0 = Some(h);
        Some(Dop853 { opts })
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
        explicit::solve::<Self, S, D, 12, 16>(&self.opts, sys, (t0, y0, t1), events, observer)
    }
}

/// `k[0..12]` the step's stages, `k[12] = f(t + h, y1)`, `k[13..16]` the dense stages.
impl Pair<12, 16> for Dop853 {
    const TABLEAU: &'static Erk<12> = &DOP853;
    const ORDER: i32 = 8;
    const STIFF_LIMIT: f64 = Self::STIFF_HLAMBDA;
    const STIFF_FROM_END: bool = true;
    const DENSE_CALLS: usize = DOP853_DENSE_C.len();
    const ERROR_SQUARED: bool = false;

    fn controller() -> PiController {
        Self::controller()
    }

    #[inline]
    fn underflow(h: f64, t: f64) -> bool {
        0.1 * h <= t.abs() * f64::EPSILON
    }

    #[inline]
    fn error<const D: usize>(
        k: &[Vector<D>; 12],
        y: &Vector<D>,
        y1: &Vector<D>,
        h: f64,
        rtol: f64,
        atol: f64,
    ) -> f64 {
        dop853_error(k, y, y1, h, rtol, atol)
    }

    #[inline]
    fn segment<F: OdeSystem<D>, const D: usize>(
        sys: &F,
        t: f64,
        h: f64,
        y: &Vector<D>,
        y1: &Vector<D>,
        k: &mut [Vector<D>; 16],
    ) -> Result<Segment<D>> {
        dense_segment(sys, t, h, y, y1, k)
    }
}
