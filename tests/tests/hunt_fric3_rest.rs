//! Holding at rest for a long time without creep, and sticking to a moving surface: a block
//! stuck on an oscillating cart (its load changes sign every half period) for 10^4 s with
//! every integrator, and a block dropped on a conveyor belt that it catches up with and
//! then rides exactly. Closed forms derived beside each test.

use mbd::hybrid::{self, HybridSolution};
use mbd::integrate::{Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Radau5, Rk4, Vern9};
use mbd::prelude::*;
use mbd::{Hybrid, Slip};

/// Tight tolerances, and steps enough for 10^4 s of oscillation.
fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        max_steps: 10_000_000,
        ..Options::default()
    }
}

/// One run per method from `(0, y0)` to `t1`: `(name, run)`.
fn every_method<S: Hybrid<4>>(
    sys: &S,
    y0: Vector<4>,
    t1: f64,
    h: f64,
) -> Vec<(&'static str, HybridSolution<4, S::Mode>)> {
    let go = |name: &'static str, r: mbd::Result<HybridSolution<4, S::Mode>>| {
        (name, r.unwrap_or_else(|e| panic!("{name}: {e}")))
    };
    vec![
        go(
            "DOPRI5",
            hybrid::solve(&Dopri5::new(tight()), sys, 0.0, y0, t1, &[]),
        ),
        go(
            "DOP853",
            hybrid::solve(&Dop853::new(tight()), sys, 0.0, y0, t1, &[]),
        ),
        go(
            "Vern9",
            hybrid::solve(&Vern9::new(tight()), sys, 0.0, y0, t1, &[]),
        ),
        go(
            "Auto",
            hybrid::solve(&Auto::new(tight()), sys, 0.0, y0, t1, &[]),
        ),
        go(
            "Radau5",
            hybrid::solve(&Radau5::new(tight()), sys, 0.0, y0, t1, &[]),
        ),
        go("RK4", hybrid::solve(&Rk4::new(h), sys, 0.0, y0, t1, &[])),
        go(
            "Gauss",
            hybrid::solve(&Gauss::new(h), sys, 0.0, y0, t1, &[]),
        ),
        go(
            "generalized-alpha",
            hybrid::solve(&GeneralizedAlpha::new(0.9, h), sys, 0.0, y0, t1, &[]),
        ),
    ]
}

/// A cart `M` on a smooth floor, tied to the wall by a spring `k`, carrying a block `m` at
/// `X + s` with friction on `s` (normal `m g`).
#[derive(Debug, Mechanism)]
#[coords(cx, s)]
#[particle(cart, mass = mc, at = [cx, 0.0])]
#[particle(block, mass = m, at = [cx + s, 0.0])]
#[spring(tie, from = [0.0, 0.0], to = cart, k = k)]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
pub struct Cart {
    pub mc: f64,
    pub m: f64,
    pub k: f64,
    pub g: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// Released from `X = A` at rest with the block stuck, the two move as one mass:
/// `X = A cos(w t)`, `w^2 = k / (M + m)`; the block needs `m X'' = -m w^2 X`, at most
/// `m w^2 A`, below `mu_s m g` here (`w^2 A = 1.6`, `mu_s g = 2.94`), so it never slips:
/// `s` stays exactly `0` and `s'` exactly `0`, bit for bit, through 10^4 s (about 3000
/// reversals of the load) with every method, and no switch happens.
#[test]
fn a_block_on_an_oscillating_cart_never_slips_in_ten_thousand_seconds() {
    let p = Cart {
        mc: 3.0,
        m: 1.0,
        k: 16.0,
        g: 9.81,
        mu_k: 0.2,
        mu_s: 0.3,
    };
    let (a, w) = (0.4, (p.k / (p.mc + p.m)).sqrt());
    assert!(w * w * a < p.mu_s * p.g);
    let t1 = 1e4;
    for (name, run) in every_method(&p, Vector::<4>::new(a, 0.0, 0.0, 0.0), t1, 0.01) {
        assert!(run.switches.is_empty(), "{name}: {:?}", &run.switches[..1]);
        assert_eq!(run.mode, [Slip::Stick], "{name}");
        assert!(
            run.solution.y.iter().all(|y| y[1] == 0.0 && y[3] == 0.0),
            "{name}: the block crept"
        );
        let (t, y) = run.solution.last();
        assert_eq!(t, t1, "{name}");
        // The cart itself to each method's accuracy over ~3000 periods (measured: Vern9
        // 3e-11, DOPRI5 4.5e-9, Radau5 4.6e-8, RK4 6e-6 at h = 0.01; generalized-alpha's
        // phase error at h = 0.01 is 7e-2 by then).
        let bound = match name {
            "RK4" | "Gauss" => 1e-5,
            "generalized-alpha" => 0.1,
            _ => 1e-7,
        };
        let want = a * (w * t1).cos();
        assert!(
            (y[0] - want).abs() < bound,
            "{name}: X off by {:e}",
            y[0] - want
        );
    }
}

/// A block set down at rest on a belt running at `V`; `s` is its place on the belt,
/// `x = V t + s`, so it starts sliding back on it at `s' = -V`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[drive(belt = v * t)]
#[particle(block, mass = m, at = [belt + s, 0.0])]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
pub struct Conveyor {
    pub m: f64,
    pub g: f64,
    pub v: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// Kinetic friction `mu_k m g` drags it forward: `s'' = mu_k g` until `s' = 0` at
/// `t* = V / (mu_k g)`, where `s* = -V^2 / (2 mu_k g)`. Then it rides the belt (stuck, and
/// a constant belt speed asks no load of it): `s = s*` exactly from then on, so
/// `x = V t + s*`, through 10^4 s.
#[test]
fn a_block_set_on_a_conveyor_catches_up_and_then_rides_it_exactly() {
    let p = Conveyor {
        m: 2.0,
        g: 9.81,
        v: 1.5,
        mu_k: 0.3,
        mu_s: 0.4,
    };
    let t_star = p.v / (p.mu_k * p.g);
    let s_star = -p.v * p.v / (2.0 * p.mu_k * p.g);
    let y0 = Vector::<2>::new(0.0, -p.v);
    let runs = [
        (
            "DOPRI5",
            hybrid::solve(&Dopri5::new(tight()), &p, 0.0, y0, 1e4, &[]),
        ),
        (
            "Radau5",
            hybrid::solve(&Radau5::new(tight()), &p, 0.0, y0, 1e4, &[]),
        ),
        ("RK4", hybrid::solve(&Rk4::new(0.01), &p, 0.0, y0, 1e4, &[])),
        (
            "generalized-alpha",
            hybrid::solve(&GeneralizedAlpha::new(0.9, 0.01), &p, 0.0, y0, 1e4, &[]),
        ),
    ];
    for (name, run) in runs {
        let run = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        let stop = &run.switches[0];
        assert_eq!(stop.to, [Slip::Stick], "{name}");
        // s is quadratic while sliding: exact for every method here.
        assert!(
            (stop.t - t_star).abs() < 1e-12,
            "{name}: stops at {}",
            stop.t
        );
        let at_stop = run.solution.at(stop.t).unwrap();
        assert!(
            (at_stop[0] - s_star).abs() < 1e-12,
            "{name}: s* = {}",
            at_stop[0]
        );
        let (t, y) = run.solution.last();
        assert_eq!(t, 1e4);
        assert_eq!((y[0], y[1]), (at_stop[0], 0.0), "{name}: crept on the belt");
    }
}
