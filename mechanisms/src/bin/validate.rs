//! The validation report: every case of the manual, theory vs RecurDyn vs mbd.
//!
//! `cargo run --release -p mechanisms --bin validate [-- --json] [--case N] [--out DIR]`

use clap::Parser;
use mechanisms::cases;
use mechanisms::report::{CaseRun, LEGEND, ReportRow, corrected, sig, summary};
use mechanisms::validation::{Case, ManualRow, Outcome, error_pct, manual_rows};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Parser, Debug)]
#[command(
    about = "Reproduce the validation manual's comparison tables with mbd",
    after_help = "Prints one row per compared quantity (the manual's theory and RecurDyn \
                  values, mbd's value, each error in percent against the exact reference, \
                  how mbd got it, the case's run time), then a summary (the largest errors, \
                  every case that failed and why) and a legend of the columns. Exit status: \
                  1 if a case fails, 2 for a usage error."
)]
struct Args {
    /// Print one JSON array of rows instead of the table.
    #[arg(long)]
    json: bool,
    /// Run one case only (1..30).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=30))]
    case: Option<u32>,
    /// Write the report into this directory: `report.html` (self-contained: drawings,
    /// animations, plots, tables), `report.md` and one SVG plot per compared quantity.
    #[arg(long)]
    out: Option<PathBuf>,
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
    let mut failed = Vec::new();
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
                let case_rows = report_rows(case, &outcome, &manual, runtime);
                rows.extend(case_rows.iter().cloned());
                let animation = args.out.as_ref().map(|_| draw(case, &outcome));
                outcomes.push(CaseRun {
                    case: *case,
                    outcome,
                    rows: case_rows,
                    runtime_s: runtime,
                    animation: animation.unwrap_or(Err("not drawn".into())),
                });
            }
            Err(e) => {
                eprintln!("case {} failed: {e}", case.id);
                failed.push((case.id.to_string(), e.to_string()));
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
        print!("{}", table(&rows, &failed));
    }
    if let Some(dir) = &args.out
        && let Err(e) = write_report(dir, &rows, &outcomes, &failed)
    {
        eprintln!("cannot write the report to {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    if !failed.is_empty() {
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

/// Draws the case over the time span of its curves over time (2 s where none is), with a
/// still at each compared instant.
fn draw(case: &Case, outcome: &Outcome) -> Result<mechanisms::validation::Animation, String> {
    let rows = &outcome.rows;
    let span = rows
        .iter()
        .filter_map(|r| r.curve.end())
        .fold(0.0, f64::max);
    let mut at: Vec<f64> = rows
        .iter()
        .filter_map(|r| r.curve.instant(r.value))
        .collect();
    at.sort_by(f64::total_cmp);
    at.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * span);
    let span = if span > 0.0 { span } else { DEFAULT_SPAN };
    // A run the plain integrator cannot finish (friction's stop) is drawn to the last
    // compared instant, which the case itself reached.
    (case.draw)(span, &at)
        .or_else(|e| match at.last() {
            Some(&t) if t > 0.0 => (case.draw)(t, &at),
            _ => Err(e),
        })
        .map_err(|e| e.to_string())
}

/// How long a case whose plot is not over time is animated, in seconds.
const DEFAULT_SPAN: f64 = 2.0;

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v}"))
}

/// The manual's theory, marked `*` where the reference is a corrected value.
fn theory(r: &ReportRow) -> String {
    let mark = if corrected(r) { "*" } else { "" };
    format!("{}{mark}", fmt_opt(r.theory))
}

fn table(rows: &[ReportRow], failed: &[(String, String)]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<4} {:<20} {:<8} {:>10} {:>10} {:>9} {:>14} {:>9} {:>14} {:>10}  method",
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
            "{:<4} {:<20} {:<8} {:>10} {:>10} {:>9} {:>14} {:>9.1e} {:>14} {:>10}  {}",
            r.case,
            r.quantity,
            r.unit,
            theory(r),
            fmt_opt(r.recurdyn),
            r.recurdyn_error_pct
                .map_or_else(|| "-".to_string(), |e| sig(e, 2)),
            sig(r.value, 10),
            r.error_pct,
            sig(r.reference, 10),
            sig(r.runtime_s * 1e6, 3),
            r.method
        );
    }
    s.push('\n');
    s.push_str(&wrap(&summary(rows, failed).join(" "), 100));
    s.push('\n');
    for item in LEGEND {
        s.push_str(&wrap(item, 100));
    }
    s
}

/// `text` broken into lines of at most `width` characters at spaces (a longer word alone).
fn wrap(text: &str, width: usize) -> String {
    let mut out = String::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.len() + 1 + word.len() > width {
            let _ = writeln!(out, "{line}");
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    let _ = writeln!(out, "{line}");
    out
}

/// A Markdown table cell: a `|` in the text would end the cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

fn write_report(
    dir: &PathBuf,
    rows: &[ReportRow],
    runs: &[CaseRun],
    failed: &[(String, String)],
) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut md = String::from("# mbd validation report\n\n");
    let _ = writeln!(md, "{}\n", summary(rows, failed).join(" "));
    md.push_str("`report.html` beside this file has the drawings, animations and plots, and per case where the manual is wrong.\n\n");
    for item in LEGEND {
        let _ = writeln!(md, "- {}", item.replace('*', "\\*"));
    }
    md.push('\n');
    md.push_str("| case | quantity | unit | theory | RecurDyn | RecurDyn err % | mbd | mbd err % | reference | method | time [us] |\n");
    md.push_str("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {:.1e} | {} | {} | {} |",
            r.case,
            cell(&r.quantity),
            cell(&r.unit),
            theory(r).replace('*', "\\*"),
            fmt_opt(r.recurdyn),
            r.recurdyn_error_pct
                .map_or_else(|| "-".to_string(), |e| sig(e, 2)),
            sig(r.value, 10),
            r.error_pct,
            sig(r.reference, 10),
            cell(&r.method),
            sig(r.runtime_s * 1e6, 3)
        );
    }
    md.push_str("\n## Generated code per case\n\n| case | statements | parts |\n|---|---|---|\n");
    for run in runs {
        let case = &run.case;
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
    }
    md.push_str("\n## Plots\n\n");
    for run in runs {
        for (i, r) in run.rows.iter().enumerate() {
            let name = format!("case{}-{}.svg", run.case.id, r.quantity);
            let svg = mechanisms::report::row_plot(run, i).map_err(std::io::Error::other)?;
            std::fs::write(dir.join(&name), svg)?;
            let _ = writeln!(md, "![case {} {}]({name})\n", run.case.id, r.quantity);
        }
    }
    std::fs::write(dir.join("report.md"), md)?;
    std::fs::write(
        dir.join("report.html"),
        mechanisms::report::html(runs, failed),
    )
}
