//! Hunting extreme time spans. Far from t = 0 (a run started at t0 = 1e12 s, as one
//! restarted late or in epoch seconds) `t + h` rounds to the time grid (its spacing 1.2e-4 s
//! at 1e12); the explicit methods advanced the state by `h` and the time by the rounded
//! step, so a pendulum over 2 s at `tol = 1e-10` ended 5e-4 rad wrong with `Ok` (DOPRI5;
//! DOP853, Vern9 and `Auto` alike), and Radau5 refused it (its first step, 1e-6, under its
//! own step-size floor). Now each step is the one the time takes, and Radau5 starts above
//! the floor. The reference: the rigid pendulum's closed form (`exact::pendulum_angle`).
//! A span that overflows (`t1 - t0` infinite) is refused by name.

use mbd::integrate::{Auto, Dop853, Dopri5, Gauss, Integrator, Radau5, Rk4, Vern9};
use mbd::prelude::*;

#[path = "../../mbd-core/tests/exact/mod.rs"]
mod exact;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(bob, joint = revolute(q), com = [0.0, -l], mass = m)]
#[init(q = 1.0)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

const P: Pendulum = Pendulum {
    m: 1.0,
    l: 1.0,
    g: 9.81,
};

type Run = fn(f64, f64) -> Result<Solution<2>, Error>;

fn opts() -> Options {
    Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    }
}

const METHODS: [(&str, Run); 7] = [
    ("DOPRI5", |t0, t1| {
        Dopri5::new(opts()).solve(&P, t0, P.initial_state(), t1, &[])
    }),
    ("DOP853", |t0, t1| {
        Dop853::new(opts()).solve(&P, t0, P.initial_state(), t1, &[])
    }),
    ("Vern9", |t0, t1| {
        Vern9::new(opts()).solve(&P, t0, P.initial_state(), t1, &[])
    }),
    ("Auto", |t0, t1| {
        Auto::new(opts()).solve(&P, t0, P.initial_state(), t1, &[])
    }),
    ("Radau5", |t0, t1| {
        Radau5::new(opts()).solve(&P, t0, P.initial_state(), t1, &[])
    }),
    ("RK4 h = 1e-3", |t0, t1| {
        Rk4::new(1e-3).solve(&P, t0, P.initial_state(), t1, &[])
    }),
    ("Gauss h = 1e-2", |t0, t1| {
        Gauss::new(1e-2).solve(&P, t0, P.initial_state(), t1, &[])
    }),
];

#[test]
fn a_run_far_from_t_zero_is_as_accurate_as_one_from_zero() {
    let w = (P.g / P.l).sqrt();
    for t0 in [0.0, 1e9, 1e12] {
        for (name, run) in METHODS {
            let sol = run(t0, t0 + 2.0).unwrap_or_else(|e| panic!("{name} from {t0:e}: {e}"));
            let (t, y) = sol.last();
            assert_eq!(t, t0 + 2.0, "{name}");
            let end = (y[0] - exact::pendulum_angle(w, 1.0, 2.0)).abs();
            assert!(end < 1e-7, "{name} from {t0:e}: {end:e} rad off at the end");
            // Every recorded state against the closed form at its recorded time, which is
            // on the time grid: up to half its spacing (`ulp(t0)`) from the state's own time
            // at a speed below 4 rad/s.
            let grid = 2.0 * f64::EPSILON * t0;
            let worst = sol.t.iter().zip(&sol.y).fold(0.0f64, |e, (&t, y)| {
                e.max((y[0] - exact::pendulum_angle(w, 1.0, t - t0)).abs())
            });
            assert!(
                worst < 1e-7 + 4.0 * grid,
                "{name} from {t0:e}: {worst:e} rad off"
            );
        }
    }
}

#[test]
fn a_span_that_overflows_is_refused_by_name() {
    for (name, run) in METHODS {
        match run(-1e308, 1e308) {
            Err(Error::InvalidInput { what: "t0/t1", .. }) => {}
            other => panic!("{name}: {other:?}"),
        }
    }
}
