//! Closed loops at scale: the IFToMM A02 assembly of 40 four-bar loops
//! ([`mechanisms::fourbar_assembly`]) — the cost of one right-hand side and whole runs of
//! every method, with the error of crank 0's tip against the one-coordinate reduction (by quadrature, `Reduced::exact`) and
//! how far the cranks drifted from a parallelogram.
//!
//! DOPRI5, DOP853, Auto, Radau5 and generalized-alpha run through `mbd::passage`, which bridges the singular
//! positions their index-1 accelerations (or Newton iterations) stop at; `bridged` counts them.
//!
//! `cargo run --release -p mechanisms --bin loops [-- --quick] [--only DOPRI5|DOP853|Auto|Radau5|ALI3-P|gen-a]
//! [--tol 1e-7,3e-7] [--t1 3] [--passages] [--no-rhs]` (`--tol`: the DOPRI5, DOP853, Auto and Radau5 tolerances
//! run, in place of the defaults; `--t1`: a shorter span; `--passages`: list every bridge; `--no-rhs`: skip
//! timing one right-hand side, as when profiling the runs). The runs keep only the 400 output states (no
//! dense output), so memory stays small at any setting.

use clap::Parser;
use mbd::integrate::{Ali3, Auto, Dop853, GeneralizedAlpha, Radau5};
use mbd::passage::{self, Passage, Settings};
use mbd::{Dopri5, OdeSystem, Options, Record, Solution};
use mechanisms::fourbar_assembly::{self as fa, FourBarAssembly};
use std::time::Instant;

const OUTPUTS: usize = 400;

/// This thread's CPU time in seconds (NaN where the platform has no thread clock): on a
/// shared machine wall time counts the other processes' share too.
fn cpu_time() -> f64 {
    cpu_time::ThreadTime::try_now().map_or(f64::NAN, |t| t.as_duration().as_secs_f64())
}

/// Median over 51 batches of the time per call, in microseconds.
fn median_us<F: FnMut()>(mut f: F) -> f64 {
    let mut batch = 1u64;
    while {
        let s = Instant::now();
        (0..batch).for_each(|_| f());
        s.elapsed().as_secs_f64() < 2e-3
    } {
        batch *= 2;
    }
    let mut v: Vec<f64> = (0..51)
        .map(|_| {
            let s = Instant::now();
            (0..batch).for_each(|_| f());
            s.elapsed().as_secs_f64() * 1e6 / batch as f64
        })
        .collect();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Bad arguments are a usage error (exit status 2) before any run.
#[derive(Parser, Debug)]
#[command(about = "The 40-loop four-bar assembly (IFToMM A02) by every method")]
struct Args {
    /// Fewer settings per method.
    #[arg(long)]
    quick: bool,
    /// Run one method's rows only.
    #[arg(long, value_parser = ["DOPRI5", "DOP853", "Auto", "Radau5", "ALI3-P", "gen-a"])]
    only: Option<String>,
    /// The DOPRI5, DOP853, Auto and Radau5 tolerances, in place of the defaults.
    #[arg(long, value_delimiter = ',')]
    tol: Option<Vec<f64>>,
    /// Skip timing one right-hand side (as when profiling the runs).
    #[arg(long)]
    no_rhs: bool,
    /// The span integrated, in seconds (the benchmark's 20 s by default).
    #[arg(long, default_value_t = 20.0, value_parser = positive)]
    t1: f64,
    /// List every bridged passage (time, steps, error estimate of the step across).
    #[arg(long)]
    passages: bool,
    /// Print the tip error at every 10th output time (where the error is made).
    #[arg(long)]
    trace: bool,
}

fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("`{s}` is not a positive time")),
    }
}

impl Args {
    /// The tolerances of `--tol A,B,..` when given, else `default`.
    fn tolerances(&self, default: &[f64]) -> Vec<f64> {
        self.tol.clone().unwrap_or_else(|| default.to_vec())
    }

    fn runs(&self, name: &str) -> bool {
        self.only.as_deref().is_none_or(|only| only == name)
    }

    /// The output times: `OUTPUTS + 1` equally spaced over `[0, t1]`.
    fn grid(&self) -> Vec<f64> {
        (0..=OUTPUTS)
            .map(|k| self.t1 * k as f64 / OUTPUTS as f64)
            .collect()
    }

    /// The runs' options at tolerance `tol`: the output times only, no dense output.
    fn options(&self, tol: f64) -> Options {
        Options {
            rtol: tol,
            atol: tol,
            dense: false,
            record: Record::Times(self.grid()),
            ..Default::default()
        }
    }

    /// Bridges to `tol`, recording as [`Args::options`].
    fn settings(&self, tol: f64) -> Settings {
        Settings {
            dense: false,
            record: Record::Times(self.grid()),
            ..Settings::new(tol)
        }
    }
}

/// `max |B0 - B0_exact|` over the output times `grid` (infinite where one was not recorded).
fn tip_error(a: &FourBarAssembly, sol: &Solution<{ fa::D }>, grid: &[f64]) -> f64 {
    let reduced = fa::Reduced::of(a);
    grid.iter()
        .map(|&t| {
            // A recorded output time, else the dense output (ALI3-P keeps every step).
            let k = sol.t.iter().position(|&s| s == t);
            match k.map(|k| sol.y[k]).or_else(|| sol.at(t)) {
                Some(y) => {
                    let p = a.tip(&y);
                    let th = reduced.exact(-1.0 / a.l, t).0;
                    (p[0] - a.l * th.cos()).hypot(p[1] - a.l * th.sin())
                }
                None => f64::INFINITY,
            }
        })
        .fold(0.0, f64::max)
}

fn row(
    args: &Args,
    name: &str,
    setting: &str,
    a: &FourBarAssembly,
    run: impl FnOnce() -> mbd::Result<(Solution<{ fa::D }>, Vec<Passage>)>,
) {
    if !args.runs(name) {
        return;
    }
    let (start, cpu0) = (Instant::now(), cpu_time());
    let out = run();
    let (secs, cpu) = (start.elapsed().as_secs_f64(), cpu_time() - cpu0);
    match out {
        Ok((sol, passages)) => {
            let err = tip_error(a, &sol, &args.grid());
            let spread = sol.y.iter().map(|y| a.spread(y).0).fold(0.0, f64::max);
            println!(
                "{name:<8} {setting:<10} ok   tip error {err:9.2e}  max crank spread {spread:9.2e}  {:8.1} ms ({:.1} ms CPU)  steps {:7}  rhs {:8}  bridged {:3}",
                secs * 1e3,
                cpu * 1e3,
                sol.stats.n_accepted,
                sol.stats.n_rhs,
                passages.len()
            );
            if args.trace {
                for (k, &t) in args.grid().iter().enumerate().step_by(10) {
                    let e = tip_error(a, &sol, &[t]);
                    println!("    t = {t:8.3}  tip error {e:9.2e}  (k = {k})");
                }
            }
            if args.passages {
                for p in &passages {
                    println!(
                        "    passage t = {:.6}  bridge {:.6} .. {:.6}  steps {:5}  estimate {:9.2e}",
                        p.t, p.from, p.to, p.steps, p.error
                    );
                }
            }
        }
        Err(e) => println!("{name:<8} {setting:<10} FAIL {e}  ({:.1} ms)", secs * 1e3),
    }
}

fn main() {
    let args = Args::parse();
    let quick = args.quick;
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let mut y = y0;
    y[0] += 0.3;
    if !args.no_rhs {
        println!(
            "rhs: {:.2} us",
            median_us(|| {
                std::hint::black_box(a.rhs(0.1, std::hint::black_box(&y)).unwrap());
            })
        );
    }
    let dopri = args.tolerances(if quick {
        &[1e-6, 1e-8]
    } else {
        &[1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]
    });
    for &tol in &dopri {
        let opts = args.options(tol);
        row(&args, "DOPRI5", &format!("{tol:.0e}"), &a, || {
            passage::solve(
                &Dopri5::new(opts),
                &a,
                0.0,
                y0,
                args.t1,
                &[],
                &args.settings(tol),
            )
            .map(|p| (p.solution, p.passages))
        });
    }
    // The other explicit methods at the settings that meet the benchmark's 1e-3 (or nearly).
    let explicit = args.tolerances(if quick { &[1e-6] } else { &[1e-6, 1e-7] });
    for &tol in &explicit {
        let opts = args.options(tol);
        let settings = args.settings(tol);
        row(&args, "DOP853", &format!("{tol:.0e}"), &a, || {
            passage::solve(
                &Dop853::new(opts.clone()),
                &a,
                0.0,
                y0,
                args.t1,
                &[],
                &settings,
            )
            .map(|p| (p.solution, p.passages))
        });
        row(&args, "Auto", &format!("{tol:.0e}"), &a, || {
            passage::solve(&Auto::new(opts), &a, 0.0, y0, args.t1, &[], &settings)
                .map(|p| (p.solution, p.passages))
        });
    }
    let radau = args.tolerances(if quick {
        &[1e-6]
    } else {
        &[1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
    });
    for &tol in &radau {
        let opts = args.options(tol);
        row(&args, "Radau5", &format!("{tol:.0e}"), &a, || {
            passage::solve(
                &Radau5::new(opts),
                &a,
                0.0,
                y0,
                args.t1,
                &[],
                &args.settings(tol),
            )
            .map(|p| (p.solution, p.passages))
        });
    }
    let ali3: &[f64] = if quick {
        &[1e-2, 1e-3]
    } else {
        &[1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    };
    for &h in ali3 {
        let q0 = y0.fixed_rows::<{ fa::N }>(0).into_owned();
        let qd0 = y0.fixed_rows::<{ fa::N }>(fa::N).into_owned();
        row(&args, "ALI3-P", &format!("h={h:.0e}"), &a, || {
            Ali3::new(h)
                .solve::<_, { fa::N }, { fa::M }, { fa::D }>(&a, 0.0, q0, qd0, args.t1, &[])
                .map(|s| (s, Vec::new()))
        });
    }
    let alpha: &[f64] = if quick { &[1e-2] } else { &[1e-2, 1e-3, 1e-4] };
    for &h in alpha {
        row(&args, "gen-a", &format!("h={h:.0e}"), &a, || {
            passage::solve_generalized_alpha::<
                    _,
                    { fa::N },
                    { fa::M },
                    { fa::N + fa::M },
                    { fa::D },
                >(
                    &GeneralizedAlpha::new(0.9, h).recording(Record::Times(args.grid()), false),
                    &a,
                    0.0,
                    y0,
                    args.t1,
                    &[],
                    &args.settings(h * h),
                )
                .map(|p| (p.solution, p.passages))
        });
    }
}
