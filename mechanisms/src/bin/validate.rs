//! The validation report: every case of the manual, theory vs RecurDyn vs mbd.
//!
//! `cargo run --release -p mechanisms --bin validate [-- --json] [--case N] [--out DIR]`

use clap::Parser;
use mechanisms::validation::{Case, ManualRow, Outcome, error_pct, manual_rows};
use mechanisms::{cases, svg};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Parser, Debug)]
#[command(about = "Reproduce the validation manual's comparison tables with mbd")]
struct Args {
    /// Print one JSON array of rows instead of the table.
    #[arg(long)]
    json: bool,
    /// Run one case only (1..30).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=30))]
    case: Option<u32>,
    /// Write a Markdown report and one SVG plot per case into this directory.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// One row of the report (the `--json` schema).
#[derive(Serialize, Debug)]
struct ReportRow {
    case: String,
    quantity: String,
    unit: String,
    theory: Option<f64>,
    recurdyn: Option<f64>,
    value: f64,
    error_pct: f64,
    recurdyn_error_pct: Option<f64>,
    reference: f64,
    method: String,
    runtime_s: f64,
}

fn main() -> ExitCode {
    let args = Args::parse();
    // An unwritable `--out` is a usage error, found before any case runs.
    if let Some(dir) = &args.out
        && let Err(e) = writable(dir)
    {
        eprintln!("error: cannot write the report to {}: {e}", dir.display());
        return ExitCode::from(2);
    }
    let manual = manual_rows();
    let selected: Vec<Case> = cases()
        .into_iter()
        .filter(|c| args.case.is_none_or(|n| c.id.parse::<u32>() == Ok(n)))
        .collect();
    if selected.is_empty() {
        eprintln!("no case selected (cases are 1..30)");
        return ExitCode::FAILURE;
    }
    let mut rows = Vec::new();
    let mut outcomes = Vec::new();
    let mut failed = false;
    for (i, case) in selected.iter().enumerate() {
        eprintln!(
            "[{}/{}] case {}: {}",
            i + 1,
            selected.len(),
            case.id,
            case.title
        );
        let start = Instant::now();
        let result = (case.run)();
        let runtime = start.elapsed().as_secs_f64();
        match result {
            Ok(outcome) => {
                rows.extend(report_rows(case, &outcome, &manual, runtime));
                outcomes.push((*case, outcome, runtime));
            }
            Err(e) => {
                eprintln!("case {} failed: {e}", case.id);
                failed = true;
            }
        }
    }
    if args.json {
        match serde_json::to_string_pretty(&rows) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("cannot serialise the report: {e}");
                return ExitCode::FAILURE;
            }
        }
    } else {
        print!("{}", table(&rows));
    }
    if let Some(dir) = &args.out
        && let Err(e) = write_report(dir, &rows, &outcomes)
    {
        eprintln!("cannot write the report to {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Creates `dir` and checks that a file can be written in it.
fn writable(dir: &PathBuf) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let probe = dir.join(".mbd-write-probe");
    std::fs::write(&probe, b"")?;
    std::fs::remove_file(probe)
}

fn report_rows(
    case: &Case,
    outcome: &Outcome,
    manual: &[ManualRow],
    runtime: f64,
) -> Vec<ReportRow> {
    outcome
        .rows
        .iter()
        .map(|r| {
            let m = manual
                .iter()
                .find(|m| m.case == case.id && m.quantity == r.quantity);
            let recurdyn = m.and_then(|m| m.recurdyn);
            ReportRow {
                case: case.id.to_string(),
                quantity: r.quantity.to_string(),
                unit: m.map(|m| m.unit.clone()).unwrap_or_default(),
                theory: m.and_then(|m| m.theory),
                recurdyn,
                value: r.value,
                error_pct: error_pct(r.value, r.reference),
                recurdyn_error_pct: recurdyn.map(|v| error_pct(v, r.reference)),
                reference: r.reference,
                method: r.method.to_string(),
                runtime_s: runtime,
            }
        })
        .collect()
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v}"))
}

fn table(rows: &[ReportRow]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<4} {:<20} {:<8} {:>12} {:>12} {:>10} {:>18} {:>11} {:>18} {:>10}  method",
        "case",
        "quantity",
        "unit",
        "theory",
        "RecurDyn",
        "RD err %",
        "mbd",
        "mbd err %",
        "reference",
        "time [us]"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{:<4} {:<20} {:<8} {:>12} {:>12} {:>10} {:>18.12} {:>11.2e} {:>18.12} {:>10.1}  {}",
            r.case,
            r.quantity,
            r.unit,
            fmt_opt(r.theory),
            fmt_opt(r.recurdyn),
            r.recurdyn_error_pct
                .map_or_else(|| "-".to_string(), |e| format!("{e:.4}")),
            r.value,
            r.error_pct,
            r.reference,
            r.runtime_s * 1e6,
            r.method
        );
    }
    s
}

fn write_report(
    dir: &PathBuf,
    rows: &[ReportRow],
    outcomes: &[(Case, Outcome, f64)],
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut md = String::from("# mbd validation report\n\n");
    md.push_str("Errors are relative to the reference (the exact value; see each case's docs for corrections to the manual).\n\n");
    md.push_str("| case | quantity | unit | theory | RecurDyn | RecurDyn err % | mbd | mbd err % | reference | method | run time [us] |\n");
    md.push_str("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {:.12} | {:.2e} | {:.12} | {} | {:.1} |",
            r.case,
            r.quantity,
            r.unit,
            fmt_opt(r.theory),
            fmt_opt(r.recurdyn),
            r.recurdyn_error_pct
                .map_or_else(|| "-".to_string(), |e| format!("{e:.4}")),
            r.value,
            r.error_pct,
            r.reference,
            r.method,
            r.runtime_s * 1e6
        );
    }
    md.push_str("\n## Generated code per case\n\n| case | statements | parts |\n|---|---|---|\n");
    for (case, outcome, _) in outcomes {
        let statements: usize = case.generated.iter().map(|g| g.statements).sum();
        let mut parts: Vec<&str> = case
            .generated
            .iter()
            .flat_map(|g| g.parts.iter().copied())
            .collect();
        parts.sort_unstable();
        parts.dedup();
        let _ = writeln!(
            md,
            "| {} | {} | {} |",
            case.id,
            statements,
            parts.join(", ")
        );
        let title = format!("Case {}: {}", case.id, case.title);
        let plot = &outcome.plot;
        let svg = svg::line_plot(&title, plot.x_label, plot.y_label, &plot.points, plot.mark);
        std::fs::write(dir.join(format!("case{}.svg", case.id)), svg)?;
    }
    md.push_str("\n## Plots\n\n");
    for (case, _, _) in outcomes {
        let _ = writeln!(md, "![case {0}](case{0}.svg)\n", case.id);
    }
    std::fs::write(dir.join("report.md"), md)
}
