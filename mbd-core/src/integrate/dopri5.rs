//! Dormand–Prince 5(4) with Hairer's step control, dense output and stiffness detection.

#[cfg(doc)]
use super::control::error_norm_sq;
use super::control::{PiController, StiffnessDetector};
use super::explicit::{self, Pair};
use super::tableau::{DOPRI5, DOPRI5_DENSE, Erk};
use super::{Event, Integrator, Observer, Options, Segment, Solution};
#[cfg(doc)]
use crate::error::Error;
use crate::error::Result;
use crate::model::{OdeSystem, Vector};

pub use super::explicit::initial_step;

/// The explicit Dormand–Prince 5(4) pair run as Hairer's `dopri5.f` runs it (Hairer–Nørsett–
/// Wanner I, Sect. II.5 and II.6), by the shared explicit step loop: FSAL, local extrapolation, the scaled RMS
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
        explicit::solve::<Self, S, D, 7, 7>(&self.opts, sys, (t0, y0, t1), events, observer)
    }
}

impl Pair<7, 7> for Dopri5 {
    const TABLEAU: &'static Erk<7> = &DOPRI5;
    const ORDER: i32 = 5;
    const STIFF_LIMIT: f64 = Self::STIFF_HLAMBDA;

    fn controller() -> PiController {
        PiController::new()
    }

    #[inline]
    fn underflow(h: f64, t: f64) -> bool {
        h < 16.0 * f64::EPSILON * t.abs()
    }

    #[inline]
    fn segment<F: OdeSystem<D>, const D: usize>(
        _sys: &F,
        t: f64,
        h: f64,
        y: &Vector<D>,
        y1: &Vector<D>,
        k: &mut [Vector<D>; 7],
    ) -> Result<Segment<D>> {
        Ok(dense_segment(t, h, y, y1, k))
    }
}
