//! Hunt: a Grashof double-rocker (the coupler is the shortest bar: `a = 2.5`, `b = 1`,
//! `c = 2.5`, `d = 3`, `s + l = 4 <= p + q = 5`). Its input `th` rocks between limits where the
//! coupler and the output bar fall in line (`|A - D| = b + c` at `cos th = 0.2`, `th = 1.369`),
//! while the coupler turns on; the mechanism is regular there. No gravity: free motion.
//!
//! - The augmented form must pass `th`'s limit: the energy `T` summed here from the state
//!   (mass-centre velocities by hand) is conserved and the loop stays closed (by hand).
//! - The minimal form (state `th`) cannot pass it: its chart ends there; it must stop with a
//!   typed `SingularPosition` near `th = 1.369`, never return a wrong motion.

use mbd::Vector;
use mbd::integrate::{Dopri5, Integrator, Options, Radau5, Rk4};
use mbd::prelude::*;

macro_rules! double_rocker {
    ($name:ident, $($opt:ident),*) => {
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[coords(th, be, ga)]
        #[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
        #[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
        #[rigid(input, mass = m, inertia = m * a * a / 12.0,
                at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
        #[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
                at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
        #[rigid(output, mass = m, inertia = m * c * c / 12.0,
                at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
        #[init(th = 0.9, be = 0.49675274962089777, ga = 1.7995215516548775, der(th) = 1.0)]
        pub struct $name {
            #[default(2.5)] pub a: f64,
            #[default(1.0)] pub b: f64,
            #[default(2.5)] pub c: f64,
            #[default(3.0)] pub d: f64,
            #[default(1.0)] pub m: f64,
        }
    };
}
double_rocker!(DoubleRocker, jacobian);
double_rocker!(DoubleRockerAugmented, jacobian, augmented);

const LIMIT: f64 = 1.369_438_406_004_566; // acos(0.2)

/// Kinetic energy from the full state `[th, be, ga, th', be', ga']`, all bars of mass 1.
fn kinetic(y: &Vector<6>) -> f64 {
    let (a, b, c) = (2.5, 1.0, 2.5);
    let (th, be, w1, w2, w3) = (y[0], y[1], y[3], y[4], y[5]);
    let v1 = (a / 2.0 * w1).powi(2);
    let (vx, vy) = (
        -a * th.sin() * w1 - b / 2.0 * be.sin() * w2,
        a * th.cos() * w1 + b / 2.0 * be.cos() * w2,
    );
    let v3 = (c / 2.0 * w3).powi(2);
    0.5 * (v1 + vx * vx + vy * vy + v3)
        + 0.5 * (a * a * w1 * w1 + b * b * w2 * w2 + c * c * w3 * w3) / 12.0
}

fn closure(y: &Vector<6>) -> f64 {
    let (a, b, c, d) = (2.5, 1.0, 2.5, 3.0);
    let r1 = a * y[0].cos() + b * y[1].cos() - d - c * y[2].cos();
    let r2 = a * y[0].sin() + b * y[1].sin() - c * y[2].sin();
    r1.abs().max(r2.abs())
}

/// A model of type `$ty` with the bars above (all of mass 1).
macro_rules! bars {
    ($ty:ident) => {
        $ty {
            a: 2.5,
            b: 1.0,
            c: 2.5,
            d: 3.0,
            m: 1.0,
        }
    };
}

/// The methods both forms run, from `y0` to `t = 4`.
fn every_method<S: OdeSystem<D>, const D: usize>(
    p: &S,
    y0: Vector<D>,
) -> [(&'static str, mbd::Result<Solution<D>>); 3] {
    let opts = |tol: f64| Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    };
    [
        (
            "dopri5",
            Dopri5::new(opts(1e-10)).solve(p, 0.0, y0, 4.0, &[]),
        ),
        (
            "radau5",
            Radau5::new(opts(1e-8)).solve(p, 0.0, y0, 4.0, &[]),
        ),
        ("rk4", Rk4::new(1e-3).solve(p, 0.0, y0, 4.0, &[])),
    ]
}

/// The augmented runs' energy tolerances, in `every_method`'s order: dopri5, radau5, rk4.
const ENERGY_TOL: [f64; 3] = [1e-7, 1e-5, 1e-6];

#[test]
fn limits_are_where_coupler_and_output_align() {
    assert!((LIMIT - 0.2f64.acos()).abs() < 1e-15);
    assert_eq!(DoubleRocker::COORDINATES, ["th"]);
}

#[test]
fn augmented_form_passes_the_inputs_limit_on_every_method() {
    let p = bars!(DoubleRockerAugmented);
    let y0 = p.initial_state();
    let t0 = kinetic(&y0);
    for ((name, run), tol) in every_method(&p, y0).into_iter().zip(ENERGY_TOL) {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let top = sol.y.iter().map(|y| y[0]).fold(f64::MIN, f64::max);
        let (mut de, mut off) = (0.0f64, 0.0f64);
        for y in &sol.y {
            de = de.max((kinetic(y) - t0).abs() / t0);
            off = off.max(closure(y));
        }
        let turned = sol.y.last().unwrap()[1] - y0[1];
        println!(
            "{name}: top th {top:.6} (limit {LIMIT:.6}), energy {de:.2e}, closure {off:.2e}, coupler turned {turned:.3}"
        );
        assert!(
            LIMIT - top < 1e-3 && top <= LIMIT + 1e-9,
            "{name}: th reached {top}"
        );
        assert!(
            de < tol && off < 1e-9,
            "{name}: energy {de:e}, closure {off:e}"
        );
    }
}

#[test]
fn minimal_form_stops_at_the_inputs_limit_with_a_typed_error() {
    let p = bars!(DoubleRocker);
    let y0 = p.initial_state();
    for (name, run) in every_method(&p, y0) {
        match run {
            Err(mbd::Error::SingularPosition { t, detail }) => {
                println!("{name}: t = {t}: {detail}")
            }
            Ok(sol) => {
                let top = sol.y.iter().map(|y| y[0]).fold(f64::MIN, f64::max);
                panic!(
                    "{name}: Ok, th reached {top}, ends {}",
                    sol.y.last().unwrap()
                );
            }
            Err(e) => panic!("{name}: {e}"),
        }
    }
}
