//! Verner's "most efficient" 9(8) pair with its ninth-order interpolant.

use super::control::PiController;
use super::explicit::{self, Pair, extra_stages};
use super::tableau::Erk;
use super::vern9_tableau::{VERN9, VERN9_DENSE_A, VERN9_DENSE_C, VERN9_DENSE_R};
use super::{Event, Flow, Integrator, Observer, Options, Segment, Solution};
use crate::error::Result;
use crate::model::{OdeSystem, Vector};

/// Verner's 9(8) pair (J. H. Verner, Numer. Algorithms 53 (2010) 383–396; the "most
/// efficient" of his published 9(8) pairs), by the shared explicit step loop: sixteen stages, the ninth-order solution
/// propagated and the eighth-order one's difference as the error estimate (RMS norm, as
/// DOPRI5's), the controller of DOP853 with the exponent `1/9`, Hairer's initial step,
/// stiffness detection every [`Options::stiffness_check`] accepted steps, and Verner's
/// ninth-order interpolant built from nine more stages per accepted step (only when the
/// step's segment is kept, events are located or an output time falls inside it).
///
/// Output times alone (`Record::Times` without dense output, events or an observer): a
/// step that would hold one output time late in it (`theta >= 7/16`) and is no longer than
/// 25/16 of the spacing of the output times ends on that time instead of interpolating
/// (`explicit::lands_on`), and the interpolant is evaluated at each output time from its
/// weights. The steps then depend on the output times; the values at them are step ends,
/// as accurate as the run's.
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

    /// A proportional-integral controller for an eighth-order estimate (Gustafsson's
    /// exponents `0.7/9` on the error and `0.4/9` on the last accepted one), ratio
    /// `h_new / h` in `[1/3, 6]`, safety 0.9. Against DOP853's memoryless `1/9` it rejects
    /// fewer steps: to a largest error of 1e-10 it needs 4 % fewer calls on the 8-link chain,
    /// 11 % on the pendulum and 26 % on the minimal slider-crank (`work-precision
    /// --time-to-accuracy`).
    pub fn controller() -> PiController {
        PiController::with(0.7 / 9.0, 0.4 / 9.0, 0.9, 0.333, 6.0)
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
    extra_stages((sys, t0, h, y0), k, 17, &VERN9_DENSE_A, &VERN9_DENSE_C)?;
    let mut c = [*y0; 10];
    for (cm, r) in c[1..].iter_mut().zip(&VERN9_DENSE_R) {
        *cm = Erk::<26>::combine(r, k, h);
    }
    Ok(Segment::polynomial(t0, h, &c))
}

/// Verner's interpolant at `theta` of the step `[t0, t0 + h]` from `y0`, its stages `k`
/// complete (`k[17..26]` by [`extra_stages`]): `y0 + h sum_i b_i(theta) k_i` with the weights
/// `b_i(theta) = sum_m R[m-1][i] theta^m` evaluated first, so that one value costs one
/// combination of the stages where the polynomial's nine coefficients cost nine.
fn interpolate<const D: usize>(
    theta: f64,
    h: f64,
    y0: &Vector<D>,
    k: &[Vector<D>; 26],
) -> Vector<D> {
    let b: [f64; 26] = std::array::from_fn(|i| {
        VERN9_DENSE_R
            .iter()
            .rev()
            .fold(0.0, |acc, r| (acc + r[i]) * theta)
    });
    y0 + Erk::<26>::combine(&b, k, h)
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

    fn passages(&self) -> Option<crate::passage::Settings> {
        crate::passage::Settings::of(&self.opts)
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
        explicit::solve::<Self, S, D, 16, 26>(&self.opts, sys, (t0, y0, t1), events, observer)
    }
}

/// `k[0..16]` the step's stages, `k[16] = f(t + h, y1)`, `k[17..26]` the interpolant's.
impl Pair<16, 26> for Vern9 {
    const TABLEAU: &'static Erk<16> = &VERN9;
    const ORDER: i32 = 9;
    const STIFF_LIMIT: f64 = Self::STIFF_HLAMBDA;
    const DENSE_CALLS: usize = VERN9_DENSE_C.len();
    /// Its interpolant costs nine calls, more than half a step's sixteen.
    const LANDS_ON_TIMES: bool = true;

    fn controller() -> PiController {
        Self::controller()
    }

    #[inline]
    fn underflow(h: f64, t: f64) -> bool {
        0.1 * h <= t.abs() * f64::EPSILON
    }

    #[inline]
    fn segment<F: OdeSystem<D>, const D: usize>(
        sys: &F,
        t: f64,
        h: f64,
        y: &Vector<D>,
        _y1: &Vector<D>,
        k: &mut [Vector<D>; 26],
    ) -> Result<Segment<D>> {
        dense_segment(sys, t, h, y, k)
    }

    #[inline]
    fn values<F: OdeSystem<D>, const D: usize>(
        (sys, t, h, y, _y1): (&F, f64, f64, &Vector<D>, &Vector<D>),
        k: &mut [Vector<D>; 26],
        take: impl FnOnce(&mut dyn FnMut(f64) -> Vector<D>) -> Flow,
    ) -> Result<Flow> {
        extra_stages((sys, t, h, y), k, 17, &VERN9_DENSE_A, &VERN9_DENSE_C)?;
        let k = &*k;
        Ok(take(&mut |ts| interpolate((ts - t) / h, h, y, k)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interpolant evaluated at `theta` equals the polynomial of its nine coefficients
    /// (`dense_segment`'s) to rounding, for arbitrary stages: the two forms of one sum of
    /// the terms `h R[m][i] theta^(m+1) k_i`, so they differ by a few units of rounding of
    /// the sum of those terms' sizes (`4 eps h sum |R[m][i]| theta^(m+1) |k_i|`; the
    /// weights reach 1e4, so this is well above `eps |y|`).
    #[test]
    fn interpolate_equals_the_segment_polynomial() {
        let k: [Vector<2>; 26] = std::array::from_fn(|i| {
            let x = i as f64;
            Vector::<2>::new((0.7 * x).sin(), (1.3 * x + 0.2).cos() * 3.0)
        });
        let (t0, h, y0) = (0.4, 0.25, Vector::<2>::new(1.0, -2.0));
        let mut c = [y0; 10];
        for (cm, r) in c[1..].iter_mut().zip(&VERN9_DENSE_R) {
            *cm = Erk::<26>::combine(r, &k, h);
        }
        let seg = Segment::polynomial(t0, h, &c);
        for theta in [0.0, 0.1, 0.4375, 0.77, 1.0] {
            let a = interpolate(theta, h, &y0, &k);
            let b = seg.eval_theta(theta);
            let size: f64 = (0..26)
                .map(|i| {
                    let w: f64 = (0..9)
                        .map(|m| VERN9_DENSE_R[m][i].abs() * theta.powi(m as i32 + 1))
                        .sum();
                    w * k[i].amax()
                })
                .sum();
            let bound = 4.0 * f64::EPSILON * (h * size + y0.amax());
            assert!(
                (a - b).amax() <= bound,
                "theta {theta}: {a} != {b} ({bound:e})"
            );
        }
    }
}
