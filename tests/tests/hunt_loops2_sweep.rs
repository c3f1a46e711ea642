//! Hunt: kinematic analysis of a crank-rocker driven at a constant rate, with its ground
//! pivots offset from the origin and its ground line tilted (`O = (ox, oy)`, `D = O + d (cos
//! g0, sin g0)`), swept through full turns and through its transmission-angle extremes (the
//! crank along the ground line, `th = g0` and `g0 + pi`), at coarse and fine sampling.
//!
//! Reference, by hand: the rocker tip is the two-circle intersection of the circle `b`
//! about the crank tip `A = O + a (cos th, sin th)` and the circle `c` about `D`, on the
//! init's side of `AD`; rates and accelerations by five-point differences of that closure in
//! time (the crank turns at `w`).

#![allow(
    clippy::needless_range_loop,
    reason = "the references index bodies and components of parallel arrays"
)]

use mbd::analysis::{NewtonOptions, kinematic_sweep};
use mbd::prelude::*;
use std::f64::consts::PI;

/// Crank `a` (absolute angle `th`, driven), coupler `b` (`be`), rocker `c` (`ga`), ground
/// `d` at `g0`, all absolute angles.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(augmented)]
#[drive(th = th0 + w * t)]
#[coords(be, ga)]
#[constraint(a * cos(th) + b * cos(be) == d * cos(g0) + c * cos(ga))]
#[constraint(a * sin(th) + b * sin(be) == d * sin(g0) + c * sin(ga))]
#[rigid(crank, mass = 1.0, inertia = 0.1, at = [ox + a / 2.0 * cos(th), oy + a / 2.0 * sin(th)],
        angle = th)]
#[rigid(coupler, mass = 2.0, inertia = 1.5,
        at = [ox + a * cos(th) + b / 2.0 * cos(be), oy + a * sin(th) + b / 2.0 * sin(be)],
        angle = be)]
#[rigid(rocker, mass = 1.5, inertia = 0.8,
        at = [ox + d * cos(g0) + c / 2.0 * cos(ga), oy + d * sin(g0) + c / 2.0 * sin(ga)],
        angle = ga)]
pub struct Tilted {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub g0: f64,
    pub ox: f64,
    pub oy: f64,
    pub th0: f64,
    pub w: f64,
}

/// Grashof crank-rocker: `s + l = 1 + 3.2 <= p + q = 3 + 2.5`.
const P: Tilted = Tilted {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 3.2,
    g0: 0.6,
    ox: -0.7,
    oy: 1.3,
    th0: 0.6,
    w: 2.0,
};

/// `(be, ga)` at crank angle `th` on side `sign` of `AD` (`+1`: `C` to the left of `A -> D`).
fn close(th: f64, sign: f64) -> [f64; 2] {
    let (ax, ay) = (P.a * th.cos(), P.a * th.sin());
    let (dx, dy) = (P.d * P.g0.cos(), P.d * P.g0.sin());
    let (ux, uy) = (dx - ax, dy - ay);
    let l = ux.hypot(uy);
    let alpha = ((P.b * P.b + l * l - P.c * P.c) / (2.0 * P.b * l)).acos();
    let be = uy.atan2(ux) + sign * alpha;
    let (cx, cy) = (ax + P.b * be.cos(), ay + P.b * be.sin());
    [be, (cy - dy).atan2(cx - dx)]
}

/// Angle difference wrapped to `(-pi, pi]`.
fn wrap(x: f64) -> f64 {
    x - 2.0 * PI * (x / (2.0 * PI)).round()
}

/// `(q, qd, qdd)` of the hand closure at time `t` on side `sign`.
fn reference(t: f64, sign: f64) -> [[f64; 2]; 3] {
    let at = |t: f64| close(P.th0 + P.w * t, sign);
    let h = 1e-3;
    let (m2, m1, q, p1, p2) = (
        at(t - 2.0 * h),
        at(t - h),
        at(t),
        at(t + h),
        at(t + 2.0 * h),
    );
    let mut out = [q, [0.0; 2], [0.0; 2]];
    for i in 0..2 {
        // Differences of the unwrapped neighbours of q[i].
        let u = |x: [f64; 2]| q[i] + wrap(x[i] - q[i]);
        let (a, b, c, d) = (u(m2), u(m1), u(p1), u(p2));
        out[1][i] = (a - 8.0 * b + 8.0 * c - d) / (12.0 * h);
        out[2][i] = (-a + 16.0 * b - 30.0 * q[i] + 16.0 * c - d) / (12.0 * h * h);
    }
    out
}

/// Which side of `AD` the configuration `[be, ga]` at `t` is on (`+1` left).
fn side(t: f64, q: &Vector<2>) -> f64 {
    let th = P.th0 + P.w * t;
    let (ax, ay) = (P.a * th.cos(), P.a * th.sin());
    let (dx, dy) = (P.d * P.g0.cos(), P.d * P.g0.sin());
    let (cx, cy) = (ax + P.b * q[0].cos(), ay + P.b * q[0].sin());
    ((dx - ax) * (cy - ay) - (dy - ay) * (cx - ax)).signum()
}

#[test]
fn the_hand_closure_closes_both_elbows() {
    for sign in [1.0, -1.0] {
        for k in 0..12 {
            let th = k as f64 * PI / 6.0;
            let [be, ga] = close(th, sign);
            let q = Vector::<2>::new(be, ga);
            let phi = Constrained::<2, 2>::phi(&P, (th - P.th0) / P.w, &q);
            assert!(phi.norm() < 1e-14, "{phi}");
        }
    }
}

/// Two turns sampled `n` times per turn, from a rough guess near each elbow, including the
/// transmission-angle extremes (the crank along the ground line): every sample on the
/// guess's elbow, positions, rates and accelerations as the hand closure.
#[test]
fn sweeps_stay_on_the_elbow_they_start_on_at_every_sampling() {
    let turn = 2.0 * PI / P.w;
    for sign in [1.0, -1.0] {
        let exact = close(P.th0, sign);
        // A rough guess: 0.2 rad off each angle.
        let guess = Vector::<2>::new(exact[0] + 0.2, exact[1] - 0.2);
        for n in [3usize, 4, 5, 6, 8, 12, 36, 360] {
            // The samples: n per turn over two turns, plus the crank along the ground line
            // (th = g0 + pi; th0 = g0 so t = 0 is the other extreme).
            let mut times: Vec<f64> = (0..=2 * n).map(|k| k as f64 * turn / n as f64).collect();
            times.push(2.0 * turn + 0.5 * turn);
            let run = kinematic_sweep(&P, &times, &guess, &NewtonOptions::default())
                .unwrap_or_else(|e| panic!("side {sign}, {n} per turn: {e}"));
            for s in &run {
                assert_eq!(
                    side(s.t, &s.q),
                    sign,
                    "{n} per turn: switched elbow at t = {}",
                    s.t
                );
                let [q, qd, qdd] = reference(s.t, sign);
                for i in 0..2 {
                    assert!(
                        wrap(s.q[i] - q[i]).abs() < 1e-10,
                        "{n}: t {} q {} vs {q:?}",
                        s.t,
                        s.q
                    );
                    assert!(
                        (s.qd[i] - qd[i]).abs() < 1e-8,
                        "{n}: t {} qd {} vs {qd:?}",
                        s.t,
                        s.qd
                    );
                    assert!(
                        (s.qdd[i] - qdd[i]).abs() < 1e-5,
                        "{n}: t {} qdd {} vs {qdd:?}",
                        s.t,
                        s.qdd
                    );
                }
            }
        }
    }
}

/// Assembly from a rough guess (each dependent angle up to 0.4 rad off, the crank held):
/// the elbow the guess is nearer to, at every crank angle of a turn, including the
/// transmission-angle extremes.
#[test]
fn assembly_from_a_rough_guess_keeps_the_guesss_elbow() {
    use mbd::analysis::assemble;
    let held = Tilted {
        th0: 0.0,
        w: 1.0,
        ..P
    };
    let mut worst: f64 = 0.0;
    for k in 0..48 {
        let th = k as f64 * PI / 24.0;
        for sign in [1.0, -1.0] {
            let exact = close(th, sign);
            let other = close(th, -sign);
            for (db, dg) in [
                (0.4, 0.4),
                (0.4, -0.4),
                (-0.4, 0.4),
                (-0.4, -0.4),
                (0.2, -0.3),
            ] {
                let guess = Vector::<2>::new(exact[0] + db, exact[1] + dg);
                // Only guesses nearer to this elbow than to the other.
                let dist = |e: [f64; 2]| wrap(guess[0] - e[0]).hypot(wrap(guess[1] - e[1]));
                if dist(exact) >= 0.5 * dist(other) {
                    continue;
                }
                let q = assemble(
                    &held,
                    th,
                    &guess,
                    &[false, false],
                    &NewtonOptions::default(),
                )
                .unwrap_or_else(|e| panic!("th {th} side {sign}: {e}"));
                let err = wrap(q[0] - exact[0]).abs().max(wrap(q[1] - exact[1]).abs());
                worst = worst.max(err);
                assert!(
                    err < 1e-10,
                    "th {th} side {sign} guess {guess}: {q} vs {exact:?}"
                );
            }
        }
    }
    println!("worst {worst:e}");
}
