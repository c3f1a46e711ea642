//! Fixed steps too long for a model's fastest motion: RK4 beyond its stability limit
//! (`h w > 2 sqrt 2` for an undamped oscillation of `w`) grew the state by `|R(i h w)| > 1`
//! a step and returned the finite, wrong result as `Ok` (a spring of `w = 100` at `h = 0.05`
//! ended 3e26 times its amplitude); now a typed error naming `h` and a step that is stable.
//! Below the limit runs are unchanged (the closed form `x0 cos(w t)` beside each).

use mbd::integrate::{Integrator, Rk4};
use mbd::prelude::*;

/// A mass on a spring to the origin: `x'' = -(k/m) x`.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[spring(s, from = [0.0, 0.0], to = bob, k = k)]
#[init(x = x0)]
pub struct Spring {
    pub m: f64,
    pub k: f64,
    pub x0: f64,
}

/// `w = 100 rad/s`, amplitude 0.1.
const P: Spring = Spring {
    m: 1.0,
    k: 1e4,
    x0: 0.1,
};

/// The `what` and detail of an `InvalidInput`, else the outcome.
fn refused(r: Result<Solution<2>, Error>) -> (String, String) {
    match r {
        Err(Error::InvalidInput { what, detail }) => (what.into(), detail),
        Err(e) => (format!("other error: {e}"), String::new()),
        Ok(s) => (
            format!("Ok, x(end) = {:e}", s.y.last().unwrap()[0]),
            String::new(),
        ),
    }
}

#[test]
fn rk4_beyond_its_stability_limit_is_refused_not_returned() {
    let w = (P.k / P.m).sqrt();
    // (h, t1): h w = 5 over 20 steps (was Ok, x(1) = -2.9e26 x0), h = 10 s in one step
    // (was Ok, x = 4.2e10 x0), h w = 3 just past the limit over 34 steps (was Ok,
    // |R(3 i)| = 1.5 a step: x(1) = -7.1e5 x0); the same RK4 recurrence by hand.
    for (h, t1) in [(0.05, 1.0), (10.0, 10.0), (0.03, 1.0)] {
        let (what, detail) = refused(Rk4::new(h).solve(&P, 0.0, P.initial_state(), t1, &[]));
        assert_eq!(what, "h", "h w = {}: {what}", h * w);
        assert!(detail.contains("stability limit"), "{detail}");
        // The suggested step is stable: below 2 sqrt(2) / w (the estimate is exact for
        // this linear model, to rounding).
        let hint: f64 = detail
            .split("below ")
            .nth(1)
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let limit = 2.0 * 2f64.sqrt() / w;
        assert!(
            (hint - limit).abs() < 1e-3 * limit,
            "hint {hint}, limit {limit}"
        );
    }
}

#[test]
fn rk4_below_its_stability_limit_runs_as_before() {
    let w = (P.k / P.m).sqrt();
    // h w = 0.1: accurate, 1000 steps to t = 1; RK4's global error on x0 cos(w t) is about
    // t w (h w)^4 / 120 x0 = 8e-6.
    let sol = Rk4::new(1e-3)
        .solve(&P, 0.0, P.initial_state(), 1.0, &[])
        .unwrap();
    let x = sol.y.last().unwrap()[0];
    assert!((x - P.x0 * (w * 1.0).cos()).abs() < 2e-5, "x = {x}");
    // h w = 2.7, inside the stability region (|R(2.7 i)| = 0.72): a stable, damped run is
    // returned; its amplitude never exceeds x0 (the check is on stability, not accuracy).
    let sol = Rk4::new(0.027)
        .solve(&P, 0.0, P.initial_state(), 1.0, &[])
        .unwrap();
    let peak = sol.y.iter().map(|y| y[0].abs()).fold(0.0, f64::max);
    assert!(peak <= P.x0, "peak {peak}");
}

/// A pendulum swung to 170 degrees: strongly nonlinear, well resolved at `h = 1e-3`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(th)]
#[particle(bob, mass = 1.0, at = [l * sin(th), -l * cos(th)])]
#[init(th = 2.967)]
pub struct Pendulum {
    pub l: f64,
    pub g: f64,
}

#[test]
fn a_nonlinear_swing_at_a_resolving_step_is_not_refused() {
    let p = Pendulum { l: 1.0, g: 9.81 };
    let y0 = p.initial_state();
    let sol = Rk4::new(1e-3).solve(&p, 0.0, y0, 10.0, &[]).unwrap();
    // Energy per unit mass, conserved: g l (1 - cos th) + (l th')^2 / 2.
    let e = |y: &Vector<2>| p.g * p.l * (1.0 - y[0].cos()) + 0.5 * (p.l * y[1]).powi(2);
    let drift = (e(sol.y.last().unwrap()) - e(&y0)).abs() / e(&y0);
    assert!(drift < 1e-8, "energy drift {drift}");
}
