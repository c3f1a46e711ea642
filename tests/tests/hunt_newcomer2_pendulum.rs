//! A newcomer's first model, written from the README and the language reference: a
//! pendulum with viscous damping at its pivot and outputs, checked against the linear
//! closed form at small amplitude and against the work-energy theorem at large amplitude.
//!
//! Hand derivation. A bob of mass `m` on a massless rod of length `l`, angle `th` from the
//! downward vertical, bob at `(l sin th, -l cos th)`; a damping torque `-c th'` at the pivot
//! (a generalised force along `th`). Lagrange: `m l^2 th'' = -m g l sin th - c th'`.
//! Linearised, `th'' + 2 z w th' + w^2 th = 0` with `w^2 = g / l`, `z = c / (2 m l^2 w)`;
//! from `th0` at rest, `th = th0 e^(-z w t) (cos(wd t) + z w / wd sin(wd t))`,
//! `wd = w sqrt(1 - z^2)`. The energy `E = m l^2 th'^2 / 2 - m g l cos th` falls at the rate
//! of the damper's power `-c th'^2`.

use mbd::prelude::*;

/// A damped pendulum; `height` and `speed` are the bob's, `damper_power` the damper's.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(th)]
#[particle(bob, mass = m, at = [l * sin(th), -l * cos(th)])]
#[generalized_force(pivot_damper, along = th, value = -c * der(th))]
#[init(th = th0)]
#[output(height = position(bob)[1], speed = norm(velocity(bob)),
         damper_power = -c * der(th) * der(th))]
pub struct Damped {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
    pub th0: f64,
}

const P: Damped = Damped {
    m: 0.8,
    l: 0.6,
    g: 9.81,
    c: 0.15,
    th0: 1.2,
};

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

#[test]
fn acceleration_and_outputs_match_the_hand_derivation() {
    let (th, thd) = (0.9_f64, -1.7_f64);
    let q = Vector::<1>::new(th);
    let qd = Vector::<1>::new(thd);
    let got = P.acceleration(0.0, &q, &qd).unwrap()[0];
    let want = -P.g / P.l * th.sin() - P.c * thd / (P.m * P.l * P.l);
    assert!((got - want).abs() < 1e-13, "{got} vs {want}");

    let out = P.outputs(0.0, &Vector::<2>::new(th, thd)).unwrap();
    assert!((out.height + P.l * th.cos()).abs() < 1e-15);
    assert!((out.speed - P.l * thd.abs()).abs() < 1e-15);
    assert!((out.damper_power + P.c * thd * thd).abs() < 1e-15);
    assert_eq!(Damped::OUTPUTS, ["height", "speed", "damper_power"]);
}

#[test]
fn small_swings_follow_the_damped_linear_oscillator() {
    // At th0 = 1e-4 the neglected `th^3 / 6` shifts the phase by about w t th0^2 / 16,
    // 1e-8 of th0 over these 5 s: the tolerance below is well above that and far below
    // any error in the damping (z = 0.088 here changes th by 40 % of th0 per period).
    let p = Damped { th0: 1e-4, ..P };
    let w = (p.g / p.l).sqrt();
    let z = p.c / (2.0 * p.m * p.l * p.l * w);
    let wd = w * (1.0 - z * z).sqrt();
    let sol = Dopri5::new(tight())
        .solve(&p, 0.0, p.initial_state(), 5.0, &[])
        .unwrap();
    for k in 1..=50 {
        let t = 0.1 * k as f64;
        let th = sol.at(t).unwrap()[0];
        let want = p.th0 * (-z * w * t).exp() * ((wd * t).cos() + z * w / wd * (wd * t).sin());
        assert!((th - want).abs() < 1e-7 * p.th0, "t = {t}: {th} vs {want}");
    }
}

#[test]
fn large_swings_lose_exactly_the_energy_the_damper_dissipates() {
    let sol = Dopri5::new(tight())
        .solve(&P, 0.0, P.initial_state(), 4.0, &[])
        .unwrap();
    let energy = |y: &Vector<2>| {
        let q = Vector::<1>::new(y[0]);
        let qd = Vector::<1>::new(y[1]);
        P.energy(0.0, &q, &qd).unwrap()
    };
    // By hand, against the model's own `energy`.
    let y0 = P.initial_state();
    assert!((energy(&y0) + P.m * P.g * P.l * P.th0.cos()).abs() < 1e-14);
    // The damper's work: Simpson's rule on the dense output's `damper_power`.
    let n = 4000;
    let h = 4.0 / n as f64;
    let power = |t: f64| P.outputs(t, &sol.at(t).unwrap()).unwrap().damper_power;
    let work: f64 = (0..=n)
        .map(|i| {
            let wgt = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            wgt * power(i as f64 * h)
        })
        .sum::<f64>()
        * h
        / 3.0;
    let lost = energy(sol.last().1) - energy(&y0);
    assert!(lost < -0.5, "the damper took {lost} J");
    assert!(
        (lost - work).abs() < 1e-8,
        "lost {lost} J, damper work {work} J"
    );
}
