//! A sliding contact whose normal force passes through zero: `mu_k |N|` has a kink there
//! (continuous, not smooth), which the hybrid driver locates as it locates a stop
//! (`Hybrid::kink`) and restarts the method at, so no step crosses it. Both models below
//! are exact piecewise closed forms, derived beside each test; every integrator runs them.

use mbd::hybrid::{self, HybridSolution};
use mbd::integrate::{Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Radau5, Rk4, Vern9};
use mbd::prelude::*;
use mbd::{Hybrid, Slip};
use std::f64::consts::PI;

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

/// One run per method: `(name, run, bound)`, the bound being what the method's order and
/// step reach on these smooth pieces (the closed forms' error budget), measured and kept.
fn every_method<S: Hybrid<2>>(
    sys: &S,
    y0: Vector<2>,
    t1: f64,
    h: f64,
    bounds: [f64; 8],
) -> Vec<(&'static str, HybridSolution<2, S::Mode>, f64)> {
    let go = |name: &'static str, r: mbd::Result<HybridSolution<2, S::Mode>>, b: f64| {
        (name, r.unwrap_or_else(|e| panic!("{name}: {e}")), b)
    };
    vec![
        go(
            "DOPRI5",
            hybrid::solve(&Dopri5::new(tight()), sys, 0.0, y0, t1, &[]),
            bounds[0],
        ),
        go(
            "DOP853",
            hybrid::solve(&Dop853::new(tight()), sys, 0.0, y0, t1, &[]),
            bounds[1],
        ),
        go(
            "Vern9",
            hybrid::solve(&Vern9::new(tight()), sys, 0.0, y0, t1, &[]),
            bounds[2],
        ),
        go(
            "Auto",
            hybrid::solve(&Auto::new(tight()), sys, 0.0, y0, t1, &[]),
            bounds[3],
        ),
        go(
            "Radau5",
            hybrid::solve(&Radau5::new(tight()), sys, 0.0, y0, t1, &[]),
            bounds[4],
        ),
        go(
            "RK4",
            hybrid::solve(&Rk4::new(h), sys, 0.0, y0, t1, &[]),
            bounds[5],
        ),
        go(
            "Gauss",
            hybrid::solve(&Gauss::new(h), sys, 0.0, y0, t1, &[]),
            bounds[6],
        ),
        go(
            "generalized-alpha",
            hybrid::solve(&GeneralizedAlpha::new(0.9, h / 10.0), sys, 0.0, y0, t1, &[]),
            bounds[7],
        ),
    ]
}

/// A block at rest, pushed by `p`, whose normal force falls linearly in time through zero
/// (`n0 - c t`) and grows again on the other side.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = p)]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = n0 - c * t)]
pub struct Unloading {
    pub m: f64,
    pub p: f64,
    pub n0: f64,
    pub c: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// Held while `p <= mu_s (n0 - c t)`: breakaway at `t1 = (n0 - p / mu_s) / c = 1.5`. Then
/// `m v' = p - mu_k |n0 - c t|` is linear in `t` on each side of `t0 = n0 / c = 2.5`, so `v`
/// is quadratic and `x` cubic there: `m v(t0) = (p - mu_k n0)(t0 - t1) + mu_k c (t0^2 -
/// t1^2) / 2 = 1.2`, `x(t0) = 7 / 15`; after it (`s = t - t0`) `m v = 1.2 + 2 s - 0.8 s^2 / 2`
/// vanishes at `s* = 3` (`t = 5.5`), where `mu_s c s* = 6 > p` holds it for good, at
/// `x = 7 / 15 + 1.2 s* + s*^2 - 0.4 s*^3 / 3 = 7 / 15 + 5.4`. The pieces are polynomials of
/// degree 3, which every method of order 4 or more integrates exactly: with the kink
/// located, the rest position is exact to rounding.
#[test]
fn a_normal_through_zero_in_time_is_located_and_every_method_rests_exactly() {
    let p = Unloading {
        m: 1.0,
        p: 2.0,
        n0: 10.0,
        c: 4.0,
        mu_k: 0.4,
        mu_s: 0.5,
    };
    let x_stop = 7.0 / 15.0 + 5.4;
    // Generalized-alpha is of second order: its own error on the cubic pieces.
    let bounds = [1e-12, 1e-12, 1e-12, 1e-12, 1e-12, 1e-12, 1e-12, 1e-6];
    for (name, run, bound) in every_method(&p, Vector::<2>::zeros(), 8.0, 0.01, bounds) {
        let seen: Vec<_> = run.switches.iter().map(|s| (s.to, s.t)).collect();
        assert_eq!(run.switches.len(), 2, "{name}: {seen:?}");
        assert_eq!(run.switches[0].to, [Slip::Forward], "{name}");
        assert_eq!(run.switches[1].to, [Slip::Stick], "{name}");
        let y = run.solution.at(2.5).unwrap();
        assert!(
            (y[1] - 1.2).abs() < bound,
            "{name}: v(t0) off by {:e}",
            y[1] - 1.2
        );
        assert!(
            (run.switches[1].t - 5.5).abs() < 10.0 * bound,
            "{name}: {seen:?}"
        );
        let (_, y) = run.solution.last();
        assert!(
            (y[0] - x_stop).abs() < bound,
            "{name}: rests off by {:e}",
            y[0] - x_stop
        );
        assert_eq!(y[1], 0.0, "{name}");
    }
}

/// A block launched at `v0` along a track whose normal force falls with the position,
/// `N = m g - k x` (a spring lifting it), through zero at `x0 = m g / k`, and presses it
/// from above past there; no force acts along the track.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g - k * x)]
pub struct Lifted {
    pub m: f64,
    pub g: f64,
    pub k: f64,
    pub mu: f64,
}

/// With `l^2 = mu k / m`, before `x0` the friction `-mu (m g - k x)` gives
/// `x'' = l^2 (x - x0)`, so `v^2 - l^2 (x - x0)^2` is constant: `x - x0 = -x0 cosh(l t) +
/// (v0 / l) sinh(l t)`, reaching `x0` at `tanh(l t_a) = l x0 / v0` with
/// `v_a = sqrt(v0^2 - l^2 x0^2)`. Past `x0`, `x'' = -l^2 (x - x0)`: `x - x0 = (v_a / l)
/// sin(l s)`, which stops at `s = pi / (2 l)`, at `x0 + v_a / l`, with no load to move it.
/// The friction's work `mu int |m g - k x| dx` over that distance is the kinetic energy
/// `m v0^2 / 2` (`mu k x0^2 / 2 + mu k (v_a / l)^2 / 2 = m (l^2 x0^2 + v_a^2) / 2`), so the
/// rest position is the energy balance as well.
#[test]
fn a_normal_through_zero_in_position_is_located_and_the_energy_balances() {
    let p = Lifted {
        m: 2.0,
        g: 9.81,
        k: 40.0,
        mu: 0.3,
    };
    let v0: f64 = 3.0;
    let l = (p.mu * p.k / p.m).sqrt();
    let x0 = p.m * p.g / p.k;
    assert!(v0 > l * x0);
    let t_a = (l * x0 / v0).atanh() / l;
    let v_a = (v0 * v0 - l * l * x0 * x0).sqrt();
    let (t_stop, x_stop) = (t_a + PI / (2.0 * l), x0 + v_a / l);
    let work = p.mu * p.k * x0 * x0 / 2.0 + p.mu * p.k * (v_a / l).powi(2) / 2.0;
    assert!((work - p.m * v0 * v0 / 2.0).abs() < 1e-13);
    let y0 = Vector::<2>::new(0.0, v0);
    let bounds = [1e-10, 1e-10, 1e-10, 1e-10, 1e-9, 1e-10, 1e-10, 1e-8];
    for (name, run, bound) in every_method(&p, y0, 3.0, 0.002, bounds) {
        let seen: Vec<_> = run.switches.iter().map(|s| (s.to, s.t)).collect();
        assert_eq!(run.switches.len(), 1, "{name}: {seen:?}");
        assert_eq!(run.switches[0].to, [Slip::Stick], "{name}");
        assert!(
            (run.switches[0].t - t_stop).abs() < 1e3 * bound,
            "{name}: {seen:?}"
        );
        let y = run.solution.at(t_a).unwrap();
        assert!(
            (y[0] - x0).abs() < bound,
            "{name}: x(t_a) off by {:e}",
            y[0] - x0
        );
        assert!(
            (y[1] - v_a).abs() < bound,
            "{name}: v(t_a) off by {:e}",
            y[1] - v_a
        );
        let (_, y) = run.solution.last();
        assert!(
            (y[0] - x_stop).abs() < bound,
            "{name}: rests off by {:e}",
            y[0] - x_stop
        );
        assert_eq!(y[1], 0.0, "{name}");
    }
}

/// With no push, nothing loads the block: it stays at rest, exactly, while its normal
/// force (and so its friction bound) passes through zero at `t = 2.5`. With fixed steps of
/// 0.5 a step ends exactly there, where the bound `mu_s |N| - |h|` touches zero: before,
/// that touch forced a slide "in the direction of the load" (backward, for a load of zero),
/// whose kinetic friction then drove the block forward from rest (RK4: 24 m/s and 44 m by
/// `t = 8`).
#[test]
fn an_unloaded_block_stays_at_rest_while_its_normal_passes_through_zero() {
    let p = Unloading {
        m: 1.0,
        p: 0.0,
        n0: 10.0,
        c: 4.0,
        mu_k: 0.4,
        mu_s: 0.5,
    };
    for (name, run, _) in every_method(&p, Vector::<2>::zeros(), 8.0, 0.5, [0.0; 8]) {
        assert!(
            run.solution.y.iter().all(|y| *y == Vector::<2>::zeros()),
            "{name}: moved, {:?}, switches {:?}",
            run.solution.last(),
            run.switches
        );
        assert_eq!(run.mode, [Slip::Stick], "{name}");
    }
}

/// With `Settings::polish` (switches placed from step ends, for Radau IIA's degree-3 dense
/// output) the kink is polished like a switch: the block of the first test rests at
/// `7 / 15 + 5.4` to rounding with every adaptive method.
#[test]
fn polished_kinks_rest_exactly_too() {
    let p = Unloading {
        m: 1.0,
        p: 2.0,
        n0: 10.0,
        c: 4.0,
        mu_k: 0.4,
        mu_s: 0.5,
    };
    let settings = hybrid::Settings {
        polish: true,
        ..hybrid::Settings::default()
    };
    let y0 = Vector::<2>::zeros();
    let runs = [
        (
            "DOPRI5",
            hybrid::solve_with(&Dopri5::new(tight()), &p, 0.0, y0, 8.0, &[], &settings),
        ),
        (
            "Vern9",
            hybrid::solve_with(&Vern9::new(tight()), &p, 0.0, y0, 8.0, &[], &settings),
        ),
        (
            "Radau5",
            hybrid::solve_with(&Radau5::new(tight()), &p, 0.0, y0, 8.0, &[], &settings),
        ),
    ];
    for (name, run) in runs {
        let run = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(run.switches.len(), 2, "{name}: {:?}", run.switches);
        let (_, y) = run.solution.last();
        let x_stop = 7.0 / 15.0 + 5.4;
        assert!(
            (y[0] - x_stop).abs() < 1e-12,
            "{name}: rests off by {:e}",
            y[0] - x_stop
        );
        assert_eq!(y[1], 0.0, "{name}");
    }
}
