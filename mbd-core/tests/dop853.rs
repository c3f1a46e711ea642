//! DOP853 against independent truths: Hairer's published `dop853.f` runs on the van der
//! Pol oscillator (counts and final state), the asymptotic orders of the method and of its
//! dense output, closed-form solutions (oscillator, ballistic flight, the pendulum's
//! Jacobi-elliptic solution), event location, projection and the stiffness option.
#![allow(
    clippy::excessive_precision,
    reason = "dop853.f's printed digits, rounded by the compiler"
)]

use mbd_core::integrate::{Dop853, Dopri5, Integrator, Options};
use mbd_core::{Error, Vector};
use std::f64::consts::PI;

mod pairs;
use pairs::{
    at_tol, fixed_steps, log_log_slope, one_step, oscillator, oscillator_exact, pendulum,
    pendulum_worst, van_der_pol,
};

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
            let y = fixed_steps(
                Dop853::new,
                &oscillator(),
                Vector::<2>::new(1.0, 0.0),
                8.0,
                h,
            );
            (y - oscillator_exact(8.0)).amax()
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
            let sol = one_step(Dop853::new, &oscillator(), Vector::<2>::new(1.0, 0.0), h);
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
    let slope = pairs::tolerance_slope("DOP853", Dop853::new);
    assert!((slope - 1.0).abs() < 0.2, "slope {slope}");
}

// ---------------------------------------------------------------------------------------
// Exact solutions

/// theta'' = -(g/l) sin theta from rest at 60 deg against the Jacobi-elliptic solution over
/// 10 s (about 5 periods), largest error over the dense output sampled at 1001 points.
/// DOP853 at rtol = atol = 1e-11 and DOPRI5 at 1e-12 (the tolerance it needs for 1e-10)
/// both stay below 1e-10; DOP853 does it with less than half of DOPRI5's calls.
#[test]
fn dop853_pendulum_matches_the_elliptic_solution() {
    let y0 = Vector::<2>::new(PI / 3.0, 0.0);
    let sol8 = Dop853::new(at_tol(1e-11))
        .solve(&pendulum(), 0.0, y0, 10.0, &[])
        .unwrap();
    let sol5 = Dopri5::new(at_tol(1e-12))
        .solve(&pendulum(), 0.0, y0, 10.0, &[])
        .unwrap();
    let (e8, e5) = (pendulum_worst(&sol8), pendulum_worst(&sol5));
    let (n8, n5) = (sol8.stats.n_rhs, sol5.stats.n_rhs);
    println!("DOP853 {e8:e} with {n8} calls, DOPRI5 {e5:e} with {n5} calls");
    assert!(e8 < 1e-10 && e5 < 1e-10, "{e8:e} {e5:e}");
    assert!(2 * n8 < n5, "{n8} vs {n5}");
}

// ---------------------------------------------------------------------------------------
// Events and projection

/// The ball's crossings of z = 15 m at 1e-10 ([`pairs::locates_the_balls_crossings`]): the
/// terminal event to 1e-12 relative, and both crossings of its non-terminal twin.
#[test]
fn dop853_locates_events() {
    pairs::locates_the_balls_crossings(&Dop853::new(at_tol(1e-10)));
}

/// Projection onto the unit circle after every step ([`pairs::projects_onto_the_circle`]):
/// eleven calls per attempted step, one per accepted step, one per projection that moved.
#[test]
fn dop853_projects_after_each_accepted_step() {
    pairs::projects_onto_the_circle(Dop853::new, 11);
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
    pairs::stiffness_detection_is_an_option(run);
    assert!(matches!(run(Some(1)), Err(Error::Stiff { .. })));
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
    pairs::auto_picks(&[(1e-3, "DOPRI5"), (1e-4, "DOP853"), (1e-10, "DOP853")]);
}

/// With `Record::Times`, only the steps with an output time strictly inside them build the
/// seventh-order segment, three more calls each
/// ([`pairs::output_times_build_only_the_segments_they_need`]).
#[test]
fn dop853_output_times_build_only_the_segments_they_need() {
    let method = |record, dense| {
        Dop853::new(Options {
            record,
            dense,
            ..at_tol(1e-9)
        })
    };
    pairs::output_times_build_only_the_segments_they_need(method, 3);
}

/// The run ends at `t1` exactly where the last step's `t + h` rounds past it
/// ([`pairs::ends_exactly_at_t1`]).
#[test]
fn dop853_ends_exactly_at_t1() {
    pairs::ends_exactly_at_t1(Dop853::new);
}
