//! Hunt: a spatial RSSR four-bar driven through full turns: a crank `a` about the ground
//! `z` axis driven at `th = w t`, a rocker `c` about the ground `x` direction through
//! `D = (dx, dy, dz)` (`ps`, the only coordinate), a coupler `b` on ball joints between the
//! tips `A = a (cos th, sin th, 0)` and `C = D + c (0, cos ps, sin ps)` (a point mass at its
//! middle), gravity along `-z`. One loop equation `|A - C|^2 = b^2`; fully driven, so the
//! derive keeps the augmented form and the motion is the closure's.
//!
//! Reference, by hand: `P cos ps + Q sin ps = K` with `P = A_y - dy`, `Q = A_z - dz`,
//! `K = (|A - D|^2 + c^2 - b^2) / (2 c)`, so `ps = atan2(Q, P) + acos(K / hypot(P, Q))` (the
//! init's branch; `|K| / hypot(P, Q) <= 0.4` over the turn: no toggle). The energy
//! `E = T + V` of the three bodies (crank: spin `w` about its `z`; rocker: spin `ps'` about
//! its `x`) from the hand closure; the drive's effort `reaction(th)` must supply the power:
//! `reaction(th) w = dE/dt` (five-point difference in `t`).

use mbd::analysis::{NewtonOptions, kinematic_sweep};
use mbd::integrate::{Dopri5, Integrator, Options, Radau5};
use mbd::prelude::*;
use std::f64::consts::{PI, TAU};

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, 0.0, -g)]
#[drive(th = w * t)]
#[coords(ps)]
#[constraint((a * cos(th) - dx) * (a * cos(th) - dx)
    + (a * sin(th) - dy - c * cos(ps)) * (a * sin(th) - dy - c * cos(ps))
    + (dz + c * sin(ps)) * (dz + c * sin(ps)) == b * b)]
#[rigid3(crank, mass = m1, inertia = diag(i1, i1, j1),
         at = [a / 2.0 * cos(th), a / 2.0 * sin(th), 0.0], rotation = rot_z(th))]
#[rigid3(rocker, mass = m3, inertia = diag(j3, i3, i3),
         at = [dx, dy + c / 2.0 * cos(ps), dz + c / 2.0 * sin(ps)], rotation = rot_x(ps))]
#[particle(coupler, mass = m2,
           at = [(a * cos(th) + dx) / 2.0, (a * sin(th) + dy + c * cos(ps)) / 2.0,
                 (dz + c * sin(ps)) / 2.0])]
#[init(ps = -0.30696770204475365)]
#[output(motor = reaction(th))]
pub struct Rssr {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub dx: f64,
    pub dy: f64,
    pub dz: f64,
    pub m1: f64,
    pub i1: f64,
    pub j1: f64,
    pub m2: f64,
    pub m3: f64,
    pub i3: f64,
    pub j3: f64,
    pub g: f64,
    pub w: f64,
}

const A: f64 = 1.0;
const B: f64 = 3.5;
const C: f64 = 2.5;
const DD: [f64; 3] = [1.5, 1.0, 1.5];
const M1: f64 = 2.0;
const J1: f64 = 0.3;
const M2: f64 = 1.2;
const M3: f64 = 1.6;
const J3: f64 = 0.9;
const G: f64 = 9.81;
const W: f64 = 4.0;

fn model() -> Rssr {
    Rssr {
        a: A,
        b: B,
        c: C,
        dx: DD[0],
        dy: DD[1],
        dz: DD[2],
        m1: M1,
        i1: 0.2,
        j1: J1,
        m2: M2,
        m3: M3,
        i3: 0.5,
        j3: J3,
        g: G,
        w: W,
    }
}

/// `ps` at crank angle `th`, continued by whole turns to stay near `near`.
fn close(th: f64, near: f64) -> f64 {
    let (p, q) = (A * th.sin() - DD[1], -DD[2]);
    let ad2 = (A * th.cos() - DD[0]).powi(2) + p * p + q * q;
    let k = (ad2 + C * C - B * B) / (2.0 * C);
    let ps = q.atan2(p) + (k / p.hypot(q)).acos();
    ps + ((near - ps) / TAU).round() * TAU
}

/// `E = T + V` at time `t` (five-point rates in `t`).
fn energy(t: f64) -> f64 {
    let h = 1e-4;
    let ps_at = |t: f64| close(W * t, -0.3);
    let ps = ps_at(t);
    let psd = (ps_at(t - 2.0 * h) - 8.0 * ps_at(t - h) + 8.0 * ps_at(t + h) - ps_at(t + 2.0 * h))
        / (12.0 * h);
    let th = W * t;
    let v1 = A / 2.0 * W;
    let v3 = C / 2.0 * psd;
    // coupler midpoint velocity: (A' + C') / 2
    let ad = [-A * th.sin() * W, A * th.cos() * W, 0.0];
    let cd = [0.0, -C * ps.sin() * psd, C * ps.cos() * psd];
    let v2 = [0, 1, 2].map(|i| (ad[i] + cd[i]) / 2.0);
    let t_kin = M1 * v1 * v1
        + J1 * W * W
        + M3 * v3 * v3
        + J3 * psd * psd
        + M2 * (v2[0] * v2[0] + v2[1] * v2[1] + v2[2] * v2[2]);
    let v = G * (M3 * (DD[2] + C / 2.0 * ps.sin()) + M2 * (DD[2] + C * ps.sin()) / 2.0);
    t_kin / 2.0 + v
}

#[test]
fn the_init_is_on_the_hand_closure_and_the_loop_stays_augmented() {
    assert!((close(0.0, -0.3) - -0.30696770204475365).abs() < 1e-15);
    assert!(Rssr::GENERATED.parts.contains(&"augmented"));
    assert_eq!(Rssr::COORDINATES, ["ps"]);
    let p = model();
    let y = p.initial_state();
    assert!((y[0] - -0.30696770204475365).abs() < 1e-15);
}

/// Three turns sampled 12 times a turn: the sweep stays on the init's branch, and the
/// drive's effort supplies exactly the power `dE/dt`.
#[test]
fn sweep_through_three_turns_and_the_motor_supplies_the_power() {
    let p = model();
    let times: Vec<f64> = (0..=36).map(|i| i as f64 * TAU / (12.0 * W)).collect();
    let ks = kinematic_sweep(
        &p,
        &times,
        &p.initial_state().fixed_rows::<1>(0).into_owned(),
        &NewtonOptions::default(),
    )
    .unwrap();
    let mut near = -0.3;
    let mut worst = 0.0f64;
    for k in &ks {
        let ps = close(W * k.t, near);
        near = ps;
        assert!(
            (k.q[0] - ps).abs() < 1e-12,
            "t = {}: {} vs {ps}",
            k.t,
            k.q[0]
        );
        let h = 1e-4;
        let de = (energy(k.t - 2.0 * h) - 8.0 * energy(k.t - h) + 8.0 * energy(k.t + h)
            - energy(k.t + 2.0 * h))
            / (12.0 * h);
        let y = Vector::<2>::new(k.q[0], k.qd[0]);
        let motor = p.outputs(k.t, &y).unwrap().motor;
        worst = worst.max((motor * W - de).abs());
        assert!(
            (motor * W - de).abs() < 1e-6 * (1.0 + de.abs()),
            "t = {}: power {} vs dE/dt {de}",
            k.t,
            motor * W
        );
    }
    assert_eq!(ks.len(), 37);
    println!("worst power error {worst:.2e}");
}

/// Integrated (the driven loop's motion is its closure's): three turns on DOPRI5 and
/// Radau5 stay on the init's branch.
#[test]
fn integrated_three_turns_stay_on_the_branch() {
    let p = model();
    let y0 = p.initial_state();
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    let t_end = 3.0 * TAU / W;
    for (name, run) in [
        (
            "dopri5",
            Dopri5::new(opts.clone()).solve(&p, 0.0, y0, t_end, &[]),
        ),
        (
            "radau5",
            Radau5::new(opts.clone()).solve(&p, 0.0, y0, t_end, &[]),
        ),
    ] {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            let ps = close(W * t, y[0]);
            assert!((y[0] - ps).abs() < 1e-8, "{name} t = {t}: {} vs {ps}", y[0]);
            assert!(
                (ps - close(W * t, -0.3)).abs() < PI,
                "{name}: a whole turn of the rocker"
            );
        }
    }
}
