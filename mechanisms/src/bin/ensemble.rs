//! Ensemble speed-up: many variations of one generated model integrated serially and with
//! `mbd::ensemble` (rayon), same run, median of 3 each; checks that both give bitwise the
//! same final states in the same order, and prints the ratio.
//!
//! `cargo run --release -p mechanisms --bin ensemble [-- --members 64 --t-end 10 --json]`
//!
//! The model is a generated triple pendulum of uniform links (the 3-link chain of
//! `mechanisms::chain_by_hand`), chaotic at the larger amplitudes used here, so members
//! differ in their step counts as a real parameter study's do. Each member varies the link
//! length and the initial angles; DOPRI5 at `rtol = atol = 1e-10`, no dense output.

use clap::Parser;
use mbd::integrate::{Dopri5, Integrator};
use mbd::prelude::*;
use std::time::Instant;

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[coords(q1, q2, q3)]
#[rigid(link1, mass = m, inertia = m * l * l / 12.0,
        at = [l / 2.0 * sin(q1), -(l / 2.0 * cos(q1))], angle = q1)]
#[rigid(link2, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l / 2.0 * sin(q1 + q2), -(l * cos(q1) + l / 2.0 * cos(q1 + q2))],
        angle = q1 + q2)]
#[rigid(link3, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l * sin(q1 + q2) + l / 2.0 * sin(q1 + q2 + q3),
              -(l * cos(q1) + l * cos(q1 + q2) + l / 2.0 * cos(q1 + q2 + q3))],
        angle = q1 + q2 + q3)]
pub struct TriplePendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[derive(Debug, Parser)]
#[command(about = "Serial vs parallel (rayon) ensemble of one generated model")]
struct Args {
    /// Number of members (parameter and initial-condition variations), at least 1.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u64).range(1..))]
    members: u64,
    /// End time of every run, in seconds (positive and finite).
    #[arg(long, default_value_t = 10.0, value_parser = positive_seconds)]
    t_end: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// A positive, finite number of seconds.
fn positive_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v > 0.0 && v.is_finite() => Ok(v),
        Ok(v) => Err(format!("{v} is not a positive, finite time")),
        Err(e) => Err(e.to_string()),
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args = Args::parse();
    let members: Vec<Member<TriplePendulum, 6>> = (0..args.members as usize)
        .map(|k| {
            let x = k as f64 / args.members as f64;
            Member::new(
                TriplePendulum {
                    m: 1.0,
                    l: 0.5 + 0.5 * x,
                    g: 9.81,
                },
                Vector::<6>::from_column_slice(&[
                    0.5 + 1.5 * x,
                    -0.3 + 0.6 * x,
                    0.2 * x,
                    0.0,
                    0.1,
                    -0.1,
                ]),
            )
        })
        .collect();
    let method = Dopri5::new(Options {
        rtol: 1e-10,
        atol: 1e-10,
        dense: false,
        ..Options::default()
    });
    let t_end = args.t_end;
    let threads = ensemble::threads();

    let mut serial_s = Vec::new();
    let mut parallel_s = Vec::new();
    let mut serial = Vec::new();
    let mut parallel = Vec::new();
    for round in 0..3 {
        eprintln!("round {}: serial", round + 1);
        let start = Instant::now();
        serial = members
            .iter()
            .map(|m| {
                let sol = method.solve(&m.model, 0.0, m.y0, t_end, &[])?;
                let (t, y) = sol.last();
                Ok((t, *y, sol.stats.n_accepted))
            })
            .collect::<Vec<Result<_, Error>>>();
        serial_s.push(start.elapsed().as_secs_f64());
        eprintln!("round {}: parallel", round + 1);
        let start = Instant::now();
        parallel = ensemble::map(&members, |m| {
            let sol = method.solve(&m.model, 0.0, m.y0, t_end, &[])?;
            let (t, y) = sol.last();
            Ok((t, *y, sol.stats.n_accepted))
        });
        parallel_s.push(start.elapsed().as_secs_f64());
    }
    fn bits(r: &Result<(f64, Vector<6>, usize), Error>) -> Result<Vec<u64>, Error> {
        r.clone().map(|(t, y, n)| {
            let mut b = vec![t.to_bits(), n as u64];
            b.extend(y.iter().map(|v| v.to_bits()));
            b
        })
    }
    let identical = serial.len() == parallel.len()
        && serial
            .iter()
            .zip(&parallel)
            .all(|(a, b)| bits(a) == bits(b));
    let failed = serial.iter().filter(|r| r.is_err()).count();
    let steps: usize = serial
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .map(|r| r.2)
        .sum();
    let (ts, tp) = (median(serial_s.clone()), median(parallel_s.clone()));
    let speedup = ts / tp;
    // Other processes on the machine take cores from the parallel run: say how busy it was.
    let load = mechanisms::accuracy::load_average()
        .split_whitespace()
        .next()
        .and_then(|v| v.parse::<f64>().ok());
    if args.json {
        println!(
            "{}",
            serde_json::json!({
                "model": "TriplePendulum (generated, 3 links)",
                "members": args.members,
                "t_end": t_end,
                "method": "DOPRI5 rtol = atol = 1e-10",
                "threads": threads,
                "accepted_steps": steps,
                "failed_members": failed,
                "serial_s": serial_s,
                "parallel_s": parallel_s,
                "serial_median_s": ts,
                "parallel_median_s": tp,
                "speedup": speedup,
                "bitwise_identical_in_order": identical,
                "load_average_1min": load,
            })
        );
    } else {
        println!(
            "ensemble: {} members of a generated triple pendulum, DOPRI5 1e-10, 0..{} s, {} accepted steps in all, {} failed",
            args.members, t_end, steps, failed
        );
        println!("serial   (median of 3): {ts:.4} s  {serial_s:.4?}");
        println!("parallel (median of 3): {tp:.4} s  {parallel_s:.4?}  on {threads} rayon threads");
        println!("speed-up: {speedup:.2}x");
        if let Some(load) = load {
            println!("load average (1 min) at the end: {load:.2} on {threads} cores");
        }
        println!("results bitwise identical and in input order: {identical}");
    }
    if !identical {
        std::process::exit(1);
    }
}
