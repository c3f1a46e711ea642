//! Coulomb friction's cost: the stick-slip oscillator's limit cycle over 100 periods, run
//! mode by mode (`mbd::hybrid::solve`), against the same run with the friction removed.
//!
//! Per method and tolerance (or step): switches, accepted and rejected steps, steps per
//! switch (mean and the most any one mode took), right-hand-side evaluations, the largest
//! relative error of the switch times against the closed form, and the time of the friction
//! run over the frictionless one. Times are the thread's CPU time (the `cpu-time` crate's
//! `ThreadTime`): per run, over a batch of runs doubled until it
//! takes 0.25 s, median of 5 batches. The machine is shared, and wall time would count the
//! waits for a core. The load average is printed before and after.
//!
//! `cargo run --release -p mechanisms --bin friction`

use clap::Parser;
use mbd::Slip;
use mbd::hybrid::HybridSolution;
use mbd::integrate::{Dopri5, GeneralizedAlpha, Integrator, Radau5};
use mbd::{Options, Solution};
use mechanisms::stick_slip::{self, Belt};
use std::hint::black_box;

const PERIODS: usize = 100;

/// This thread's CPU time in seconds, or NaN where the platform has no thread clock.
fn cpu_time() -> f64 {
    cpu_time::ThreadTime::try_now().map_or(f64::NAN, |t| t.as_duration().as_secs_f64())
}

/// CPU time of one run of `f`, in seconds (median of 5 batches, each doubled until it
/// takes 0.25 s), and its last result.
fn timed<T>(f: impl Fn() -> T) -> (f64, T) {
    let mut times = Vec::new();
    let mut out = black_box(f());
    for _ in 0..5 {
        let mut n = 1usize;
        loop {
            let start = cpu_time();
            for _ in 0..n {
                out = black_box(f());
            }
            let spent = cpu_time() - start;
            if spent >= 0.25 || spent.is_nan() {
                times.push(spent / n as f64);
                break;
            }
            n *= 2;
        }
    }
    times.sort_by(f64::total_cmp);
    (times[2], out)
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
    compare(name, &format!("{tol:.0e}"), polish, &make(opts))
}

/// One row: the friction run and the frictionless one with `integrator`.
fn compare<I: Integrator>(
    name: &str,
    setting: &str,
    polish: bool,
    integrator: &I,
) -> mbd::Result<()> {
    let b: Belt = stick_slip::belt();
    let free = stick_slip::without_friction(&b);
    let (t_fric, run) = timed(|| stick_slip::run(integrator, black_box(&b), PERIODS, polish));
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
        "{name:<7} {setting:>7} {n_sw:>8} {:>7} {:>5} {:>9.1} {most:>5} {:>7} {err:>9} {:>8.0} | {:>7} {:>5} {:>7} {:>8.0} | {:>6.2} {:>6.2}",
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

/// No options: any argument is a usage error (exit status 2) before the runs.
#[derive(Parser, Debug)]
#[command(
    about = "Coulomb friction's cost on the stick-slip oscillator",
    after_help = "Runs the limit cycle over 100 periods mode by mode with DOPRI5 and Radau5 \
                  (1e-6, 1e-9, 1e-12; plain and with polished switches) and generalized-alpha, \
                  each against the same run without friction; a legend of the columns follows \
                  the table. Times are CPU time (several minutes on a loaded machine)."
)]
struct Args {}

fn main() -> mbd::Result<()> {
    Args::parse();
    println!(
        "stick-slip oscillator, {PERIODS} periods of the limit cycle (mode by mode) against the same run without friction"
    );
    println!(
        "load average before: {} (2 cores, shared); times are CPU time",
        mechanisms::accuracy::load_average()
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
    println!("generalized-alpha (rho_inf 0.9, fixed step h; order 2):");
    for h in [1e-2, 1e-3] {
        compare(
            "gen-a",
            &format!("h {h:.0e}"),
            false,
            &GeneralizedAlpha::new(0.9, h),
        )?;
    }
    println!(
        "load average after: {}",
        mechanisms::accuracy::load_average()
    );
    println!("{LEGEND}");
    Ok(())
}

/// What the columns mean, printed under the table.
const LEGEND: &str = "Columns, with friction (left of the first |): tol, the rtol = atol of the \
run (or the fixed step h); switches, the stick/slip switches located; steps, rej, accepted and \
rejected steps; steps/sw, accepted steps per switch; most, the most steps any one mode took; \
rhs, right-hand-side evaluations; t_err, the largest relative error of the switch times \
against the closed-form limit cycle; us, CPU time of the run in microseconds. The same run \
without friction (between the |s): steps, rej, rhs, us. Ratios (right of the second |): rhs x, \
time x, friction run over frictionless run.";
