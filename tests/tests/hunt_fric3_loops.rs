//! Friction in a revolute joint of a closed loop, with the normal force the joint's own
//! reaction (load dependent, implicit): the friction circle of a slider-crank's main pin.
//! The reference is the statics derived beside the test.

use mbd::integrate::{Dopri5, Radau5};
use mbd::prelude::*;
use mbd::{Hybrid, Slip};

/// A slider-crank in augmented coordinates `(th, be, x)` closed by two constraints: crank
/// `a` about a pin whose place `(px, py)` is relaxed (so that `reaction(px)`,
/// `reaction(py)` are the pin's force on the crank), rod `l`, piston on `y = 0` under the
/// load `-P` along `x`, no gravity. The pin's friction is the torque `c |R|` on `th`
/// (`c = mu r`, friction radius times coefficient), `|R|` the full reaction.
#[derive(Debug, Mechanism)]
#[coords(th, be, x)]
#[relaxed(px, py)]
#[constraint(x == px + a * cos(th) + l * cos(be))]
#[constraint(py + a * sin(th) - l * sin(be) == 0.0)]
#[rigid(crank, mass = mc, inertia = jc, at = [px, py], angle = th)]
#[rigid(rod, mass = mr, inertia = mr * l * l / 12.0,
        at = [px + a * cos(th) + l / 2.0 * cos(be), py + a * sin(th) - l / 2.0 * sin(be)],
        angle = -be)]
#[particle(piston, mass = mp, at = [x, 0.0])]
#[generalized_force(load, along = x, value = -p)]
#[friction(along = th, mu = c, normal = hypot(reaction(px), reaction(py)))]
pub struct RoughCrank {
    pub a: f64,
    pub l: f64,
    pub mc: f64,
    pub jc: f64,
    pub mr: f64,
    pub mp: f64,
    pub p: f64,
    pub c: f64,
}

fn crank(p: f64, c: f64) -> RoughCrank {
    RoughCrank {
        a: 0.1,
        l: 0.35,
        mc: 1.0,
        jc: 0.02,
        mr: 0.4,
        mp: 0.6,
        p,
        c,
    }
}

/// The state at rest at crank angle `th` on the closed loop.
fn at_rest(k: &RoughCrank, th: f64) -> Vector<6> {
    let be = (k.a * th.sin() / k.l).asin();
    Vector::<6>::new(th, be, k.a * th.cos() + k.l * be.cos(), 0.0, 0.0, 0.0)
}

/// At rest nothing accelerates, so with no gravity every link is in static equilibrium:
/// the rod is a two-force member carrying `F = P / cos be` along itself (its `x` part holds
/// the piston), and the crank's pin carries the same force, `|R| = P / cos be`, while the
/// torque to hold the crank is `F` times the rod's arm about the pin, `a |sin(th + be)|`
/// (the rod through `A = a (cos th, sin th)` along `(cos be, -sin be)`). The pin holds while
/// `F a |sin(th + be)| <= c F`: `a |sin(th + be)| <= c`, the friction circle, whatever
/// the load `P`. Just inside it (`c = c* (1 + 1e-9)`) the crank holds exactly under loads
/// from 1 mN to 1 MN; just outside (`c* (1 - 1e-9)`) it turns.
#[test]
fn a_rough_crank_pin_holds_inside_its_friction_circle_whatever_the_load() {
    for th in [0.3f64, 1.0, 2.0, 2.8, 4.0, 5.5] {
        let k0 = crank(1.0, 0.0);
        let be = (k0.a * th.sin() / k0.l).asin();
        let c_star = k0.a * (th + be).sin().abs();
        for p in [1e-3, 1.0, 1e6] {
            for (scale, holds) in [(1.0 + 1e-9, true), (1.0 - 1e-9, false)] {
                let k = crank(p, c_star * scale);
                let y = at_rest(&k, th);
                let mode = k.mode_at(0.0, &y).unwrap();
                let a = k
                    .acceleration(0.0, &y.fixed_rows::<3>(0).into(), &Vector::<3>::zeros())
                    .unwrap();
                let what = format!("th = {th}, P = {p}, c = c* {scale}");
                if holds {
                    assert_eq!(mode, [Slip::Stick], "{what}");
                    assert_eq!(a[0], 0.0, "{what}");
                } else {
                    assert_ne!(mode, [Slip::Stick], "{what}");
                    assert!(a[0] != 0.0, "{what}");
                }
            }
        }
    }
}

/// Held inside its friction circle, the crank stays for good: its angle does not move by a
/// bit over 1000 s, with DOPRI5 and Radau IIA (the stuck mode's state is constant).
#[test]
fn a_held_crank_does_not_creep() {
    let th = 1.0f64;
    let k0 = crank(50.0, 0.0);
    let be = (k0.a * th.sin() / k0.l).asin();
    let k = crank(50.0, k0.a * (th + be).sin().abs() * 1.001);
    let y0 = at_rest(&k, th);
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    for (name, run) in [
        (
            "DOPRI5",
            mbd::hybrid::solve(&Dopri5::new(opts.clone()), &k, 0.0, y0, 1e3, &[]),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(&Radau5::new(opts.clone()), &k, 0.0, y0, 1e3, &[]),
        ),
    ] {
        let run = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(run.switches.is_empty(), "{name}: {:?}", run.switches);
        let (t, y) = run.solution.last();
        assert_eq!(t, 1e3);
        assert_eq!(y[0], th, "{name}");
        assert_eq!(y[3], 0.0, "{name}");
    }
}
