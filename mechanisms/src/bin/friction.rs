//! Coulomb friction's cost: the stick-slip oscillator's limit cycle over 100 periods, run
//! mode by mode (`mbd::hybrid::solve`), against the same run with the friction removed.
//!
//! Per method and tolerance: switches, accepted and rejected steps, steps per switch (mean
//! and the most any one mode took), right-hand-side evaluations, the largest relative error
//! of the switch times against the closed form, and the wall time (median of 7 runs) of the
//! friction run over the frictionless one.
//!
//! `cargo run --release -p mechanisms --bin friction`

use mbd::Slip;
use mbd::hybrid::HybridSolution;
use mbd::integrate::{Dopri5, Integrator, Radau5};
use mbd::{Options, Solution};
use mechanisms::stick_slip::{self, Belt};
use std::hint::black_box;
use std::time::Instant;

const PERIODS: usize = 100;

/// Median wall time of `f` over 7 runs, in seconds, and its last result.
fn timed<T>(f: impl Fn() -> T) -> (f64, T) {
    let mut times = Vec::new();
    let mut out = None;
    for _ in 0..7 {
        let start = Instant::now();
        out = Some(black_box(f()));
        times.push(start.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    (times[3], out.expect("seven runs"))
}

fn row<I: Integrator>(
    name: &str,
    tol: f64,
    polish: bool,
    make: impl Fn(Options) -> I,
) -> mbd::Result<()> {
    let opts = Options {
        rtol: tol,
        atol: tol,
        dense: true,
        ..Options::default()
    };
    let b: Belt = stick_slip::belt();
    let free = stick_slip::without_friction(&b);
    let integrator = make(opts);
    let (t_fric, run) = timed(|| stick_slip::run(&integrator, black_box(&b), PERIODS, polish));
    let run: HybridSolution<2, [Slip; 1]> = run?;
    let t1 = run.solution.last().0;
    let (t_free, smooth) =
        timed(|| integrator.solve(black_box(&free), 0.0, free.initial_state(), t1, &[]));
    let smooth: Solution<2> = smooth?;
    let (s, f) = (run.solution.stats, smooth.stats);
    let n_sw = run.switches.len();
    let most = run.switches.iter().map(|w| w.steps).max().unwrap_or(0);
    let err = stick_slip::switch_error(&b, &run)
        .map_or("wrong modes".to_string(), |e| format!("{e:.1e}"));
    println!(
        "{name:<7} {tol:>7.0e} {n_sw:>8} {:>7} {:>5} {:>9.1} {most:>5} {:>7} {err:>9} {:>8.0} | {:>7} {:>5} {:>7} {:>8.0} | {:>6.2} {:>6.2}",
        s.n_accepted,
        s.n_rejected,
        s.n_accepted as f64 / n_sw.max(1) as f64,
        s.n_rhs,
        t_fric * 1e6,
        f.n_accepted,
        f.n_rejected,
        f.n_rhs,
        t_free * 1e6,
        s.n_rhs as f64 / f.n_rhs as f64,
        t_fric / t_free,
    );
    Ok(())
}

fn main() -> mbd::Result<()> {
    println!(
        "stick-slip oscillator, {PERIODS} periods of the limit cycle (mode by mode) against the same run without friction"
    );
    println!(
        "{:<7} {:>7} {:>8} {:>7} {:>5} {:>9} {:>5} {:>7} {:>9} {:>8} | {:>7} {:>5} {:>7} {:>8} | {:>6} {:>6}",
        "method",
        "tol",
        "switches",
        "steps",
        "rej",
        "steps/sw",
        "most",
        "rhs",
        "t_err",
        "us",
        "steps",
        "rej",
        "rhs",
        "us",
        "rhs x",
        "time x"
    );
    for polish in [false, true] {
        if polish {
            println!("polished switches (hybrid::Settings::polish):");
        }
        for tol in [1e-6, 1e-9, 1e-12] {
            row("DOPRI5", tol, polish, Dopri5::new)?;
            row("Radau5", tol, polish, Radau5::new)?;
        }
    }
    Ok(())
}
