//! The default explicit method: Vern9 for the tightest tolerances, DOP853 for tight ones,
//! DOPRI5 for loose ones.

use super::{Dop853, Dopri5, Event, Integrator, Observer, Options, Solution, Vern9};
use crate::error::Result;
use crate::model::{OdeSystem, Vector};

/// Picks the explicit pair for a non-stiff problem from the tolerance: [`Vern9`] when
/// `rtol <= Auto::VERN9_AT_OR_BELOW`, DOP853 when `rtol <= Auto::DOP853_AT_OR_BELOW`,
/// DOPRI5 above. Overridable by using [`Vern9`], [`Dop853`] or [`Dopri5`] directly; a stiff
/// problem wants [`Radau5`](super::Radau5) (the explicit methods stop with `Error::Stiff`
/// when their stiffness test finds it).
///
/// Why there: on the pendulum from 60 deg over 10 s (the `overhead` bench's problem), at
/// rtol = atol = 1e-3 DOPRI5 takes 194 calls to an end error of 4e-2 and DOP853 228 calls
/// to 4e-3; from 1e-4 on DOP853 takes fewer calls for a smaller error (1e-4: 310 calls,
/// 7e-4, against 320, 5e-3; 1e-10: 1708 calls, 6e-11, against 4220, 3e-9), and a call costs
/// the same inside either loop. So DOPRI5 only where the tolerance is loose enough that
/// its cheaper steps win.
///
/// Why Vern9 from `1e-11`: at one tolerance Vern9 is the more accurate of the eighth- and
/// ninth-order pairs, so they are compared at equal error (`work-precision --
/// --time-to-accuracy`: largest error over 101 sample times, dense output included, quarter
/// decades of tolerance). To 1e-10, Vern9 wins on the 8-link chain (3282 calls at
/// `tol = 1.8e-9` against DOP853's 3843 at `1.8e-10`) and on the 32-link chain, but loses
/// on the pendulum (2963 calls against 2593, both at `3.2e-11`) and on the slider-crank
/// (3524 against 2895; 3622 against 3291 in one coordinate): there the choice depends on the
/// problem. At tighter tolerances the ninth order pays everywhere measured (8-link chain to
/// 1e-12: 4472 calls at `3.2e-11` against 6020 at `1.8e-12`), so Vern9 takes over where
/// the tolerance itself asks for about 1e-11.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Auto {
    /// Tolerances and settings, passed on to the method picked.
    pub opts: Options,
}

impl Auto {
    /// The largest relative tolerance given to DOP853.
    pub const DOP853_AT_OR_BELOW: f64 = 1e-4;
    /// The largest relative tolerance given to Vern9.
    pub const VERN9_AT_OR_BELOW: f64 = 1e-11;

    /// The automatic choice with the given options.
    pub fn new(opts: Options) -> Self {
        Auto { opts }
    }

    /// Whether DOP853 is the method picked.
    pub fn picks_dop853(&self) -> bool {
        self.opts.rtol <= Self::DOP853_AT_OR_BELOW && !self.picks_vern9()
    }

    /// Whether Vern9 is the method picked.
    pub fn picks_vern9(&self) -> bool {
        self.opts.rtol <= Self::VERN9_AT_OR_BELOW
    }
}

impl Integrator for Auto {
    fn passages(&self) -> Option<crate::passage::Settings> {
        crate::passage::Settings::of(&self.opts)
    }

    fn name(&self) -> &'static str {
        if self.picks_vern9() {
            "VERN9"
        } else if self.picks_dop853() {
            "DOP853"
        } else {
            "DOPRI5"
        }
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
        let opts = self.opts.clone();
        if self.picks_vern9() {
            Vern9::new(opts).solve_observed(sys, t0, y0, t1, events, observer)
        } else if self.picks_dop853() {
            Dop853::new(opts).solve_observed(sys, t0, y0, t1, events, observer)
        } else {
            Dopri5::new(opts).solve_observed(sys, t0, y0, t1, events, observer)
        }
    }
}
