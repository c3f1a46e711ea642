//! Work-precision report: error against run time for every model that integrates in time
//! and every integrator; the generated/hand-written ratio of three models; mbd against a
//! peer crate (`differential-equations`) on the same generated right-hand side.
//!
//! `cargo run --release -p mechanisms --bin work-precision [-- --json] [--out DIR]
//! [--repeats N] [--only NAME] [--time-to-accuracy]`

use clap::Parser;
use mechanisms::accuracy;
use mechanisms::plot::{self, Series};
use mechanisms::workprecision::{
    self, ERROR_FLOOR, Failure, MAX_RUN_S, Method, Problem, RHO_INF, Run, Timing, excluded_cases,
    pilot_span, sweep, time_to_reach, zero_overhead,
};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Parser, Debug)]
#[command(about = "Error against run time for every model and integrator of mbd")]
struct Args {
    /// Print one JSON object (settings, summary, rows) instead of the summary.
    #[arg(long)]
    json: bool,
    /// Write rows.csv, report.json, summary.md and one SVG work-precision plot per mechanism here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Timed repeats per run (the run time is their median; 0 times the first run only).
    #[arg(long, default_value_t = 7)]
    repeats: usize,
    /// Sweep only the mechanisms whose name contains this.
    #[arg(long)]
    only: Option<String>,
    /// Print only the time-to-accuracy table (pendulum, chains of 8 and 32 links,
    /// slider-crank; DOPRI5, DOP853 and Vern9 to 1e-6 and 1e-10 over a sample grid), with the step
    /// loop's cost per evaluation; also written to `time_to_accuracy.md` with `--out`.
    #[arg(long)]
    time_to_accuracy: bool,
}

/// One row of the report (the `--json` and CSV schema). A run that could not be made has
/// no error, time or counters, and says why in `note`.
#[derive(Serialize, Debug, Clone)]
struct Row {
    mechanism: String,
    method: String,
    setting: String,
    error: Option<f64>,
    runtime_s: Option<f64>,
    steps: Option<usize>,
    rhs_evals: Option<usize>,
    jac_evals: Option<usize>,
    note: Option<String>,
}

/// All runs of one mechanism and method.
struct Curve {
    mechanism: &'static str,
    method: Method,
    runs: Vec<Run>,
}

impl Curve {
    fn points(&self) -> Vec<(f64, f64)> {
        self.runs.iter().filter_map(Run::point).collect()
    }

    fn time_to(&self, target: f64) -> Option<f64> {
        time_to_reach(&self.points(), target)
    }

    /// Why the method produced no point at all, if it did not.
    fn skipped(&self) -> Option<String> {
        if !self.points().is_empty() {
            return None;
        }
        self.runs.iter().find_map(|r| match &r.outcome {
            Err(Failure::Unsupported(why)) => Some(format!("skipped: {why}")),
            _ => None,
        })
    }
}

fn rows(curve: &Curve) -> Vec<Row> {
    curve
        .runs
        .iter()
        .map(|r| {
            let base = Row {
                mechanism: curve.mechanism.to_string(),
                method: curve.method.name().to_string(),
                setting: r.setting.label(),
                error: None,
                runtime_s: None,
                steps: None,
                rhs_evals: None,
                jac_evals: None,
                note: None,
            };
            match &r.outcome {
                Ok((m, t)) => Row {
                    error: Some(m.error()),
                    runtime_s: Some(*t),
                    steps: Some(m.stats.n_steps),
                    rhs_evals: Some(m.stats.n_rhs),
                    jac_evals: Some(m.stats.n_jac),
                    ..base
                },
                Err(f) => Row {
                    note: Some(f.to_string()),
                    ..base
                },
            }
        })
        .collect()
}

/// Sweep a group of problems that share settings (one case, or a generated model and its
/// hand-written twin) with the methods they have in common, then the rest alone.
fn sweep_group(group: &[&Problem], timing: Timing, progress: &mut Progress) -> Vec<Curve> {
    let mut curves = Vec::new();
    let span = match pilot_span(group[0]) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{}: the pilot run failed ({e}); not swept", group[0].name);
            return curves;
        }
    };
    let mut methods: Vec<Method> = group
        .iter()
        .flat_map(|p| p.methods.iter().copied())
        .collect();
    methods.sort_unstable();
    methods.dedup();
    for method in methods {
        let members: Vec<&Problem> = group
            .iter()
            .copied()
            .filter(|p| p.methods.contains(&method))
            .collect();
        let start = Instant::now();
        let runs = sweep(&members, method, span, timing);
        for (p, runs) in members.iter().zip(runs) {
            curves.push(Curve {
                mechanism: p.name,
                method,
                runs,
            });
        }
        let names: Vec<&str> = members.iter().map(|p| p.name).collect();
        progress.tick(&names.join(" + "), method, start.elapsed().as_secs_f64());
    }
    curves
}

struct Progress {
    done: usize,
    total: usize,
    start: Instant,
}

impl Progress {
    fn tick(&mut self, what: &str, method: Method, secs: f64) {
        self.done += 1;
        eprintln!(
            "[{}/{}] {what}: {method} ({secs:.1} s; {:.0} s in all)",
            self.done,
            self.total,
            self.start.elapsed().as_secs_f64()
        );
    }
}

fn fmt_time(t: Option<f64>) -> String {
    t.map_or_else(|| "-".to_string(), |t| format!("{t:.3e}"))
}

fn fmt_ratio(r: Option<f64>) -> String {
    r.map_or_else(|| "-".to_string(), |r| format!("{r:.3}"))
}

/// Every run of every method of a mechanism within this of the exact result (a decade
/// below the smallest target, 1e-10): the errors are round-off (the motion is a polynomial
/// the methods integrate exactly; what is left is rounding in the event location), so no
/// method is faster to an accuracy than another.
const ROUND_OFF: f64 = 1e-11;

/// Whether a mechanism's runs all end at round-off (see [`ROUND_OFF`]).
fn round_off_only(curves: &[&Curve]) -> bool {
    let mut errors = curves
        .iter()
        .filter(|c| c.method != Method::PeerDopri5)
        .flat_map(|c| c.points())
        .map(|p| p.1)
        .peekable();
    errors.peek().is_some() && errors.all(|e| e <= ROUND_OFF)
}

/// The fastest method of a mechanism to reach `target`, and its time; none where every
/// run is at round-off.
fn fastest(curves: &[&Curve], target: f64) -> Option<(Method, f64)> {
    if round_off_only(curves) {
        return None;
    }
    curves
        .iter()
        .filter(|c| c.method != Method::PeerDopri5)
        .filter_map(|c| c.time_to(target).map(|t| (c.method, t)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// One model and method of the zero-overhead comparison.
struct ZeroOverhead {
    model: String,
    method: Method,
    /// Times to reach [`RATIO_TARGET`], generated and hand-written, and their ratio.
    generated: Option<f64>,
    hand: Option<f64>,
    ratio: Option<f64>,
    /// The ratio of the times to reach 1e-6.
    ratio_1e6: Option<f64>,
    /// The median over the sweep's settings of the ratio of run times at the same setting
    /// (the same steps and evaluations: a cross-check less sensitive to one noisy run).
    median_ratio: Option<f64>,
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    v.retain(|x| x.is_finite());
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(v[n / 2]),
        _ => Some(0.5 * (v[n / 2 - 1] + v[n / 2])),
    }
}

/// The fastest method to an error, and its time.
type Fastest = Option<(Method, f64)>;

/// mbd against the peer on one model: (model, mbd method, t_mbd, t_peer, ratio) at 1e-8.
type PeerRow = (String, Method, Option<f64>, Option<f64>, Option<f64>);

struct Figures {
    /// Per mechanism, in order: (name, title, round-off only, fastest to 1e-6, fastest to
    /// 1e-10).
    per_mechanism: Vec<(String, String, bool, Fastest, Fastest)>,
    /// Generated against hand-written, per model and method.
    zero_overhead: Vec<ZeroOverhead>,
    /// (model, mbd method, t_mbd, t_peer, ratio) at 1e-8.
    peer: Vec<PeerRow>,
    /// (mechanism, method, reason).
    skipped: Vec<(String, Method, String)>,
}

/// Every method, in the order of the plots' colours.
const ALL_METHODS: [Method; 8] = [
    Method::Rk4,
    Method::Dopri5,
    Method::Dop853,
    Method::Vern9,
    Method::Radau5,
    Method::GeneralizedAlpha,
    Method::Dopri5NoProjection,
    Method::PeerDopri5,
];

/// The error at which the zero-overhead and peer ratios are read.
const RATIO_TARGET: f64 = 1e-8;

fn figures(curves: &[Curve], problems: &[Problem], pairs: &[(Problem, Problem)]) -> Figures {
    let of =
        |name: &str| -> Vec<&Curve> { curves.iter().filter(|c| c.mechanism == name).collect() };
    let per_mechanism = problems
        .iter()
        .map(|p| {
            let cs = of(p.name);
            (
                p.name.to_string(),
                p.title.to_string(),
                round_off_only(&cs),
                fastest(&cs, 1e-6),
                fastest(&cs, 1e-10),
            )
        })
        .collect();
    let find = |name: &str, m: Method| curves.iter().find(|c| c.mechanism == name && c.method == m);
    let ratio = |a: Option<f64>, b: Option<f64>| a.zip(b).map(|(a, b)| a / b);
    let mut zero = Vec::new();
    let mut peer = Vec::new();
    for (generated, hand) in pairs {
        for m in Method::MBD {
            let (tg, th) = (
                find(generated.name, m).and_then(|c| c.time_to(RATIO_TARGET)),
                find(hand.name, m).and_then(|c| c.time_to(RATIO_TARGET)),
            );
            let at = |name: &str, target| find(name, m).and_then(|c| c.time_to(target));
            if let (Some(cg), Some(ch)) = (find(generated.name, m), find(hand.name, m)) {
                let per_setting: Vec<f64> = cg
                    .runs
                    .iter()
                    .zip(&ch.runs)
                    .filter_map(|(a, b)| Some(a.point()?.0 / b.point()?.0))
                    .collect();
                zero.push(ZeroOverhead {
                    model: generated.name.to_string(),
                    method: m,
                    generated: tg,
                    hand: th,
                    ratio: ratio(tg, th),
                    ratio_1e6: ratio(at(generated.name, 1e-6), at(hand.name, 1e-6)),
                    median_ratio: median(per_setting),
                });
            }
        }
        if let Some(pc) = find(generated.name, Method::PeerDopri5) {
            let tp = pc.time_to(RATIO_TARGET);
            for m in [Method::Dopri5NoProjection, Method::Dopri5] {
                if let Some(c) = find(generated.name, m) {
                    let tm = c.time_to(RATIO_TARGET);
                    peer.push((generated.name.to_string(), m, tm, tp, ratio(tm, tp)));
                }
            }
        }
    }
    let skipped = curves
        .iter()
        .filter_map(|c| {
            c.skipped()
                .map(|why| (c.mechanism.to_string(), c.method, why))
        })
        .collect();
    Figures {
        per_mechanism,
        zero_overhead: zero,
        peer,
        skipped,
    }
}

fn summary_text(f: &Figures) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<32} {:>24} {:>24}",
        "mechanism", "fastest to 1e-6 [s]", "fastest to 1e-10 [s]"
    );
    let cell = |x: &Option<(Method, f64)>| {
        x.map_or_else(
            || "not reached".to_string(),
            |(m, t)| format!("{t:.3e} {m}"),
        )
    };
    for (name, _, round_off, a, b) in &f.per_mechanism {
        if *round_off {
            let _ = writeln!(
                s,
                "{name:<32} {:>49}",
                format!("round-off only: every run within {ROUND_OFF:.0e}")
            );
        } else {
            let _ = writeln!(s, "{:<32} {:>24} {:>24}", name, cell(a), cell(b));
        }
    }
    let _ = writeln!(
        s,
        "\nzero overhead: time to reach {RATIO_TARGET:e} relative error, generated / hand-written"
    );
    for z in &f.zero_overhead {
        let _ = writeln!(
            s,
            "  {:<16} {:<18} generated {:>10}  hand-written {:>10}  ratio {:>6}  (at 1e-6: {:>6}; median per setting: {:>6})",
            z.model,
            z.method.name(),
            fmt_time(z.generated),
            fmt_time(z.hand),
            fmt_ratio(z.ratio),
            fmt_ratio(z.ratio_1e6),
            fmt_ratio(z.median_ratio)
        );
    }
    let _ = writeln!(
        s,
        "\npeer: time to reach {RATIO_TARGET:e}, mbd / differential-equations DOPRI5 (same generated rhs)"
    );
    for (name, m, tm, tp, r) in &f.peer {
        let _ = writeln!(
            s,
            "  {:<18} {:<24} mbd {:>10}  peer {:>10}  ratio {}",
            name,
            m.name(),
            fmt_time(*tm),
            fmt_time(*tp),
            fmt_ratio(*r)
        );
    }
    if !f.skipped.is_empty() {
        let _ = writeln!(s, "\nnot run:");
        for (name, m, why) in &f.skipped {
            let _ = writeln!(s, "  {name} / {m}: {why}");
        }
    }
    s
}

/// The report as JSON: the numeric settings it was made with, the summary, every row.
fn json_report(rows: &[Row], f: &Figures, timing: Timing) -> serde_json::Value {
    let fastest =
        |x: &Fastest| x.map(|(m, t)| serde_json::json!({ "method": m.name(), "time_s": t }));
    let methods: Vec<serde_json::Value> = ALL_METHODS
        .iter()
        .map(|m| {
            let sweep = if m.fixed_step() {
                "step h = span / 2^k"
            } else {
                "rtol = atol = 1e-3 .. 1e-12"
            };
            serde_json::json!({ "method": m.name(), "sweep": sweep })
        })
        .collect();
    serde_json::json!({
        "settings": {
            "repeats": timing.repeats,
            "min_batch_s": timing.min_batch_s,
            "error_floor": ERROR_FLOOR,
            "round_off": ROUND_OFF,
            "max_run_s": MAX_RUN_S,
            "ratio_target": RATIO_TARGET,
            "targets": [1e-6, 1e-10],
            "generalized_alpha_rho_inf": RHO_INF,
            "methods": methods,
        },
        "summary": {
            "per_mechanism": f.per_mechanism.iter().map(|(name, title, round_off, a, b)| serde_json::json!({
                "mechanism": name, "measured": title, "round_off_only": round_off,
                "fastest_to_1e-6": fastest(a), "fastest_to_1e-10": fastest(b),
            })).collect::<Vec<_>>(),
            "zero_overhead": f.zero_overhead.iter().map(|z| serde_json::json!({
                "model": z.model, "method": z.method.name(), "generated_s": z.generated,
                "hand_written_s": z.hand, "ratio": z.ratio, "ratio_at_1e-6": z.ratio_1e6,
                "median_ratio_per_setting": z.median_ratio,
            })).collect::<Vec<_>>(),
            "peer": f.peer.iter().map(|(name, m, tm, tp, r)| serde_json::json!({
                "model": name, "mbd_method": m.name(), "mbd_s": tm, "peer_s": tp, "ratio": r,
            })).collect::<Vec<_>>(),
            "skipped": f.skipped.iter().map(|(name, m, why)| serde_json::json!({
                "mechanism": name, "method": m.name(), "why": why,
            })).collect::<Vec<_>>(),
        },
        "rows": rows,
    })
}

fn slug(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect::<String>()
        .replace("__", "_")
        .trim_matches('_')
        .to_string()
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn write_report(
    dir: &Path,
    rows: &[Row],
    curves: &[Curve],
    problems: &[Problem],
    f: &Figures,
    timing: Timing,
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut csv =
        String::from("mechanism,method,setting,error,runtime_s,steps,rhs_evals,jac_evals,note\n");
    let opt = |v: Option<String>| v.unwrap_or_default();
    for r in rows {
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{}",
            csv_field(&r.mechanism),
            csv_field(&r.method),
            csv_field(&r.setting),
            opt(r.error.map(|v| format!("{v:e}"))),
            opt(r.runtime_s.map(|v| format!("{v:e}"))),
            opt(r.steps.map(|v| v.to_string())),
            opt(r.rhs_evals.map(|v| v.to_string())),
            opt(r.jac_evals.map(|v| v.to_string())),
            csv_field(r.note.as_deref().unwrap_or(""))
        );
    }
    std::fs::write(dir.join("rows.csv"), csv)?;

    let mut md = String::from("# mbd work-precision report\n\n");
    let _ = writeln!(
        md,
        "Error: the largest relative error of a run's measured quantities against their exact \
         references (the cases' own). Time: wall time of the whole run (integration, events, \
         outputs), median of {} repeats. Times to an error are interpolated in log-log on each \
         method's Pareto front. Every row is in `rows.csv`.\n",
        timing.repeats
    );
    md.push_str("## Fastest method per mechanism\n\n");
    md.push_str(
        "| mechanism | measured | to 1e-6: method | time [s] | to 1e-10: method | time [s] |\n",
    );
    md.push_str("|---|---|---|---|---|---|\n");
    let cell = |x: &Option<(Method, f64)>| {
        x.map_or_else(
            || "not reached | -".to_string(),
            |(m, t)| format!("{m} | {t:.3e}"),
        )
    };
    for (name, title, round_off, a, b) in &f.per_mechanism {
        if *round_off {
            let _ = writeln!(
                md,
                "| {name} | {title} | round-off only: every run within {ROUND_OFF:.0e}, no fastest | - | - | - |"
            );
        } else {
            let _ = writeln!(md, "| {name} | {title} | {} | {} |", cell(a), cell(b));
        }
    }
    let _ = writeln!(
        md,
        "\n## Zero overhead: generated / hand-written, time to {RATIO_TARGET:e}\n\n\
         The hand-written twins (`mechanisms::handwritten`) run through the same integrators.\n\n\
         | model | method | generated [s] | hand-written [s] | ratio | ratio at 1e-6 | median ratio per setting |\n\
         |---|---|---|---|---|---|---|"
    );
    for z in &f.zero_overhead {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} |",
            z.model,
            z.method,
            fmt_time(z.generated),
            fmt_time(z.hand),
            fmt_ratio(z.ratio),
            fmt_ratio(z.ratio_1e6),
            fmt_ratio(z.median_ratio)
        );
    }
    let _ = writeln!(
        md,
        "\n## Against a peer: mbd / `differential-equations` DOPRI5, time to {RATIO_TARGET:e}\n\n\
         Both integrate the same generated right-hand side; the peer has no projection onto \
         the constraint manifolds, so on the slider-crank `DOPRI5 (no projection)` is the same \
         algorithm.\n\n\
         | model | mbd method | mbd [s] | peer [s] | ratio |\n|---|---|---|---|---|"
    );
    for (name, m, tm, tp, r) in &f.peer {
        let _ = writeln!(
            md,
            "| {name} | {m} | {} | {} | {} |",
            fmt_time(*tm),
            fmt_time(*tp),
            fmt_ratio(*r)
        );
    }
    if !f.skipped.is_empty() {
        md.push_str("\n## Not run\n\n");
        for (name, m, why) in &f.skipped {
            let _ = writeln!(md, "- {name} / {m}: {why}");
        }
    }
    md.push_str("\n## Cases without a time integration\n\n");
    for (case, why) in excluded_cases() {
        let _ = writeln!(md, "- {case}: {why}");
    }
    md.push_str("\n## Plots\n\n");
    for p in problems {
        // Every method in a fixed order, so that a method has the same colour in every plot;
        // errors are floored at 1e-16 (an exact result) and runs off by more than 10x left out.
        let series: Vec<Series> = ALL_METHODS
            .iter()
            .map(|&m| Series {
                name: m.name().to_string(),
                points: curves
                    .iter()
                    .find(|c| c.mechanism == p.name && c.method == m)
                    .map(|c| c.points())
                    .unwrap_or_default()
                    .into_iter()
                    .filter(|&(_, e)| e <= 10.0)
                    .map(|(t, e)| (t, e.max(1e-16)))
                    .collect(),
                line: true,
                markers: true,
            })
            .collect();
        let file = format!("{}.svg", slug(p.name));
        let round_off = f.per_mechanism.iter().any(|m| m.0 == p.name && m.2);
        let title = if round_off {
            format!("{}: work-precision (round-off only)", p.name)
        } else {
            format!("{}: work-precision", p.name)
        };
        let svg = plot::log_log_plot(&title, "run time [s]", "max relative error", &series)
            .map_err(std::io::Error::other)?;
        std::fs::write(dir.join(&file), svg)?;
        let _ = writeln!(md, "![{}]({file})\n", p.name);
    }
    std::fs::write(dir.join("summary.md"), md)
}

fn main() -> ExitCode {
    let args = Args::parse();
    if args.time_to_accuracy {
        let load = accuracy::load_average();
        let table = accuracy::table(&accuracy::all_sweeps(), &load);
        print!("{table}");
        if let Some(dir) = &args.out
            && let Err(e) = std::fs::create_dir_all(dir)
                .and_then(|()| std::fs::write(dir.join("time_to_accuracy.md"), &table))
        {
            eprintln!("cannot write {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
        return ExitCode::SUCCESS;
    }
    let timing = Timing {
        repeats: args.repeats,
        ..Timing::default()
    };
    let keep = |p: &Problem| args.only.as_deref().is_none_or(|s| p.name.contains(s));
    let cases: Vec<Problem> = workprecision::cases()
        .into_iter()
        .filter(|p| keep(p))
        .collect();
    let pairs: Vec<(Problem, Problem)> = zero_overhead()
        .into_iter()
        .filter(|(g, h)| keep(g) || keep(h))
        .collect();
    let mut problems: Vec<Problem> = cases.clone();
    for (g, h) in &pairs {
        problems.extend([*g, *h]);
    }
    if problems.is_empty() {
        eprintln!("no mechanism matches {:?}", args.only);
        return ExitCode::FAILURE;
    }
    let method_count = |ps: &[&Problem]| {
        let mut m: Vec<Method> = ps.iter().flat_map(|p| p.methods.iter().copied()).collect();
        m.sort_unstable();
        m.dedup();
        m.len()
    };
    let total = cases.iter().map(|c| method_count(&[c])).sum::<usize>()
        + pairs
            .iter()
            .map(|(g, h)| method_count(&[g, h]))
            .sum::<usize>();
    let mut progress = Progress {
        done: 0,
        total,
        start: Instant::now(),
    };
    let mut curves = Vec::new();
    for case in &cases {
        curves.extend(sweep_group(&[case], timing, &mut progress));
    }
    for (g, h) in &pairs {
        curves.extend(sweep_group(&[g, h], timing, &mut progress));
    }
    let all_rows: Vec<Row> = curves.iter().flat_map(rows).collect();
    let figs = figures(&curves, &problems, &pairs);
    let summary = summary_text(&figs);
    let report = json_report(&all_rows, &figs, timing);
    if args.json {
        match serde_json::to_string_pretty(&report) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("cannot serialise the rows: {e}");
                return ExitCode::FAILURE;
            }
        }
        eprint!("{summary}");
    } else {
        print!("{summary}");
    }
    if let Some(dir) = &args.out
        && let Err(e) =
            write_report(dir, &all_rows, &curves, &problems, &figs, timing).and_then(|()| {
                let text = serde_json::to_string_pretty(&report).map_err(std::io::Error::other)?;
                std::fs::write(dir.join("report.json"), text)
            })
    {
        eprintln!("cannot write the report to {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    eprintln!(
        "work-precision: {} runs in {:.0} s",
        all_rows.len(),
        progress.start.elapsed().as_secs_f64()
    );
    ExitCode::SUCCESS
}
