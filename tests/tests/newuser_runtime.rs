//! Run-time edge cases a new user meets first: a chain of one link, an integration of zero
//! length or backwards, an event whose function starts at zero, outputs at the start, and
//! a closed loop started off its constraint. References beside each test.

use mbd::integrate::{
    Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4,
};
use mbd::prelude::*;

/// `#[chain]` of one link is a compound pendulum: a uniform bar `l`, `m` about its end,
/// `(m l^2 / 3) q'' = -m g (l / 2) sin q`, its tip at `l (sin q, -cos q)`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 1, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
#[output(tip = position(link_1, [0.0, -l]), centre = position(link_1))]
pub struct Chain1 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn chain_of_one_link_is_the_compound_pendulum() {
    let p = Chain1 {
        m: 2.0,
        l: 0.8,
        g: 9.81,
    };
    assert_eq!(Chain1::COORDINATES, ["link_q1"]);
    for (q, qd) in [(0.4f64, 0.0), (-2.0, 3.0), (3.0, -1.0)] {
        let acc = p
            .acceleration(0.0, &Vector::<1>::new(q), &Vector::<1>::new(qd))
            .unwrap()[0];
        let want = -1.5 * p.g / p.l * q.sin();
        assert!((acc - want).abs() < 1e-13, "q = {q}");
        let out = p.outputs(0.0, &Vector::<2>::new(q, qd)).unwrap();
        assert!((out.tip_x - p.l * q.sin()).abs() < 1e-15);
        assert!((out.tip_y + p.l * q.cos()).abs() < 1e-15);
        assert!((out.centre_x - p.l / 2.0 * q.sin()).abs() < 1e-15);
    }
}

/// A ball thrown up from `y = 0`: `y = v0 t - g t^2 / 2`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(y)]
#[particle(ball, mass = m, at = [0.0, y])]
#[init(y = 0.0, der(y) = v0)]
#[event(landing = y, falling, terminal)]
#[output(height = y, speed = der(y))]
pub struct Ball {
    pub m: f64,
    pub g: f64,
    pub v0: f64,
}

/// Each method's end state from `t0` to `t1`, or its error.
fn every_method(b: &Ball, t0: f64, t1: f64) -> Vec<(&'static str, Result<Solution<2>, Error>)> {
    let y0 = b.initial_state();
    let (q0, qd0) = (Vector::<1>::new(y0[0]), Vector::<1>::new(y0[1]));
    let opts = Options::default();
    vec![
        (
            "DOPRI5",
            Dopri5::new(opts.clone()).solve(b, t0, y0, t1, &[]),
        ),
        (
            "DOP853",
            Dop853::new(opts.clone()).solve(b, t0, y0, t1, &[]),
        ),
        ("Auto", Auto::new(opts.clone()).solve(b, t0, y0, t1, &[])),
        ("Radau5", Radau5::new(opts).solve(b, t0, y0, t1, &[])),
        ("RK4", Rk4::new(0.01).solve(b, t0, y0, t1, &[])),
        ("Gauss", Gauss::new(0.01).solve(b, t0, y0, t1, &[])),
        (
            "generalized-alpha",
            GeneralizedAlpha::new(0.9, 0.01).solve(b, t0, q0, qd0, t1, &[]),
        ),
    ]
}

#[test]
fn zero_length_span_returns_the_initial_state_and_a_backward_one_is_refused() {
    let b = Ball {
        m: 1.0,
        g: 9.81,
        v0: 5.0,
    };
    for (method, run) in every_method(&b, 1.5, 1.5) {
        let sol = run.unwrap_or_else(|e| panic!("{method}: {e}"));
        assert_eq!(sol.t, [1.5], "{method}");
        assert_eq!(sol.y, [b.initial_state()], "{method}");
    }
    for (method, run) in every_method(&b, 1.5, 1.0) {
        assert!(
            matches!(run, Err(Error::InvalidInput { what: "t1", .. })),
            "{method}: {:?}",
            run.map(|s| s.t)
        );
    }
}

/// The landing event's function `y` is zero at the start: a start value of exactly zero
/// is not a crossing (documented), so the run does not stop at `t0`; the ball lands at
/// `2 v0 / g`, where the event is located. The outputs at the start are the initial state's.
#[test]
fn an_event_zero_at_the_start_fires_at_the_landing_not_at_t0() {
    let b = Ball {
        m: 1.0,
        g: 9.81,
        v0: 5.0,
    };
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let events = b.events();
    let sol = Dopri5::new(opts)
        .solve(&b, 0.0, b.initial_state(), 3.0, &events)
        .unwrap();
    assert_eq!(sol.events.len(), 1);
    let landing = 2.0 * b.v0 / b.g;
    assert!((sol.events[0].t - landing).abs() < 1e-12);
    assert!((sol.t.last().unwrap() - landing).abs() < 1e-12);
    let start = b.outputs(sol.t[0], &sol.y[0]).unwrap();
    assert_eq!((start.height, start.speed), (0.0, b.v0));
}

/// A pendulum in Cartesian coordinates on `x^2 + y^2 = l^2`, kept augmented.
#[derive(Debug, Mechanism)]
#[mechanism(planar, augmented)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint(x * x + y * y == l * l)]
pub struct Cartesian {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// Started at `r = 2.2` on a rod of `l = 2`, or on the circle but moving along the rod, the
/// state is not the pendulum's: every method refuses it with a typed error before a step,
/// rather than project it after the first step without a word. On the circle, moving across
/// the rod, it runs.
#[test]
fn a_loop_started_off_its_constraint_is_refused() {
    let p = Cartesian {
        m: 1.0,
        l: 2.0,
        g: 9.81,
    };
    let off_circle = Vector::<4>::new(2.2, 0.0, 0.0, 0.5);
    let along_rod = Vector::<4>::new(2.0, 0.0, 0.3, 0.5);
    for y0 in [off_circle, along_rod] {
        let runs = [
            Dopri5::new(Options::default()).solve(&p, 0.0, y0, 1.0, &[]),
            Radau5::new(Options::default()).solve(&p, 0.0, y0, 1.0, &[]),
            Rk4::new(1e-3).solve(&p, 0.0, y0, 1.0, &[]),
        ];
        for run in runs {
            assert!(
                matches!(run, Err(Error::InvalidInput { .. })),
                "{y0:?}: {run:?}"
            );
        }
    }
    let on = Vector::<4>::new(2.0, 0.0, 0.0, 0.5);
    let sol = Dopri5::new(Options::default())
        .solve(&p, 0.0, on, 1.0, &[])
        .unwrap();
    let r = sol.y.last().unwrap().fixed_rows::<2>(0).norm();
    assert!((r - p.l).abs() < 1e-9);
}

/// A mass on a zero-length spring to the origin: the force is `-k (x, y)`, defined
/// everywhere, so launched from the origin at `v0` along `x` it moves as
/// `x = v0 / w sin(w t)`, `w^2 = k / m`.
#[derive(Debug, Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[spring(s, from = bob, to = [0.0, 0.0], k = k)]
pub struct Tethered {
    pub m: f64,
    pub k: f64,
}

/// At coincident ends a spring of rest length zero pulls with `k d`, zero at the origin: its
/// potential is `k d.d / 2`, not differentiated through `l = sqrt(d . d)` (0/0 there).
/// Started there with speed 3 it is the oscillator `x = 3 sin(w t) / w`.
#[test]
fn zero_length_spring_is_defined_at_coincident_ends() {
    let p = Tethered { m: 2.0, k: 8.0 };
    let zero = Vector::<2>::zeros();
    assert_eq!(p.acceleration(0.0, &zero, &zero).unwrap(), zero);
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let y0 = Vector::<4>::new(0.0, 0.0, 3.0, 0.0);
    let sol = Dopri5::new(opts).solve(&p, 0.0, y0, 1.0, &[]).unwrap();
    let w = (p.k / p.m).sqrt();
    assert!((sol.y.last().unwrap()[0] - 3.0 / w * w.sin()).abs() < 1e-9);
}
