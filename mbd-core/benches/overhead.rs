//! The step loop's overhead per right-hand-side evaluation: wall time of an integration
//! divided by its `rhs` calls, against the wall time of one bare call of the same `rhs`
//! (the pendulum `theta'' = -(g/l) sin theta` as the derive generates it: one `sin`, one
//! product). Pendulum from rest at 60 deg over 10 s at rtol = atol = 1e-10.
//!
//! Prints, for DOPRI5, DOP853 and Vern9 keeping the final state only, every step, every step
//! with dense output, and 101 output times (from the dense output, segments not kept), `ns/eval` and the ratios to the bare call (independent calls) and to
//! a dependent chain of calls (each input the last output, as in the stages). Timings are the minimum over interleaved batches (the machine is shared).

use mbd_core::integrate::{Dop853, Dopri5, Integrator, Options, Record, Vern9};
use mbd_core::{OdeSystem, Result, Vector};
use std::hint::black_box;
use std::time::Instant;

struct Pendulum {
    g_over_l: f64,
}

impl OdeSystem<2> for Pendulum {
    #[inline]
    fn rhs(&self, _t: f64, y: &Vector<2>) -> Result<Vector<2>> {
        Ok(Vector::<2>::new(y[1], -self.g_over_l * y[0].sin()))
    }
}

const TOL: f64 = 1e-10;

/// One timed case: runs once and returns its `rhs` calls.
type Case<'a> = Box<dyn Fn() -> usize + 'a>;

fn min_batch(run: &dyn Fn() -> usize, reps: usize) -> (f64, usize) {
    let start = Instant::now();
    let mut calls = 0;
    for _ in 0..reps {
        calls += run();
    }
    (start.elapsed().as_secs_f64(), calls)
}

fn main() {
    let sys = &Pendulum { g_over_l: 9.81 };
    let y0 = Vector::<2>::new(std::f64::consts::FRAC_PI_3, 0.0);
    let opts = |record: Record, dense: bool| Options {
        rtol: TOL,
        atol: TOL,
        dense,
        record,
        ..Options::default()
    };
    let times = || Record::Times((0..=100).map(|i| 0.1 * f64::from(i)).collect());
    // Bare calls on states that change (as the stages' do), one call per iteration.
    let bare = move || {
        let mut y = black_box(y0);
        let mut acc = Vector::<2>::zeros();
        for i in 0..4000 {
            y[0] += 1e-6;
            acc += sys.rhs(i as f64, black_box(&y)).unwrap();
        }
        black_box(acc);
        4000
    };
    let run = |solver: &dyn Fn() -> usize| solver();
    let d5 = |o: Options| {
        let s = Dopri5::new(o);
        move || {
            s.solve(sys, 0.0, black_box(y0), 10.0, &[])
                .unwrap()
                .stats
                .n_rhs
        }
    };
    let d8 = |o: Options| {
        let s = Dop853::new(o);
        move || {
            s.solve(sys, 0.0, black_box(y0), 10.0, &[])
                .unwrap()
                .stats
                .n_rhs
        }
    };
    let v9 = |o: Options| {
        let s = Vern9::new(o);
        move || {
            s.solve(sys, 0.0, black_box(y0), 10.0, &[])
                .unwrap()
                .stats
                .n_rhs
        }
    };
    // Bare calls in a dependent chain (each call's input is the last one's output, as a
    // stage's is): the call's latency, which bounds a step more than its throughput.
    let chain = move || {
        let mut y = black_box(y0);
        for i in 0..4000 {
            y += sys.rhs(i as f64, &y).unwrap() * 1e-3;
        }
        black_box(y);
        4000
    };
    let cases: Vec<(&str, Case)> = vec![
        ("bare rhs", Box::new(bare)),
        ("bare rhs, dependent chain", Box::new(chain)),
        (
            "DOPRI5 final state",
            Box::new(d5(opts(Record::Final, false))),
        ),
        (
            "DOPRI5 every step",
            Box::new(d5(opts(Record::Steps, false))),
        ),
        (
            "DOPRI5 every step + dense",
            Box::new(d5(opts(Record::Steps, true))),
        ),
        (
            "DOPRI5 101 output times",
            Box::new(d5(opts(times(), false))),
        ),
        (
            "DOP853 final state",
            Box::new(d8(opts(Record::Final, false))),
        ),
        (
            "DOP853 every step",
            Box::new(d8(opts(Record::Steps, false))),
        ),
        (
            "DOP853 every step + dense",
            Box::new(d8(opts(Record::Steps, true))),
        ),
        (
            "DOP853 101 output times",
            Box::new(d8(opts(times(), false))),
        ),
        (
            "VERN9 final state",
            Box::new(v9(opts(Record::Final, false))),
        ),
        ("VERN9 101 output times", Box::new(v9(opts(times(), false)))),
    ];
    let mut best = vec![f64::INFINITY; cases.len()];
    let mut calls = vec![0usize; cases.len()];
    for _ in 0..60 {
        for (i, (_, f)) in cases.iter().enumerate() {
            let (t, n) = min_batch(&|| run(f.as_ref()), 10);
            best[i] = best[i].min(t / n as f64);
            calls[i] = n / 10;
        }
    }
    println!("pendulum 60 deg, 10 s, tol {TOL:e}; min over 60 interleaved batches");
    println!(
        "{:<28} {:>10} {:>10} {:>8} {:>8}",
        "case", "rhs calls", "ns/eval", "x bare", "x chain"
    );
    for (i, (name, _)) in cases.iter().enumerate() {
        println!(
            "{:<28} {:>10} {:>10.2} {:>8.2} {:>8.2}",
            name,
            calls[i],
            best[i] * 1e9,
            best[i] / best[0],
            best[i] / best[1]
        );
    }
}
