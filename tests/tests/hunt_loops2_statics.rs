//! Hunt: reactions of a closed loop written as a joint tree with a closing pin, against
//! Newton–Euler statics by hand. A four-bar whose ground pivots are offset from the origin
//! and whose ground line is tilted (`O = (ox, oy)`, `D = O + d (cos g0, sin g0)`), under
//! gravity, with a spring from a ground point to a point fixed on the coupler; the crank is
//! held at a constant angle by a drive, so the mechanism is at rest and every force is static.
//! `reaction(th)` is the holding torque; the rocker's `reaction` coordinates give the
//! ground pivot's force on the rocker.
//!
//! Reference, by hand: the closure (two-circle intersection, the init's elbow) and the nine
//! equilibrium equations of the three bars (forces and moments), unknowns the pin forces at
//! `O`, `A` (crank on coupler), `C` (rocker on coupler), `D` and the drive's torque.

#![allow(
    clippy::needless_range_loop,
    reason = "the references index bodies and components of parallel arrays"
)]

use mbd::prelude::*;
use mbd::{Matrix, Vector};
use std::f64::consts::PI;

macro_rules! four_bar {
    ($name:ident, [$($law:tt)*], [$($extra:ident),*]) => {
        /// The four-bar, its crank driven by the law given; `ph` is the coupler's angle
        /// relative to the crank.
        #[derive(Debug, Clone, Mechanism)]
        #[gravity(0.0, -g)]
        #[drive(th = $($law)*)]
        #[body(crank, joint = revolute(th), at = [ox, oy], com = [a / 2.0, 0.0], mass = 1.0,
               inertia = a * a / 12.0)]
        #[body(coupler, parent = crank, joint = revolute(ph), at = [a, 0.0], com = [b / 2.0, 0.0],
               mass = 2.0, inertia = 2.0 * b * b / 12.0)]
        #[body(rocker, joint = revolute(ga), at = [ox + d * cos(g0), oy + d * sin(g0)],
               com = [c / 2.0, 0.0], mass = 1.5, inertia = 1.5 * c * c / 12.0, reaction)]
        #[close(pin, a = coupler, at_a = [b, 0.0], b = rocker, at_b = [c, 0.0])]
        #[point(hook, on = coupler, at = [b / 2.0, 0.3])]
        #[point(anchor, at = [1.0, 3.0])]
        #[spring(s, from = anchor, to = hook, k = k, length = 0.5)]
        #[output(holding = reaction(th), fx = reaction(rocker_rx), fy = reaction(rocker_ry))]
        pub struct $name {
            pub a: f64,
            pub b: f64,
            pub c: f64,
            pub d: f64,
            pub g0: f64,
            pub ox: f64,
            pub oy: f64,
            pub th0: f64,
            pub k: f64,
            pub g: f64,
            $(pub $extra: f64,)*
        }
    };
}
four_bar!(Held, [th0], []);
four_bar!(Turning, [th0 + w * t], [w]);

const P: Held = Held {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 3.2,
    g0: 0.4,
    ox: -0.5,
    oy: 0.8,
    th0: 1.3,
    k: 40.0,
    g: 9.81,
};
const MASS: [f64; 3] = [1.0, 2.0, 1.5];

fn u(x: f64) -> [f64; 2] {
    [x.cos(), x.sin()]
}

fn cross(r: [f64; 2], f: [f64; 2]) -> f64 {
    r[0] * f[1] - r[1] * f[0]
}

fn sub(p: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    [p[0] - q[0], p[1] - q[1]]
}

fn along(p: [f64; 2], s: f64, e: [f64; 2]) -> [f64; 2] {
    [p[0] + s * e[0], p[1] + s * e[1]]
}

/// `(be, ga)` (coupler's and rocker's absolute angles) at `th`, `C` to the left of `A -> D`.
fn close(th: f64) -> (f64, f64) {
    let o = [P.ox, P.oy];
    let a = along(o, P.a, u(th));
    let d = along(o, P.d, u(P.g0));
    let ad = sub(d, a);
    let l = ad[0].hypot(ad[1]);
    let alpha = ((P.b * P.b + l * l - P.c * P.c) / (2.0 * P.b * l)).acos();
    let be = ad[1].atan2(ad[0]) + alpha;
    let c = along(a, P.b, u(be));
    let dc = sub(c, d);
    (be, dc[1].atan2(dc[0]))
}

/// Each bar's mass centre and angle at `th`: crank, coupler, rocker.
fn bars(th: f64) -> [[f64; 3]; 3] {
    let (be, ga) = close(th);
    let o = [P.ox, P.oy];
    let a = along(o, P.a, u(th));
    let d = along(o, P.d, u(P.g0));
    let [g1, g2, g3] = [
        along(o, P.a / 2.0, u(th)),
        along(a, P.b / 2.0, u(be)),
        along(d, P.c / 2.0, u(ga)),
    ];
    [[g1[0], g1[1], th], [g2[0], g2[1], be], [g3[0], g3[1], ga]]
}

/// The bars' accelerations `(a_x, a_y, alpha)` with the crank turning steadily at `w`:
/// `w^2` times the second derivatives in `th` (five-point differences, step 1e-3).
fn accelerations(th: f64, w: f64) -> [[f64; 3]; 3] {
    let h = 1e-3;
    let s = [-2.0, -1.0, 0.0, 1.0, 2.0].map(|k| bars(th + k * h));
    let mut out = [[0.0; 3]; 3];
    for b in 0..3 {
        for k in 0..3 {
            let v = |i: usize| s[i][b][k];
            out[b][k] =
                w * w * (-v(0) + 16.0 * v(1) - 30.0 * v(2) + 16.0 * v(3) - v(4)) / (12.0 * h * h);
        }
    }
    out
}

/// `[F_O, F_A, F_C, F_D, tau]` of the static equilibrium at `th` (forces on the crank at `O`
/// from the ground, on the coupler at `A` from the crank, on the coupler at `C` from the
/// rocker, on the rocker at `D` from the ground; the drive's torque on the crank).
fn statics(th: f64) -> Vector<9> {
    newton_euler(th, 0.0)
}

/// [`statics`] with the crank turning steadily at `w`: d'Alembert's inertial loads
/// `-m a` at the mass centres and `-I alpha` on each bar join the loads.
fn newton_euler(th: f64, w: f64) -> Vector<9> {
    let acc = accelerations(th, w);
    let inertia = [
        P.a * P.a / 12.0,
        2.0 * P.b * P.b / 12.0,
        1.5 * P.c * P.c / 12.0,
    ];
    let (be, ga) = close(th);
    let o = [P.ox, P.oy];
    let a = along(o, P.a, u(th));
    let d = along(o, P.d, u(P.g0));
    let c = along(a, P.b, u(be));
    let g1 = along(o, P.a / 2.0, u(th));
    let g2 = along(a, P.b / 2.0, u(be));
    let g3 = along(d, P.c / 2.0, u(ga));
    // The hook: [b/2, 0.3] in the coupler's frame.
    let n = u(be + PI / 2.0);
    let hook = along(g2, 0.3, n);
    let to_anchor = sub([1.0, 3.0], hook);
    let len = to_anchor[0].hypot(to_anchor[1]);
    let fs = [
        P.k * (len - 0.5) * to_anchor[0] / len,
        P.k * (len - 0.5) * to_anchor[1] / len,
    ];
    let w: [[f64; 2]; 3] =
        std::array::from_fn(|b| [-MASS[b] * acc[b][0], -MASS[b] * (P.g + acc[b][1])]);
    let spin: [f64; 3] = std::array::from_fn(|b| -inertia[b] * acc[b][2]);
    // Unknowns z = [FOx, FOy, FAx, FAy, FCx, FCy, FDx, FDy, tau]; rows: M z = rhs.
    let mut m = Matrix::<9, 9>::zeros();
    let mut rhs = Vector::<9>::zeros();
    // Crank: F_O - F_A + W1 = 0; about O: (A - O) x (-F_A) + (G1 - O) x W1 + tau = 0.
    let (ra, rg1) = (sub(a, o), sub(g1, o));
    m[(0, 0)] = 1.0;
    m[(0, 2)] = -1.0;
    rhs[0] = -w[0][0];
    m[(1, 1)] = 1.0;
    m[(1, 3)] = -1.0;
    rhs[1] = -w[0][1];
    m[(2, 2)] = ra[1];
    m[(2, 3)] = -ra[0];
    m[(2, 8)] = 1.0;
    rhs[2] = -cross(rg1, w[0]) - spin[0];
    // Coupler: F_A + F_C + W2 + F_s = 0; about A: (C - A) x F_C + (G2 - A) x W2 + (H - A) x F_s = 0.
    let (rc, rg2, rh) = (sub(c, a), sub(g2, a), sub(hook, a));
    m[(3, 2)] = 1.0;
    m[(3, 4)] = 1.0;
    rhs[3] = -w[1][0] - fs[0];
    m[(4, 3)] = 1.0;
    m[(4, 5)] = 1.0;
    rhs[4] = -w[1][1] - fs[1];
    m[(5, 4)] = -rc[1];
    m[(5, 5)] = rc[0];
    rhs[5] = -cross(rg2, w[1]) - cross(rh, fs) - spin[1];
    // Rocker: F_D - F_C + W3 = 0; about D: (C - D) x (-F_C) + (G3 - D) x W3 = 0.
    let (rcd, rg3) = (sub(c, d), sub(g3, d));
    m[(6, 6)] = 1.0;
    m[(6, 4)] = -1.0;
    rhs[6] = -w[2][0];
    m[(7, 7)] = 1.0;
    m[(7, 5)] = -1.0;
    rhs[7] = -w[2][1];
    m[(8, 4)] = rcd[1];
    m[(8, 5)] = -rcd[0];
    rhs[8] = -cross(rg3, w[2]) - spin[2];
    m.lu().solve(&rhs).expect("a regular configuration")
}

/// The model's state at rest at `th`.
fn state_at_rest(th: f64) -> Vector<4> {
    let (be, ga) = close(th);
    Vector::<4>::new(be - th, ga, 0.0, 0.0)
}

#[test]
fn the_relaxed_pivot_leaves_the_state_and_the_hand_closure_closes_the_model() {
    assert_eq!(Held::COORDINATES, ["ph", "ga"]);
    assert_eq!(Held::GENERATED.constraints, 2);
    for th0 in [1.3, 0.2, 2.5, -1.0, 4.0] {
        let p = Held { th0, ..P };
        let y = state_at_rest(th0);
        let phi = Constrained::<2, 2>::phi(&p, 0.0, &y.fixed_rows::<2>(0).into_owned());
        assert!(phi.amax() < 1e-14, "{phi}");
    }
}

#[test]
fn holding_torque_and_pivot_force_match_hand_statics() {
    for th0 in [1.3, 0.2, 2.5, -1.0, 4.0] {
        let p = Held { th0, ..P };
        let z = statics(th0);
        let y = state_at_rest(th0);
        let out = p.outputs(0.0, &y).unwrap();
        println!(
            "th {th0}: holding {} vs {}, pivot ({}, {}) vs ({}, {})",
            out.holding, z[8], out.fx, out.fy, z[6], z[7]
        );
        let scale = z.amax();
        assert!(
            (out.holding - z[8]).abs() < 1e-10 * scale,
            "th {th0}: {} vs {}",
            out.holding,
            z[8]
        );
        assert!((out.fx - z[6]).abs() < 1e-10 * scale && (out.fy - z[7]).abs() < 1e-10 * scale);
        // At rest and held, nothing accelerates.
        let (q, qd) = (
            y.fixed_rows::<2>(0).into_owned(),
            y.fixed_rows::<2>(2).into_owned(),
        );
        let acc = p.acceleration(0.0, &q, &qd).unwrap();
        assert!(acc.amax() < 1e-9, "th {th0}: {acc}");
    }
}

/// The crank turned at a constant rate through two turns (the transmission angle through its
/// extremes, the crank along the tilted ground line at `th = g0`, `g0 + pi`): the drive's
/// torque and the rocker pivot's force are Newton–Euler's with d'Alembert's inertial loads.
#[test]
fn motor_torque_and_pivot_force_of_the_turning_crank_match_newton_euler() {
    let w = 2.5;
    let p = Turning {
        a: P.a,
        b: P.b,
        c: P.c,
        d: P.d,
        g0: P.g0,
        ox: P.ox,
        oy: P.oy,
        th0: P.g0,
        k: P.k,
        g: P.g,
        w,
    };
    for k in 0..=16 {
        let th = P.g0 + k as f64 * PI / 8.0;
        let t = (th - P.g0) / w;
        let (be, ga) = close(th);
        // Rates: first derivatives in th, times w.
        let h = 1e-5;
        let (bp, gp) = close(th + h);
        let (bm, gm) = close(th - h);
        let wrap = |x: f64| x - 2.0 * PI * (x / (2.0 * PI)).round();
        let (bed, gad) = (wrap(bp - bm) / (2.0 * h) * w, wrap(gp - gm) / (2.0 * h) * w);
        let y = Vector::<4>::new(wrap(be - th), ga, bed - w, gad);
        let out = p.outputs(t, &y).unwrap();
        let z = newton_euler(th, w);
        let scale = z.amax();
        assert!(
            (out.holding - z[8]).abs() < 1e-6 * scale,
            "th {th}: motor {} vs {}",
            out.holding,
            z[8]
        );
        assert!(
            (out.fx - z[6]).abs() < 1e-6 * scale && (out.fy - z[7]).abs() < 1e-6 * scale,
            "th {th}: pivot ({}, {}) vs ({}, {})",
            out.fx,
            out.fy,
            z[6],
            z[7]
        );
    }
}
