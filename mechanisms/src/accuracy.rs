//! Time to accuracy: how long each explicit method needs to bring the largest error over a
//! grid of 101 sample times below 1e-6 and 1e-10, on the pendulum released at 60 deg (10 s),
//! planar chains of 8 and 32 links (2 s; the hand-written articulated-body rhs and the
//! generated `#[chain]` model) and the free slider-crank (2 s; three coordinates with two
//! projected constraints, and the generated model in its one minimal coordinate), with the
//! step loop's cost per right-hand-side evaluation beside the bare call's.
//!
//! Error: the largest absolute error of the coordinates `q` over the grid (radians and
//! metres), the states taken at the grid times as a user gets them with `Record::Times`
//! (segments not kept): from each step's dense output, or for Vern9 from the end of a step
//! it ended on a grid time where that is cheaper than its interpolant. References: the pendulum's Jacobi-elliptic
//! solution (exact); for the other models, DOP853 at `rtol = atol = 1e-14` on the *other*
//! implementation of the same mechanism (the generated model for the hand-written one and
//! back; the expert one-coordinate slider-crank for both slider-cranks), so that no run is
//! compared with itself or with its own round-off. The table prints the two references'
//! largest difference over the grid: an error below it cannot be told from the reference's.
//!
//! Tolerances: `rtol = atol = 10^(-k/4)`, quarter decades from 1e-3 to 1e-14: the error of
//! a run is not smooth in the tolerance, and on half decades the fastest run to 1e-10 of
//! the 8-link chain's DOP853 was 9% slower than on quarter decades (4180 calls at 1e-10
//! against 3843 at 1.8e-10).
//!
//! Timing: each run's time is the least over batches of about half a millisecond (a run
//! longer than that alone), as many as fit in 0.15 s and at least five: a shared machine
//! only adds time, and a batch short against the scheduler's time slice is seldom
//! interrupted. The bare call is timed the same way over the reference states.

use crate::chain_by_hand::ChainByHand;
use crate::handwritten::{self, FreeSliderCrank, Pendulum, SliderCrank, SliderCrankClosedByHand};
use mbd::integrate::{Dop853, Dopri5, Integrator, Record, Vern9};
use mbd::prelude::*;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

/// The 8-link chain of [`ChainByHand`] as the derive generates it (relative angles
/// `link_q1..`, zero straight down, as the hand-written one).
#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 8, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
pub struct Chain8 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// The 32-link chain, generated.
#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 32, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
pub struct Chain32 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// Links of the chains: 1 kg, 0.5 m, g = 9.81.
const LINK: (f64, f64, f64) = (1.0, 0.5, 9.81);

/// Samples of the error grid (including `t0`).
pub const GRID: usize = 101;

/// The adaptive methods compared.
pub const METHODS: [&str; 3] = ["DOPRI5", "DOP853", "VERN9"];

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
    /// The bare call's latency: its time in a dependent chain of calls (each argument made
    /// from the last result, as a stage's is), the floor of a step loop's time per call.
    pub rhs_chain_ns: f64,
    /// Largest difference over the grid between two independent references (`0` for an
    /// exact one): the floor below which the error is not measured.
    pub reference_spread: f64,
    /// Largest difference over the grid made by nudging the first initial coordinate by
    /// one unit in the last place (the reference method, the same model): how far the
    /// problem itself amplifies round-off, below which no double-precision run can be
    /// told right from wrong.
    pub ulp_spread: f64,
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

/// The least time of one call of `f`: batches of about 0.5 ms (one call when a call is
/// longer), as many as fit in 0.15 s and at least five.
pub fn least_time(f: &dyn Fn()) -> f64 {
    let start = Instant::now();
    f();
    let once = start.elapsed().as_secs_f64().max(1e-9);
    let reps = ((5e-4 / once).ceil() as usize).clamp(1, 1_000_000);
    let budget = Instant::now();
    let mut best = f64::INFINITY;
    let mut batches = 0;
    while batches < 5 || (batches < 400 && budget.elapsed().as_secs_f64() < 0.15) {
        let start = Instant::now();
        for _ in 0..reps {
            f();
        }
        best = best.min(start.elapsed().as_secs_f64() / reps as f64);
        batches += 1;
    }
    best
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
    let sol = match method {
        "DOP853" => Dop853::new(opts).solve(sys, 0.0, y0, t1, &[])?,
        "VERN9" => Vern9::new(opts).solve(sys, 0.0, y0, t1, &[])?,
        _ => Dopri5::new(opts).solve(sys, 0.0, y0, t1, &[])?,
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

/// Sweep `method` over `tol = 10^(-k/4)`, 1e-3 .. 1e-14, on one model against `reference`
/// (its states at the grid times; `spread` its own uncertainty); `n` coordinates count.
/// Stops after a run at rounding level (1e-13), one slower than 0.3 s, or the fifth run
/// at 1e-10 (tighter runs only cost more).
#[allow(clippy::too_many_arguments, reason = "one sweep's settings")]
pub fn sweep<S: OdeSystem<D>, const D: usize>(
    model: &'static str,
    method: &'static str,
    sys: &S,
    y0: Vector<D>,
    t1: f64,
    (reference, spread): (&[Vector<D>], f64),
    n: usize,
) -> Sweep {
    let mut nudged = y0;
    nudged[0] *= 1.0 + f64::EPSILON;
    let ulp_spread = match (
        states("DOP853", sys, y0, t1, 1e-14),
        states("DOP853", sys, nudged, t1, 1e-14),
    ) {
        (Ok((a, _)), Ok((b, _))) => grid_error(&a, &b, n),
        _ => f64::NAN,
    };
    let mut points = Vec::new();
    let mut reached = 0;
    // The bare call is timed over the states of a run (the reference may hold only the
    // compared coordinates).
    let mut visited = Vec::new();
    for k in 12..=56 {
        let tol = 10f64.powf(-f64::from(k) / 4.0);
        let Ok((y, n_rhs)) = states(method, sys, y0, t1, tol) else {
            continue;
        };
        let error = grid_error(&y, reference, n);
        if visited.is_empty() {
            visited.clone_from(&y);
        }
        let time_s = least_time(&|| {
            black_box(states(method, sys, black_box(y0), t1, tol).ok());
        });
        points.push(Point {
            tol,
            error,
            n_rhs,
            time_s,
        });
        reached += usize::from(error <= 1e-10);
        if error < 1e-13 || time_s > 0.3 || reached == 5 {
            break;
        }
    }
    let rhs_ns =
        1e9 * least_time(&|| {
            for y in &visited {
                black_box(sys.rhs(0.0, black_box(y)).ok());
            }
        }) / visited.len().max(1) as f64;
    // Adding `0 * sum(f)` leaves the states as they are but makes every argument wait for
    // the whole last result.
    let rhs_chain_ns =
        1e9 * least_time(&|| {
            let mut f = Vector::<D>::zeros();
            for y in &visited {
                f = sys.rhs(0.0, &y.add_scalar(f.sum() * 0.0)).unwrap_or(f);
            }
            black_box(f);
        }) / visited.len().max(1) as f64;
    Sweep {
        model,
        method,
        points,
        rhs_ns,
        rhs_chain_ns,
        reference_spread: spread,
        ulp_spread,
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

/// All models, both methods: the sweeps of the report's time-to-accuracy table.
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
        out.push(sweep(
            "pendulum 60 deg, 10 s",
            m,
            &p,
            y0,
            t1,
            (&reference, 0.0),
            1,
        ));
    }
    out.extend(chain_sweeps::<Chain8, 8, 16>(
        "chain of 8 links, 2 s",
        &black_box(Chain8 {
            m: LINK.0,
            l: LINK.1,
            g: LINK.2,
        }),
    ));
    out.extend(chain_sweeps::<Chain32, 32, 64>(
        "chain of 32 links, 2 s",
        &black_box(Chain32 {
            m: LINK.0,
            l: LINK.1,
            g: LINK.2,
        }),
    ));
    out.extend(slider_crank_sweeps());
    out
}

/// The reference states of `sys` (DOP853 at 1e-14), or `None` when it fails.
fn reference<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    y0: Vector<D>,
    t1: f64,
) -> Option<Vec<Vector<D>>> {
    states("DOP853", sys, y0, t1, 1e-14).ok().map(|(y, _)| y)
}

/// A chain hand-written and generated, each against the other's reference.
fn chain_sweeps<G: OdeSystem<D>, const N: usize, const D: usize>(
    name: &'static str,
    generated: &G,
) -> Vec<Sweep> {
    // Released from rest with every joint at 0.3 rad.
    let hand: ChainByHand<N> = black_box(ChainByHand::new(LINK.0, LINK.1, LINK.2));
    let y0 = Vector::<D>::from_fn(|i, _| if i < N { 0.3 } else { 0.0 });
    let (Some(ref_hand), Some(ref_gen)) =
        (reference(&hand, y0, 2.0), reference(generated, y0, 2.0))
    else {
        return Vec::new();
    };
    let spread = grid_error(&ref_hand, &ref_gen, N);
    let mut out = Vec::new();
    for m in METHODS {
        out.push(sweep(name, m, &hand, y0, 2.0, (&ref_gen, spread), N));
    }
    let gen_name = if N == 8 {
        "chain of 8 links, 2 s, generated"
    } else {
        "chain of 32 links, 2 s, generated"
    };
    for m in METHODS {
        out.push(sweep(
            gen_name,
            m,
            generated,
            y0,
            2.0,
            (&ref_hand, spread),
            N,
        ));
    }
    out
}

/// The free slider-crank from 0.3 rad at rest, 2 s: three coordinates with two projected
/// constraints, and the generated one-coordinate model; both against the expert
/// one-coordinate twin's reference (its angle is the crank angle, the first coordinate of
/// both).
fn slider_crank_sweeps() -> Vec<Sweep> {
    let s: SliderCrank = black_box(handwritten::SLIDER_CRANK);
    let free: FreeSliderCrank = black_box(handwritten::FREE_SLIDER_CRANK);
    let expert = SliderCrankClosedByHand::from(&free);
    let y1 = Vector::<2>::new(0.3, 0.0);
    let y3 = handwritten::slider_crank_state(&s, 0.3, 0.0);
    let (Some(ref_expert), Some(ref_free)) =
        (reference(&expert, y1, 2.0), reference(&free, y1, 2.0))
    else {
        return Vec::new();
    };
    let spread = grid_error(&ref_expert, &ref_free, 1);
    // The expert reference as 6-states (only the crank angle is compared).
    let ref6: Vec<Vector<6>> = ref_expert
        .iter()
        .map(|y| Vector::<6>::from_fn(|i, _| if i == 0 { y[0] } else { f64::NAN }))
        .collect();
    let mut out = Vec::new();
    for m in METHODS {
        out.push(sweep(
            "slider-crank, 3 coordinates, 2 s",
            m,
            &s,
            y3,
            2.0,
            (&ref6, spread),
            1,
        ));
    }
    for m in METHODS {
        out.push(sweep(
            "slider-crank, minimal, 2 s",
            m,
            &free,
            y1,
            2.0,
            (&ref_expert, spread),
            1,
        ));
    }
    out
}

/// The machine's load averages (1, 5, 15 min) as Linux publishes them, or `?` elsewhere:
/// the one place the reports read them.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|| "?".to_string())
}

/// The time-to-accuracy table in Markdown, with the load averages before and after the
/// sweeps (`load_before`, read by the caller before it ran them).
pub fn table(sweeps: &[Sweep], load_before: &str) -> String {
    let mut s = format!(
        "## Time to accuracy\n\nLargest error of the coordinates over 101 sample times (dense \
         output, `Record::Times`), fastest tolerance that reaches it; `ns/eval` is the run time \
         per rhs call, `loop ns/eval` what of it is not the bare call (the step loop's \
         overhead per evaluation), `x rhs` the run time per call over the bare call's time \
         (independent calls) and `x chain` over its latency (`chain ns`: calls in a dependent \
         chain, as the stages are); \
         `ref spread` the largest difference between two independent references (module \
         docs), `1 ulp` the largest change made by nudging the first initial coordinate by \
         one unit in the last place (the problem's own amplification of round-off: a target \
         below it cannot be resolved in double precision). Load average (1, 5, 15 min): {load_before} before, {} after.\n\n\
         | model | method | target | time | tol | rhs calls | ns/eval | bare rhs ns | chain ns | loop ns/eval | x rhs | x chain | ref spread | 1 ulp |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        load_average()
    );
    for sw in sweeps {
        for target in [1e-6, 1e-10] {
            let spread = if sw.reference_spread > 0.0 {
                format!("{:.1e}", sw.reference_spread)
            } else {
                "exact".to_string()
            };
            let ulp = sw.ulp_spread;
            match sw.fastest(target) {
                Some(p) => {
                    let per_eval = p.time_s * 1e9 / p.n_rhs as f64;
                    let _ = writeln!(
                        s,
                        "| {} | {} | {target:.0e} | {:.1} us | {:.1e} | {} | {per_eval:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {spread} | {ulp:.1e} |",
                        sw.model,
                        sw.method,
                        p.time_s * 1e6,
                        p.tol,
                        p.n_rhs,
                        sw.rhs_ns,
                        sw.rhs_chain_ns,
                        per_eval - sw.rhs_ns,
                        per_eval / sw.rhs_ns,
                        per_eval / sw.rhs_chain_ns
                    );
                }
                None => {
                    let best = sw
                        .points
                        .iter()
                        .map(|p| p.error)
                        .fold(f64::INFINITY, f64::min);
                    let _ = writeln!(
                        s,
                        "| {} | {} | {target:.0e} | not reached (best {best:.1e}) | | | | {:.1} | {:.1} | | | | {spread} | {ulp:.1e} |",
                        sw.model, sw.method, sw.rhs_ns, sw.rhs_chain_ns
                    );
                }
            }
        }
    }
    s
}
