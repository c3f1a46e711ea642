//! Hunt: a Watt six-bar (two four-bar loops in series) with its crank driven at a constant
//! rate through full turns, under gravity: the kinematic sweep, sampled coarsely (8 times a
//! turn), and the drive's effort. Crank `th = w t` about the origin, coupler `be`, rocker
//! `ga` about `(d, 0)`; a second coupler `de` from the rocker's tip to a second rocker `ep`
//! about `(d2, 0)` (the dimensions of `hunt_loops_sixbar.rs`, where it runs free).
//!
//! Reference, by hand: the closure by two two-circle intersections (the elbows above the
//! ground line), each bar's mass centre and angle as functions of `th`, their derivatives by
//! five-point differences, and the drive's effort from Lagrange's equation at `th'' = 0`:
//! `effort = C w^2 - Q`, `C = sum m p'.p'' + I phi' phi''`, `Q = -g sum m p'_y` (`'` = `d/dth`).

use mbd::analysis::{NewtonOptions, kinematic_sweep};
use mbd::prelude::*;
use std::f64::consts::TAU;

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[drive(th = 0.5 + w * t)]
#[coords(be, ga, de, ep)]
#[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
#[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
#[constraint(d + c * cos(ga) + e * cos(de) == d2 + f * cos(ep))]
#[constraint(c * sin(ga) + e * sin(de) == f * sin(ep))]
#[rigid(crank, mass = m, inertia = m * a * a / 12.0,
        at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
#[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
        at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
#[rigid(rocker, mass = m, inertia = m * c * c / 12.0,
        at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
#[rigid(link, mass = m, inertia = m * e * e / 12.0,
        at = [d + c * cos(ga) + e / 2.0 * cos(de), c * sin(ga) + e / 2.0 * sin(de)], angle = de)]
#[rigid(rocker2, mass = m, inertia = m * f * f / 12.0,
        at = [d2 + f / 2.0 * cos(ep), f / 2.0 * sin(ep)], angle = ep)]
#[init(be = 0.726016592102178, ga = 1.7229599395818347, de = -0.18570003070547192,
       ep = 1.2820616702455918)]
#[output(motor = reaction(th))]
pub struct WattDriven {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub e: f64,
    pub f: f64,
    pub d2: f64,
    pub m: f64,
    pub g: f64,
    pub w: f64,
}

const L: [f64; 5] = [1.0, 3.0, 2.5, 3.0, 2.0];
const D: f64 = 3.5;
const D2: f64 = 5.5;
const G: f64 = 9.81;
const W: f64 = 3.0;

fn model() -> WattDriven {
    WattDriven {
        a: L[0],
        b: L[1],
        c: L[2],
        d: D,
        e: L[3],
        f: L[4],
        d2: D2,
        m: 1.0,
        g: G,
        w: W,
    }
}

/// The angles `(AC, DC)` of the point `C` at `r1` from `A` and `r2` from `D`, left of `A -> D`.
fn two_circles(a: (f64, f64), r1: f64, d: (f64, f64), r2: f64) -> (f64, f64) {
    let (vx, vy) = (d.0 - a.0, d.1 - a.1);
    let l = vx.hypot(vy);
    let alpha = ((r1 * r1 + l * l - r2 * r2) / (2.0 * r1 * l)).acos();
    let first = vy.atan2(vx) + alpha;
    let (cx, cy) = (a.0 + r1 * first.cos(), a.1 + r1 * first.sin());
    (first, (cy - d.1).atan2(cx - d.0))
}

/// `[be, ga, de, ep]` at crank angle `th`.
fn close(th: f64) -> [f64; 4] {
    let (be, ga) = two_circles((L[0] * th.cos(), L[0] * th.sin()), L[1], (D, 0.0), L[2]);
    let c = (D + L[2] * ga.cos(), L[2] * ga.sin());
    let (de, ep) = two_circles(c, L[3], (D2, 0.0), L[4]);
    [be, ga, de, ep]
}

/// The bars' `(x, y, angle)`, flattened: crank, coupler, rocker, link, rocker2.
fn bars(th: f64) -> [f64; 15] {
    let [be, ga, de, ep] = close(th);
    let (a, b, c, e, f) = (L[0], L[1], L[2], L[3], L[4]);
    let tip = (D + c * ga.cos(), c * ga.sin());
    [
        a / 2.0 * th.cos(),
        a / 2.0 * th.sin(),
        th,
        a * th.cos() + b / 2.0 * be.cos(),
        a * th.sin() + b / 2.0 * be.sin(),
        be,
        D + c / 2.0 * ga.cos(),
        c / 2.0 * ga.sin(),
        ga,
        tip.0 + e / 2.0 * de.cos(),
        tip.1 + e / 2.0 * de.sin(),
        de,
        D2 + f / 2.0 * ep.cos(),
        f / 2.0 * ep.sin(),
        ep,
    ]
}

fn wrap(x: f64) -> f64 {
    (x + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI
}

/// Five-point first and second derivatives in `th` of `bars` (angles unwrapped locally).
fn diff(th: f64) -> ([f64; 15], [f64; 15]) {
    let h = 1e-3;
    let mid = bars(th);
    let s = [-2.0, -1.0, 1.0, 2.0].map(|k| {
        let mut b = bars(th + k * h);
        for j in (2..15).step_by(3) {
            b[j] = mid[j] + wrap(b[j] - mid[j]);
        }
        b
    });
    let (mut d1, mut d2) = ([0.0; 15], [0.0; 15]);
    for j in 0..15 {
        let (m2, m1, p1, p2) = (s[0][j], s[1][j], s[2][j], s[3][j]);
        d1[j] = (m2 - 8.0 * m1 + 8.0 * p1 - p2) / (12.0 * h);
        d2[j] = (-m2 + 16.0 * m1 - 30.0 * mid[j] + 16.0 * p1 - p2) / (12.0 * h * h);
    }
    (d1, d2)
}

fn effort(th: f64) -> f64 {
    let (d1, d2) = diff(th);
    let (mut c, mut q) = (0.0, 0.0);
    for (k, len) in L.iter().enumerate() {
        let i = len * len / 12.0;
        let j = 3 * k;
        c += d1[j] * d2[j] + d1[j + 1] * d2[j + 1] + i * d1[j + 2] * d2[j + 2];
        q -= G * d1[j + 1];
    }
    c * W * W - q
}

#[test]
fn the_init_is_on_the_hand_closure_and_the_loop_is_augmented() {
    let x = close(0.5);
    let init = [
        0.726016592102178,
        1.7229599395818347,
        -0.18570003070547192,
        1.2820616702455918,
    ];
    for (a, b) in x.iter().zip(&init) {
        assert!((a - b).abs() < 1e-14);
    }
    assert!(WattDriven::GENERATED.parts.contains(&"augmented"));
}

/// Three turns sampled 8 times a turn: every sample on the hand closure's elbows, the rates
/// `d/dt = w d/dth`, and the drive's effort Lagrange's.
#[test]
fn a_coarse_sweep_through_three_turns_stays_on_the_elbows_and_the_effort_is_lagranges() {
    let p = model();
    let times: Vec<f64> = (0..=24).map(|i| i as f64 * TAU / (8.0 * W)).collect();
    let guess = p.initial_state().fixed_rows::<4>(0).into_owned();
    let ks = kinematic_sweep(&p, &times, &guess, &NewtonOptions::default()).unwrap();
    for k in &ks {
        let th = 0.5 + W * k.t;
        let x = close(th);
        let (d1, _) = diff(th);
        let rates = [d1[5], d1[8], d1[11], d1[14]].map(|r| r * W);
        for i in 0..4 {
            assert!(
                wrap(k.q[i] - x[i]).abs() < 1e-12,
                "t = {}: q{i} {} vs {}",
                k.t,
                k.q[i],
                x[i]
            );
            assert!(
                (k.qd[i] - rates[i]).abs() < 1e-8 * (1.0 + rates[i].abs()),
                "t = {}",
                k.t
            );
        }
        let y = Vector::<8>::from_fn(|i, _| if i < 4 { k.q[i] } else { k.qd[i - 4] });
        let got = p.outputs(k.t, &y).unwrap().motor;
        let want = effort(th);
        assert!(
            (got - want).abs() < 1e-6 * (1.0 + want.abs()),
            "t = {}: {got} vs {want}",
            k.t
        );
    }
}
