//! Hunting friction defects as a new user: models written from the crate docs, each checked
//! against a closed form derived beside it, on several integrators through `hybrid::solve`.

use mbd::Slip;
use mbd::hybrid::HybridSolution;
use mbd::integrate::{Auto, Dop853, Dopri5, Integrator, Radau5, Vern9};
use mbd::prelude::*;
use std::f64::consts::PI;

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

/// A run of a model with one contact.
type Run1 = HybridSolution<2, [Slip; 1]>;

/// Runs `f` with each adaptive method at tight tolerances, naming it.
fn each_method(mut f: impl FnMut(&str, &dyn Fn() -> Box<dyn Run>)) {
    f("DOPRI5", &|| Box::new(Dopri5::new(tight())));
    f("DOP853", &|| Box::new(Dop853::new(tight())));
    f("Vern9", &|| Box::new(Vern9::new(tight())));
    f("Radau5", &|| Box::new(Radau5::new(tight())));
    f("Auto", &|| Box::new(Auto::new(tight())));
}

/// An object-safe handle on `hybrid::solve` for the models below.
trait Run {
    fn oscillator(&self, p: &Damped, t1: f64) -> Result<HybridSolution<2, [Slip; 1]>, Error>;
    fn ramp(&self, p: &Ramp, t1: f64) -> Result<HybridSolution<2, [Slip; 1]>, Error>;
    fn pair(&self, p: &Pair, t1: f64) -> Result<HybridSolution<4, [Slip; 2]>, Error>;
}

impl<I: Integrator> Run for I {
    fn oscillator(&self, p: &Damped, t1: f64) -> Result<HybridSolution<2, [Slip; 1]>, Error> {
        mbd::hybrid::solve(self, p, 0.0, p.initial_state(), t1, &[])
    }
    fn ramp(&self, p: &Ramp, t1: f64) -> Result<HybridSolution<2, [Slip; 1]>, Error> {
        mbd::hybrid::solve(self, p, 0.0, p.initial_state(), t1, &[])
    }
    fn pair(&self, p: &Pair, t1: f64) -> Result<HybridSolution<4, [Slip; 2]>, Error> {
        mbd::hybrid::solve(self, p, 0.0, p.initial_state(), t1, &[])
    }
}

/// A mass on a spring to the wall, on a rough floor (`n` relaxed: `reaction(n)` is the
/// normal force), released at rest from `x0`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[relaxed(n)]
#[particle(block, mass = m, at = [x, n])]
#[point(wall, at = [0.0, 0.0])]
#[spring(s, from = wall, to = [x, 0.0], k = k)]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = reaction(n))]
#[init(x = x0)]
pub struct Damped {
    pub m: f64,
    pub k: f64,
    pub g: f64,
    pub mu_k: f64,
    pub mu_s: f64,
    pub x0: f64,
}

/// The Coulomb-damped oscillator by hand. Sliding away from a turning point `x_j` the
/// kinetic friction `mu_k m g` is constant, so the motion is a half cosine of period
/// `pi / w` (`w^2 = k / m`) about the shifted centre `c = sign(x_j) x_f`, `x_f = mu_k g / w^2`:
/// the next turning point is `2 c - x_j`, reached `pi / w` later. At a turning point the
/// spring pulls with `k |x_j|`; the block stays when that is within `mu_s m g`, i.e.
/// `|x_j| <= x_s = mu_s g / w^2`. Returns the turning points after `x0` up to the one it
/// sticks at, each reached `pi / w` after the previous.
fn turning_points(p: &Damped) -> Vec<f64> {
    let w2 = p.k / p.m;
    let (x_f, x_s) = (p.mu_k * p.g / w2, p.mu_s * p.g / w2);
    let mut x = p.x0;
    let mut out = Vec::new();
    while x.abs() > x_s {
        x = 2.0 * x.signum() * x_f - x;
        out.push(x);
    }
    out
}

const DAMPED: Damped = Damped {
    m: 1.0,
    k: 4.0,
    g: 9.81,
    mu_k: 0.1,
    mu_s: 0.1,
    x0: 1.0,
};

/// Released from 1 m with `x_f = 0.24525 m`: turning points -0.5095 (slides on, the
/// spring's 2.04 N beats 0.981 N) and 0.019 (sticks), at `pi / 2` and `pi`. With
/// `mu_s = 0.25` (`x_s = 0.613 m`) it already sticks at -0.5095.
#[test]
fn coulomb_damped_oscillator_stops_at_the_closed_form_turning_point() {
    let half = PI / 2.0; // pi / w with w = 2
    for p in [
        DAMPED,
        Damped {
            mu_s: 0.25,
            ..DAMPED
        },
    ] {
        let turns = turning_points(&p);
        assert_eq!(turns.len(), if p.mu_s == 0.1 { 2 } else { 1 });
        let stop_t = half * turns.len() as f64;
        let stop_x = *turns.last().unwrap();
        each_method(|name, make| {
            let run = make().oscillator(&p, 5.0).unwrap();
            let last = run.switches.last().unwrap();
            assert_eq!(last.to, [Slip::Stick], "{name}: {:?}", run.switches);
            assert!(
                (last.t - stop_t).abs() < 1e-9,
                "{name} mu_s {}: stuck at {} against {stop_t}",
                p.mu_s,
                last.t
            );
            // Every turning point on the way is a switch at k pi / w.
            for (k, &x) in turns.iter().enumerate() {
                let t = half * (k + 1) as f64;
                let y = run.solution.at(t).unwrap();
                assert!((y[0] - x).abs() < 1e-9, "{name}: x({t}) = {} vs {x}", y[0]);
            }
            let (t, y) = run.solution.last();
            assert_eq!(t, 5.0);
            assert!((y[0] - stop_x).abs() < 1e-9, "{name}: rests at {}", y[0]);
            assert_eq!(y[1], 0.0, "{name}: moving at the end");
            assert_eq!(run.mode, [Slip::Stick]);
        });
    }
}

/// `mu = 0` is no friction at all: the block oscillates as `x0 cos(w t)` through its
/// turning points (where it is momentarily at rest under the full spring force).
#[test]
fn zero_friction_coefficient_is_the_harmonic_oscillator() {
    let p = Damped {
        mu_k: 0.0,
        mu_s: 0.0,
        ..DAMPED
    };
    each_method(|name, make| {
        let run = make().oscillator(&p, 4.0).unwrap();
        assert!(
            run.switches.iter().all(|s| s.to != [Slip::Stick]),
            "{name}: {:?}",
            run.switches
        );
        for t in [0.3, 1.0, PI / 2.0, 2.5, PI, 4.0] {
            let y = run.solution.at(t).unwrap();
            assert!(
                (y[0] - (2.0 * t).cos()).abs() < 1e-9,
                "{name}: x({t}) = {} vs {}",
                y[0],
                (2.0 * t).cos()
            );
        }
    });
}

/// A block at rest pushed by a force growing in time, `c t`: static friction holds it up
/// to `t* = mu_s m g / c`; after that `m x'' = c t - mu_k m g`, so
/// `m x(t) = c (t^3 - t*^3) / 6 - c t*^2 (t - t*) / 2 - mu_k m g (t - t*)^2 / 2`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = c * t)]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
pub struct Ramp {
    pub m: f64,
    pub g: f64,
    pub c: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

#[test]
fn a_block_under_a_rising_push_breaks_away_at_the_static_limit() {
    let p = Ramp {
        m: 2.0,
        g: 9.81,
        c: 3.0,
        mu_k: 0.3,
        mu_s: 0.5,
    };
    let ts = p.mu_s * p.m * p.g / p.c;
    let x = |t: f64| {
        let d = t - ts;
        (p.c * (t.powi(3) - ts.powi(3)) / 6.0
            - p.c * ts * ts * d / 2.0
            - p.mu_k * p.m * p.g * d * d / 2.0)
            / p.m
    };
    let t1 = ts + 1.5;
    each_method(|name, make| {
        let run = make().ramp(&p, t1).unwrap();
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        let sw = &run.switches[0];
        assert_eq!((sw.from, sw.to), ([Slip::Stick], [Slip::Forward]), "{name}");
        assert!(
            (sw.t - ts).abs() < 1e-9,
            "{name}: breaks at {} vs {ts}",
            sw.t
        );
        // Held exactly until then.
        assert_eq!(run.solution.at(0.9 * ts).unwrap()[0], 0.0, "{name}");
        let (t, y) = run.solution.last();
        assert!((y[0] - x(t)).abs() < 1e-9, "{name}: {} vs {}", y[0], x(t));
    });
}

/// Two blocks on one rough floor joined by a spring of rest length `l`; the first is pushed
/// by a constant `f`. While the second holds, the first is a mass on a spring under
/// `f - mu_k m1 g`: `x1 = a (1 - cos(w t))`, `a = (f - mu_k m1 g) / k`, `w^2 = k / m1`. The
/// spring pulls the second with `k x1`, and it breaks away when that reaches
/// `mu_s m2 g`: `cos(w t*) = 1 - mu_s m2 g / (k a)`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x1, x2)]
#[particle(first, mass = m1, at = [x1, 0.0])]
#[particle(second, mass = m2, at = [x2 - l, 0.0])]
#[spring(tie, from = first, to = second, k = k, length = l)]
#[generalized_force(push, along = x1, value = -f)]
#[friction(along = x1, mu_k = mu_k, mu_s = mu_s, normal = m1 * g)]
#[friction(along = x2, mu_k = mu_k, mu_s = mu_s, normal = m2 * g)]
pub struct Pair {
    pub m1: f64,
    pub m2: f64,
    pub k: f64,
    pub l: f64,
    pub g: f64,
    pub f: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

#[test]
fn spring_coupled_blocks_break_away_in_turn_at_the_closed_form_time() {
    // The push is -f (to the left, away from the second block, which sits at x2 - l <= x1):
    // the tie stretches as x1 falls, x1 = -a (1 - cos(w t)).
    let p = Pair {
        m1: 1.0,
        m2: 2.0,
        k: 50.0,
        l: 0.5,
        g: 9.81,
        f: 10.0,
        mu_k: 0.3,
        mu_s: 0.4,
    };
    // At rest with f below the first block's static bound neither moves.
    let weak = Pair { f: 3.9, ..p };
    let rest = mbd::Vector::<2>::zeros();
    assert_eq!(weak.acceleration(0.0, &rest, &rest).unwrap(), rest);
    let w = (p.k / p.m1).sqrt();
    let a = (p.f - p.mu_k * p.m1 * p.g) / p.k;
    let t_star = (1.0 - p.mu_s * p.m2 * p.g / (p.k * a)).acos() / w;
    each_method(|name, make| {
        let run = make().pair(&p, t_star + 0.05).unwrap();
        // The first block breaks away at once (no switch: the initial mode); the second's
        // breakaway is the one switch.
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        let second = &run.switches[0];
        assert_eq!(second.from, [Slip::Backward, Slip::Stick], "{name}");
        assert_eq!(second.to, [Slip::Backward, Slip::Backward], "{name}");
        assert!(
            (second.t - t_star).abs() < 1e-9,
            "{name}: second breaks at {} vs {t_star}",
            second.t
        );
        let y = run.solution.at(0.5 * t_star).unwrap();
        let x1 = -a * (1.0 - (w * 0.5 * t_star).cos());
        assert!((y[0] - x1).abs() < 1e-9, "{name}: x1 {} vs {x1}", y[0]);
        assert_eq!(y[1], 0.0, "{name}");
    });
}

/// A huge coefficient: a block launched at `v0` stops after `v0 / (mu g)`, a tenth of a
/// millisecond, having slid `v0^2 / (2 mu g)`, and stays.
#[test]
fn a_huge_coefficient_stops_the_block_at_the_closed_form_instant() {
    let p = Ramp {
        m: 2.0,
        g: 9.81,
        c: 0.0,
        mu_k: 1000.0,
        mu_s: 1000.0,
    };
    let y0 = mbd::Vector::<2>::new(0.0, 1.0);
    let t_stop = 1.0 / (1000.0 * 9.81);
    let s_stop = 1.0 / (2.0 * 1000.0 * 9.81);
    let mut runs: Vec<(&str, HybridSolution<2, [Slip; 1]>)> = vec![];
    runs.push((
        "DOPRI5",
        mbd::hybrid::solve(&Dopri5::new(tight()), &p, 0.0, y0, 1.0, &[]).unwrap(),
    ));
    runs.push((
        "Radau5",
        mbd::hybrid::solve(&Radau5::new(tight()), &p, 0.0, y0, 1.0, &[]).unwrap(),
    ));
    runs.push((
        "Auto",
        mbd::hybrid::solve(&Auto::new(tight()), &p, 0.0, y0, 1.0, &[]).unwrap(),
    ));
    for (name, run) in runs {
        assert_eq!(run.switches.len(), 1, "{name}");
        assert!((run.switches[0].t - t_stop).abs() < 1e-12, "{name}");
        let (_, y) = run.solution.last();
        assert!((y[0] - s_stop).abs() < 1e-12, "{name}: {}", y[0]);
        assert_eq!(y[1], 0.0);
    }
}

/// A wheel on a spatial hinge about the ground `z` axis with a bearing friction torque
/// `mu r |n|` (`mu` written as the coefficient times the radius, as the docs say): spun at
/// `w0` it decelerates at `mu r n / c`, stops after `w0 c / (mu r n)` having turned
/// `w0^2 / (2 mu r n / c)`, and stays.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[body(wheel, joint = revolute(q, z), mass = m, inertia = diag(a, a, c))]
#[friction(along = q, mu = mu * r, normal = n)]
#[init(der(q) = w0)]
pub struct Wheel {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub mu: f64,
    pub r: f64,
    pub n: f64,
    pub w0: f64,
}

#[test]
fn a_spatial_hinge_with_bearing_friction_stops_at_the_closed_form_turn() {
    let p = Wheel {
        m: 2.0,
        a: 0.1,
        c: 0.2,
        mu: 0.3,
        r: 0.05,
        n: 20.0,
        w0: 5.0,
    };
    let decel = p.mu * p.r * p.n / p.c;
    let (t_stop, q_stop) = (p.w0 / decel, p.w0 * p.w0 / (2.0 * decel));
    let runs: [(&str, Result<Run1, Error>); 3] = [
        (
            "DOP853",
            mbd::hybrid::solve(&Dop853::new(tight()), &p, 0.0, p.initial_state(), 5.0, &[]),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(&Radau5::new(tight()), &p, 0.0, p.initial_state(), 5.0, &[]),
        ),
        (
            "Vern9",
            mbd::hybrid::solve(&Vern9::new(tight()), &p, 0.0, p.initial_state(), 5.0, &[]),
        ),
    ];
    for (name, run) in runs {
        let run = run.unwrap();
        assert_eq!(run.switches.len(), 1, "{name}");
        assert!((run.switches[0].t - t_stop).abs() < 1e-10, "{name}");
        let (_, y) = run.solution.last();
        assert!((y[0] - q_stop).abs() < 1e-9, "{name}: {}", y[0]);
        assert_eq!(y[1], 0.0, "{name}");
    }
}

/// Three blocks written as repeated cells, each on the rough floor with its own contact,
/// launched at `i` m/s: block `i` stops after `i / (mu g)`, at `i^2 / (2 mu g)`, the three
/// contacts sticking one after another while the others still slide.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[repeat(i in 1..=3,
    coords(x[i]),
    particle(b[i], mass = m, at = [x[i], 0.0]),
    friction(along = x[i], mu = mu, normal = m * g),
    init(der(x[i]) = i))]
pub struct Three {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
}

#[test]
fn repeated_blocks_stick_one_after_another_at_the_closed_form_times() {
    let p = Three {
        m: 0.5,
        g: 9.81,
        mu: 0.2,
    };
    let y0 = p.initial_state();
    assert_eq!(y0.fixed_rows::<3>(3).as_slice(), [1.0, 2.0, 3.0]);
    let decel = p.mu * p.g;
    for (name, run) in [
        (
            "DOPRI5",
            mbd::hybrid::solve(&Dopri5::new(tight()), &p, 0.0, y0, 2.0, &[]),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(&Radau5::new(tight()), &p, 0.0, y0, 2.0, &[]),
        ),
    ] {
        let run = run.unwrap();
        assert_eq!(run.switches.len(), 3, "{name}: {:?}", run.switches);
        for (k, sw) in run.switches.iter().enumerate() {
            let v = (k + 1) as f64;
            assert!(
                (sw.t - v / decel).abs() < 1e-10,
                "{name}: block {} at {}",
                k + 1,
                sw.t
            );
            assert_eq!(sw.to[k], Slip::Stick, "{name}");
        }
        let (_, y) = run.solution.last();
        for k in 0..3 {
            let v = (k + 1) as f64;
            assert!(
                (y[k] - v * v / (2.0 * decel)).abs() < 1e-9,
                "{name}: {}",
                y[k]
            );
            assert_eq!(y[3 + k], 0.0);
        }
        assert_eq!(run.mode, [Slip::Stick; 3]);
    }
}
