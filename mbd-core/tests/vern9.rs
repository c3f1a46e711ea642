//! Vern9 against independent truths: the asymptotic orders of the method (9) and of its
//! interpolant (9, local error O(h^10)), the tolerance proportionality, the pendulum's
//! Jacobi-elliptic solution, event location, projection, the stiffness option, the
//! recording's counts and the automatic choice. (No count-for-count reference run is
//! published for this pair as Hairer's are for DOPRI5 and DOP853.)

use mbd_core::Vector;
use mbd_core::integrate::{Integrator, Options, Record, Vern9};
use std::f64::consts::PI;

mod pairs;
use pairs::{
    at_tol, fixed_steps, log_log_slope, one_step, pendulum, pendulum_exact, pendulum_worst,
    van_der_pol,
};

/// Fixed steps (tolerance too loose to reject, `h_max = h`) on the pendulum over 2 s: the
/// end error falls at least as h^9. Measured: slope 10.3 over h = 0.4, 0.2, 0.1 (3.2e-6,
/// 2.2e-9, 2.0e-12; the next halving is at rounding); the pair's tenth-order error terms are small by
/// design ("most efficient"), so the h^9 term the order conditions leave
/// (`vern9_tableau_has_orders_9_8`) does not dominate above rounding.
#[test]
fn vern9_converges_with_order_9() {
    let hs = [0.4, 0.2, 0.1];
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let y = fixed_steps(
                Vern9::new,
                &pendulum(),
                Vector::<2>::new(PI / 3.0, 0.0),
                2.0,
                h,
            );
            (y[0] - pendulum_exact(2.0)).abs()
        })
        .collect();
    let slope = log_log_slope(&hs, &errs);
    println!("Vern9 fixed-step slope {slope}, errors {errs:?}");
    assert!(
        slope > 8.7 && slope < 10.7,
        "slope {slope}, errors {errs:?}"
    );
}

/// The ninth-order interpolant has local error O(h^10) inside one step from the exact
/// state (Hairer–Nørsett–Wanner I, Sect. II.6), on the pendulum.
#[test]
fn vern9_interpolant_has_local_order_10() {
    let hs = [0.4, 0.2, 0.1];
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let sol = one_step(Vern9::new, &pendulum(), Vector::<2>::new(PI / 3.0, 0.0), h);
            (1..10)
                .map(|i| {
                    let t = h * f64::from(i) / 10.0;
                    (sol.at(t).unwrap()[0] - pendulum_exact(t)).abs()
                })
                .fold(0.0, f64::max)
        })
        .collect();
    let slope = log_log_slope(&hs, &errs);
    println!("Vern9 dense slope {slope}, errors {errs:?}");
    assert!((slope - 10.0).abs() < 0.4, "slope {slope}, errors {errs:?}");
}

/// Tolerance proportionality: the global error scales like tol^(9/9) = tol^1 (slope
/// 1 +- 0.2 over tol = 1e-4 ... 1e-12).
#[test]
fn vern9_global_error_is_proportional_to_tolerance() {
    let slope = pairs::tolerance_slope("Vern9", Vern9::new);
    assert!((slope - 1.0).abs() < 0.2, "slope {slope}");
}

/// theta'' = -(g/l) sin theta from rest at 60 deg against the Jacobi-elliptic solution over
/// 10 s, largest error over the interpolant at 1001 points: within 1.5 tol at
/// `rtol = atol = 1e-9 .. 1e-11` (so below 1e-10 at 1e-11), within 4 tol at 1e-12.
#[test]
fn vern9_pendulum_matches_the_elliptic_solution() {
    let y0 = Vector::<2>::new(PI / 3.0, 0.0);
    for tol in [1e-9, 1e-10, 1e-11, 1e-12] {
        let sol = Vern9::new(at_tol(tol))
            .solve(&pendulum(), 0.0, y0, 10.0, &[])
            .unwrap();
        let e = pendulum_worst(&sol);
        println!("Vern9 tol {tol:e}: {e:e} with {} calls", sol.stats.n_rhs);
        // Measured 1.04, 1.38, 1.48 and 3.5 tol (the last with the interpolant's
        // rounding, about 1e-12 of `h |f|`, in it).
        let bound = if tol < 1e-11 { 4.0 * tol } else { 1.5 * tol };
        assert!(e < bound, "tol {tol:e}: {e:e}");
    }
}

/// The ball's crossings of z = 15 m at 1e-10 ([`pairs::locates_the_balls_crossings`]), with
/// steps of at most 0.5 s: on the ball (a quadratic, no error to control) the steps would
/// grow to the whole flight, and the interpolant's rounding (its weights are polynomials
/// with coefficients up to 1e4, so about 1e-12 of `h |f|`) would then be 1e-11 of the
/// crossing time.
#[test]
fn vern9_locates_events() {
    let capped = Vern9::new(Options {
        h_max: Some(0.5),
        ..at_tol(1e-10)
    });
    pairs::locates_the_balls_crossings(&capped);
}

/// Projection onto the unit circle after every step ([`pairs::projects_onto_the_circle`]):
/// fifteen calls per attempted step, one per accepted step, one per projection that moved.
#[test]
fn vern9_projects_after_each_accepted_step() {
    pairs::projects_onto_the_circle(Vern9::new, 15);
}

/// Van der Pol with eps = 1e-6 is very stiff ([`pairs::stiffness_detection_is_an_option`]):
/// Vern9 at 1e-6 from (2, 0) stops with `Error::Stiff`, or with the test off at the step limit.
#[test]
fn vern9_stiffness_detection_is_an_option() {
    pairs::stiffness_detection_is_an_option(|check| {
        Vern9::new(Options {
            stiffness_check: check,
            dense: false,
            record: Record::Final,
            ..at_tol(1e-6)
        })
        .solve(
            &van_der_pol(1e-6),
            0.0,
            Vector::<2>::new(2.0, 0.0),
            2.0,
            &[],
        )
    });
}

/// With output times alone (no dense output, events or observer), a step that would hold
/// one output time, at `theta >= 7/16` of it, ends there instead (the progress given up
/// costs fewer than the interpolant's nine calls) when it is no longer than 25/16 of the
/// spacing to the next output time, and the step after it is the one it replaced (or
/// longer, as the short step's error allows). On `y' = (1, t)` (a polynomial the method and its interpolant reproduce, so
/// every error estimate is rounding and every step the largest, `h_max = 1`) from `h0 = 1`,
/// times 0.3, 1.5, 2.9 over [0, 4], the steps are worked out by hand:
/// [0, 1] holds 0.3 at theta 0.3 (interpolated, nine calls); [1, 1.5] ends on 1.5 (theta
/// 0.5 of [1, 2]); [1.5, 2.5] holds nothing (2.9 lies beyond); [2.5, 3.5] holds 2.9 at
/// theta 0.4 (interpolated); [3.5, 4] is the last. Calls: `f(t0)`, 16 per step, 9 twice.
/// Recorded only at the end, the same run takes [0, 1], [1, 2], [2, 3], [3, 4].
#[test]
fn vern9_ends_steps_on_output_times_where_that_is_cheaper() {
    let ramp = pairs::Ode(|t: f64, _y: &Vector<2>| Vector::<2>::new(1.0, t));
    let run = |record| {
        Vern9::new(Options {
            record,
            dense: false,
            h0: Some(1.0),
            h_max: Some(1.0),
            ..at_tol(1e-6)
        })
        .solve(&ramp, 0.0, Vector::<2>::zeros(), 4.0, &[])
        .unwrap()
    };
    let times = run(Record::Times(vec![0.3, 1.5, 2.9]));
    assert_eq!(times.stats.n_accepted, 5);
    assert_eq!(times.stats.n_rejected, 0);
    assert_eq!(times.stats.n_rhs, 1 + 5 * 16 + 2 * 9);
    assert_eq!(times.t, [0.0, 0.3, 1.5, 2.9, 4.0]);
    // Step ends to rounding; interpolated values to the interpolant's rounding, about
    // 1e-12 of `h |f|` (its weights reach 1e4), here `h = 1`, `|f| <= 4`.
    for (t, y) in times.t.iter().zip(&times.y) {
        let err = (y[0] - t).abs().max((y[1] - t * t / 2.0).abs());
        assert!(err <= 4e-12, "{t}: {y}");
    }
    let fin = run(Record::Final);
    assert_eq!(fin.stats.n_accepted, 4);
    assert_eq!(fin.stats.n_rhs, 1 + 4 * 16);
}

/// On the oscillator over 10 s with an output time every 0.5 at 1e-9 (steps of about 0.36,
/// so a step holds at most one, as on the time-to-accuracy table's grids): the recorded
/// states are within the tolerance of `(cos t, -sin t)`, and ending steps on output times
/// costs fewer calls than interpolating in every step that holds one (the `Record::Steps`
/// run's steps plus nine calls for each that holds an output time): 611 against 621. With
/// an output time every 0.25 the two cost about the same (685 against 684): the rule
/// weighs one step and the spacing, not the phase of the steps after it.
#[test]
fn vern9_output_times_are_accurate_and_cheaper_than_interpolating_all() {
    let sys = pairs::oscillator();
    let y0 = Vector::<2>::new(1.0, 0.0);
    let run = |record| {
        Vern9::new(Options {
            record,
            dense: false,
            ..at_tol(1e-9)
        })
        .solve(&sys, 0.0, y0, 10.0, &[])
        .unwrap()
    };
    let times: Vec<f64> = (0..=20).map(|i| 0.5 * f64::from(i)).collect();
    let at_times = run(Record::Times(times.clone()));
    assert_eq!(at_times.t, times);
    for (t, y) in at_times.t.iter().zip(&at_times.y) {
        let err = (y - pairs::oscillator_exact(*t)).amax();
        assert!(err <= 1e-9, "t = {t}: {err:e}");
    }
    let steps = run(Record::Steps);
    let inside = steps
        .t
        .windows(2)
        .filter(|w| times.iter().any(|&t| w[0] < t && t < w[1]))
        .count();
    let interpolating_all = steps.stats.n_rhs + 9 * inside;
    println!("{} calls against {interpolating_all}", at_times.stats.n_rhs);
    assert!(at_times.stats.n_rhs < interpolating_all);
}

/// `Auto` runs Vern9 at rtol <= 1e-11, DOP853 up to 1e-4: its solution equals the chosen
/// method's, step for step.
#[test]
fn auto_picks_vern9_for_the_tightest_tolerances() {
    pairs::auto_picks(&[(1e-11, "VERN9"), (1e-12, "VERN9"), (1e-10, "DOP853")]);
}

/// The run ends at `t1` exactly where the last step's `t + h` rounds past it
/// ([`pairs::ends_exactly_at_t1`]).
#[test]
fn vern9_ends_exactly_at_t1() {
    pairs::ends_exactly_at_t1(Vern9::new);
}
