//! A stuck contact whose load meets its static bound `mu_s |N|` exactly: for an instant (a
//! tangent touch, which static friction holds) or from the start (equal coefficients, so
//! the state at rest is stuck on its boundary) under a load that then grows. Both were
//! wrong answers: the touch, hit exactly by a fixed step, started a slide whose friction
//! then drove the block backwards against its push (RK4: 13.5 m by t = 5.5); the start at the
//! bound never broke away at all, with every method. Closed forms beside each test.

use mbd::hybrid::{self, HybridSolution};
use mbd::integrate::{Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Radau5, Rk4, Vern9};
use mbd::prelude::*;
use mbd::{Hybrid, Slip};

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

type Runs<M> = Vec<(&'static str, HybridSolution<2, M>)>;

/// One run per method from `(0, y0)` to `t1`; fixed-step methods with step `h`.
fn every_method<S: Hybrid<2>>(sys: &S, y0: Vector<2>, t1: f64, h: f64) -> Runs<S::Mode> {
    let go = |name: &'static str, r: mbd::Result<HybridSolution<2, S::Mode>>| {
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

/// A block pushed by `p`, whose normal force dips to `n0` at `t = 2.5` and rises again.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = p)]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = n0 + c * (t - 2.5) * (t - 2.5))]
pub struct Dip {
    pub m: f64,
    pub p: f64,
    pub n0: f64,
    pub c: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// `mu_s |N| = 1 + 2 (t - 2.5)^2 >= p = 1` at every instant: static friction holds the
/// block throughout, touching its bound at `t = 2.5` only, whether `mu_k` equals `mu_s` or
/// is lower. Fixed steps of 0.5 land exactly on the touch.
#[test]
fn a_load_that_touches_the_static_bound_for_an_instant_is_held() {
    for mu_k in [0.5, 0.4] {
        let p = Dip {
            m: 1.0,
            p: 1.0,
            n0: 2.0,
            c: 4.0,
            mu_k,
            mu_s: 0.5,
        };
        for (name, run) in every_method(&p, Vector::<2>::zeros(), 5.5, 0.5) {
            assert!(
                run.solution.y.iter().all(|y| *y == Vector::<2>::zeros()),
                "{name}, mu_k = {mu_k}: moved to {:?}, switches {:?}",
                run.solution.last(),
                run.switches
            );
            assert_eq!(run.mode, [Slip::Stick], "{name}");
        }
    }
}

/// A block at rest under `p0 + c t`, with `mu_k = mu_s`, normal `n`.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = p0 + c * t)]
#[friction(along = x, mu = mu, normal = n)]
pub struct AtTheBound {
    pub m: f64,
    pub p0: f64,
    pub c: f64,
    pub n: f64,
    pub mu: f64,
}

/// Starting exactly at the bound, `p0 = mu n = 5`: at rest it is stuck on its boundary
/// (equal coefficients: no slide accelerates). A rising load (`c = 3`) exceeds the bound
/// at once, so it breaks away at `t = 0+` and `m x'' = p0 + c t - mu n = c t`:
/// `x = c t^3 / (6 m)`, `v = c t^2 / (2 m)` (2 m and 3 m/s at `t = 2`). A falling load
/// (`c = -3`) falls inside the bound: it never moves.
#[test]
fn a_load_starting_at_the_static_bound_breaks_away_when_it_grows() {
    for c in [3.0, -3.0] {
        let p = AtTheBound {
            m: 2.0,
            p0: 5.0,
            c,
            n: 10.0,
            mu: 0.5,
        };
        for (name, run) in every_method(&p, Vector::<2>::zeros(), 2.0, 0.01) {
            let (_, y) = run.solution.last();
            if c < 0.0 {
                assert!(run.switches.is_empty(), "{name}: {:?}", run.switches);
                assert_eq!(*y, Vector::<2>::zeros(), "{name}");
                continue;
            }
            assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
            assert_eq!(run.switches[0].to, [Slip::Forward], "{name}");
            assert!(run.switches[0].t < 1e-15, "{name}: {}", run.switches[0].t);
            // Cubic: exact for the methods of order 4 and more; generalized-alpha is of
            // second order (its h^2 error, measured 2.6e-5 at h = 0.01).
            let bound = if name == "generalized-alpha" {
                1e-4
            } else {
                1e-12
            };
            assert!((y[0] - 2.0).abs() < bound, "{name}: x = {}", y[0]);
            assert!((y[1] - 3.0).abs() < bound, "{name}: v = {}", y[1]);
        }
    }
}
