//! DOP853 against independent truths: Hairer's published `dop853.f` runs on the van der
//! Pol oscillator (counts and final state), the asymptotic orders of the method and of its
//! dense output, closed-form solutions (oscillator, ballistic flight, the pendulum's
//! Jacobi-elliptic solution), event location, projection and the stiffness option.
#![allow(
    clippy::excessive_precision,
    reason = "dop853.f's printed digits, rounded by the compiler"
)]

use mbd_core::integrate::{
    Direction, Dop853, Dopri5, Event, Integrator, Options, Record, Solution,
};
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

/// x'' = -x: x = cos t from (1, 0).
fn oscillator() -> Ode<impl Fn(f64, &Vector<2>) -> Vector<2>> {
    Ode(|_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -y[0]))
}

fn oscillator_exact(t: f64) -> Vector<2> {
    Vector::<2>::new(t.cos(), -t.sin())
}

/// Van der Pol in Hairer's scaled form: y1' = y2, y2' = ((1 - y1^2) y2 - y1) / eps.
fn van_der_pol(eps: f64) -> Ode<impl Fn(f64, &Vector<2>) -> Vector<2>> {
    Ode(move |_t: f64, y: &Vector<2>| {
        Vector::<2>::new(y[1], ((1.0 - y[0] * y[0]) * y[1] - y[0]) / eps)
    })
}

fn dop853(rtol: f64, atol: f64) -> Dop853 {
    Dop853::new(Options {
        rtol,
        atol,
        ..Options::default()
    })
}

/// Least-squares slope of log(err) against log(x).
fn log_log_slope(x: &[f64], err: &[f64]) -> f64 {
    let n = x.len() as f64;
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let le: Vec<f64> = err.iter().map(|v| v.ln()).collect();
    let (mx, me) = (lx.iter().sum::<f64>() / n, le.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&le).map(|(a, b)| (a - mx) * (b - me)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

// ---------------------------------------------------------------------------------------
// Controller fidelity: Hairer's dop853.f on van der Pol

/// `dop853.f` on van der Pol, eps = 0.003, y0 = (2, 0), [0, 2], RTOL = ATOL = 1e-3,
/// H = 1e-4, no dense output: 235 steps (215 accepted, 20 rejected), NFCN = 2802, ending at
/// y = (1.819907445729370, -7.866363461162956e-1) (the output of dop853.f quoted by
/// cpmech/russell, `russell_ode/tests/test_dopri8_van_der_pol_debug.rs`). NFCN counts two
/// calls at t0 where one is made (the second is for the initial step guess, not called
/// when H is given): 2802 = 2 + 11 * 235 + 215, so our count is 2801.
#[test]
fn dop853_reproduces_hairers_van_der_pol_run() {
    let solver = Dop853::new(Options {
        rtol: 1e-3,
        atol: 1e-3,
        h0: Some(1e-4),
        dense: false,
        ..Options::default()
    });
    let sol = solver
        .solve(
            &van_der_pol(0.003),
            0.0,
            Vector::<2>::new(2.0, 0.0),
            2.0,
            &[],
        )
        .unwrap();
    let s = sol.stats;
    assert_eq!(
        (s.n_rhs, s.n_steps, s.n_accepted, s.n_rejected),
        (2802 - 1, 235, 215, 20)
    );
    let (t, y) = sol.last();
    assert_eq!(t, 2.0);
    assert!((y[0] - 1.819907445729370).abs() < 1e-9, "{}", y[0]);
    assert!((y[1] + 7.866363461162956e-1).abs() < 1e-8, "{}", y[1]);
}

/// The same with eps = 1e-3, H = 1e-6, RTOL = ATOL = 1e-9 and dense output on (three more
/// calls per accepted step): 1469 steps (1348 accepted, 121 rejected),
/// NFCN = 21553 = 2 + 11 * 1469 + 4 * 1348, y = (1.763234540172087, -8.356886819301910e-1)
/// (`russell_ode/tests/test_dopri8_van_der_pol.rs`, the output of dop853.f).
#[test]
fn dop853_reproduces_hairers_dense_van_der_pol_run() {
    let solver = Dop853::new(Options {
        rtol: 1e-9,
        atol: 1e-9,
        h0: Some(1e-6),
        ..Options::default()
    });
    let sol = solver
        .solve(
            &van_der_pol(1e-3),
            0.0,
            Vector::<2>::new(2.0, 0.0),
            2.0,
            &[],
        )
        .unwrap();
    let s = sol.stats;
    assert_eq!(
        (s.n_rhs, s.n_steps, s.n_accepted, s.n_rejected),
        (21553 - 1, 1469, 1348, 121)
    );
    assert_eq!(sol.segments.len(), 1348);
    let (_, y) = sol.last();
    assert!((y[0] - 1.763234540172087).abs() < 1e-12, "{}", y[0]);
    assert!((y[1] + 8.356886819301910e-1).abs() < 1e-11, "{}", y[1]);
}

// ---------------------------------------------------------------------------------------
// Orders

/// Fixed steps (h0 = h_max = h, tolerances so loose that every step is accepted at h_max):
/// the global error at t = 8 on the oscillator is O(h^8) (the weights satisfy the order
/// conditions of order 8; Hairer–Nørsett–Wanner I, Thm. II.3.6).
#[test]
fn dop853_converges_with_order_8() {
    let hs = [0.8, 0.4, 0.2];
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let solver = Dop853::new(Options {
                rtol: 1e3,
                atol: 1e3,
                h0: Some(h),
                h_max: Some(h),
                dense: false,
                ..Options::default()
            });
            let sol = solver
                .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), 8.0, &[])
                .unwrap();
            assert_eq!(sol.stats.n_rejected, 0);
            assert_eq!(sol.stats.n_accepted, (8.0 / h).round() as usize);
            (sol.last().1 - oscillator_exact(8.0)).amax()
        })
        .collect();
    let slope = log_log_slope(&hs, &errs);
    println!("DOP853 fixed-step slope {slope}, errors {errs:?}");
    assert!((slope - 8.0).abs() < 0.3, "slope {slope}, errors {errs:?}");
}

/// The seventh-order dense output has local error O(h^8) inside one step from the exact
/// state (Hairer–Nørsett–Wanner I, Sect. II.6).
#[test]
fn dop853_dense_output_has_order_7() {
    let hs = [0.8, 0.4, 0.2];
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let solver = Dop853::new(Options {
                rtol: 1e3,
                atol: 1e3,
                h0: Some(h),
                ..Options::default()
            });
            let sol = solver
                .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), h, &[])
                .unwrap();
            assert_eq!(sol.segments.len(), 1);
            assert_eq!(sol.segments[0].eval_theta(0.0), Vector::<2>::new(1.0, 0.0));
            (1..10)
                .map(|i| {
                    let t = h * i as f64 / 10.0;
                    (sol.at(t).unwrap() - oscillator_exact(t)).amax()
                })
                .fold(0.0, f64::max)
        })
        .collect();
    let slope = log_log_slope(&hs, &errs);
    println!("DOP853 dense slope {slope}, errors {errs:?}");
    assert!((slope - 8.0).abs() < 0.3, "slope {slope}, errors {errs:?}");
}

/// Tolerance proportionality: the controller keeps an error of order 8 near tol, so the
/// global error scales like tol^1 (slope 1 +- 0.2 over tol = 1e-4 ... 1e-12).
#[test]
fn dop853_global_error_is_proportional_to_tolerance() {
    let tols: Vec<f64> = (4..=12).map(|k| 10f64.powi(-k)).collect();
    let errs: Vec<f64> = tols
        .iter()
        .map(|&tol| {
            let sol = dop853(tol, tol)
                .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), 20.0, &[])
                .unwrap();
            (sol.last().1 - oscillator_exact(20.0)).amax()
        })
        .collect();
    let slope = log_log_slope(&tols, &errs);
    println!("DOP853 tolerance slope {slope}, errors {errs:?}");
    assert!((slope - 1.0).abs() < 0.2, "slope {slope}, errors {errs:?}");
}

// ---------------------------------------------------------------------------------------
// Exact solutions

/// theta'' = -(g/l) sin theta from rest at 60 deg against the Jacobi-elliptic solution over
/// 10 s (about 5 periods), largest error over the dense output sampled at 1001 points.
/// DOP853 at rtol = atol = 1e-11 and DOPRI5 at 1e-12 (the tolerance it needs for 1e-10)
/// both stay below 1e-10; DOP853 does it with less than half of DOPRI5's calls.
#[test]
fn dop853_pendulum_matches_the_elliptic_solution() {
    let w2 = 9.81;
    let pendulum = Ode(move |_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -w2 * y[0].sin()));
    let theta0 = PI / 3.0;
    let y0 = Vector::<2>::new(theta0, 0.0);
    let worst = |sol: &Solution<2>| {
        (0..=1000)
            .map(|i| {
                let t = 10.0 * i as f64 / 1000.0;
                (sol.at(t).unwrap()[0] - pendulum_angle(w2.sqrt(), theta0, t)).abs()
            })
            .fold(0.0, f64::max)
    };
    let sol8 = dop853(1e-11, 1e-11)
        .solve(&pendulum, 0.0, y0, 10.0, &[])
        .unwrap();
    let sol5 = Dopri5::new(Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    })
    .solve(&pendulum, 0.0, y0, 10.0, &[])
    .unwrap();
    let (e8, e5) = (worst(&sol8), worst(&sol5));
    let (n8, n5) = (sol8.stats.n_rhs, sol5.stats.n_rhs);
    println!("DOP853 {e8:e} with {n8} calls, DOPRI5 {e5:e} with {n5} calls");
    assert!(e8 < 1e-10 && e5 < 1e-10, "{e8:e} {e5:e}");
    assert!(2 * n8 < n5, "{n8} vs {n5}");
}

// ---------------------------------------------------------------------------------------
// Events and projection

const G: f64 = 9.807;
const V0: f64 = 25.0;

/// A ball thrown up at 25 m/s stops (terminal event) where it falls through 15 m, at
/// t = v0/g + sqrt(2 (v0^2/(2g) - 15) / g), to 1e-12 relative; the state is z = 15,
/// v = v0 - g t; a non-terminal twin sees both crossings and runs to the end.
#[test]
fn dop853_locates_events() {
    let ball = Ode(|_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -G));
    let apex = V0 / G;
    let d = (2.0 * (V0 * V0 / (2.0 * G) - 15.0) / G).sqrt();
    let (t_rise, t_fall) = (apex - d, apex + d);
    let at_15 = |dir| Event::new("z = 15", |_t, y: &Vector<2>| y[0] - 15.0, dir);
    let y0 = Vector::<2>::new(0.0, V0);
    let stop = dop853(1e-10, 1e-10)
        .solve(&ball, 0.0, y0, 6.0, &[at_15(Direction::Falling).terminal()])
        .unwrap();
    assert_eq!(stop.stopped_by, Some(0));
    let hit = &stop.events[0];
    assert!(((hit.t - t_fall) / t_fall).abs() < 1e-12, "{}", hit.t);
    assert!((hit.y[0] - 15.0).abs() < 1e-11);
    assert!((hit.y[1] - (V0 - G * t_fall)).abs() < 1e-11);
    assert_eq!(stop.last(), (hit.t, &hit.y));
    let both = dop853(1e-10, 1e-10)
        .solve(&ball, 0.0, y0, 6.0, &[at_15(Direction::Either)])
        .unwrap();
    let times: Vec<f64> = both.events.iter().map(|e| e.t).collect();
    assert_eq!(times.len(), 2);
    assert!(((times[0] - t_rise) / t_rise).abs() < 1e-12);
    assert!(((times[1] - t_fall) / t_fall).abs() < 1e-12);
    assert_eq!(both.last().0, 6.0);
}

/// Uniform rotation projected back onto the unit circle after every step: accepted states
/// lie on the circle to rounding, the solution is still (cos t, sin t), and each step that
/// the projection moved costs one more call (the next step's first stage at the new state).
#[test]
fn dop853_projects_after_each_accepted_step() {
    struct Circle;
    impl OdeSystem<2> for Circle {
        fn rhs(&self, _t: f64, y: &Vector<2>) -> Result<Vector<2>> {
            Ok(Vector::<2>::new(-y[1], y[0]))
        }
        fn project(&self, _t: f64, y: &mut Vector<2>) -> Result<()> {
            *y /= y.norm();
            Ok(())
        }
    }
    let solver = Dop853::new(Options {
        rtol: 1e-6,
        atol: 1e-6,
        dense: false,
        ..Options::default()
    });
    let sol = solver
        .solve(&Circle, 0.0, Vector::<2>::new(1.0, 0.0), 20.0, &[])
        .unwrap();
    for y in &sol.y {
        assert!((y.norm() - 1.0).abs() < 4.0 * f64::EPSILON);
    }
    let (t, y) = sol.last();
    assert!((y - Vector::<2>::new(t.cos(), t.sin())).amax() < 1e-5);
    let s = sol.stats;
    let base = 2 + 11 * s.n_steps + s.n_accepted;
    assert!(s.n_rhs > base && s.n_rhs <= base + s.n_accepted);
}

// ---------------------------------------------------------------------------------------
// Stiffness option

/// Van der Pol with eps = 1e-6 is very stiff. With Hairer's test every 1000 accepted steps
/// DOP853 stops with `Error::Stiff`; with the test off it runs on into the step limit.
#[test]
fn dop853_stiffness_detection_is_an_option() {
    let y0 = Vector::<2>::new(2.0, -0.66);
    let run = |stiffness_check| {
        Dop853::new(Options {
            max_steps: 20_000,
            stiffness_check,
            dense: false,
            ..Options::default()
        })
        .solve(&van_der_pol(1e-6), 0.0, y0, 2.0, &[])
    };
    assert!(matches!(run(Some(1000)), Err(Error::Stiff { .. })));
    assert!(matches!(run(Some(1)), Err(Error::Stiff { .. })));
    assert!(matches!(run(None), Err(Error::TooManySteps { .. })));
    assert!(matches!(
        run(Some(0)),
        Err(Error::InvalidInput {
            what: "stiffness_check",
            ..
        })
    ));
}

// ---------------------------------------------------------------------------------------
// The automatic choice

/// `Auto` runs DOP853 at 1e-11 < rtol <= 1e-4 and DOPRI5 above, with the options given: its
/// solution equals the chosen method's, step for step.
#[test]
fn auto_picks_dop853_for_tight_tolerances() {
    use mbd_core::integrate::Auto;
    let y0 = Vector::<2>::new(1.0, 0.0);
    for (tol, name) in [(1e-3, "DOPRI5"), (1e-4, "DOP853"), (1e-10, "DOP853")] {
        let o = Options {
            rtol: tol,
            atol: tol,
            ..Options::default()
        };
        let auto = Auto::new(o.clone());
        assert_eq!(auto.name(), name);
        let a = auto.solve(&oscillator(), 0.0, y0, 5.0, &[]).unwrap();
        let b = if name == "DOP853" {
            Dop853::new(o)
                .solve(&oscillator(), 0.0, y0, 5.0, &[])
                .unwrap()
        } else {
            Dopri5::new(o)
                .solve(&oscillator(), 0.0, y0, 5.0, &[])
                .unwrap()
        };
        assert_eq!(a.stats, b.stats);
        assert_eq!(a.last(), b.last());
    }
}

/// With `Record::Times`, only the steps with an output time strictly inside them build the
/// seventh-order segment (three more calls each): the count is the `Record::Final` run's
/// plus three per such step, the steps being those of the same run recorded every step
/// (the step sequence does not depend on what is recorded), and the recorded states are
/// the dense run's segments evaluated at those times, bit for bit.
#[test]
fn dop853_output_times_build_only_the_segments_they_need() {
    let sys = oscillator();
    let y0 = Vector::<2>::new(1.0, 0.0);
    let run = |record: Record, dense: bool| {
        Dop853::new(Options {
            rtol: 1e-9,
            atol: 1e-9,
            record,
            dense,
            ..Options::default()
        })
        .solve(&sys, 0.0, y0, 10.0, &[])
        .unwrap()
    };
    // Output times between steps, at step ends and at t0 / t1.
    let times: Vec<f64> = (0..=40).map(|i| 0.25 * f64::from(i)).collect();
    let steps = run(Record::Steps, false);
    let final_only = run(Record::Final, false);
    let at_times = run(Record::Times(times.clone()), false);
    let dense = run(Record::Steps, true);
    let inside = steps
        .t
        .windows(2)
        .filter(|w| times.iter().any(|&t| w[0] < t && t < w[1]))
        .count();
    assert!(inside > 0 && inside < steps.t.len() - 1, "{inside}");
    assert_eq!(final_only.stats.n_rhs, steps.stats.n_rhs);
    assert_eq!(at_times.stats.n_rhs, final_only.stats.n_rhs + 3 * inside);
    assert_eq!(at_times.t, times);
    for (t, y) in at_times.t.iter().zip(&at_times.y) {
        assert_eq!(dense.at(*t).unwrap(), *y, "t = {t}");
    }
}
