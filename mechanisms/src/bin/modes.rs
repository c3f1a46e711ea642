//! Linear modes of mechanisms about operating points against closed forms
//! ([`mechanisms::modes`]), each point with the cost of its exact linearisation beside a
//! finite-difference Jacobian of the same model.
//!
//! `cargo run --release -p mechanisms --bin modes [-- --json] [--svg DIR]`: with `--svg`,
//! the mode shapes of the planar mechanisms as SVG files in `DIR`
//! ([`mechanisms::mode_svg`]).

use clap::Parser;
use mbd::prelude::Vector;
use mechanisms::modes::{self, Cost, DOUBLE, FOUR_BAR, GOAL};

fn print_cost(name: &str, c: Option<Cost>) {
    match c {
        Some(c) => println!(
            "  {name:<48} rhs {:7.3} us, exact A {:7.3} us, forward differences {:7.3} us: exact / differences {:.2}",
            c.rhs_us, c.exact_a_us, c.forward_difference_us, c.ratio
        ),
        None => println!("  {name:<48} (not timed: an evaluation failed)"),
    }
}

/// Writes the mode-shape drawings into `dir`.
fn write_svgs(dir: &str) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
    for (name, svg) in mechanisms::mode_svg::drawings().map_err(|e| e.to_string())? {
        let path = std::path::Path::new(dir).join(name);
        std::fs::write(&path, svg).map_err(|e| format!("{}: {e}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

#[derive(Parser, Debug)]
#[command(about = "Linear modes of mechanisms against closed forms")]
struct Args {
    /// Print the rows as JSON.
    #[arg(long)]
    json: bool,
    /// Write the planar mechanisms' mode shapes as SVG files into this directory.
    #[arg(long)]
    svg: Option<String>,
}

fn main() {
    let args = Args::parse();
    let json = args.json;
    if let Some(dir) = &args.svg
        && let Err(e) = write_svgs(dir)
    {
        eprintln!("modes: {e}");
        std::process::exit(1);
    }
    let rows = match modes::rows_timed(true) {
        Ok(rows) => rows,
        Err(e) => {
            eprintln!("modes: {e}");
            std::process::exit(1);
        }
    };
    let failed = rows
        .iter()
        .filter(|r| r.rel_error.is_nan() || r.rel_error > GOAL)
        .count();
    if json {
        match serde_json::to_string_pretty(&rows) {
            Ok(s) => println!("{s}"),
            Err(e) => {
                eprintln!("modes: {e}");
                std::process::exit(1);
            }
        }
    } else {
        println!(
            "{:<30} {:<27} {:>2} {:<11} {:>14} {:>14} {:>9} {:>14} {:>9}  {:<8} {:>8} {:>8}",
            "mechanism",
            "point",
            "#",
            "kind",
            "f_n [Hz]",
            "f_d [Hz]",
            "zeta",
            "ref f_n [Hz]",
            "error",
            "stable",
            "A [us]",
            "FD [us]"
        );
        for r in &rows {
            let zeta = r
                .damping_ratio
                .map_or("-".to_string(), |z| format!("{z:.6}"));
            let (exact, fd) = r.cost.map_or(("-".into(), "-".into()), |c| {
                (
                    format!("{:.3}", c.exact_a_us),
                    format!("{:.3}", c.forward_difference_us),
                )
            });
            println!(
                "{:<30} {:<27} {:>2} {:<11} {:>14.10} {:>14.10} {:>9} {:>14.10} {:>9.1e}  {:<8} {:>8} {:>8}",
                r.mechanism,
                r.point,
                r.mode,
                r.kind,
                r.frequency_hz,
                r.damped_hz,
                zeta,
                r.reference_hz,
                r.rel_error,
                if r.unstable { "UNSTABLE" } else { "yes" },
                exact,
                fd
            );
        }
        println!("{} rows, {failed} above the goal {GOAL:e}", rows.len());
        println!(
            "f_n, f_d: natural and damped frequency of each eigenvalue pair of the linearised \
             state matrix A; zeta: damping ratio (- where f_n = 0); ref f_n: the closed form; \
             error: the largest of the relative errors of f_n and f_d against the closed forms \
             (absolute where the reference is 0) and the absolute error of zeta; stable: \
             UNSTABLE where the mode grows (an eigenvalue with a positive real part); the goal is error <= {GOAL:e} (exit code 1 \
             otherwise)."
        );
        println!(
            "A [us]: the exact A (one generated evaluation: accelerations, the residuals' \
             derivatives, one factorisation, 2N solves); FD [us]: forward differences \
             (D + 1 right-hand sides); least time over 31 interleaved batches.\n"
        );
        println!("moving states:");
        print_cost(
            "double pendulum (D = 4)",
            modes::cost(true, &DOUBLE, &Vector::<4>::new(0.7, -0.4, 1.3, -2.1)),
        );
        let (p, v) = (0.3, 0.8);
        print_cost(
            "sprung four-bar, augmented, on its loop (D = 4)",
            modes::cost(true, &FOUR_BAR, &Vector::<4>::new(p, p, v, v)),
        );
    }
    if failed > 0 {
        std::process::exit(1);
    }
}
