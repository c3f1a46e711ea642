//! Hunt: the forces in every pin of a free crank-rocker in motion, against Newton–Euler on
//! each bar by hand. The crank-rocker is a planar joint tree closed by a pin (`a = 1`,
//! `b = 2.5`, `c = 2`, `d = 3`, gravity): crank `th` about the origin `O`, coupler `ph`
//! relative to it at the crank's tip `A`, rocker `ps` about `D = (d, 0)`, the coupler's far
//! end pinned to the rocker's tip `C`. The ground pins' forces are asked for with
//! `reaction` on the crank and the rocker; the closing pin's force is the multipliers'
//! (`-Phi_q^T lambda` the constraint force, `Phi = p_coupler - p_rocker`, so the rocker's
//! force on the coupler is `-lambda`).
//!
//! Reference, by hand: the closure (two-circle intersection, the rocker tip left of
//! `A -> D`), the rates `be' = kb th'`, `ps' = kg th'` (Cramer's rule on the loop's rate
//! equations) and `be'' = kb th'' + kb' th'^2` (`kb'` by a five-point difference), each
//! bar's mass-centre acceleration linear in `th''`; then the nine equations of the three
//! free bodies (force and moment about the mass centre each) in the nine unknowns `th''`,
//! `F_O`, `F_A` (crank on coupler), `F_C` (rocker on coupler), `F_D`, solved by LU.

use mbd::prelude::*;
use mbd::{Matrix, Vector};

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[body(crank, joint = revolute(th), com = [a / 2.0, 0.0], mass = m1,
       inertia = m1 * a * a / 12.0, reaction)]
#[body(coupler, parent = crank, joint = revolute(ph), at = [a, 0.0],
       com = [b / 2.0, 0.0], mass = m2, inertia = m2 * b * b / 12.0)]
#[body(rocker, joint = revolute(ps), at = [d, 0.0], com = [c / 2.0, 0.0], mass = m3,
       inertia = m3 * c * c / 12.0, reaction)]
#[close(pin, a = coupler, at_a = [b, 0.0], b = rocker, at_b = [c, 0.0])]
#[output(o_x = reaction(crank_rx), o_y = reaction(crank_ry),
         d_x = reaction(rocker_rx), d_y = reaction(rocker_ry))]
pub struct Pins {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub g: f64,
}

const A: f64 = 1.0;
const B: f64 = 2.5;
const C: f64 = 2.0;
const D: f64 = 3.0;
const M: [f64; 3] = [1.0, 2.0, 1.5];
const G: f64 = 9.81;

fn model() -> Pins {
    Pins {
        a: A,
        b: B,
        c: C,
        d: D,
        m1: M[0],
        m2: M[1],
        m3: M[2],
        g: G,
    }
}

fn close(th: f64) -> (f64, f64) {
    let [ax, ay] = [A * th.cos(), A * th.sin()];
    let (dx, dy) = (D - ax, -ay);
    let l = dx.hypot(dy);
    let x = (l * l + B * B - C * C) / (2.0 * l);
    let h = (B * B - x * x).sqrt();
    let (ex, ey) = (dx / l, dy / l);
    let (cx, cy) = (ax + x * ex - h * ey, ay + x * ey + h * ex);
    ((cy - ay).atan2(cx - ax), cy.atan2(cx - D))
}

fn ratios(th: f64) -> [f64; 2] {
    let (be, ga) = close(th);
    let (m11, m12, m21, m22) = (-B * be.sin(), C * ga.sin(), B * be.cos(), -C * ga.cos());
    let (r1, r2) = (A * th.sin(), -A * th.cos());
    let det = m11 * m22 - m12 * m21;
    [(r1 * m22 - m12 * r2) / det, (m11 * r2 - m21 * r1) / det]
}

fn ratio_slopes(th: f64) -> [f64; 2] {
    let h = 1e-3;
    let f = |k: f64| ratios(th + k * h);
    let (m2, m1, p1, p2) = (f(-2.0), f(-1.0), f(1.0), f(2.0));
    [0, 1].map(|i| (m2[i] - 8.0 * m1[i] + 8.0 * p1[i] - p2[i]) / (12.0 * h))
}

/// The moment `r x F` as coefficients of `(F_x, F_y)`.
fn moment_arm(r: [f64; 2]) -> [f64; 2] {
    [-r[1], r[0]]
}

/// `(th'', F_O, F_A, F_C, F_D)` by Newton–Euler at `(th, th')`.
fn newton_euler(th: f64, w: f64) -> Vector<9> {
    let (be, ga) = close(th);
    let [kb, kg] = ratios(th);
    let [kb1, kg1] = ratio_slopes(th);
    let u = |x: f64| [x.cos(), x.sin()];
    let du = |x: f64| [-x.sin(), x.cos()];
    // each mass centre's acceleration = s * th'' + r, and each angular one = s * th'' + r
    let lin = |p: [f64; 2], s: f64| [p[0] * s, p[1] * s];
    let (bw, gw) = (kb * w, kg * w);
    let acc = [
        (lin(du(th), A / 2.0), lin(u(th), -A / 2.0 * w * w)),
        (
            [
                A * du(th)[0] + B / 2.0 * du(be)[0] * kb,
                A * du(th)[1] + B / 2.0 * du(be)[1] * kb,
            ],
            [
                -A * u(th)[0] * w * w + B / 2.0 * (du(be)[0] * kb1 * w * w - u(be)[0] * bw * bw),
                -A * u(th)[1] * w * w + B / 2.0 * (du(be)[1] * kb1 * w * w - u(be)[1] * bw * bw),
            ],
        ),
        (
            lin(du(ga), C / 2.0 * kg),
            [
                C / 2.0 * (du(ga)[0] * kg1 * w * w - u(ga)[0] * gw * gw),
                C / 2.0 * (du(ga)[1] * kg1 * w * w - u(ga)[1] * gw * gw),
            ],
        ),
    ];
    let ang = [(1.0, 0.0), (kb, kb1 * w * w), (kg, kg1 * w * w)];
    let inertia = [A * A / 12.0, B * B / 12.0, C * C / 12.0];
    let o = [0.0, 0.0];
    let pa = [A * th.cos(), A * th.sin()];
    let pc = [D + C * ga.cos(), C * ga.sin()];
    let pd = [D, 0.0];
    let com = [
        [A / 2.0 * th.cos(), A / 2.0 * th.sin()],
        [pa[0] + B / 2.0 * be.cos(), pa[1] + B / 2.0 * be.sin()],
        [D + C / 2.0 * ga.cos(), C / 2.0 * ga.sin()],
    ];
    // unknowns: 0 th'', 1-2 F_O, 3-4 F_A, 5-6 F_C, 7-8 F_D
    // forces on each body: crank F_O - F_A; coupler F_A + F_C; rocker -F_C + F_D
    let loads: [[(usize, f64, [f64; 2]); 2]; 3] = [
        [(1, 1.0, o), (3, -1.0, pa)],
        [(3, 1.0, pa), (5, 1.0, pc)],
        [(5, -1.0, pc), (7, 1.0, pd)],
    ];
    let mut k = Matrix::<9, 9>::zeros();
    let mut r = Vector::<9>::zeros();
    for b in 0..3 {
        let (s, rest) = acc[b];
        for i in 0..2 {
            // m (s th'' + rest) - sum F = m g
            k[(3 * b + i, 0)] = M[b] * s[i];
            for &(col, sign, _) in &loads[b] {
                k[(3 * b + i, col + i)] -= sign;
            }
            r[3 * b + i] = -M[b] * rest[i] + if i == 1 { -M[b] * G } else { 0.0 };
        }
        // I (s th'' + rest) - sum (p - com) x F = 0
        let (s, rest) = ang[b];
        k[(3 * b + 2, 0)] = M[b] * inertia[b] * s;
        for &(col, sign, p) in &loads[b] {
            let arm = [p[0] - com[b][0], p[1] - com[b][1]];
            let m = moment_arm(arm);
            k[(3 * b + 2, col)] -= sign * m[0];
            k[(3 * b + 2, col + 1)] -= sign * m[1];
        }
        r[3 * b + 2] = -M[b] * inertia[b] * rest;
    }
    k.lu().solve(&r).expect("regular")
}

/// The augmented state (`COORDINATES` order) at `(th, th')`.
fn state(th: f64, w: f64) -> Vector<6> {
    let (be, ga) = close(th);
    let [kb, kg] = ratios(th);
    let (q, qd) = ([th, be - th, ga], [w, (kb - 1.0) * w, kg * w]);
    let mut y = Vector::<6>::zeros();
    for (i, name) in Pins::COORDINATES.iter().enumerate() {
        let j = ["th", "ph", "ps"].iter().position(|c| c == name).unwrap();
        (y[i], y[3 + i]) = (q[j], qd[j]);
    }
    y
}

#[test]
fn every_pin_force_in_motion_is_newton_eulers() {
    assert_eq!(Pins::COORDINATES, ["th", "ph", "ps"]);
    let p = model();
    let mut worst = 0.0f64;
    for th in [0.0, 0.9, 2.0, 3.1, 4.4, 5.6] {
        for w in [0.0, 3.0, -7.0] {
            let ne = newton_euler(th, w);
            let y = state(th, w);
            let q = y.fixed_rows::<3>(0).into_owned();
            let qd = y.fixed_rows::<3>(3).into_owned();
            let (qdd, lambda) = p.acceleration_and_multipliers(0.0, &q, &qd).unwrap();
            let o = p.outputs(0.0, &y).unwrap();
            let scale = ne.amax();
            let got = [qdd[0], o.o_x, o.o_y, -lambda[0], -lambda[1], o.d_x, o.d_y];
            let want = [ne[0], ne[1], ne[2], ne[5], ne[6], ne[7], ne[8]];
            for (g, w_) in got.iter().zip(&want) {
                worst = worst.max((g - w_).abs() / scale);
            }
            assert!(
                got.iter()
                    .zip(&want)
                    .all(|(g, w_)| (g - w_).abs() < 1e-8 * scale),
                "th = {th}, w = {w}: {got:?} vs {want:?}"
            );
        }
    }
    println!("worst relative {worst:.2e}");
}
