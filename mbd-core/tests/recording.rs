//! Recording options: every integrator keeps what `Record` and `dense` ask and nothing
//! more, with the same final state as a full record (the steps taken do not depend on what
//! is kept); output times come from the same dense polynomials; the observer sees every
//! accepted step and can stop the run. (The memory of a million-step run is measured in
//! `bounded_memory.rs`, alone in its process.)

mod models;

use mbd_core::integrate::{
    Dop853, Dopri5, Flow, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Record, Rk4,
    Solution, Step,
};
use mbd_core::{Error, OdeSystem, Result, Vector};
use models::Oscillator;

/// x'' = -x as a first-order system.
struct Osc;

impl OdeSystem<2> for Osc {
    fn rhs(&self, _t: f64, y: &Vector<2>) -> Result<Vector<2>> {
        Ok(Vector::<2>::new(y[1], -y[0]))
    }
}

fn opts(record: Record, dense: bool) -> Options {
    Options {
        rtol: 1e-8,
        atol: 1e-8,
        record,
        dense,
        ..Options::default()
    }
}

/// Runs one method with (record, dense) over [0, 10] from (1, 0).
type Run<'a> = dyn Fn(Record, bool) -> Solution<2> + 'a;

fn all_methods() -> Vec<(&'static str, Box<Run<'static>>)> {
    let y0 = Vector::<2>::new(1.0, 0.0);
    let osc = Oscillator { m: 1.0, k: 1.0 };
    vec![
        (
            "RK4",
            Box::new(move |r, d| {
                let s = Rk4::new(0.01).recording(r, d);
                s.solve(&Osc, 0.0, y0, 10.0, &[]).unwrap()
            }),
        ),
        (
            "DOPRI5",
            Box::new(move |r, d| {
                Dopri5::new(opts(r, d))
                    .solve(&Osc, 0.0, y0, 10.0, &[])
                    .unwrap()
            }),
        ),
        (
            "DOP853",
            Box::new(move |r, d| {
                Dop853::new(opts(r, d))
                    .solve(&Osc, 0.0, y0, 10.0, &[])
                    .unwrap()
            }),
        ),
        (
            "Radau5",
            Box::new(move |r, d| {
                Radau5::new(opts(r, d))
                    .solve(&Osc, 0.0, y0, 10.0, &[])
                    .unwrap()
            }),
        ),
        (
            "Gauss",
            Box::new(move |r, d| {
                let s = Gauss {
                    dense: d,
                    record: r,
                    ..Gauss::new(0.05)
                };
                s.solve(&Osc, 0.0, y0, 10.0, &[]).unwrap()
            }),
        ),
        (
            "generalized-alpha",
            Box::new(move |r, d| {
                GeneralizedAlpha::new(0.9, 0.01)
                    .recording(r, d)
                    .solve::<_, 1, 2>(
                        &osc,
                        0.0,
                        Vector::<1>::new(1.0),
                        Vector::<1>::new(0.0),
                        10.0,
                        &[],
                    )
                    .unwrap()
            }),
        ),
    ]
}

/// Final only, every k-th step, output times: the same final state, bit for bit, and the
/// number of stored points and segments the option implies.
#[test]
fn every_method_keeps_what_was_asked_and_ends_alike() {
    for (name, run) in all_methods() {
        let full = run(Record::Steps, true);
        let n = full.stats.n_accepted;
        assert_eq!(full.t.len(), n + 1, "{name}");
        assert_eq!(full.segments.len(), n, "{name}");
        let end = full.last();
        assert_eq!(end.0, 10.0, "{name}");

        let fin = run(Record::Final, false);
        assert_eq!(fin.last(), end, "{name}");
        // The same steps (DOP853 skips its three dense stages when no segment is needed).
        let steps = |s: &Solution<2>| (s.stats.n_steps, s.stats.n_accepted, s.stats.n_rejected);
        assert_eq!(steps(&fin), steps(&full), "{name}");
        assert_eq!(
            (fin.t.len(), fin.y.len(), fin.segments.len()),
            (2, 2, 0),
            "{name}"
        );
        assert_eq!(fin.t, [0.0, 10.0], "{name}");
        assert!(fin.at(5.0).is_none(), "{name}: no dense output kept");

        let k = 7;
        let every = run(Record::Every(k), false);
        assert_eq!(every.last(), end, "{name}");
        let kept = n / k + usize::from(n % k != 0);
        assert_eq!(every.t.len(), 1 + kept, "{name}");
        for (j, t) in every.t.iter().enumerate().skip(1).take(n / k) {
            assert_eq!(*t, full.t[j * k], "{name}");
            assert_eq!(every.y[j], full.y[j * k], "{name}");
        }

        let times: Vec<f64> = (1..=20).map(|i| 0.45 * i as f64).collect();
        let at = run(Record::Times(times.clone()), false);
        assert_eq!(at.last(), end, "{name}");
        assert_eq!(at.segments.len(), 0, "{name}");
        assert_eq!(at.t[0], 0.0);
        assert_eq!(&at.t[1..=20], &times[..], "{name}");
        assert_eq!(at.t.len(), 22, "{name}: t0, 20 times, the end");
        for (i, &t) in times.iter().enumerate() {
            assert_eq!(at.y[i + 1], full.at(t).unwrap(), "{name} at {t}");
        }
    }
}

/// The observer sees each accepted step once, in order, ending at the final state; its
/// `Flow::Stop` ends the run there.
#[test]
fn observer_sees_every_step_and_can_stop() {
    let y0 = Vector::<2>::new(1.0, 0.0);
    let solver = Dop853::new(opts(Record::Final, false));
    let mut seen: Vec<f64> = Vec::new();
    let mut obs = |s: &Step<'_, 2>| {
        seen.push(s.t);
        Flow::Continue
    };
    let sol = solver
        .solve_observed(&Osc, 0.0, y0, 10.0, &[], Some(&mut obs))
        .unwrap();
    assert_eq!(seen.len(), sol.stats.n_accepted);
    assert!(seen.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(*seen.last().unwrap(), 10.0);

    let mut stop = |s: &Step<'_, 2>| {
        if s.t > 3.0 {
            Flow::Stop
        } else {
            Flow::Continue
        }
    };
    let sol = Rk4::new(0.5)
        .solve_observed(&Osc, 0.0, y0, 10.0, &[], Some(&mut stop))
        .unwrap();
    assert_eq!(sol.last().0, 3.5);
    assert_eq!(sol.stats.n_accepted, 7);
}

/// Bad recording options are typed errors.
#[test]
fn bad_records_are_rejected() {
    let y0 = Vector::<2>::new(1.0, 0.0);
    for r in [
        Record::Every(0),
        Record::Times(vec![2.0, 1.0]),
        Record::Times(vec![f64::NAN]),
    ] {
        let e = Dopri5::new(opts(r.clone(), false)).solve(&Osc, 0.0, y0, 1.0, &[]);
        assert!(
            matches!(e, Err(Error::InvalidInput { what: "record", .. })),
            "{r:?}"
        );
        let e = Rk4::new(0.1)
            .recording(r, false)
            .solve(&Osc, 0.0, y0, 1.0, &[]);
        assert!(matches!(e, Err(Error::InvalidInput { what: "record", .. })));
    }
}

/// An empty record (fields are public, so one can be made) answers `None` from `at` and
/// its final state from `last`, without panicking.
#[test]
fn an_empty_solution_does_not_panic() {
    let sol = Solution::<2> {
        t: vec![],
        y: vec![],
        segments: vec![],
        events: vec![],
        stats: Default::default(),
        stopped_by: None,
        t_end: 1.0,
        y_end: Vector::<2>::new(3.0, 4.0),
        passages: vec![],
        switches: vec![],
    };
    assert!(sol.at(1.0).is_none());
    assert_eq!(sol.last(), (1.0, &Vector::<2>::new(3.0, 4.0)));
}
