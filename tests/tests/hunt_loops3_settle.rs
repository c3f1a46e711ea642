//! Hunt: a crank-rocker (`a = 1`, `b = 2.5`, `c = 2`, `d = 3`; Grashof, the crank the
//! shortest bar) under gravity with a torsion spring at the rocker's pivot (`k (ga - ga0)^2
//! / 2`) and viscous dampers on the crank (`-cd th'`) and on the rocker (`-cr ga'`, a
//! generalised force along a *dependent* coordinate), written with `#[coords(th, be, ga)]`
//! and two loop equations, in both forms. It is released at rest and settles.
//!
//! Reference, derived here (no model code): the closure by hand (the two-circle
//! intersection, the rocker tip `C` left of `A -> D`); the rates by Cramer's rule on the
//! loop's rate equations, `be' = kb th'`, `ga' = kg th'`; the potential
//! `V(th) = g sum m y + k (ga - ga0)^2 / 2`, its slope `V'(th) = g sum m y' + k (ga - ga0) kg`
//! in closed form, the equilibrium `V'(th*) = 0` by bisection and `K = V''(th*)` by a
//! central difference of `V'`; the reduced inertia `J = sum m |p'|^2 + I phi'^2` and damping
//! `C = cd + cr kg^2` at `th*`, so the linearised motion has `J s^2 + C s + K = 0`.
//!
//! The coupler point `P` (body-fixed offset `[px, py]` from the coupler's mass centre) is
//! checked against the coupler curve's implicit equation, eliminated here from the two
//! circles (no angle of the mechanism enters it): with `P - A = rA u(phi + al)` and
//! `P - C = rC u(phi + bt)` (`phi` the coupler's angle), `|A| = a` and `|C - D| = c` are two
//! equations linear in `(cos phi, sin phi)`; `cos^2 + sin^2 = 1` of their Cramer solution is
//! the coupler curve `F(x, y) = 0` (a sextic).

use mbd::analysis::{
    self, NewtonOptions, constrained_modes, linearize, modes, static_equilibrium,
    static_equilibrium_constrained,
};
use mbd::integrate::{Dopri5, Integrator, Options, Radau5};
use mbd::prelude::*;

macro_rules! rocker {
    ($name:ident, $($opt:ident),*) => {
        /// The damped crank-rocker with a torsion spring at the rocker's pivot.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[gravity(0.0, -g)]
        #[coords(th, be, ga)]
        #[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
        #[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
        #[rigid(crank, mass = m1, inertia = m1 * a * a / 12.0,
                at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
        #[rigid(coupler, mass = m2, inertia = m2 * b * b / 12.0,
                at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)],
                angle = be)]
        #[rigid(rocker, mass = m3, inertia = m3 * c * c / 12.0,
                at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
        #[potential(k / 2.0 * (ga - ga0) * (ga - ga0))]
        #[generalized_force(crank_damper, along = th, value = -cd * der(th))]
        #[generalized_force(rocker_damper, along = ga, value = -cr * der(ga))]
        #[torque(motor, on = crank, value = tau)]
        #[input(tau)]
        #[init(th = 1.0, be = 0.47548940880699897, ga = 1.68958837974869)]
        #[output(p = position(coupler, [px, py]), rocker_angle = ga, crank_angle = th)]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(2.5)] pub b: f64,
            #[default(2.0)] pub c: f64,
            #[default(3.0)] pub d: f64,
            pub m1: f64,
            pub m2: f64,
            pub m3: f64,
            pub g: f64,
            pub k: f64,
            pub ga0: f64,
            pub cd: f64,
            pub cr: f64,
            pub px: f64,
            pub py: f64,
            pub tau: f64,
        }
    };
}
rocker!(Rocker, jacobian);
rocker!(RockerAugmented, jacobian, augmented);

const A: f64 = 1.0;
const B: f64 = 2.5;
const C: f64 = 2.0;
const D: f64 = 3.0;
const M: [f64; 3] = [1.0, 2.0, 1.5];
const G: f64 = 9.81;
const K: f64 = 40.0;
const GA0: f64 = 1.4;
const CD: f64 = 0.8;
const CR: f64 = 1.5;
const PX: f64 = 0.3;
const PY: f64 = 0.7;

macro_rules! reference {
    ($ty:ident $(, $field:ident: $value:expr)*) => {
        {
            #[allow(unused_mut)]
            let mut p = $ty {
                a: A, b: B, c: C, d: D, m1: M[0], m2: M[1], m3: M[2], g: G, k: K, ga0: GA0,
                cd: CD, cr: CR, px: PX, py: PY, tau: 0.0,
            };
            $(p.$field = $value;)*
            p
        }
    };
}

fn u(x: f64) -> [f64; 2] {
    [x.cos(), x.sin()]
}

/// `(be, ga)` at crank angle `th`: the rocker tip left of `A -> D`.
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

/// `(kb, kg)`: `be' = kb th'`, `ga' = kg th'`, by Cramer's rule on
/// `-b sin be be' + c sin ga ga' = a sin th th'`, `b cos be be' - c cos ga ga' = -a cos th th'`.
fn ratios(th: f64) -> (f64, f64) {
    let (be, ga) = close(th);
    let (m11, m12, m21, m22) = (-B * be.sin(), C * ga.sin(), B * be.cos(), -C * ga.cos());
    let (r1, r2) = (A * th.sin(), -A * th.cos());
    let det = m11 * m22 - m12 * m21;
    ((r1 * m22 - m12 * r2) / det, (m11 * r2 - m21 * r1) / det)
}

/// `V'(th)` in closed form.
fn slope(th: f64) -> f64 {
    let (be, ga) = close(th);
    let (kb, kg) = ratios(th);
    let y1 = A / 2.0 * th.cos();
    let y2 = A * th.cos() + B / 2.0 * be.cos() * kb;
    let y3 = C / 2.0 * ga.cos() * kg;
    G * (M[0] * y1 + M[1] * y2 + M[2] * y3) + K * (ga - GA0) * kg
}

/// The reduced inertia `J(th)`.
fn inertia(th: f64) -> f64 {
    let (be, ga) = close(th);
    let (kb, kg) = ratios(th);
    let p1 = [-A / 2.0 * th.sin(), A / 2.0 * th.cos()];
    let p2 = [
        -A * th.sin() - B / 2.0 * be.sin() * kb,
        A * th.cos() + B / 2.0 * be.cos() * kb,
    ];
    let p3 = [-C / 2.0 * ga.sin() * kg, C / 2.0 * ga.cos() * kg];
    let i = [A * A / 12.0, B * B / 12.0, C * C / 12.0];
    let v2 = |p: [f64; 2]| p[0] * p[0] + p[1] * p[1];
    M[0] * (v2(p1) + i[0]) + M[1] * (v2(p2) + i[1] * kb * kb) + M[2] * (v2(p3) + i[2] * kg * kg)
}

/// The stable equilibrium: `V'` changes sign from negative to positive; bisection.
fn equilibrium() -> f64 {
    let (mut lo, mut hi) = (-3.0, 3.0);
    // bracket found by scanning (V' is continuous on the crank's full turn)
    let n = 600;
    for i in 0..n {
        let (x0, x1) = (
            -3.0 + 6.0 * i as f64 / n as f64,
            -3.0 + 6.0 * (i + 1) as f64 / n as f64,
        );
        if slope(x0) < 0.0 && slope(x1) >= 0.0 {
            (lo, hi) = (x0, x1);
            break;
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if slope(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The roots of `J s^2 + C s + K = 0` at the equilibrium (a complex pair: `(re, im)`).
fn hand_pair() -> (f64, f64) {
    let th = equilibrium();
    let h = 1e-5;
    let kk = (slope(th + h) - slope(th - h)) / (2.0 * h);
    let (_, kg) = ratios(th);
    let (j, cc) = (inertia(th), CD + CR * kg * kg);
    let disc = 4.0 * j * kk - cc * cc;
    assert!(disc > 0.0 && kk > 0.0, "an underdamped stable equilibrium");
    (-cc / (2.0 * j), disc.sqrt() / (2.0 * j))
}

fn full_state(th: f64, thd: f64) -> Vector<6> {
    let (be, ga) = close(th);
    let (kb, kg) = ratios(th);
    Vector::<6>::from([th, be, ga, thd, kb * thd, kg * thd])
}

/// The coupler curve's implicit function `F(x, y)`, scaled to be dimensionless.
fn coupler_curve(x: f64, y: f64) -> f64 {
    // P - A = rA u(phi + al): the mass centre at b/2 along the coupler, then (px, py)
    let (ra, al) = ((B / 2.0 + PX).hypot(PY), PY.atan2(B / 2.0 + PX));
    let (rc, bt) = ((PX - B / 2.0).hypot(PY), PY.atan2(PX - B / 2.0));
    // |P - rA u(phi + al)|^2 = a^2:
    // (x cos al + y sin al) cos phi + (y cos al - x sin al) sin phi = (x^2 + y^2 + rA^2 - a^2) / (2 rA)
    let row = |x: f64, y: f64, r: f64, an: f64, len: f64| {
        (
            x * an.cos() + y * an.sin(),
            y * an.cos() - x * an.sin(),
            (x * x + y * y + r * r - len * len) / (2.0 * r),
        )
    };
    let (a11, a12, e1) = row(x, y, ra, al, A);
    let (a21, a22, e2) = row(x - D, y, rc, bt, C);
    let det = a11 * a22 - a12 * a21;
    let cs = e1 * a22 - e2 * a12;
    let sn = a11 * e2 - a21 * e1;
    (cs * cs + sn * sn - det * det) / (x * x + y * y + 1.0).powi(3)
}

/// The coupler point by hand at crank angle `th`.
fn coupler_point(th: f64) -> [f64; 2] {
    let (be, _) = close(th);
    let [ux, uy] = u(be);
    [
        A * th.cos() + (B / 2.0 + PX) * ux - PY * uy,
        A * th.sin() + (B / 2.0 + PX) * uy + PY * ux,
    ]
}

#[test]
fn the_hand_closure_reproduces_the_init_and_the_curve_holds_on_it() {
    let (be, ga) = close(1.0);
    assert!((be - 0.47548940880699897).abs() < 1e-14 && (ga - 1.68958837974869).abs() < 1e-14);
    for i in 0..64 {
        let th = i as f64 * std::f64::consts::TAU / 64.0;
        let [x, y] = coupler_point(th);
        assert!(coupler_curve(x, y).abs() < 1e-13, "th = {th}");
        // and off the curve it is not zero: the check can fail
        assert!(coupler_curve(x + 1e-3, y).abs() > 1e-9, "th = {th}");
    }
}

#[test]
fn generated_says_which_form_and_the_state_is_the_crank() {
    assert!(Rocker::GENERATED.parts.contains(&"minimal_closed_form"));
    assert!(!Rocker::GENERATED.parts.contains(&"augmented"));
    assert_eq!(Rocker::COORDINATES, ["th"]);
    assert!(RockerAugmented::GENERATED.parts.contains(&"augmented"));
    assert_eq!(RockerAugmented::COORDINATES, ["th", "be", "ga"]);
}

/// `V'` has two roots on the crank's turn: the stable `th*` (`V'' > 0`, where the motion
/// settles) and an unstable one near `1.95` (`V'' < 0`). Statics is Newton's method: from
/// each guess it must land on the hand root nearest it, in both forms.
#[test]
fn statics_in_both_forms_is_the_hand_equilibrium() {
    let stable = equilibrium();
    let unstable = {
        let (mut lo, mut hi) = (1.8, 2.1);
        assert!(slope(lo) > 0.0 && slope(hi) < 0.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if slope(mid) > 0.0 { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    };
    let opts = NewtonOptions::default();
    let p = reference!(Rocker);
    let pa = reference!(RockerAugmented);
    for (guess, th) in [(-0.8, stable), (1.0, unstable), (2.4, unstable)] {
        let q = static_equilibrium(&p, 0.0, &Vector::<1>::new(guess), &opts).unwrap();
        assert!((q[0] - th).abs() < 1e-9, "minimal {} vs {th}", q[0]);
        let (be, ga) = close(guess);
        let (qa, _) = static_equilibrium_constrained::<_, 3, 2, 5>(
            &pa,
            0.0,
            &Vector::<3>::new(guess, be, ga),
            &opts,
        )
        .unwrap();
        let (be_s, ga_s) = close(th);
        assert!(
            (qa[0] - th).abs() < 1e-9 && (qa[1] - be_s).abs() < 1e-9 && (qa[2] - ga_s).abs() < 1e-9,
            "augmented {qa} vs {th}"
        );
    }
}

#[test]
fn released_at_rest_it_settles_at_the_static_equilibrium_in_both_forms() {
    let th = equilibrium();
    let (re, _) = hand_pair();
    let t_end = 40.0 / -re; // e^-40 of the start's distance
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-12,
        ..Options::default()
    };
    let p = reference!(Rocker);
    let sol = Dopri5::new(opts.clone())
        .solve(&p, 0.0, p.initial_state(), t_end, &[])
        .unwrap();
    let y = sol.y.last().unwrap();
    assert!(
        (y[0] - th).abs() < 1e-8 && y[1].abs() < 1e-8,
        "minimal {y} vs {th}"
    );
    let pa = reference!(RockerAugmented);
    let y0 = pa.initial_state();
    assert!((y0 - full_state(1.0, 0.0)).norm() < 1e-14, "{y0}");
    let want = full_state(th, 0.0);
    for (name, run) in [
        (
            "dopri5",
            Dopri5::new(opts.clone()).solve(&pa, 0.0, y0, t_end, &[]),
        ),
        (
            "radau5",
            Radau5::new(opts.clone()).solve(&pa, 0.0, y0, t_end, &[]),
        ),
    ] {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let y = sol.y.last().unwrap();
        assert!((y - want).amax() < 1e-8, "augmented {name}: {y} vs {want}");
    }
}

#[test]
fn modes_about_the_equilibrium_are_the_hand_characteristic_roots_in_both_forms() {
    let th = equilibrium();
    let (re, im) = hand_pair();
    let check = |name: &str, ms: &[analysis::Mode]| {
        let osc: Vec<_> = ms.iter().filter(|m| m.eigenvalue.im.abs() > 1e-6).collect();
        assert_eq!(osc.len(), 1, "{name}: {ms:?}");
        let l = osc[0].eigenvalue;
        assert!(
            (l.re - re).abs() < 1e-7 * im && (l.im.abs() - im).abs() < 1e-7 * im,
            "{name}: {l} vs {re} +- {im} i"
        );
    };
    let p = reference!(Rocker);
    let a = linearize(&p, 0.0, &Vector::<2>::new(th, 0.0)).unwrap();
    check("minimal", &modes(&a).unwrap());
    let pa = reference!(RockerAugmented);
    let (be, ga) = close(th);
    let ms = constrained_modes::<_, 3, 2, 6>(&pa, 0.0, &Vector::<3>::new(th, be, ga)).unwrap();
    check("augmented", &ms);
}

#[test]
fn the_coupler_point_traces_the_coupler_curve_in_both_forms() {
    // undamped and no spring: the crank turns over and over
    let p = reference!(Rocker, k: 0.0, cd: 0.0, cr: 0.0);
    let pa = reference!(RockerAugmented, k: 0.0, cd: 0.0, cr: 0.0);
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let y0 = Vector::<2>::new(1.0, 9.0);
    let sol = Dopri5::new(opts.clone())
        .solve(&p, 0.0, y0, 4.0, &[])
        .unwrap();
    assert!(sol.y.last().unwrap()[0] > 1.0 + 2.0 * std::f64::consts::TAU);
    for (&t, y) in sol.t.iter().zip(&sol.y) {
        let o = p.outputs(t, y).unwrap();
        let [x, yy] = coupler_point(y[0]);
        assert!(
            (o.p_x - x).abs() < 1e-12 && (o.p_y - yy).abs() < 1e-12,
            "minimal t = {t}"
        );
        assert!(coupler_curve(o.p_x, o.p_y).abs() < 1e-12, "minimal t = {t}");
    }
    let sol = Dopri5::new(opts)
        .solve(&pa, 0.0, full_state(1.0, 9.0), 4.0, &[])
        .unwrap();
    assert!(sol.y.last().unwrap()[0] > 1.0 + 2.0 * std::f64::consts::TAU);
    for (&t, y) in sol.t.iter().zip(&sol.y) {
        let o = pa.outputs(t, y).unwrap();
        let [x, yy] = coupler_point(y[0]);
        assert!(
            (o.p_x - x).abs() < 1e-9 && (o.p_y - yy).abs() < 1e-9,
            "augmented t = {t}: ({}, {}) vs ({x}, {yy})",
            o.p_x,
            o.p_y
        );
        assert!(
            coupler_curve(o.p_x, o.p_y).abs() < 1e-9,
            "augmented t = {t}"
        );
    }
}

/// The motor torque's frequency response to the crank angle about the equilibrium is the
/// hand's `1 / (K - J w^2 + i C w)`, in both forms (`state_space` of the minimal model,
/// `constrained_state_space` of the augmented one).
#[test]
fn the_torque_to_crank_frequency_response_is_the_hand_one_in_both_forms() {
    use mbd::analysis::{Parametric, constrained_state_space, state_space};
    let th = equilibrium();
    let h = 1e-5;
    let kk = (slope(th + h) - slope(th - h)) / (2.0 * h);
    let (_, kg) = ratios(th);
    let (j, cc) = (inertia(th), CD + CR * kg * kg);
    let out = <Rocker as Parametric<2>>::OUTPUT_NAMES
        .iter()
        .position(|n| *n == "crank_angle")
        .unwrap();
    let p = reference!(Rocker);
    let ss = state_space(&p, 0.0, &Vector::<2>::new(th, 0.0)).unwrap();
    assert_eq!(ss.inputs, ["tau"]);
    let pa = reference!(RockerAugmented);
    let (be, ga) = close(th);
    let (ssa, _) =
        constrained_state_space::<_, 3, 2, 6>(&pa, 0.0, &Vector::<3>::new(th, be, ga)).unwrap();
    for w in [0.3, 1.0, 2.0, 6.0] {
        let want = num_complex_inverse(kk - j * w * w, cc * w);
        for (name, g) in [
            ("minimal", ss.frequency_response(w).unwrap()),
            ("augmented", ssa.frequency_response(w).unwrap()),
        ] {
            let got = g[(out, 0)];
            let err = ((got.re - want.0).powi(2) + (got.im - want.1).powi(2)).sqrt();
            let size = want.0.hypot(want.1);
            assert!(err < 1e-7 * size, "{name} w = {w}: {got} vs {want:?}");
        }
    }
}

/// `1 / (re + i im)` as `(re, im)`.
fn num_complex_inverse(re: f64, im: f64) -> (f64, f64) {
    let d = re * re + im * im;
    (re / d, -im / d)
}
