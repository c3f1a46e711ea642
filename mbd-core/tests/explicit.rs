//! RK4 and DOPRI5 against independent truths: closed-form solutions (harmonic oscillator,
//! ballistic flight, the pendulum's Jacobi-elliptic solution), Hairer's published `dopri5.f`
//! run on the Arenstorf orbit, and the asymptotic orders the theory predicts.

use mbd_core::integrate::{Direction, Dopri5, Event, Integrator, Options, Rk4, Solution};
use mbd_core::{Error, Result, Vector};
use std::cell::Cell;
use std::f64::consts::PI;

mod pairs;
use pairs::exact::{elliptic_k, jacobi_sn, pendulum_angle};
use pairs::{Ode, log_log_slope, oscillator, oscillator_exact};

fn dopri5(rtol: f64, atol: f64) -> Dopri5 {
    Dopri5::new(Options {
        rtol,
        atol,
        ..Options::default()
    })
}

// ---------------------------------------------------------------------------------------
// Orders

/// RK4's global error is O(h^4) (Hairer–Nørsett–Wanner I, Thm. II.3.6): fixed steps
/// h = 0.5 ... 0.5/32 on [0, 10], error at t = 10 against cos t.
#[test]
fn rk4_converges_with_order_4() {
    let hs: Vec<f64> = (0..6).map(|i| 0.5 / 2f64.powi(i)).collect();
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let sol = Rk4::new(h)
                .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), 10.0, &[])
                .unwrap();
            let (t, y) = sol.last();
            assert_eq!(t, 10.0);
            assert_eq!(sol.stats.n_steps, (10.0 / h).round() as usize);
            (y - oscillator_exact(10.0)).amax()
        })
        .collect();
    let slope = log_log_slope(&hs, &errs);
    assert!((slope - 4.0).abs() < 0.2, "slope {slope}, errors {errs:?}");
}

/// Tolerance proportionality of DOPRI5. The controller keeps the embedded (order 4) local
/// error estimate, which is O(h^5), near tol, so h ~ tol^(1/5); the propagated solution is
/// of order 5, so the global error is O(h^5) ~ tol^(5/5) = tol^1 (Hairer–Nørsett–Wanner I,
/// Sect. II.4, "tolerance proportionality"). The fitted slope over tol = 1e-3 ... 1e-11
/// must be within 1 +- 0.2; the band allows for the non-asymptotic loose end and the
/// integer number of steps, not for a different exponent (order-4 error per unit step
/// would give 4/5 at the edge, order-6 local error with no extrapolation 6/5).
#[test]
fn dopri5_global_error_is_proportional_to_tolerance() {
    let tols: Vec<f64> = (3..=11).map(|k| 10f64.powi(-k)).collect();
    let errs: Vec<f64> = tols
        .iter()
        .map(|&tol| {
            let sol = dopri5(tol, tol)
                .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), 20.0, &[])
                .unwrap();
            (sol.last().1 - oscillator_exact(20.0)).amax()
        })
        .collect();
    let slope = log_log_slope(&tols, &errs);
    println!("tolerance proportionality slope {slope}, errors {errs:?}");
    assert!((slope - 1.0).abs() < 0.2, "slope {slope}, errors {errs:?}");
}

// ---------------------------------------------------------------------------------------
// Controller fidelity: Hairer's dopri5.f on the Arenstorf orbit

/// Initial y2' and period of the Arenstorf orbit, as published (Hairer–Nørsett–Wanner I,
/// Sect. II.0, eq. (0.2)); y(0) = (0.994, 0, 0, y2'(0)).
#[allow(
    clippy::excessive_precision,
    reason = "the published digits, rounded by the compiler"
)]
const ARENSTORF_V0: f64 = -2.00158510637908252240537862224;
#[allow(
    clippy::excessive_precision,
    reason = "the published digits, rounded by the compiler"
)]
const ARENSTORF_PERIOD: f64 = 17.0652165601579625588917206249;

/// The restricted three-body problem (Hairer–Nørsett–Wanner I, Sect. II.0, eq. (0.1)),
/// y = (y1, y2, y1', y2'), mu = 0.012277471.
fn arenstorf() -> Ode<impl Fn(f64, &Vector<4>) -> Vector<4>> {
    const MU: f64 = 0.012277471;
    const MU1: f64 = 1.0 - MU;
    Ode(|_t: f64, y: &Vector<4>| {
        let d1 = ((y[0] + MU).powi(2) + y[1].powi(2)).powf(1.5);
        let d2 = ((y[0] - MU1).powi(2) + y[1].powi(2)).powf(1.5);
        Vector::<4>::new(
            y[2],
            y[3],
            y[0] + 2.0 * y[3] - MU1 * (y[0] + MU) / d1 - MU * (y[0] - MU1) / d2,
            y[1] - 2.0 * y[2] - MU1 * y[1] / d1 - MU * y[1] / d2,
        )
    })
}

/// `dopri5.f` with RTOL = ATOL = 1e-7 and H = 1e-4 over one period of the Arenstorf orbit
/// takes 238 steps (217 accepted, 21 rejected) and 1429 function calls (one at t0 plus six
/// per step), ending at y = (0.9940021704030663, 9.040891036151961e-6,
/// 1.459758305600828e-3, -2.001245515834718) (the output of dopri5.f quoted by
/// cpmech/russell, `russell_ode/tests/test_dopri5_arenstorf_debug.rs`). Matching the counts
/// exactly checks every decision of the controller; the state agrees to rounding effects.
#[test]
fn dopri5_reproduces_hairers_arenstorf_run() {
    let solver = Dopri5::new(Options {
        rtol: 1e-7,
        atol: 1e-7,
        h0: Some(1e-4),
        ..Options::default()
    });
    let y0 = Vector::<4>::new(0.994, 0.0, 0.0, ARENSTORF_V0);
    let period = ARENSTORF_PERIOD;
    let sol = solver.solve(&arenstorf(), 0.0, y0, period, &[]).unwrap();
    let s = sol.stats;
    assert_eq!(
        (s.n_rhs, s.n_steps, s.n_accepted, s.n_rejected),
        (1429, 238, 217, 21)
    );
    let (t, y) = sol.last();
    assert_eq!(t, period);
    let hairer = [
        9.940021704030663e-01,
        9.040891036151961e-06,
        1.459758305600828e-03,
        -2.001245515834718e+00,
    ];
    // The orbit passes close to the earth, so the last bits of every step's arithmetic
    // (which summation order dopri5.f used) are amplified. Their size is measured here: rerun
    // with one initial component moved by one rounding unit either way. Hairer's state must
    // agree with ours to within that spread, component by component (observed: ~1/5 of it).
    let mut spread = Vector::<4>::zeros();
    for ulp in [1.0, -1.0] {
        let mut moved = y0;
        moved[3] *= 1.0 + ulp * f64::EPSILON;
        let other = solver.solve(&arenstorf(), 0.0, moved, period, &[]).unwrap();
        assert_eq!(other.stats, s);
        spread = spread.sup(&(other.last().1 - y).abs());
    }
    for (i, want) in hairer.iter().enumerate() {
        let diff = (y[i] - want).abs();
        assert!(
            diff <= spread[i],
            "y[{i}] = {} vs {want}: {diff:e} > spread {:e}",
            y[i],
            spread[i]
        );
    }
}

// ---------------------------------------------------------------------------------------
// Pendulum against its elliptic-function solution

/// The reference routines against known values: K(sin 30 deg) = 1.685750354812596
/// (A&S Table 17.1), sn(K) = 1, sn(K/2) = 1/sqrt(1 + k') (A&S 16.5.2), sn(u, 0) = sin u.
#[test]
fn elliptic_reference_matches_known_values() {
    let k = 0.5;
    let kk = elliptic_k(k);
    assert!((kk - 1.685750354812596).abs() < 1e-15);
    assert!((jacobi_sn(kk, k) - 1.0).abs() < 1e-15);
    let kp = (1.0 - k * k).sqrt();
    assert!((jacobi_sn(0.5 * kk, k) - 1.0 / (1.0 + kp).sqrt()).abs() < 1e-15);
    assert!((jacobi_sn(-0.5 * kk, k) + 1.0 / (1.0 + kp).sqrt()).abs() < 1e-15);
    assert!((jacobi_sn(0.7, 0.0) - 0.7f64.sin()).abs() < 1e-15);
}

/// theta'' = -(g/l) sin theta from rest at 60 deg: sin(theta/2) = k sn(K(k) - w t, k),
/// k = sin 30 deg, w = sqrt(g/l) (Lawden, Elliptic Functions and Applications, Sect. 5.2).
#[test]
fn dopri5_pendulum_matches_the_elliptic_solution() {
    let (g, l) = (9.81, 1.0);
    let w2 = g / l;
    let pendulum = Ode(move |_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -w2 * y[0].sin()));
    let theta0 = PI / 3.0;
    let exact = |t: f64| pendulum_angle(w2.sqrt(), theta0, t);
    let sol = dopri5(1e-13, 1e-13)
        .solve(&pendulum, 0.0, Vector::<2>::new(theta0, 0.0), 10.0, &[])
        .unwrap();
    let (t, y) = sol.last();
    assert_eq!(t, 10.0);
    let want = exact(10.0);
    println!("theta(10) = {} vs exact {want}", y[0]);
    assert!(want.abs() > 0.1, "pick a time away from a zero of theta");
    assert!(((y[0] - want) / want).abs() < 1e-10);
}

// ---------------------------------------------------------------------------------------
// Dense output

/// Each DOPRI5 segment ends at its step's y1 (the sum of its coefficients, up to the
/// rounding of that sum), and `at(t_end)` is exactly the last accepted state.
#[test]
fn dopri5_segments_end_at_the_accepted_states() {
    let y0 = Vector::<4>::new(0.994, 0.0, 0.0, ARENSTORF_V0);
    let sol = dopri5(1e-7, 1e-7)
        .solve(&arenstorf(), 0.0, y0, ARENSTORF_PERIOD, &[])
        .unwrap();
    assert_eq!(sol.segments.len(), sol.t.len() - 1);
    for (i, seg) in sol.segments.iter().enumerate() {
        assert_eq!(seg.t0, sol.t[i]);
        let scale: f64 = seg.coeffs.iter().map(|c| c.amax()).sum();
        let gap = (seg.eval_theta(1.0) - sol.y[i + 1]).amax();
        assert!(gap <= 8.0 * f64::EPSILON * scale, "step {i}: {gap}");
        assert_eq!(seg.eval_theta(0.0), sol.y[i]);
    }
    let (t_end, y_end) = sol.last();
    assert_eq!(sol.at(t_end).unwrap(), *y_end);
    assert!(sol.at(t_end + 1e-9).is_none());
    assert!(sol.at(-1e-9).is_none());
}

/// Maximum interpolation error over theta in (0, 1) of one step of size h from the exact
/// state of the oscillator.
fn one_step_dense_error<I: Integrator>(solver: &I, h: f64) -> f64 {
    let sol = solver
        .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), h, &[])
        .unwrap();
    assert_eq!(sol.segments.len(), 1);
    (1..10)
        .map(|i| {
            let t = h * i as f64 / 10.0;
            (sol.at(t).unwrap() - oscillator_exact(t)).amax()
        })
        .fold(0.0, f64::max)
}

/// A dense output of order q has local error O(h^(q+1)) inside a step (Hairer–Nørsett–
/// Wanner I, Sect. II.6): q = 4 for Shampine's DOPRI5 extension, q = 3 for the cubic
/// Hermite of RK4.
#[test]
fn dense_output_has_the_expected_order() {
    let hs = [0.4, 0.2, 0.1, 0.05];
    // One step exactly: h0 = interval, tolerance loose enough to accept it.
    let dp: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let solver = Dopri5::new(Options {
                rtol: 1.0,
                atol: 1.0,
                h0: Some(h),
                ..Options::default()
            });
            one_step_dense_error(&solver, h)
        })
        .collect();
    let slope = log_log_slope(&hs, &dp);
    assert!(
        (slope - 5.0).abs() < 0.2,
        "DOPRI5 dense slope {slope}: {dp:?}"
    );
    let rk: Vec<f64> = hs
        .iter()
        .map(|&h| one_step_dense_error(&Rk4::new(h), h))
        .collect();
    let slope = log_log_slope(&hs, &rk);
    assert!(
        (slope - 4.0).abs() < 0.2,
        "RK4 Hermite slope {slope}: {rk:?}"
    );
}

// ---------------------------------------------------------------------------------------
// Events

const G: f64 = 9.807;
const V0: f64 = 25.0;

/// Height and velocity of a ball thrown up at 25 m/s: y = (z, v), z'' = -g.
fn ball() -> Ode<impl Fn(f64, &Vector<2>) -> Vector<2>> {
    Ode(|_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -G))
}

/// z(t) = 15 at t = v0/g -+ sqrt(2 (v0^2/(2g) - 15) / g): rising, then falling.
fn ball_times() -> (f64, f64) {
    let apex = V0 / G;
    let d = (2.0 * (V0 * V0 / (2.0 * G) - 15.0) / G).sqrt();
    (apex - d, apex + d)
}

fn at_15m<'a>(direction: Direction) -> Event<'a, 2> {
    Event::new("z = 15 m", |_t, y: &Vector<2>| y[0] - 15.0, direction)
}

fn throw(events: &[Event<'_, 2>]) -> Solution<2> {
    dopri5(1e-10, 1e-10)
        .solve(&ball(), 0.0, Vector::<2>::new(0.0, V0), 6.0, events)
        .unwrap()
}

/// A terminal Falling event ends the solution at the closed-form time, to 1e-12 relative;
/// the last state is the event state (z = 15 m, v = -g d).
#[test]
fn terminal_event_stops_at_the_crossing() {
    let (_, t_fall) = ball_times();
    let sol = throw(&[at_15m(Direction::Falling).terminal()]);
    assert_eq!(sol.stopped_by, Some(0));
    assert_eq!(sol.events.len(), 1);
    let hit = &sol.events[0];
    assert!(
        ((hit.t - t_fall) / t_fall).abs() < 1e-12,
        "{} vs {t_fall}",
        hit.t
    );
    assert!((hit.y[0] - 15.0).abs() < 1e-11);
    assert!((hit.y[1] - (V0 - G * t_fall)).abs() < 1e-11);
    let (t, y) = sol.last();
    assert_eq!(t, hit.t);
    assert_eq!(*y, hit.y);
    assert_eq!(sol.at(t).unwrap(), hit.y);
    assert_eq!(sol.segments.last().unwrap().t1(), t);
}

/// A non-terminal event is recorded at both crossings and the integration goes on to t1.
#[test]
fn non_terminal_event_is_recorded_and_integration_continues() {
    let (t_rise, t_fall) = ball_times();
    let sol = throw(&[at_15m(Direction::Either)]);
    assert_eq!(sol.stopped_by, None);
    assert_eq!(sol.last().0, 6.0);
    let times: Vec<f64> = sol.events.iter().map(|e| e.t).collect();
    assert_eq!(times.len(), 2);
    assert!(((times[0] - t_rise) / t_rise).abs() < 1e-12);
    assert!(((times[1] - t_fall) / t_fall).abs() < 1e-12);
}

/// Rising only sees the way up, Falling only the way down; with both registered the hits
/// come in time order with their event indices.
#[test]
fn direction_filters_crossings() {
    let (t_rise, t_fall) = ball_times();
    let up = throw(&[at_15m(Direction::Rising)]);
    assert_eq!(up.events.len(), 1);
    assert!(((up.events[0].t - t_rise) / t_rise).abs() < 1e-12);
    let down = throw(&[at_15m(Direction::Falling)]);
    assert_eq!(down.events.len(), 1);
    assert!(((down.events[0].t - t_fall) / t_fall).abs() < 1e-12);
    let both = throw(&[at_15m(Direction::Falling), at_15m(Direction::Rising)]);
    let order: Vec<usize> = both.events.iter().map(|e| e.event).collect();
    assert_eq!(order, [1, 0]);
}

/// The shared recorder serves RK4 too: the Hermite cubic is exact for the parabola.
#[test]
fn rk4_locates_events_too() {
    let (_, t_fall) = ball_times();
    let sol = Rk4::new(0.1)
        .solve(
            &ball(),
            0.0,
            Vector::<2>::new(0.0, V0),
            6.0,
            &[at_15m(Direction::Falling).terminal()],
        )
        .unwrap();
    assert_eq!(sol.stopped_by, Some(0));
    assert!(((sol.last().0 - t_fall) / t_fall).abs() < 1e-12);
}

// ---------------------------------------------------------------------------------------
// Stiffness and failures

/// Van der Pol in scaled form with eps = 1e-6 is very stiff: DOPRI5's stability bound keeps
/// h below ~3.3e-6 while the solution is smooth, so an explicit run must give up, through
/// the stiffness detector or the step limit, after bounded work.
#[test]
fn dopri5_gives_up_on_stiff_van_der_pol() {
    let calls = Cell::new(0usize);
    let eps = 1e-6;
    let vdp = Ode(|_t: f64, y: &Vector<2>| {
        calls.set(calls.get() + 1);
        Vector::<2>::new(y[1], ((1.0 - y[0] * y[0]) * y[1] - y[0]) / eps)
    });
    let solver = Dopri5::new(Options {
        max_steps: 100_000,
        ..Options::default()
    });
    let result = solver.solve(&vdp, 0.0, Vector::<2>::new(2.0, -0.66), 2.0, &[]);
    println!("{result:?} after {} rhs calls", calls.get());
    assert!(matches!(
        result,
        Err(Error::Stiff { .. } | Error::TooManySteps { .. })
    ));
    assert!(calls.get() <= 2 + 6 * 100_000);
}

#[test]
fn nonsense_options_are_rejected() {
    let y0 = Vector::<2>::new(1.0, 0.0);
    let invalid = |r: Result<Solution<2>>| matches!(r, Err(Error::InvalidInput { .. }));
    assert!(invalid(dopri5(-1e-6, 1e-6).solve(
        &oscillator(),
        0.0,
        y0,
        1.0,
        &[]
    )));
    assert!(invalid(dopri5(1e-6, f64::NAN).solve(
        &oscillator(),
        0.0,
        y0,
        1.0,
        &[]
    )));
    let nan_h0 = Dopri5::new(Options {
        h0: Some(f64::NAN),
        ..Options::default()
    });
    assert!(invalid(nan_h0.solve(&oscillator(), 0.0, y0, 1.0, &[])));
    assert!(invalid(Dopri5::default().solve(
        &oscillator(),
        1.0,
        y0,
        0.0,
        &[]
    )));
    assert!(invalid(Dopri5::default().solve(
        &oscillator(),
        0.0,
        y0,
        f64::INFINITY,
        &[]
    )));
    let nan_y0 = Vector::<2>::new(f64::NAN, 0.0);
    assert!(invalid(Dopri5::default().solve(
        &oscillator(),
        0.0,
        nan_y0,
        1.0,
        &[]
    )));
    assert!(invalid(Rk4::new(f64::NAN).solve(
        &oscillator(),
        0.0,
        y0,
        1.0,
        &[]
    )));
    assert!(invalid(Rk4::new(-0.1).solve(
        &oscillator(),
        0.0,
        y0,
        1.0,
        &[]
    )));
    assert!(invalid(Rk4::new(0.1).solve(
        &oscillator(),
        1.0,
        y0,
        0.0,
        &[]
    )));
}

/// A right-hand side that returns NaN from t = 0.5 on (as sqrt of a negative would) stops
/// both methods with NonFinite near there, never a panic and never a NaN in the solution.
#[test]
fn nan_from_the_rhs_is_an_error() {
    let poisoned = Ode(|t: f64, y: &Vector<1>| {
        if t > 0.5 {
            Vector::<1>::new(f64::NAN)
        } else {
            Vector::<1>::new(-y[0])
        }
    });
    let y0 = Vector::<1>::new(1.0);
    for result in [
        Dopri5::default().solve(&poisoned, 0.0, y0, 2.0, &[]),
        Rk4::new(0.01).solve(&poisoned, 0.0, y0, 2.0, &[]),
    ] {
        match result {
            Err(Error::NonFinite { t }) => assert!(t > 0.5 && t < 0.6, "t = {t}"),
            other => panic!("expected NonFinite, got {other:?}"),
        }
    }
    let always_nan = Ode(|_t: f64, _y: &Vector<1>| Vector::<1>::new(f64::NAN));
    assert!(matches!(
        Dopri5::default().solve(&always_nan, 0.0, y0, 1.0, &[]),
        Err(Error::NonFinite { t: 0.0 })
    ));
}

/// t1 = t0 is a valid empty run: the solution is the initial point.
#[test]
fn empty_interval_returns_the_initial_point() {
    let y0 = Vector::<2>::new(1.0, 0.0);
    let sol = Dopri5::default()
        .solve(&oscillator(), 3.0, y0, 3.0, &[])
        .unwrap();
    assert_eq!(sol.last(), (3.0, &y0));
    let sol = Rk4::new(0.1)
        .solve(&oscillator(), 3.0, y0, 3.0, &[])
        .unwrap();
    assert_eq!(sol.last(), (3.0, &y0));
}

/// RK4 shortens only its last step to land on t1: h = 0.3 on [0, 1] takes steps ending at
/// 0.3, 0.6, 0.9 and 1.0; the error stays at the O(h^4) level of the full steps.
#[test]
fn rk4_last_step_lands_on_t1() {
    let sol = Rk4::new(0.3)
        .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), 1.0, &[])
        .unwrap();
    assert_eq!(sol.t.len(), 5);
    for (t, want) in sol.t.iter().zip([0.0, 0.3, 0.6, 0.9, 1.0]) {
        assert!((t - want).abs() < 1e-15);
    }
    assert_eq!(sol.last().0, 1.0);
    // Local error of RK4 per step is about h^5/120 for this problem; 4 steps.
    assert!((sol.last().1 - oscillator_exact(1.0)).amax() < 4.0 * 0.3f64.powi(5) / 120.0);
}

/// `h_max` caps every DOPRI5 step, and the run still ends exactly at t1.
#[test]
fn dopri5_respects_h_max() {
    let solver = Dopri5::new(Options {
        h_max: Some(0.05),
        ..Options::default()
    });
    let sol = solver
        .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), 3.0, &[])
        .unwrap();
    assert!(
        sol.t
            .windows(2)
            .all(|w| w[1] - w[0] <= 0.05 * (1.0 + 1e-12))
    );
    assert!(sol.stats.n_accepted >= 60);
    assert_eq!(sol.last().0, 3.0);
}

/// The run ends at `t1` exactly where the last step's `t + h` rounds past it
/// ([`pairs::ends_exactly_at_t1`]).
#[test]
fn dopri5_ends_exactly_at_t1() {
    pairs::ends_exactly_at_t1(Dopri5::new);
}
