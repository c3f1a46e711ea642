//! Problems, references and checks shared by the tests of the explicit pairs (`explicit.rs`,
//! `dop853.rs`, `vern9.rs`): each check takes the method as a constructor and asserts what
//! any of the pairs must do, so that a pair's test file says only what is its own.
#![allow(dead_code, reason = "each test file uses a subset")]

use mbd_core::integrate::events::EVENT_TIME_TOL;
use mbd_core::integrate::{
    Auto, Direction, Dop853, Dopri5, Event, Integrator, Options, Record, Solution, Vern9,
};
use mbd_core::{Error, OdeSystem, Result, Vector};
use std::f64::consts::PI;

#[path = "../exact/mod.rs"]
pub mod exact;
pub use exact::pendulum_angle;

/// `y' = f(t, y)` from a closure.
pub struct Ode<F>(pub F);

impl<const D: usize, F: Fn(f64, &Vector<D>) -> Vector<D>> OdeSystem<D> for Ode<F> {
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        Ok((self.0)(t, y))
    }
}

/// x'' = -x as y = (x, x'): x = cos t, x' = -sin t from (1, 0).
pub fn oscillator() -> Ode<impl Fn(f64, &Vector<2>) -> Vector<2>> {
    Ode(|_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -y[0]))
}

pub fn oscillator_exact(t: f64) -> Vector<2> {
    Vector::<2>::new(t.cos(), -t.sin())
}

/// Van der Pol in Hairer's scaled form: y1' = y2, y2' = ((1 - y1^2) y2 - y1) / eps.
pub fn van_der_pol(eps: f64) -> Ode<impl Fn(f64, &Vector<2>) -> Vector<2>> {
    Ode(move |_t: f64, y: &Vector<2>| {
        Vector::<2>::new(y[1], ((1.0 - y[0] * y[0]) * y[1] - y[0]) / eps)
    })
}

/// theta'' = -w^2 sin theta, `w^2 = 9.81`, released from rest at 60 deg in the tests.
pub fn pendulum() -> Ode<impl Fn(f64, &Vector<2>) -> Vector<2>> {
    Ode(|_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -9.81 * y[0].sin()))
}

/// [`pendulum`]'s angle from rest at 60 deg (Jacobi's elliptic solution).
pub fn pendulum_exact(t: f64) -> f64 {
    pendulum_angle(9.81f64.sqrt(), PI / 3.0, t)
}

/// The largest error of [`pendulum`]'s angle from rest at 60 deg over 10 s, from the
/// solution's dense output at 1001 points.
pub fn pendulum_worst(sol: &Solution<2>) -> f64 {
    (0..=1000)
        .map(|i| {
            let t = 10.0 * f64::from(i) / 1000.0;
            (sol.at(t).unwrap()[0] - pendulum_exact(t)).abs()
        })
        .fold(0.0, f64::max)
}

/// Least-squares slope of log(err) against log(x).
pub fn log_log_slope(x: &[f64], err: &[f64]) -> f64 {
    let n = x.len() as f64;
    let lx: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let le: Vec<f64> = err.iter().map(|v| v.ln()).collect();
    let (mx, me) = (lx.iter().sum::<f64>() / n, le.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&le).map(|(a, b)| (a - mx) * (b - me)).sum();
    let sxx: f64 = lx.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// Options at tolerance `tol` (relative and absolute), the rest default.
pub fn at_tol(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    }
}

/// A run of fixed steps `h` (first and largest step `h`, tolerances so loose that every
/// step is accepted) from `y0` at 0 to `t1`, no dense output: its end state. Asserts that
/// no step was rejected and that `t1 / h` were taken.
pub fn fixed_steps<I: Integrator>(
    method: impl Fn(Options) -> I,
    sys: &impl OdeSystem<2>,
    y0: Vector<2>,
    t1: f64,
    h: f64,
) -> Vector<2> {
    let sol = method(Options {
        rtol: 1e3,
        atol: 1e3,
        h0: Some(h),
        h_max: Some(h),
        dense: false,
        ..Options::default()
    })
    .solve(sys, 0.0, y0, t1, &[])
    .unwrap();
    assert_eq!(sol.stats.n_rejected, 0);
    assert_eq!(sol.stats.n_accepted, (t1 / h).round() as usize);
    *sol.last().1
}

/// One step of size `h` from `y0` at 0 (tolerances so loose that it is accepted), with its
/// dense output: the solution, of one segment.
pub fn one_step<I: Integrator>(
    method: impl Fn(Options) -> I,
    sys: &impl OdeSystem<2>,
    y0: Vector<2>,
    h: f64,
) -> Solution<2> {
    let sol = method(Options {
        rtol: 1e3,
        atol: 1e3,
        h0: Some(h),
        ..Options::default()
    })
    .solve(sys, 0.0, y0, h, &[])
    .unwrap();
    assert_eq!(sol.segments.len(), 1);
    sol
}

/// The slope of the oscillator's end error at t = 20 against the tolerance over
/// `rtol = atol = 1e-4 ... 1e-12` (printed with the errors under `name`).
pub fn tolerance_slope<I: Integrator>(name: &str, method: impl Fn(Options) -> I) -> f64 {
    let tols: Vec<f64> = (4..=12).map(|k| 10f64.powi(-k)).collect();
    let errs: Vec<f64> = tols
        .iter()
        .map(|&tol| {
            let sol = method(at_tol(tol))
                .solve(&oscillator(), 0.0, Vector::<2>::new(1.0, 0.0), 20.0, &[])
                .unwrap();
            (sol.last().1 - oscillator_exact(20.0)).amax()
        })
        .collect();
    let slope = log_log_slope(&tols, &errs);
    println!("{name} tolerance slope {slope}, errors {errs:?}");
    slope
}

pub const G: f64 = 9.807;
pub const V0: f64 = 25.0;

/// A ball thrown up at 25 m/s stops (terminal event) where it falls through 15 m, at
/// t = v0/g + sqrt(2 (v0^2/(2g) - 15) / g), to 1e-12 relative; the state is z = 15,
/// v = v0 - g t; a non-terminal twin sees both crossings and runs to the end (6 s).
pub fn locates_the_balls_crossings<I: Integrator>(solver: &I) {
    let ball = Ode(|_t: f64, y: &Vector<2>| Vector::<2>::new(y[1], -G));
    let apex = V0 / G;
    let d = (2.0 * (V0 * V0 / (2.0 * G) - 15.0) / G).sqrt();
    let (t_rise, t_fall) = (apex - d, apex + d);
    let at_15 = |dir| Event::new("z = 15", |_t, y: &Vector<2>| y[0] - 15.0, dir);
    let y0 = Vector::<2>::new(0.0, V0);
    let stop = solver
        .solve(&ball, 0.0, y0, 6.0, &[at_15(Direction::Falling).terminal()])
        .unwrap();
    assert_eq!(stop.stopped_by, Some(0));
    let hit = &stop.events[0];
    assert!(((hit.t - t_fall) / t_fall).abs() < 1e-12, "{}", hit.t);
    assert!((hit.y[0] - 15.0).abs() < 1e-11);
    assert!((hit.y[1] - (V0 - G * t_fall)).abs() < 1e-11);
    assert_eq!(stop.last(), (hit.t, &hit.y));
    let both = solver
        .solve(&ball, 0.0, y0, 6.0, &[at_15(Direction::Either)])
        .unwrap();
    let times: Vec<f64> = both.events.iter().map(|e| e.t).collect();
    assert_eq!(times.len(), 2);
    // Event times are resolved to `EVENT_TIME_TOL (|t| + 1)` (the bracket's end past the
    // crossing is returned), which for t < 1 is wider than 1e-12 of t.
    let resolved = |t: f64, exact: f64| (t - exact).abs() <= EVENT_TIME_TOL * (exact + 1.0);
    assert!(resolved(times[0], t_rise), "{} vs {t_rise}", times[0]);
    assert!(resolved(times[1], t_fall), "{} vs {t_fall}", times[1]);
    assert_eq!(both.last().0, 6.0);
}

/// Uniform rotation projected back onto the unit circle after every step (rtol = atol =
/// 1e-6, 20 s): accepted states lie on the circle to rounding, the solution is still
/// (cos t, sin t), and each step that the projection moved costs one more call (the next
/// step's first stage at the new state) above `2 + calls_per_step n_steps + n_accepted`.
pub fn projects_onto_the_circle<I: Integrator>(
    method: impl Fn(Options) -> I,
    calls_per_step: usize,
) {
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
    let sol = method(Options {
        dense: false,
        ..at_tol(1e-6)
    })
    .solve(&Circle, 0.0, Vector::<2>::new(1.0, 0.0), 20.0, &[])
    .unwrap();
    for y in &sol.y {
        assert!((y.norm() - 1.0).abs() < 4.0 * f64::EPSILON);
    }
    let (t, y) = sol.last();
    assert!((y - Vector::<2>::new(t.cos(), t.sin())).amax() < 1e-5);
    let s = sol.stats;
    let base = 2 + calls_per_step * s.n_steps + s.n_accepted;
    assert!(s.n_rhs > base && s.n_rhs <= base + s.n_accepted);
}

/// Van der Pol with eps = 1e-6 from `y0` over 2 s is very stiff: with Hairer's test every
/// 1000 accepted steps the run stops with `Error::Stiff`; with the test off it runs on
/// into the step limit. `run(stiffness_check)` is the run.
pub fn stiffness_detection_is_an_option(run: impl Fn(Option<usize>) -> Result<Solution<2>>) {
    assert!(matches!(run(Some(1000)), Err(Error::Stiff { .. })));
    assert!(matches!(run(None), Err(Error::TooManySteps { .. })));
}

/// With `Record::Times` (every 0.25 over 10 s of the oscillator), only the steps with an
/// output time strictly inside them build the segment (`dense_calls` more calls each):
/// the count is the `Record::Final` run's plus `dense_calls` per such step, the steps
/// being those of the same run recorded every step (the step sequence does not depend on
/// what is recorded), and the recorded states are the dense run's segments evaluated at
/// those times, bit for bit. `method(record, dense)` is the method at 1e-9.
pub fn output_times_build_only_the_segments_they_need<I: Integrator>(
    method: impl Fn(Record, bool) -> I,
    dense_calls: usize,
) {
    let sys = oscillator();
    let y0 = Vector::<2>::new(1.0, 0.0);
    let run = |record: Record, dense: bool| {
        method(record, dense)
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
    assert_eq!(
        at_times.stats.n_rhs,
        final_only.stats.n_rhs + dense_calls * inside
    );
    assert_eq!(at_times.t, times);
    for (t, y) in at_times.t.iter().zip(&at_times.y) {
        assert_eq!(dense.at(*t).unwrap(), *y, "t = {t}");
    }
}

/// `Auto` at each `(tol, name)` picks the method `name` and, with the options given, its
/// solution of the oscillator over 5 s equals that method's, step for step.
pub fn auto_picks(cases: &[(f64, &str)]) {
    let y0 = Vector::<2>::new(1.0, 0.0);
    for &(tol, name) in cases {
        let o = at_tol(tol);
        let auto = Auto::new(o.clone());
        assert_eq!(auto.name(), name);
        let a = auto.solve(&oscillator(), 0.0, y0, 5.0, &[]).unwrap();
        let b = match name {
            "VERN9" => Vern9::new(o).solve(&oscillator(), 0.0, y0, 5.0, &[]),
            "DOP853" => Dop853::new(o).solve(&oscillator(), 0.0, y0, 5.0, &[]),
            _ => Dopri5::new(o).solve(&oscillator(), 0.0, y0, 5.0, &[]),
        }
        .unwrap();
        assert_eq!(a.stats, b.stats);
        assert_eq!(a.last(), b.last());
    }
}

/// A run ends at `t1` exactly, also where its last step builds a segment: `y' = (1, 0)` from
/// 0 to `t1 = 0.7231300081617925` with a first step of `0.16846557934290035` has no error,
/// so the second step grows to the whole rest and is cut to `t1 - t`, and there `t + (t1 -
/// t)` rounds to one ulp above `t1`. The recorded times, the final state, the last
/// segment's end and the state at `t1` from the dense output all say `t1`.
pub fn ends_exactly_at_t1<I: Integrator>(method: impl Fn(Options) -> I) {
    let (t, t1) = (0.16846557934290035, 0.7231300081617925);
    assert_ne!(t + (t1 - t), t1, "the case must round");
    let line = Ode(|_t: f64, _y: &Vector<2>| Vector::<2>::new(1.0, 0.0));
    let sol = method(Options {
        h0: Some(t),
        ..Options::default()
    })
    .solve(&line, 0.0, Vector::<2>::new(0.0, 0.0), t1, &[])
    .unwrap();
    assert_eq!(sol.stats.n_accepted, 2);
    assert_eq!(sol.t, [0.0, t, t1]);
    assert_eq!(sol.last().0, t1);
    assert!((sol.last().1[0] - t1).abs() <= 4.0 * f64::EPSILON);
    assert!(sol.at(t1).is_some());
}
