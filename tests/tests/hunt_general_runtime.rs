//! Hunting silent wrong answers at run time: element laws that leave their domain during a
//! run, tolerances at the edge of their domain, and what each recording option keeps.

use mbd::integrate::{
    Auto, Dop853, Dopri5, GeneralizedAlpha, Integrator, Radau5, Record, Rk4, Vern9,
};
use mbd::prelude::*;

/// A block on a spring whose stiffness and damping are laws in time, `k0 - a t` and
/// `c0 - b t`: the docs say `k >= 0` and `c >= 0`, so once either law turns negative the
/// model means nothing and a run must stop with a typed error instead of integrating a
/// spring that pushes.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[point(wall, at = [0.0, 0.0])]
#[spring(s, from = wall, to = block, k = k0 - a * t)]
#[damper(d, from = wall, to = block, c = c0 - b * t)]
#[init(x = 1.0)]
pub struct Fading {
    pub m: f64,
    pub k0: f64,
    pub a: f64,
    pub c0: f64,
    pub b: f64,
}

fn invalid(err: Error) -> String {
    match err {
        Error::InvalidParameter { what, value, .. } => {
            assert!(value < 0.0, "{what}: {value}");
            what
        }
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

#[test]
fn a_stiffness_law_that_turns_negative_stops_the_run() {
    // k = 4 - 2 t is negative after t = 2; c = 0.1 - 0.01 t after t = 10.
    let p = Fading {
        m: 1.0,
        k0: 4.0,
        a: 2.0,
        c0: 0.1,
        b: 0.01,
    };
    let q = Vector::<1>::new(1.0);
    let qd = Vector::<1>::new(0.0);
    // Within the law's domain the force is -k(t) x: at t = 1, k = 2.
    assert!((p.acceleration(1.0, &q, &qd).unwrap()[0] + 2.0).abs() < 1e-15);
    let what = invalid(p.acceleration(3.0, &q, &qd).unwrap_err());
    assert!(what.contains("spring `s`"), "{what}");
    let what = invalid(p.rhs(3.0, &Vector::<2>::new(1.0, 0.0)).unwrap_err());
    assert!(what.contains("spring `s`"), "{what}");
    let opts = Options::default();
    let y0 = p.initial_state();
    for (name, run) in [
        (
            "DOPRI5",
            Dopri5::new(opts.clone()).solve(&p, 0.0, y0, 5.0, &[]),
        ),
        (
            "Radau5",
            Radau5::new(opts.clone()).solve(&p, 0.0, y0, 5.0, &[]),
        ),
        ("RK4", Rk4::new(0.01).solve(&p, 0.0, y0, 5.0, &[])),
    ] {
        let what = invalid(run.expect_err(name));
        assert!(what.contains("spring `s`"), "{name}: {what}");
    }
    // The damping law alone.
    let p = Fading { a: 0.0, ..p };
    let what = invalid(p.acceleration(11.0, &q, &qd).unwrap_err());
    assert!(what.contains("damping of `d`"), "{what}");
}

/// A harmonic oscillator `x'' = -4 x` from `x = 1` at rest: `x = cos 2 t`.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[generalized_force(spring, along = x, value = -4.0 * x)]
#[init(x = 1.0)]
pub struct Oscillator {}

fn exact(t: f64) -> f64 {
    (2.0 * t).cos()
}

/// `Record::Times` keeps `t0`, the requested times inside the run (a repeated time twice,
/// those outside not at all) and the end, each as accurate as the method's steps.
#[test]
fn recorded_times_hold_the_exact_states_with_every_method() {
    let p = Oscillator {};
    let y0 = p.initial_state();
    let times = vec![-1.0, 0.0, 0.5, 0.5, 1.3, 2.0, 3.0];
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        record: Record::Times(times.clone()),
        dense: false,
        ..Options::default()
    };
    let runs: Vec<(&str, Solution<2>, f64)> = vec![
        (
            "DOPRI5",
            Dopri5::new(opts.clone())
                .solve(&p, 0.0, y0, 2.0, &[])
                .unwrap(),
            1e-9,
        ),
        (
            "DOP853",
            Dop853::new(opts.clone())
                .solve(&p, 0.0, y0, 2.0, &[])
                .unwrap(),
            1e-9,
        ),
        (
            "Vern9",
            Vern9::new(opts.clone())
                .solve(&p, 0.0, y0, 2.0, &[])
                .unwrap(),
            1e-9,
        ),
        (
            "Auto",
            Auto::new(opts.clone())
                .solve(&p, 0.0, y0, 2.0, &[])
                .unwrap(),
            1e-9,
        ),
        (
            "Radau5",
            Radau5::new(opts.clone())
                .solve(&p, 0.0, y0, 2.0, &[])
                .unwrap(),
            1e-8,
        ),
        (
            "RK4",
            Rk4::new(1e-3)
                .recording(Record::Times(times.clone()), false)
                .solve(&p, 0.0, y0, 2.0, &[])
                .unwrap(),
            1e-11,
        ),
        (
            "generalized-alpha",
            GeneralizedAlpha::new(0.9, 1e-3)
                .recording(Record::Times(times.clone()), false)
                .solve(
                    &p,
                    0.0,
                    Vector::<1>::new(1.0),
                    Vector::<1>::new(0.0),
                    2.0,
                    &[],
                )
                .unwrap(),
            1e-5,
        ),
    ];
    for (name, sol, tol) in runs {
        assert_eq!(sol.t, [0.0, 0.5, 0.5, 1.3, 2.0], "{name}");
        for (t, y) in sol.t.iter().zip(&sol.y) {
            assert!((y[0] - exact(*t)).abs() < tol, "{name}: x({t}) = {}", y[0]);
        }
        // Nothing dense was kept: `at` answers None rather than a guess.
        assert!(sol.segments.is_empty() && sol.at(1.0).is_none(), "{name}");
    }
}

/// `Record::Every(k)` keeps `t0`, every `k`-th step and the end; `Record::Final` only the
/// ends; both keep the final state exact to the tolerance.
#[test]
fn sparse_records_keep_their_steps_and_the_end() {
    let p = Oscillator {};
    let y0 = p.initial_state();
    let base = Options {
        rtol: 1e-10,
        atol: 1e-10,
        dense: false,
        ..Options::default()
    };
    let all = Dopri5::new(base.clone())
        .solve(&p, 0.0, y0, 2.0, &[])
        .unwrap();
    let every = Dopri5::new(Options {
        record: Record::Every(7),
        ..base.clone()
    })
    .solve(&p, 0.0, y0, 2.0, &[])
    .unwrap();
    let kept: Vec<f64> = all.t.iter().copied().step_by(7).collect();
    assert_eq!(&every.t[..kept.len()], &kept[..]);
    assert_eq!(*every.t.last().unwrap(), 2.0);
    let last = Dopri5::new(Options {
        record: Record::Final,
        ..base
    })
    .solve(&p, 0.0, y0, 2.0, &[])
    .unwrap();
    assert_eq!(last.t, [0.0, 2.0]);
    assert!((last.last().1[0] - exact(2.0)).abs() < 1e-9);
    assert_eq!(last.y_end, all.y_end);
}

/// `atol = 0` (a pure relative tolerance): on a state with a zero component (the oscillator
/// released at rest) the error weights `atol + rtol |y|` vanish; the answer must be an
/// accurate `Ok` or an `InvalidInput` naming `atol`, not an error that blames the model.
#[test]
fn a_pure_relative_tolerance_is_run_or_refused_by_name() {
    let p = Oscillator {};
    let y0 = p.initial_state();
    let opts = Options {
        rtol: 1e-8,
        atol: 0.0,
        ..Options::default()
    };
    let check = |name: &str, run: Result<Solution<2>, Error>| match run {
        Ok(sol) => assert!((sol.last().1[0] - exact(2.0)).abs() < 1e-6, "{name}"),
        Err(Error::InvalidInput { what, .. }) => assert_eq!(what, "atol", "{name}"),
        Err(other) => panic!("{name}: {other:?}"),
    };
    check(
        "DOPRI5",
        Dopri5::new(opts.clone()).solve(&p, 0.0, y0, 2.0, &[]),
    );
    check(
        "DOP853",
        Dop853::new(opts.clone()).solve(&p, 0.0, y0, 2.0, &[]),
    );
    check(
        "Vern9",
        Vern9::new(opts.clone()).solve(&p, 0.0, y0, 2.0, &[]),
    );
    check("Radau5", Radau5::new(opts).solve(&p, 0.0, y0, 2.0, &[]));
}

/// A block launched on a rough floor.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g)]
#[init(der(x) = 1.0)]
pub struct Launched {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
}

/// A bad parameter of a friction model is named by every entry point, the mode choice at
/// the start of a hybrid run included (it reported a negative mass as
/// `MassMatrixNotPositiveDefinite` and a NaN coefficient as "friction coefficients").
#[test]
fn a_friction_models_bad_parameters_are_named_by_the_hybrid_run() {
    let good = Launched {
        m: 1.0,
        g: 9.81,
        mu: 0.3,
    };
    let y0 = good.initial_state();
    let (q, qd) = (Vector::<1>::zeros(), Vector::<1>::new(1.0));
    let coefficient = "the friction coefficient along `x`";
    for (bad, names) in [
        (Launched { m: -1.0, ..good }, vec!["the mass of `block`"]),
        // A NaN coefficient: as the parameter or as the coefficient it is.
        (
            Launched {
                mu: f64::NAN,
                ..good
            },
            vec!["parameter `mu`", coefficient],
        ),
        (Launched { mu: -0.3, ..good }, vec![coefficient]),
    ] {
        let named = |err: Error, entry: &str| match err {
            Error::InvalidParameter { what, .. } => {
                assert!(names.contains(&what.as_str()), "{entry}: {what}")
            }
            other => panic!("{entry}: {other:?}"),
        };
        named(bad.acceleration(0.0, &q, &qd).unwrap_err(), "acceleration");
        let run = mbd::hybrid::solve(&Dopri5::new(Options::default()), &bad, 0.0, y0, 1.0, &[]);
        named(run.unwrap_err(), "hybrid DOPRI5");
        let run = mbd::hybrid::solve(&Rk4::new(0.01), &bad, 0.0, y0, 1.0, &[]);
        named(run.unwrap_err(), "hybrid RK4");
    }
}
