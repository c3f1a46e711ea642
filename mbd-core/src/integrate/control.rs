//! Error norm and step-size control of the embedded explicit methods.

use crate::model::Vector;

/// The scaled RMS norm of a local error estimate `e` for a step from `y0` to `y1`:
///
/// `err = sqrt( (1/D) sum_i ( e_i / (atol + rtol max(|y0_i|, |y1_i|)) )^2 )`
///
/// (Hairer–Nørsett–Wanner I, Sect. II.4, eq. (4.11); `dopri5.f`, label 41). A step is
/// accepted when `err <= 1`.
#[inline]
pub fn error_norm<const D: usize>(
    e: &Vector<D>,
    y0: &Vector<D>,
    y1: &Vector<D>,
    rtol: f64,
    atol: f64,
) -> f64 {
    let mut sum = 0.0;
    for i in 0..D {
        let sk = atol + rtol * y0[i].abs().max(y1[i].abs());
        sum += (e[i] / sk).powi(2);
    }
    // A system with no state (everything driven) has nothing to be wrong about.
    if D == 0 { 0.0 } else { (sum / D as f64).sqrt() }
}

/// The square of [`error_norm`] for the estimate `e = h acc`, computed as the step loop
/// needs it: the weights `h / sk_i` depend on `y0`, `y1` only, so they are ready before the
/// last stage is, and no square root is taken (`err <= 1` iff `err^2 <= 1`; the controller
/// takes `ln err = ln(err^2) / 2`).
#[inline]
pub fn error_norm_sq<const D: usize>(
    acc: &Vector<D>,
    h: f64,
    y0: &Vector<D>,
    y1: &Vector<D>,
    rtol: f64,
    atol: f64,
) -> f64 {
    let mut sum = 0.0;
    for i in 0..D {
        let w = h / (atol + rtol * y0[i].abs().max(y1[i].abs()));
        sum += (acc[i] * w).powi(2);
    }
    if D == 0 { 0.0 } else { sum * (1.0 / D as f64) }
}

/// The step `h` from `t` as the time takes it, where `t + h` rounds by more than a
/// hundredth of `rtol h` (far from t = 0, t0 = 1e12): else the state would drift from its
/// times by the sum. Below that, `h` is kept (Hairer's arithmetic: `t + h` as it rounds).
#[inline]
pub(crate) fn as_time_takes(t: f64, h: f64, rtol: f64) -> f64 {
    let stepped = (t + h) - t;
    if (stepped - h).abs() > 0.01 * rtol * h {
        stepped
    } else {
        h
    }
}

/// The PI step-size controller of `dopri5.f` (Gustafsson's "Lund stabilisation";
/// Hairer–Nørsett–Wanner I, Sect. IV.2, eq. (2.43c)):
///
/// `h_new = h / clamp( err^ALPHA / err_old^BETA / SAFETY, 1/FAC_MAX, 1/FAC_MIN )`,
///
/// with `err_old = max(err, 1e-4)` of the last accepted step (`1e-4` before the first).
/// After a rejection `h_new = h / min(1/FAC_MIN, err^ALPHA / SAFETY)`, and the step that
/// follows a rejection may not grow.
///
/// The constants are DOPRI5's by default ([`PiController::new`]); [`PiController::with`]
/// sets others (DOP853's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiController {
    /// `BETA ln(err_old)`: the memory term kept as a logarithm, so that an accepted step
    /// costs one `ln` and one `exp` (two `powf` before; the controller sits on the step
    /// loop's critical path, between one step's last stage and the next one's first).
    beta_ln_err_old: f64,
    rejected: bool,
    alpha: f64,
    beta: f64,
    safety: f64,
    fac_min: f64,
    fac_max: f64,
}

impl PiController {
    /// Safety factor on the predicted optimal step (`dopri5.f` `WORK(2)`).
    pub const SAFETY: f64 = 0.9;
    /// Smallest ratio `h_new / h` (`WORK(3)`).
    pub const FAC_MIN: f64 = 0.2;
    /// Largest ratio `h_new / h` (`WORK(4)`).
    pub const FAC_MAX: f64 = 10.0;
    /// Exponent on the previous error (`WORK(5)`).
    pub const BETA: f64 = 0.04;
    /// Exponent on the current error, `1/5 - 0.75 BETA` (`EXPO1`).
    pub const ALPHA: f64 = 0.2 - 0.75 * Self::BETA;
    /// Floor on the remembered error, and its value before the first accepted step (`FACOLD`).
    pub const ERR_OLD_MIN: f64 = 1e-4;

    /// A controller with no history and DOPRI5's constants.
    pub fn new() -> Self {
        Self::with(
            Self::ALPHA,
            Self::BETA,
            Self::SAFETY,
            Self::FAC_MIN,
            Self::FAC_MAX,
        )
    }

    /// A controller with no history: exponents `alpha` on the error and `beta` on the
    /// last accepted one, `safety`, and `h_new / h` kept in `[fac_min, fac_max]`.
    pub fn with(alpha: f64, beta: f64, safety: f64, fac_min: f64, fac_max: f64) -> Self {
        PiController {
            beta_ln_err_old: beta * Self::ERR_OLD_MIN.ln(),
            rejected: false,
            alpha,
            beta,
            safety,
            fac_min,
            fac_max,
        }
    }

    /// The next step after an accepted step of size `h` with error `err <= 1`; updates the
    /// memory. Never larger than `h` right after a rejection.
    #[inline]
    pub fn accept(&mut self, h: f64, err: f64) -> f64 {
        self.accept_ln(h, err.ln())
    }

    /// [`Self::accept`] given `ln err`, as
    /// `h_new = h clamp(SAFETY exp(BETA ln err_old - ALPHA ln err), FAC_MIN, FAC_MAX)`: one
    /// `exp` and products where the formula has two powers and two quotients, since this
    /// sits on the step loop's critical path, between one step's last stage and the next
    /// one's first. (`ln 0 = -inf` gives the largest growth, as `0^ALPHA` does.)
    #[inline]
    pub fn accept_ln(&mut self, h: f64, ln_err: f64) -> f64 {
        let ratio = (self.safety * (self.beta_ln_err_old - self.alpha * ln_err).exp())
            .clamp(self.fac_min, self.fac_max);
        let mut h_new = h * ratio;
        self.beta_ln_err_old = self.beta * ln_err.max(Self::ERR_OLD_MIN.ln());
        if self.rejected {
            h_new = h_new.min(h);
        }
        self.rejected = false;
        h_new
    }

    /// [`Self::accept_ln`] for an accepted step cut shorter than the controller proposed
    /// (onto an output time): the next step from its error, but the memory keeps the last
    /// full step's (the short step's small error is no measure of the proposal, and
    /// remembered it would shrink the steps after it).
    #[inline]
    pub fn accept_short_ln(&mut self, h: f64, ln_err: f64) -> f64 {
        let memory = self.beta_ln_err_old;
        let h_new = self.accept_ln(h, ln_err);
        self.beta_ln_err_old = memory;
        h_new
    }

    /// The retry step after a rejected step of size `h` with error `err > 1`.
    #[inline]
    pub fn reject(&mut self, h: f64, err: f64) -> f64 {
        self.reject_ln(h, err.ln())
    }

    /// [`Self::reject`] given `ln err`: `h max(SAFETY exp(-ALPHA ln err), FAC_MIN)`.
    #[inline]
    pub fn reject_ln(&mut self, h: f64, ln_err: f64) -> f64 {
        self.rejected = true;
        h * (self.safety * (-self.alpha * ln_err).exp()).max(self.fac_min)
    }
}

impl Default for PiController {
    fn default() -> Self {
        Self::new()
    }
}

/// Hairer's stiffness test (`dopri5.f`, `dop853.f`; Hairer–Wanner II, Sect. IV.2): every
/// `every` accepted steps, and on every step while a suspicion lasts, estimate `h |lambda|`
/// of the dominant eigenvalue from two stages at the same time; [`Self::STIFF_COUNT`]
/// consecutive estimates above the method's stability limit mean the problem is stiff,
/// [`Self::NONSTIFF_COUNT`] below clear the suspicion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessDetector {
    every: Option<usize>,
    limit: f64,
    h_lambda: f64,
    n_stiff: usize,
    n_nonstiff: usize,
}

impl StiffnessDetector {
    /// Consecutive stiff estimates that stop the integration.
    pub const STIFF_COUNT: usize = 15;
    /// Consecutive non-stiff estimates that clear the count.
    pub const NONSTIFF_COUNT: usize = 6;

    /// A detector testing every `every` accepted steps (`None`: never) against `limit`.
    pub fn new(every: Option<usize>, limit: f64) -> Self {
        StiffnessDetector {
            every,
            limit,
            h_lambda: 0.0,
            n_stiff: 0,
            n_nonstiff: 0,
        }
    }

    /// Whether the `n_accepted`-th accepted step is tested.
    #[inline]
    pub fn due(&self, n_accepted: usize) -> bool {
        self.every
            .is_some_and(|every| n_accepted.is_multiple_of(every) || self.n_stiff > 0)
    }

    /// After a step of size `h` that was [`Self::due`]: `h ||fa - fb|| / ||ya - yb||` with
    /// `fa = f(ya)`, `fb = f(yb)` at one time. `true` once the problem is judged stiff.
    pub fn stiff_after<const D: usize>(
        &mut self,
        h: f64,
        fa: &Vector<D>,
        fb: &Vector<D>,
        ya: &Vector<D>,
        yb: &Vector<D>,
    ) -> bool {
        let den = (ya - yb).norm_squared();
        if den > 0.0 {
            self.h_lambda = h * ((fa - fb).norm_squared() / den).sqrt();
        }
        if self.h_lambda > self.limit {
            self.n_nonstiff = 0;
            self.n_stiff += 1;
            self.n_stiff == Self::STIFF_COUNT
        } else {
            self.n_nonstiff += 1;
            if self.n_nonstiff == Self::NONSTIFF_COUNT {
                self.n_stiff = 0;
            }
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-computed: with no history, err = 0.5 gives
    /// fac = 0.5^0.17 / 1e-4^0.04 / 0.9, h_new = h / fac.
    #[test]
    fn first_accept_follows_the_formula() {
        let mut c = PiController::new();
        let fac = 0.5f64.powf(0.17) / 1e-4f64.powf(0.04) / 0.9;
        assert!((c.accept(1.0, 0.5) - 1.0 / fac).abs() < 1e-15);
    }

    #[test]
    fn growth_and_shrink_are_bounded() {
        let mut c = PiController::new();
        assert_eq!(c.accept(1.0, 0.0), 10.0);
        assert!((c.reject(1.0, 1e12) - 0.2).abs() < 1e-15);
        // After a rejection, even a perfect step does not grow.
        assert_eq!(c.accept(1.0, 0.0), 1.0);
    }

    /// err = 1 in every component gives norm 1; scale uses the larger of |y0|, |y1|.
    #[test]
    fn norm_scales_by_tolerance() {
        let y0 = Vector::<2>::new(1.0, -3.0);
        let y1 = Vector::<2>::new(2.0, 0.0);
        let (rtol, atol) = (1e-3, 1e-6);
        let e = Vector::<2>::new(atol + rtol * 2.0, atol + rtol * 3.0);
        assert!((error_norm(&e, &y0, &y1, rtol, atol) - 1.0).abs() < 1e-15);
    }
}
