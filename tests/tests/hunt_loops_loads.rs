//! Hunt: loads on a closed loop, in both forms: a crank-rocker with a spring from a ground
//! point to a point fixed on the coupler, a damper from a ground point to the rocker's mass
//! centre, and a follower force at the coupler's end (fixed in the coupler's axes), under
//! gravity.
//!
//! Reference, derived here: the closure by hand (two-circle intersection, elbow above the
//! ground line), every body's mass centre and angle and every load point as functions of the
//! crank angle `th`, five-point derivatives, and Lagrange's equation in `th`:
//! `J th'' + C th'^2 = Q`, `Q = -g sum m p'_y - k (s - s0) s' - c d'^2 th' + F . p_f'`
//! (`s` the spring's length, `d` the damper's, `p_f` the force's point, `'` = `d/dth`).

use mbd::Vector;
use mbd::prelude::*;

macro_rules! loaded {
    ($name:ident, $($opt:ident),*) => {
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[gravity(0.0, -g)]
        #[coords(th, be, ga)]
        #[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
        #[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
        #[rigid(crank, mass = m, inertia = m * a * a / 12.0,
                at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
        #[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
                at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
        #[rigid(rocker, mass = m, inertia = m * c * c / 12.0,
                at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
        #[point(hook, on = coupler, at = [0.5, 0.3])]
        #[point(wall, at = [1.0, 3.0])]
        #[point(floor, at = [4.0, -1.0])]
        #[spring(s, from = wall, to = hook, k = k, length = s0)]
        #[damper(dmp, from = floor, to = rocker, c = cd)]
        #[force(push, at = position(coupler, [b / 2.0, 0.0]), value = [-f * sin(be), f * cos(be)])]
        #[init(th = 0.5, be = 0.7260165921021776, ga = 1.7229599395818342)]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(3.0)] pub b: f64,
            #[default(2.5)] pub c: f64,
            #[default(3.5)] pub d: f64,
            #[default(1.0)] pub m: f64,
            #[default(9.81)] pub g: f64,
            #[default(20.0)] pub k: f64,
            #[default(1.0)] pub s0: f64,
            #[default(3.0)] pub cd: f64,
            #[default(5.0)] pub f: f64,
        }
    };
}
loaded!(Loaded, jacobian);
loaded!(LoadedAugmented, jacobian, augmented);

const L: [f64; 4] = [1.0, 3.0, 2.5, 3.5];
const G: f64 = 9.81;
const K: f64 = 20.0;
const S0: f64 = 1.0;
const CD: f64 = 3.0;
const F: f64 = 5.0;

/// A model of type `$ty` with the reference's parameters.
macro_rules! reference {
    ($ty:ident) => {
        $ty {
            a: L[0],
            b: L[1],
            c: L[2],
            d: L[3],
            m: 1.0,
            g: G,
            k: K,
            s0: S0,
            cd: CD,
            f: F,
        }
    };
}

/// `(be, ga)` at crank angle `th`, the elbow above the ground line.
fn close(th: f64) -> (f64, f64) {
    let [a, b, c, d] = L;
    let (ax, ay) = (a * th.cos(), a * th.sin());
    let (vx, vy) = (d - ax, -ay);
    let l = vx.hypot(vy);
    let alpha = ((b * b + l * l - c * c) / (2.0 * b * l)).acos();
    let be = vy.atan2(vx) + alpha;
    let (cx, cy) = (ax + b * be.cos(), ay + b * be.sin());
    (be, cy.atan2(cx - d))
}

/// Bodies `(x, y, angle)` x3, then the spring's length, the damper's length, the force
/// point `(x, y)` (the coupler's far end) and the coupler angle: 14 functions of `th`.
fn geometry(th: f64) -> [f64; 14] {
    let [a, b, c, d] = L;
    let (be, ga) = close(th);
    let (ax, ay) = (a * th.cos(), a * th.sin());
    let rot = |x: f64, y: f64| (x * be.cos() - y * be.sin(), x * be.sin() + y * be.cos());
    // A free rigid body's frame is at its mass centre (the offsets rule).
    let centre = (ax + b / 2.0 * be.cos(), ay + b / 2.0 * be.sin());
    let hook = rot(0.5, 0.3);
    let (hx, hy) = (centre.0 + hook.0, centre.1 + hook.1);
    let rocker = (d + c / 2.0 * ga.cos(), c / 2.0 * ga.sin());
    let tip = rot(b / 2.0, 0.0);
    [
        a / 2.0 * th.cos(),
        a / 2.0 * th.sin(),
        th,
        centre.0,
        centre.1,
        be,
        rocker.0,
        rocker.1,
        ga,
        (hx - 1.0).hypot(hy - 3.0),
        (rocker.0 - 4.0).hypot(rocker.1 + 1.0),
        centre.0 + tip.0,
        centre.1 + tip.1,
        be,
    ]
}

fn diff(th: f64) -> ([f64; 14], [f64; 14]) {
    let h = 1e-3;
    let s = [-2.0, -1.0, 1.0, 2.0].map(|k| geometry(th + k * h));
    let mid = geometry(th);
    let (mut d1, mut d2) = ([0.0; 14], [0.0; 14]);
    for j in 0..14 {
        let (m2, m1, p1, p2) = (s[0][j], s[1][j], s[2][j], s[3][j]);
        d1[j] = (m2 - 8.0 * m1 + 8.0 * p1 - p2) / (12.0 * h);
        d2[j] = (-m2 + 16.0 * m1 - 30.0 * mid[j] + 16.0 * p1 - p2) / (12.0 * h * h);
    }
    (d1, d2)
}

fn lagrange(th: f64, thd: f64) -> f64 {
    lagrange_with(th, thd, [K, CD, F])
}

fn lagrange_with(th: f64, thd: f64, [k, cd, f]: [f64; 3]) -> f64 {
    let (d1, d2) = diff(th);
    let g0 = geometry(th);
    let (mut j, mut c, mut q) = (0.0, 0.0, 0.0);
    for (b, len) in L[..3].iter().enumerate() {
        let (k, i) = (3 * b, len * len / 12.0);
        j += d1[k].powi(2) + d1[k + 1].powi(2) + i * d1[k + 2].powi(2);
        c += d1[k] * d2[k] + d1[k + 1] * d2[k + 1] + i * d1[k + 2] * d2[k + 2];
        q -= G * d1[k + 1];
    }
    q -= k * (g0[9] - S0) * d1[9];
    q -= cd * d1[10] * d1[10] * thd;
    let be = g0[13];
    q += f * (-be.sin() * d1[11] + be.cos() * d1[12]);
    (q - c * thd * thd) / j
}

#[test]
fn accelerations_under_spring_damper_and_follower_force_match_lagrange_in_both_forms() {
    let p = reference!(Loaded);
    let pa = reference!(LoadedAugmented);
    assert_eq!(Loaded::COORDINATES, ["th"]);
    for th in [0.5, 1.5, 2.5, 3.5, 5.0] {
        for thd in [0.0, 2.0, -4.0] {
            let want = lagrange(th, thd);
            let tol = 1e-7 * (1.0 + want.abs());
            let got = p.rhs(0.0, &Vector::<2>::new(th, thd)).unwrap()[1];
            assert!(
                (got - want).abs() < tol,
                "minimal th = {th}, thd = {thd}: {got} vs {want}"
            );
            let (be, ga) = close(th);
            let (d1, _) = diff(th);
            let y = Vector::<6>::from([th, be, ga, thd, d1[5] * thd, d1[8] * thd]);
            let got = pa.rhs(0.0, &y).unwrap()[3];
            assert!(
                (got - want).abs() < tol,
                "augmented th = {th}, thd = {thd}: {got} vs {want}"
            );
        }
    }
}
