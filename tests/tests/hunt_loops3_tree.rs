//! Hunt: a crank-rocker written as a planar joint tree with relative angles and closed by a
//! pin (`a = 1`, `b = 2.5`, `c = 2`, `d = 3`, the crank the shortest bar): crank `th` about
//! the origin, coupler `ph` relative to the crank at its tip, rocker `ps` about `(d, 0)`,
//! the coupler's far end pinned to the rocker's tip. Free under gravity, the crank turning
//! over, on every method. A tree closed by `close` names relative angles, which the closed
//! forms do not match, so the default form is the augmented one (`GENERATED` says so).
//!
//! Reference, by hand: the closure (the two-circle intersection, the rocker tip left of
//! `A -> D`), giving the coupler's absolute angle `be` and the rocker's `ps`, so `ph = be - th`;
//! the rates by Cramer's rule on the loop's rate equations (`be' = kb th'`, `ps' = kg th'`);
//! the energy `T + V` summed over the three bars from their mass centres
//! (`a/2 u(th)`, `A + b/2 u(be)`, `D + c/2 u(ps)`) and angular rates.

use mbd::integrate::{
    Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;
use std::f64::consts::TAU;

macro_rules! tree {
    ($name:ident, $($opt:ident),*) => {
        /// The crank-rocker as a joint tree closed by a pin.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[gravity(0.0, -g)]
        #[body(crank, joint = revolute(th), com = [a / 2.0, 0.0], mass = m1,
               inertia = m1 * a * a / 12.0)]
        #[body(coupler, parent = crank, joint = revolute(ph), at = [a, 0.0],
               com = [b / 2.0, 0.0], mass = m2, inertia = m2 * b * b / 12.0)]
        #[body(rocker, joint = revolute(ps), at = [d, 0.0], com = [c / 2.0, 0.0], mass = m3,
               inertia = m3 * c * c / 12.0)]
        #[close(pin, a = coupler, at_a = [b, 0.0], b = rocker, at_b = [c, 0.0])]
        #[init(th = 1.0, ph = -0.524_510_591_193_001, ps = 1.68958837974869, der(th) = 7.0)]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(2.5)] pub b: f64,
            #[default(2.0)] pub c: f64,
            #[default(3.0)] pub d: f64,
            #[default(1.0)] pub m1: f64,
            #[default(2.0)] pub m2: f64,
            #[default(1.5)] pub m3: f64,
            #[default(9.81)] pub g: f64,
        }
    };
}
tree!(Tree, jacobian);

const A: f64 = 1.0;
const B: f64 = 2.5;
const C: f64 = 2.0;
const D: f64 = 3.0;
const M: [f64; 3] = [1.0, 2.0, 1.5];
const G: f64 = 9.81;

fn model() -> Tree {
    Tree {
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

/// `(be, ps)`: the coupler's absolute angle and the rocker's, at crank angle `th`.
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

/// `(kb, kg)`: `be' = kb th'`, `ps' = kg th'`.
fn ratios(th: f64) -> (f64, f64) {
    let (be, ga) = close(th);
    let (m11, m12, m21, m22) = (-B * be.sin(), C * ga.sin(), B * be.cos(), -C * ga.cos());
    let (r1, r2) = (A * th.sin(), -A * th.cos());
    let det = m11 * m22 - m12 * m21;
    ((r1 * m22 - m12 * r2) / det, (m11 * r2 - m21 * r1) / det)
}

fn wrap(x: f64) -> f64 {
    (x + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI
}

/// `T + V` from the crank angle and rate, and from the tree's own three angles and rates.
fn energy(q: [f64; 3], qd: [f64; 3]) -> f64 {
    let [th, ph, ps] = q;
    let (be, bed) = (th + ph, qd[0] + qd[1]);
    let u = |x: f64| [x.cos(), x.sin()];
    let du = |x: f64, w: f64| [-x.sin() * w, x.cos() * w];
    let p = [
        [A / 2.0 * u(th)[0], A / 2.0 * u(th)[1]],
        [
            A * u(th)[0] + B / 2.0 * u(be)[0],
            A * u(th)[1] + B / 2.0 * u(be)[1],
        ],
        [D + C / 2.0 * u(ps)[0], C / 2.0 * u(ps)[1]],
    ];
    let v = [
        [A / 2.0 * du(th, qd[0])[0], A / 2.0 * du(th, qd[0])[1]],
        [
            A * du(th, qd[0])[0] + B / 2.0 * du(be, bed)[0],
            A * du(th, qd[0])[1] + B / 2.0 * du(be, bed)[1],
        ],
        [C / 2.0 * du(ps, qd[2])[0], C / 2.0 * du(ps, qd[2])[1]],
    ];
    let w = [qd[0], bed, qd[2]];
    let len = [A, B, C];
    (0..3)
        .map(|k| {
            M[k] * (v[k][0].powi(2) + v[k][1].powi(2)) / 2.0
                + M[k] * len[k] * len[k] / 12.0 * w[k] * w[k] / 2.0
                + M[k] * G * p[k][1]
        })
        .sum()
}

fn full(th: f64, thd: f64) -> ([f64; 3], [f64; 3]) {
    let (be, ps) = close(th);
    let (kb, kg) = ratios(th);
    ([th, be - th, ps], [thd, (kb - 1.0) * thd, kg * thd])
}

#[test]
fn the_init_is_on_the_hand_closure_and_the_form_is_named() {
    let (q, _) = full(1.0, 0.0);
    assert!(
        (q[1] - -0.524_510_591_193_001).abs() < 1e-14 && (q[2] - 1.68958837974869).abs() < 1e-14
    );
    assert!(Tree::GENERATED.parts.contains(&"augmented"));
    assert!(!Tree::GENERATED.parts.contains(&"minimal_closed_form"));
    assert_eq!(Tree::COORDINATES, ["th", "ph", "ps"]);
    // `init` gives the crank's rate alone: the others follow from the velocity constraints
    let y = model().initial_state();
    let (q, qd) = full(1.0, 7.0);
    let want = Vector::<6>::from([q[0], q[1], q[2], qd[0], qd[1], qd[2]]);
    assert!((y - want).amax() < 1e-12, "{y} vs {want}");
}

fn opts(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    }
}

/// Several crank turns on every method: the energy by hand is conserved and
/// the rocker stays on the init's elbow (the hand closure's).
#[test]
fn crank_turns_on_every_method() {
    let pa = model();
    let ya0 = pa.initial_state();
    let e0 = {
        let (q, qd) = full(1.0, 7.0);
        energy(q, qd)
    };
    let t_end = 4.0;
    type Track = Vec<([f64; 3], [f64; 3])>;
    let aug = |r: mbd::Result<Solution<6>>| -> mbd::Result<Track> {
        r.map(|s| {
            s.y.iter()
                .map(|y| ([y[0], y[1], y[2]], [y[3], y[4], y[5]]))
                .collect()
        })
    };
    let alpha = GeneralizedAlpha::new(1.0, 2.5e-4);
    let runs: Vec<(&str, mbd::Result<Track>, f64)> = vec![
        (
            "dopri5 aug",
            aug(Dopri5::new(opts(1e-10)).solve(&pa, 0.0, ya0, t_end, &[])),
            1e-8,
        ),
        (
            "dop853 aug",
            aug(Dop853::new(opts(1e-10)).solve(&pa, 0.0, ya0, t_end, &[])),
            1e-8,
        ),
        (
            "vern9 aug",
            aug(Vern9::new(opts(1e-10)).solve(&pa, 0.0, ya0, t_end, &[])),
            1e-8,
        ),
        (
            "radau5 aug",
            aug(Radau5::new(opts(1e-8)).solve(&pa, 0.0, ya0, t_end, &[])),
            1e-5,
        ),
        (
            "rk4 aug",
            aug(Rk4::new(1e-3).solve(&pa, 0.0, ya0, t_end, &[])),
            1e-6,
        ),
        (
            "gauss aug",
            aug(Gauss::new(2e-3).solve(&pa, 0.0, ya0, t_end, &[])),
            1e-6,
        ),
        (
            "alpha aug",
            aug(Integrator::solve(&alpha, &pa, 0.0, ya0, t_end, &[])),
            1e-4,
        ),
    ];
    for (name, run, tol) in runs {
        let track = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let last = track.last().unwrap().0[0];
        assert!(last > 1.0 + 2.0 * TAU, "{name}: th = {last}");
        let (mut de, mut elbow) = (0.0f64, 0.0f64);
        for (q, qd) in &track {
            de = de.max((energy(*q, *qd) - e0).abs() / e0.abs());
            let (be, ps) = close(q[0]);
            elbow = elbow
                .max(wrap(q[0] + q[1] - be).abs())
                .max(wrap(q[2] - ps).abs());
        }
        println!(
            "{name}: {} states, energy {de:.2e}, elbow {elbow:.2e}",
            track.len()
        );
        assert!(
            de < tol && elbow < tol.max(1e-9),
            "{name}: {de:.2e} {elbow:.2e}"
        );
    }
}
