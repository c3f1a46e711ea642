//! Time to accuracy: how long each explicit method needs to bring the largest error over a
//! grid of 101 sample times below 1e-6 and 1e-10, on the pendulum released at 60 deg (10 s),
//! planar chains of 8 and 32 links (2 s) and the free slider-crank (2 s), with the step
//! loop's cost per right-hand-side evaluation beside the bare call's.
//!
//! Error: the largest absolute error of the coordinates `q` over the grid (radians and
//! metres), the states taken at the grid times from each step's dense output
//! (`Record::Times`, segments not kept). References: the pendulum's Jacobi-elliptic
//! solution (exact); for the chains and the slider-crank, DOP853 at `rtol = atol = 1e-14`,
//! one decade below the tightest tolerance swept (1e-13), so no run is compared with
//! itself; DOP853's error falls in proportion to the tolerance, so the 1e-13 row bounds the
//! reference's own error from above (to about ten times its size).
//!
//! Timing: each run's time is the least over 9 batches, each at least 10 ms long (the
//! machine is shared; slow spells only add). The bare call is timed the same way, over the
//! reference states.

use crate::chain_by_hand::ChainByHand;
use crate::handwritten::{self, Pendulum, SliderCrank};
use mbd::integrate::{Dop853, Dopri5, Integrator, Record};
use mbd::{OdeSystem, Options, Vector};
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::Instant;

/// Samples of the error grid (including `t0`).
pub const GRID: usize = 101;

/// The adaptive methods compared.
pub const METHODS: [&str; 2] = ["DOPRI5", "DOP853"];

/// One run of the sweep: its tolerance, largest error, `rhs` calls and time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub tol: f64,
    pub error: f64,
    pub n_rhs: usize,
    pub time_s: f64,
}

/// One model and method: the sweep, and the bare call's time.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    pub model: &'static str,
    pub method: &'static str,
    pub points: Vec<Point>,
    pub rhs_ns: f64,
}

impl Sweep {
    /// The fastest run whose error is at or below `target`.
    pub fn fastest(&self, target: f64) -> Option<&Point> {
        self.points
            .iter()
            .filter(|p| p.error <= target)
            .min_by(|a, b| a.time_s.total_cmp(&b.time_s))
    }
}

/// The least time of one call of `f`, over 9 batches each at least 10 ms long.
pub fn least_time(f: &dyn Fn()) -> f64 {
    let start = Instant::now();
    f();
    let once = start.elapsed().as_secs_f64().max(1e-9);
    let reps = ((0.01 / once).ceil() as usize).clamp(1, 1_000_000);
    (0..9)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                f();
            }
            start.elapsed().as_secs_f64() / reps as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn grid(t1: f64) -> Vec<f64> {
    (0..GRID)
        .map(|i| t1 * i as f64 / (GRID - 1) as f64)
        .collect()
}

/// The states at the grid times of `[0, t1]` from one run of `method` at `tol`.
pub fn states<S: OdeSystem<D>, const D: usize>(
    method: &str,
    sys: &S,
    y0: Vector<D>,
    t1: f64,
    tol: f64,
) -> mbd::Result<(Vec<Vector<D>>, usize)> {
    let opts = Options {
        rtol: tol,
        atol: tol,
        dense: false,
        record: Record::Times(grid(t1)),
        ..Options::default()
    };
    let sol = if method == "DOP853" {
        Dop853::new(opts).solve(sys, 0.0, y0, t1, &[])?
    } else {
        Dopri5::new(opts).solve(sys, 0.0, y0, t1, &[])?
    };
    // t0, the 100 grid times after it (the last is t1 itself).
    Ok((sol.y, sol.stats.n_rhs))
}

/// Largest error of the first `n` components over the grid.
fn grid_error<const D: usize>(y: &[Vector<D>], reference: &[Vector<D>], n: usize) -> f64 {
    if y.len() != reference.len() {
        return f64::INFINITY;
    }
    y.iter()
        .zip(reference)
        .flat_map(|(a, b)| (0..n).map(move |i| (a[i] - b[i]).abs()))
        .fold(0.0, f64::max)
}

/// Sweep `method` over `tol = 1e-3 .. 1e-13` on one model against `reference` (its states
/// at the grid times); `n` coordinates count. Stops after a run at rounding level (1e-13)
/// or one slower than 0.5 s.
pub fn sweep<S: OdeSystem<D>, const D: usize>(
    model: &'static str,
    method: &'static str,
    sys: &S,
    y0: Vector<D>,
    t1: f64,
    reference: &[Vector<D>],
    n: usize,
) -> Sweep {
    let mut points = Vec::new();
    for k in 3..=13 {
        let tol = 10f64.powi(-k);
        let Ok((y, n_rhs)) = states(method, sys, y0, t1, tol) else {
            continue;
        };
        let error = grid_error(&y, reference, n);
        let time_s = least_time(&|| {
            black_box(states(method, sys, black_box(y0), t1, tol).ok());
        });
        points.push(Point {
            tol,
            error,
            n_rhs,
            time_s,
        });
        if error < 1e-13 || time_s > 0.5 {
            break;
        }
    }
    let rhs_ns =
        1e9 * least_time(&|| {
            for y in reference {
                black_box(sys.rhs(0.0, black_box(y)).ok());
            }
        }) / reference.len() as f64;
    Sweep {
        model,
        method,
        points,
        rhs_ns,
    }
}

/// The arithmetic-geometric mean.
fn agm(mut a: f64, mut b: f64) -> f64 {
    while (a - b).abs() > 4.0 * f64::EPSILON * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// Jacobi `sn(u, k)` by the descending Landen (AGM) scheme (Abramowitz & Stegun 16.4).
fn jacobi_sn(u: f64, k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    let (mut av, mut cv) = (vec![a], vec![k]);
    while cv.last().is_some_and(|c| c.abs() > 4.0 * f64::EPSILON) && cv.len() < 40 {
        let c = 0.5 * (a - b);
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
        av.push(a);
        cv.push(c);
    }
    let n = av.len() - 1;
    let mut phi = 2f64.powi(n as i32) * av[n] * u;
    for i in (1..=n).rev() {
        phi = 0.5 * (phi + (cv[i] * phi.sin() / av[i]).asin());
    }
    phi.sin()
}

/// The pendulum `theta'' = -w^2 sin theta` released from rest at `theta0`:
/// `sin(theta/2) = s sn(K(s) - w t, s)`, `s = sin(theta0/2)`, `K(s) = pi / (2 AGM(1, s'))`.
pub fn pendulum_angle(w: f64, theta0: f64, t: f64) -> f64 {
    let s = (theta0 / 2.0).sin();
    let k = PI / (2.0 * agm(1.0, (1.0 - s * s).sqrt()));
    2.0 * (s * jacobi_sn(k - w * t, s)).asin()
}

/// All four models, both methods: the sweeps of the report's time-to-accuracy table.
pub fn all_sweeps() -> Vec<Sweep> {
    let mut out = Vec::new();
    // Pendulum, 60 deg, 10 s, against its exact solution.
    let p: Pendulum = black_box(handwritten::PENDULUM);
    let (t1, theta0) = (10.0, PI / 3.0);
    let w = (p.g / p.l).sqrt();
    let reference: Vec<Vector<2>> = grid(t1)
        .iter()
        .map(|&t| Vector::<2>::new(pendulum_angle(w, theta0, t), 0.0))
        .collect();
    for m in METHODS {
        let y0 = Vector::<2>::new(theta0, 0.0);
        out.push(sweep("pendulum 60 deg, 10 s", m, &p, y0, t1, &reference, 1));
    }
    out.extend(chain_sweeps::<8, 16>("chain of 8 links, 2 s"));
    out.extend(chain_sweeps::<32, 64>("chain of 32 links, 2 s"));
    // The free slider-crank (3 coordinates, 2 constraints, projected), from 0.3 rad, 2 s.
    let s: SliderCrank = black_box(handwritten::SLIDER_CRANK);
    let y0 = handwritten::slider_crank_state(&s, 0.3, 0.0);
    if let Ok((reference, _)) = states("DOP853", &s, y0, 2.0, 1e-14) {
        for m in METHODS {
            out.push(sweep("slider-crank, 2 s", m, &s, y0, 2.0, &reference, 3));
        }
    }
    out
}

fn chain_sweeps<const N: usize, const D: usize>(name: &'static str) -> Vec<Sweep> {
    // Links of 1 kg and 0.5 m, released from rest with every joint at 0.3 rad.
    let c: ChainByHand<N> = black_box(ChainByHand::new(1.0, 0.5, 9.81));
    let y0 = Vector::<D>::from_fn(|i, _| if i < N { 0.3 } else { 0.0 });
    let Ok((reference, _)) = states("DOP853", &c, y0, 2.0, 1e-14) else {
        return Vec::new();
    };
    METHODS
        .iter()
        .map(|m| sweep(name, m, &c, y0, 2.0, &reference, N))
        .collect()
}
