//! Linear modes of mechanisms about operating points against closed forms
//! ([`mechanisms::modes`]), and the cost of one exact linearisation beside finite-difference
//! Jacobians of the same model.
//!
//! `cargo run --release -p mechanisms --bin modes [-- --json]`

use mbd::OdeSystem;
use mbd::analysis::linear::{central_difference, linearize};
use mbd::jacobian::forward_difference;
use mbd::prelude::Vector;
use mechanisms::modes::{self, DOUBLE, FOUR_BAR, GOAL};
use std::hint::black_box;
use std::time::Instant;

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

/// One model at one state: one rhs, the exact `A`, forward and central differences
/// (`D + 1` and `2 D` right-hand sides).
fn timings<S: OdeSystem<D>, const D: usize>(name: &str, m: &S, y: &Vector<D>) {
    let rhs = median_us(|| {
        black_box(m.rhs(0.0, black_box(y)).unwrap());
    });
    let exact = median_us(|| {
        black_box(linearize(m, 0.0, black_box(y)).unwrap());
    });
    let forward = median_us(|| {
        black_box(forward_difference(|y| m.rhs(0.0, y), black_box(y)).unwrap());
    });
    let central = median_us(|| {
        black_box(central_difference(m, 0.0, black_box(y), 1e-5).unwrap());
    });
    println!("{name} (D = {D}), median time per call:");
    println!("  rhs                          {rhs:8.3} us");
    println!("  exact A (generated)          {exact:8.3} us");
    println!("  forward differences (D+1 f)  {forward:8.3} us");
    println!("  central differences (2D f)   {central:8.3} us");
}

fn main() {
    let json = std::env::args().any(|a| a == "--json");
    let rows = match modes::rows() {
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
            "{:<30} {:<27} {:>2} {:<11} {:>14} {:>14} {:>9} {:>14} {:>9}  stable",
            "mechanism",
            "point",
            "#",
            "kind",
            "f_n [Hz]",
            "f_d [Hz]",
            "zeta",
            "ref f_n [Hz]",
            "error"
        );
        for r in &rows {
            let zeta = r
                .damping_ratio
                .map_or("-".to_string(), |z| format!("{z:.6}"));
            println!(
                "{:<30} {:<27} {:>2} {:<11} {:>14.10} {:>14.10} {:>9} {:>14.10} {:>9.1e}  {}",
                r.mechanism,
                r.point,
                r.mode,
                r.kind,
                r.frequency_hz,
                r.damped_hz,
                zeta,
                r.reference_hz,
                r.rel_error,
                if r.unstable { "UNSTABLE" } else { "yes" }
            );
        }
        println!("{} rows, {failed} above the goal {GOAL:e}\n", rows.len());
        timings(
            "double pendulum, moving",
            &DOUBLE,
            &Vector::<4>::new(0.7, -0.4, 1.3, -2.1),
        );
        let (p, v) = (0.3, 0.8);
        timings(
            "sprung four-bar (augmented), moving on its loop",
            &FOUR_BAR,
            &Vector::<4>::new(p, p, v, v),
        );
    }
    if failed > 0 {
        std::process::exit(1);
    }
}
