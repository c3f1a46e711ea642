//! Hunt: a planar five-bar with two cranks (two degrees of freedom), free under gravity, in
//! minimal coordinates (the cranks' angles) and augmented; and with its first crank driven in
//! time (one degree of freedom left), with the drive's effort.
//!
//! Cranks `a1` about `O1 = (0, 0)` (angle `t1`) and `a2` about `O2 = (d, 0)` (`t2`); distal
//! links `b1` (`p1`) from the first crank's tip `A1` and `b2` (`p2`) from `A2`, pinned
//! together at `P`, which carries a point mass. All angles absolute.
//!
//! Reference, derived here: the closure by hand (`P` the intersection of the circles `b1`
//! about `A1` and `b2` about `A2`, on the init's side of `A1 A2`), the bodies' mass centres
//! and angles as functions of `(t1, t2)`, and Lagrange's equations `M q'' + c = Q` with
//! `M = sum m J^T J + I j^T j` (`J = dp/dq`, `j = dphi/dq`, five-point differences),
//! `c = sum m J^T (q'^T p_qq q') + I j^T (q'^T phi_qq q')` (five-point second differences
//! along `q'`) and `Q = -g sum m J_y`. Energy `T + V` from the same functions.

#![allow(
    clippy::needless_range_loop,
    reason = "the references index bodies and components of parallel arrays"
)]

use mbd::integrate::{Dop853, Dopri5, Integrator, Radau5, Vern9};
use mbd::prelude::*;
use std::f64::consts::PI;

macro_rules! five_bar {
    ($name:ident, [$($opt:ident),*]) => {
        /// The free five-bar.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism(planar $(, $opt)*)]
        #[gravity(0.0, -g)]
        #[coords(t1, t2, p1, p2)]
        #[constraint(a1 * cos(t1) + b1 * cos(p1) == d + a2 * cos(t2) + b2 * cos(p2))]
        #[constraint(a1 * sin(t1) + b1 * sin(p1) == a2 * sin(t2) + b2 * sin(p2))]
        #[rigid(crank1, mass = m1, inertia = m1 * a1 * a1 / 12.0,
                at = [a1 / 2.0 * cos(t1), a1 / 2.0 * sin(t1)], angle = t1)]
        #[rigid(crank2, mass = m2, inertia = m2 * a2 * a2 / 12.0,
                at = [d + a2 / 2.0 * cos(t2), a2 / 2.0 * sin(t2)], angle = t2)]
        #[rigid(link1, mass = n1, inertia = n1 * b1 * b1 / 12.0,
                at = [a1 * cos(t1) + b1 / 2.0 * cos(p1), a1 * sin(t1) + b1 / 2.0 * sin(p1)],
                angle = p1)]
        #[rigid(link2, mass = n2, inertia = n2 * b2 * b2 / 12.0,
                at = [d + a2 * cos(t2) + b2 / 2.0 * cos(p2), a2 * sin(t2) + b2 / 2.0 * sin(p2)],
                angle = p2)]
        #[particle(tool, mass = mp, at = [a1 * cos(t1) + b1 * cos(p1), a1 * sin(t1) + b1 * sin(p1)])]
        #[init(t1 = 2.0, t2 = 1.0, p1 = 0.8778614437645025, p2 = 2.1944226987526934,
               der(t1) = -0.5, der(t2) = 0.8)]
        pub struct $name {
            #[default(1.0)] pub d: f64,
            #[default(1.0)] pub a1: f64,
            #[default(1.0)] pub a2: f64,
            #[default(1.6)] pub b1: f64,
            #[default(1.6)] pub b2: f64,
            #[default(1.0)] pub m1: f64,
            #[default(1.2)] pub m2: f64,
            #[default(0.8)] pub n1: f64,
            #[default(0.9)] pub n2: f64,
            #[default(0.5)] pub mp: f64,
            #[default(9.81)] pub g: f64,
        }
    };
}
five_bar!(FiveBar, []);
five_bar!(FiveBarAugmented, [augmented]);

/// The first crank driven at `w` from `t1 = 2`; the second crank free.
#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[drive(t1 = 2.0 + w * t)]
#[coords(t2, p1, p2)]
#[constraint(a1 * cos(t1) + b1 * cos(p1) == d + a2 * cos(t2) + b2 * cos(p2))]
#[constraint(a1 * sin(t1) + b1 * sin(p1) == a2 * sin(t2) + b2 * sin(p2))]
#[rigid(crank1, mass = m1, inertia = m1 * a1 * a1 / 12.0,
        at = [a1 / 2.0 * cos(t1), a1 / 2.0 * sin(t1)], angle = t1)]
#[rigid(crank2, mass = m2, inertia = m2 * a2 * a2 / 12.0,
        at = [d + a2 / 2.0 * cos(t2), a2 / 2.0 * sin(t2)], angle = t2)]
#[rigid(link1, mass = n1, inertia = n1 * b1 * b1 / 12.0,
        at = [a1 * cos(t1) + b1 / 2.0 * cos(p1), a1 * sin(t1) + b1 / 2.0 * sin(p1)],
        angle = p1)]
#[rigid(link2, mass = n2, inertia = n2 * b2 * b2 / 12.0,
        at = [d + a2 * cos(t2) + b2 / 2.0 * cos(p2), a2 * sin(t2) + b2 / 2.0 * sin(p2)],
        angle = p2)]
#[particle(tool, mass = mp, at = [a1 * cos(t1) + b1 * cos(p1), a1 * sin(t1) + b1 * sin(p1)])]
#[init(t2 = 1.0, p1 = 0.8778614437645025, p2 = 2.1944226987526934)]
#[output(effort = reaction(t1))]
pub struct DrivenFiveBar {
    #[default(1.0)]
    pub d: f64,
    #[default(1.0)]
    pub a1: f64,
    #[default(1.0)]
    pub a2: f64,
    #[default(1.6)]
    pub b1: f64,
    #[default(1.6)]
    pub b2: f64,
    #[default(1.0)]
    pub m1: f64,
    #[default(1.2)]
    pub m2: f64,
    #[default(0.8)]
    pub n1: f64,
    #[default(0.9)]
    pub n2: f64,
    #[default(0.5)]
    pub mp: f64,
    #[default(9.81)]
    pub g: f64,
    #[default(1.5)]
    pub w: f64,
}

/// Both cranks driven (`t1 = 2 + w t`, `t2 = 1 + w2 t`): no degree of freedom is left.
#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[drive(t1 = 2.0 + w * t)]
#[drive(t2 = 1.0 + w2 * t)]
#[coords(p1, p2)]
#[constraint(a1 * cos(t1) + b1 * cos(p1) == d + a2 * cos(t2) + b2 * cos(p2))]
#[constraint(a1 * sin(t1) + b1 * sin(p1) == a2 * sin(t2) + b2 * sin(p2))]
#[rigid(crank1, mass = m1, inertia = m1 * a1 * a1 / 12.0,
        at = [a1 / 2.0 * cos(t1), a1 / 2.0 * sin(t1)], angle = t1)]
#[rigid(crank2, mass = m2, inertia = m2 * a2 * a2 / 12.0,
        at = [d + a2 / 2.0 * cos(t2), a2 / 2.0 * sin(t2)], angle = t2)]
#[rigid(link1, mass = n1, inertia = n1 * b1 * b1 / 12.0,
        at = [a1 * cos(t1) + b1 / 2.0 * cos(p1), a1 * sin(t1) + b1 / 2.0 * sin(p1)],
        angle = p1)]
#[rigid(link2, mass = n2, inertia = n2 * b2 * b2 / 12.0,
        at = [d + a2 * cos(t2) + b2 / 2.0 * cos(p2), a2 * sin(t2) + b2 / 2.0 * sin(p2)],
        angle = p2)]
#[particle(tool, mass = mp, at = [a1 * cos(t1) + b1 * cos(p1), a1 * sin(t1) + b1 * sin(p1)])]
#[init(p1 = 0.8778614437645025, p2 = 2.1944226987526934)]
#[output(effort1 = reaction(t1), effort2 = reaction(t2))]
pub struct BothDriven {
    #[default(1.0)]
    pub d: f64,
    #[default(1.0)]
    pub a1: f64,
    #[default(1.0)]
    pub a2: f64,
    #[default(1.6)]
    pub b1: f64,
    #[default(1.6)]
    pub b2: f64,
    #[default(1.0)]
    pub m1: f64,
    #[default(1.2)]
    pub m2: f64,
    #[default(0.8)]
    pub n1: f64,
    #[default(0.9)]
    pub n2: f64,
    #[default(0.5)]
    pub mp: f64,
    #[default(9.81)]
    pub g: f64,
    #[default(1.5)]
    pub w: f64,
    #[default(-0.7)]
    pub w2: f64,
}

const D: f64 = 1.0;
const A: [f64; 2] = [1.0, 1.0];
const B: [f64; 2] = [1.6, 1.6];
/// Masses and inertias of crank1, crank2, link1, link2, tool.
const MASS: [f64; 5] = [1.0, 1.2, 0.8, 0.9, 0.5];
const INERTIA: [f64; 5] = [
    1.0 / 12.0,
    1.2 / 12.0,
    0.8 * 2.56 / 12.0,
    0.9 * 2.56 / 12.0,
    0.0,
];
const G: f64 = 9.81;
const W: f64 = 1.5;

macro_rules! params {
    ($ty:ident $(, $f:ident: $v:expr)*) => {
        $ty { d: D, a1: A[0], a2: A[1], b1: B[0], b2: B[1], m1: MASS[0], m2: MASS[1],
              n1: MASS[2], n2: MASS[3], mp: MASS[4], g: G $(, $f: $v)* }
    };
}

/// `(p1, p2)` at `(t1, t2)`, `P` to the left of `A1 -> A2`; `None` where the circles miss.
fn close(t1: f64, t2: f64) -> Option<(f64, f64)> {
    let (a1x, a1y) = (A[0] * t1.cos(), A[0] * t1.sin());
    let (a2x, a2y) = (D + A[1] * t2.cos(), A[1] * t2.sin());
    let (ux, uy) = (a2x - a1x, a2y - a1y);
    let l = ux.hypot(uy);
    let cos_alpha = (B[0] * B[0] + l * l - B[1] * B[1]) / (2.0 * B[0] * l);
    if cos_alpha.abs() >= 1.0 {
        return None;
    }
    let p1 = uy.atan2(ux) + cos_alpha.acos();
    let (px, py) = (a1x + B[0] * p1.cos(), a1y + B[0] * p1.sin());
    Some((p1, (py - a2y).atan2(px - a2x)))
}

/// Each body's `(x, y, angle)` at `(t1, t2)`.
fn bodies(q: [f64; 2]) -> [[f64; 3]; 5] {
    let [t1, t2] = q;
    let (p1, p2) = close(t1, t2).expect("assembles");
    let a1 = [A[0] * t1.cos(), A[0] * t1.sin()];
    let a2 = [D + A[1] * t2.cos(), A[1] * t2.sin()];
    [
        [a1[0] / 2.0, a1[1] / 2.0, t1],
        [D + A[1] / 2.0 * t2.cos(), A[1] / 2.0 * t2.sin(), t2],
        [
            a1[0] + B[0] / 2.0 * p1.cos(),
            a1[1] + B[0] / 2.0 * p1.sin(),
            p1,
        ],
        [
            a2[0] + B[1] / 2.0 * p2.cos(),
            a2[1] + B[1] / 2.0 * p2.sin(),
            p2,
        ],
        [a1[0] + B[0] * p1.cos(), a1[1] + B[0] * p1.sin(), 0.0],
    ]
}

/// Five-point first and second derivatives of `bodies` along `dir` at `q` (`s` the step).
fn along(q: [f64; 2], dir: [f64; 2]) -> ([[f64; 3]; 5], [[f64; 3]; 5]) {
    let h = 1e-3;
    let at = |s: f64| bodies([q[0] + s * dir[0], q[1] + s * dir[1]]);
    let (m2, m1, c, p1, p2) = (at(-2.0 * h), at(-h), at(0.0), at(h), at(2.0 * h));
    let (mut d1, mut d2) = ([[0.0; 3]; 5], [[0.0; 3]; 5]);
    for b in 0..5 {
        for k in 0..3 {
            // Angles unwrapped about the centre value.
            let u = |x: f64| c[b][k] + (x - c[b][k] + PI).rem_euclid(2.0 * PI) - PI;
            let (a, e, f, g) = (u(m2[b][k]), u(m1[b][k]), u(p1[b][k]), u(p2[b][k]));
            d1[b][k] = (a - 8.0 * e + 8.0 * f - g) / (12.0 * h);
            d2[b][k] = (-a + 16.0 * e - 30.0 * c[b][k] + 16.0 * f - g) / (12.0 * h * h);
        }
    }
    (d1, d2)
}

/// `(M, c, Q)` of Lagrange's equations at `(q, q')`.
fn lagrange(q: [f64; 2], qd: [f64; 2]) -> ([[f64; 2]; 2], [f64; 2], [f64; 2]) {
    let jac = [along(q, [1.0, 0.0]).0, along(q, [0.0, 1.0]).0];
    let conv = along(q, qd).1;
    let (mut m, mut c, mut f) = ([[0.0; 2]; 2], [0.0; 2], [0.0; 2]);
    for b in 0..5 {
        let dot = |u: [f64; 3], v: [f64; 3]| {
            MASS[b] * (u[0] * v[0] + u[1] * v[1]) + INERTIA[b] * u[2] * v[2]
        };
        for i in 0..2 {
            for j in 0..2 {
                m[i][j] += dot(jac[i][b], jac[j][b]);
            }
            c[i] += dot(jac[i][b], conv[b]);
            f[i] -= G * MASS[b] * jac[i][b][1];
        }
    }
    (m, c, f)
}

/// `q''` of the free five-bar by Lagrange's equations.
fn free_acceleration(q: [f64; 2], qd: [f64; 2]) -> [f64; 2] {
    let (m, c, f) = lagrange(q, qd);
    let r = [f[0] - c[0], f[1] - c[1]];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    [
        (r[0] * m[1][1] - m[0][1] * r[1]) / det,
        (m[0][0] * r[1] - m[1][0] * r[0]) / det,
    ]
}

/// `T + V` at `(q, q')`.
fn energy(q: [f64; 2], qd: [f64; 2]) -> f64 {
    let (m, _, _) = lagrange(q, qd);
    let t =
        0.5 * (m[0][0] * qd[0] * qd[0] + 2.0 * m[0][1] * qd[0] * qd[1] + m[1][1] * qd[1] * qd[1]);
    t + G * bodies(q)
        .iter()
        .zip(MASS)
        .map(|(b, m)| m * b[1])
        .sum::<f64>()
}

/// The full augmented state at `(q, q')`: the dependent angles and rates from the closure.
fn augmented_state(q: [f64; 2], qd: [f64; 2]) -> (Vector<4>, Vector<4>) {
    let (p1, p2) = close(q[0], q[1]).unwrap();
    let d = along(q, qd).0;
    (
        Vector::<4>::new(q[0], q[1], p1, p2),
        Vector::<4>::new(qd[0], qd[1], d[2][2], d[3][2]),
    )
}

const STATES: [([f64; 2], [f64; 2]); 4] = [
    ([2.0, 1.0], [1.5, -2.0]),
    ([1.6, 0.4], [-0.7, 0.3]),
    ([2.6, 1.4], [0.0, 0.0]),
    ([1.2, 1.8], [2.0, 2.5]),
];

#[test]
fn the_state_is_both_crank_angles_and_the_init_is_on_the_hand_closure() {
    assert_eq!(FiveBar::COORDINATES, ["t1", "t2"]);
    assert_eq!(FiveBarAugmented::GENERATED.constraints, 2);
    assert_eq!(DrivenFiveBar::COORDINATES, ["t2"]);
    assert!(FiveBar::GENERATED.parts.contains(&"minimal_closed_form"));
    assert!(!FiveBar::GENERATED.parts.contains(&"augmented"));
    assert!(FiveBarAugmented::GENERATED.parts.contains(&"augmented"));
    // Both cranks driven leaves no independent coordinate to keep: the loop stays augmented.
    assert_eq!(BothDriven::COORDINATES, ["p1", "p2"]);
    let (p1, p2) = close(2.0, 1.0).unwrap();
    assert!((p1 - 0.8778614437645025).abs() < 1e-14 && (p2 - 2.1944226987526934).abs() < 1e-14);
}

#[test]
fn accelerations_match_lagrange_in_both_forms() {
    let (p, pa) = (params!(FiveBar), params!(FiveBarAugmented));
    for (q, qd) in STATES {
        let want = free_acceleration(q, qd);
        let got = p
            .acceleration(0.0, &Vector::<2>::from(q), &Vector::<2>::from(qd))
            .unwrap();
        let (qa, qda) = augmented_state(q, qd);
        let aug = pa.acceleration(0.0, &qa, &qda).unwrap();
        for i in 0..2 {
            let tol = 1e-7 * want[i].abs().max(1.0);
            assert!(
                (got[i] - want[i]).abs() < tol,
                "minimal {q:?} {qd:?}: {got} vs {want:?}"
            );
            assert!(
                (aug[i] - want[i]).abs() < tol,
                "augmented {q:?} {qd:?}: {aug} vs {want:?}"
            );
        }
    }
}

/// Half a second of free motion (the tips stay apart: checked), on the
/// adaptive methods: the hand energy is conserved and the augmented form stays on the hand
/// closure and agrees with the minimal form.
#[test]
fn free_motion_conserves_the_hand_energy_in_both_forms() {
    let (p, pa) = (params!(FiveBar), params!(FiveBarAugmented));
    let e0 = energy([2.0, 1.0], [-0.5, 0.8]);
    let t1 = 0.5;
    let opts = |tol: f64| Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    };
    let runs: Vec<(&str, mbd::Result<Solution<4>>)> = vec![
        (
            "dopri5",
            Dopri5::new(opts(1e-11)).solve(&p, 0.0, p.initial_state(), t1, &[]),
        ),
        (
            "dop853",
            Dop853::new(opts(1e-11)).solve(&p, 0.0, p.initial_state(), t1, &[]),
        ),
        (
            "vern9",
            Vern9::new(opts(1e-11)).solve(&p, 0.0, p.initial_state(), t1, &[]),
        ),
        (
            "radau5",
            Radau5::new(opts(1e-10)).solve(&p, 0.0, p.initial_state(), t1, &[]),
        ),
    ];
    let mut ends = vec![];
    for (name, run) in runs {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        for y in &sol.y {
            let e = energy([y[0], y[1]], [y[2], y[3]]);
            assert!(
                (e - e0).abs() < 1e-6 * e0.abs().max(1.0),
                "{name}: {e} vs {e0} at {y:?}"
            );
        }
        ends.push(*sol.y.last().unwrap());
    }
    let ya = pa.initial_state();
    let (qa, qda) = augmented_state([2.0, 1.0], [-0.5, 0.8]);
    for i in 0..4 {
        assert!(
            (ya[i] - qa[i]).abs() < 1e-10 && (ya[4 + i] - qda[i]).abs() < 1e-8,
            "{ya}"
        );
    }
    let sol = Dopri5::new(opts(1e-11))
        .solve(&pa, 0.0, ya, t1, &[])
        .unwrap();
    let y = sol.y.last().unwrap();
    for end in &ends {
        assert!(
            (y[0] - end[0]).abs() < 1e-6 && (y[1] - end[1]).abs() < 1e-6,
            "{y} vs {end}"
        );
    }
    for y in &sol.y {
        assert!(tips_apart(y[0], y[1]) > 0.1, "{y}");
        let (p1, p2) = close(y[0], y[1]).expect("never stretched");
        let u = |x: f64| (x + PI).rem_euclid(2.0 * PI) - PI;
        assert!(
            u(y[2] - p1).abs() < 1e-8 && u(y[3] - p2).abs() < 1e-8,
            "{y}"
        );
    }
}

/// The first crank driven at `w`: `t2'' = (Q_2 - c_2 - M_21 0) / M_22` (the driven angle does
/// not accelerate), and the drive's effort is the first equation's balance,
/// `tau = M_12 t2'' + c_1 - Q_1`.
#[test]
fn driven_crank_accelerations_and_effort_match_lagrange() {
    let p = params!(DrivenFiveBar, w: W);
    for (q, qd) in STATES {
        let t = (q[0] - 2.0) / W;
        let qd = [W, qd[1]];
        let (m, c, f) = lagrange(q, qd);
        let t2dd = (f[1] - c[1]) / m[1][1];
        let effort = m[0][1] * t2dd + c[0] - f[0];
        let got = p
            .acceleration(t, &Vector::<1>::new(q[1]), &Vector::<1>::new(qd[1]))
            .unwrap()[0];
        assert!(
            (got - t2dd).abs() < 1e-7 * t2dd.abs().max(1.0),
            "{q:?}: {got} vs {t2dd}"
        );
        let out = p.outputs(t, &Vector::<2>::new(q[1], qd[1])).unwrap();
        assert!(
            (out.effort - effort).abs() < 1e-7 * effort.abs().max(1.0),
            "{q:?}: effort {} vs {effort}",
            out.effort
        );
    }
}

/// With shorter distal links set at run time (`b1 = b2 = 1.2`: the cranks can hold them
/// `3 > 2.4` apart), pulled apart (no gravity, the cranks opening), they reach a straight
/// line (`|A1 A2| = b1 + b2`): the edge of the `(t1, t2)` chart. The minimal form must stop there
/// with a typed error, not return a motion.
#[test]
fn minimal_form_stops_where_the_distal_links_straighten() {
    let p = FiveBar {
        g: 0.0,
        b1: 1.2,
        b2: 1.2,
        ..params!(FiveBar)
    };
    let mut y0 = p.initial_state();
    y0[2] = 3.0;
    y0[3] = -3.0;
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    match Dopri5::new(opts).solve(&p, 0.0, y0, 2.0, &[]) {
        Err(mbd::Error::SingularPosition { t, .. }) => {
            // Where the run stopped, the hand closure is at its edge.
            let sol = Dopri5::new(Options {
                rtol: 1e-10,
                atol: 1e-10,
                ..Options::default()
            })
            .solve(&p, 0.0, y0, 0.999 * t, &[])
            .unwrap();
            let y = sol.y.last().unwrap();
            let (a1x, a1y) = (A[0] * y[0].cos(), A[0] * y[0].sin());
            let (a2x, a2y) = (D + A[1] * y[1].cos(), A[1] * y[1].sin());
            let l = (a2x - a1x).hypot(a2y - a1y);
            assert!(2.4 - l < 1e-2, "stopped at t = {t} with |A1 A2| = {l}");
        }
        Ok(sol) => panic!("Ok, ends at {}", sol.y.last().unwrap()),
        Err(e) => panic!("{e}"),
    }
}

/// `T + V` from the augmented state `[t1, t2, p1, p2, rates]`, by hand (no closure used).
fn energy_full(y: &Vector<8>) -> f64 {
    let e = |a: f64| [-a.sin(), a.cos()];
    let (r1, r2, s1, s2) = (e(y[0]), e(y[1]), e(y[2]), e(y[3]));
    let v = |terms: &[(f64, [f64; 2])]| {
        let (x, z) = terms
            .iter()
            .fold((0.0, 0.0), |(x, z), (k, u)| (x + k * u[0], z + k * u[1]));
        x * x + z * z
    };
    let (w1, w2, u1, u2) = (y[4], y[5], y[6], y[7]);
    let speeds = [
        v(&[(A[0] / 2.0 * w1, r1)]),
        v(&[(A[1] / 2.0 * w2, r2)]),
        v(&[(A[0] * w1, r1), (B[0] / 2.0 * u1, s1)]),
        v(&[(A[1] * w2, r2), (B[1] / 2.0 * u2, s2)]),
        v(&[(A[0] * w1, r1), (B[0] * u1, s1)]),
    ];
    let spins = [w1, w2, u1, u2, 0.0];
    let heights = [
        A[0] / 2.0 * y[0].sin(),
        A[1] / 2.0 * y[1].sin(),
        A[0] * y[0].sin() + B[0] / 2.0 * y[2].sin(),
        A[1] * y[1].sin() + B[1] / 2.0 * y[3].sin(),
        A[0] * y[0].sin() + B[0] * y[2].sin(),
    ];
    (0..5)
        .map(|b| {
            0.5 * MASS[b] * speeds[b]
                + 0.5 * INERTIA[b] * spins[b] * spins[b]
                + G * MASS[b] * heights[b]
        })
        .sum()
}

/// `|A1 A2|` at `(t1, t2)`.
fn tips_apart(t1: f64, t2: f64) -> f64 {
    (D + A[1] * t2.cos() - A[0] * t1.cos()).hypot(A[1] * t2.sin() - A[0] * t1.sin())
}

/// From the init the cranks' tips swing together: at `t ~ 0.88` they meet (`A1 = A2`, with
/// `b1 = b2` the links then fold onto each other and `P` may turn about the common tip).
/// Minimal coordinates end there: the closed form's direction `A1 -> A2` is undefined, its
/// inertia grows without bound. The minimal form must stop with a typed
/// `SingularPosition`; the augmented form, regular there (the cranks' columns of `Phi_q`
/// keep its rank), passes it conserving the hand energy and keeping the loop closed.
///
/// Defect found: the minimal form stopped with `MassMatrixNotPositiveDefinite` ("a negative
/// mass or inertia?"), every mass valid; it is now `SingularPosition` (derive `diagnose`).
#[test]
fn crank_tips_meeting_stop_the_minimal_form_and_the_augmented_form_passes() {
    let (p, pa) = (params!(FiveBar), params!(FiveBarAugmented));
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    match Dopri5::new(opts.clone()).solve(&p, 0.0, p.initial_state(), 2.0, &[]) {
        Err(mbd::Error::SingularPosition { t, detail }) => {
            println!("minimal: t = {t}: {detail}");
            let sol = Dopri5::new(opts.clone())
                .solve(&p, 0.0, p.initial_state(), t - 1e-3, &[])
                .unwrap();
            let y = sol.y.last().unwrap();
            assert!(
                tips_apart(y[0], y[1]) < 0.02,
                "stopped at t = {t}, {y}, apart {}",
                tips_apart(y[0], y[1])
            );
        }
        Ok(sol) => panic!("minimal: Ok, ends at {}", sol.y.last().unwrap()),
        Err(e) => panic!("minimal: {e}"),
    }
    let y0 = pa.initial_state();
    let e0 = energy_full(&y0);
    assert!((e0 - energy([2.0, 1.0], [-0.5, 0.8])).abs() < 1e-8, "{e0}");
    let sol = Dopri5::new(opts).solve(&pa, 0.0, y0, 2.0, &[]).unwrap();
    let closest = sol
        .y
        .iter()
        .map(|y| tips_apart(y[0], y[1]))
        .fold(f64::MAX, f64::min);
    println!("augmented: the tips came within {closest}");
    assert!(closest < 0.02, "the tips came within {closest}");
    for y in &sol.y {
        assert!(
            (energy_full(y) - e0).abs() < 1e-6 * e0.abs(),
            "{y}: {} vs {e0}",
            energy_full(y)
        );
        let phi = Constrained::<4, 2>::phi(&pa, 0.0, &y.fixed_rows::<4>(0).into_owned());
        assert!(phi.norm() < 1e-8, "{phi}");
    }
}

/// Both cranks driven at constant rates: the efforts are Lagrange's equations' balances with
/// `q'' = 0`, `tau = c - Q`, at times along the driven motion.
#[test]
fn both_cranks_driven_efforts_match_lagrange() {
    let p = params!(BothDriven, w: W, w2: -0.7);
    for k in 0..6 {
        let t = 0.1 * k as f64;
        let q = [2.0 + W * t, 1.0 - 0.7 * t];
        let (qa, qda) = augmented_state(q, [W, -0.7]);
        let y = Vector::<4>::new(qa[2], qa[3], qda[2], qda[3]);
        let (_, c, f) = lagrange(q, [W, -0.7]);
        let out = p.outputs(t, &y).unwrap();
        for (got, want) in [(out.effort1, c[0] - f[0]), (out.effort2, c[1] - f[1])] {
            assert!(
                (got - want).abs() < 1e-7 * want.abs().max(1.0),
                "t {t}: {got} vs {want}"
            );
        }
    }
}
