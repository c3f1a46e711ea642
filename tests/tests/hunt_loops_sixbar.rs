//! Hunt: a Watt six-bar (two four-bar loops in series, one degree of freedom) written with
//! coordinates and four loop equations, in both forms, on every integrator.
//!
//! Reference, derived here: the closure by hand (two two-circle intersections, the elbows
//! above the ground line), the five bars' mass centres and angles as functions of the crank
//! angle `th`, their first and second derivatives by five-point differences (step 1e-3:
//! truncation ~1e-12, rounding ~1e-10), and Lagrange's equation in `th`:
//! `J th'' + C th'^2 = Q`, `J = sum m |p'|^2 + I phi'^2`, `C = sum m p'.p'' + I phi' phi''`,
//! `Q = -g sum m p'_y`. Energy `T + V` from the same functions is the integrated motion's
//! invariant.

use mbd::integrate::{
    Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;

macro_rules! six_bar {
    ($name:ident, $($opt:ident),*) => {
        /// Crank `th` about the origin, coupler `be`, rocker `ga` about `(d, 0)`; a second
        /// coupler `de` from the rocker's tip to a second rocker `ep` about `(d2, 0)`.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[gravity(0.0, -g)]
        #[coords(th, be, ga, de, ep)]
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
        #[init(th = 0.5, be = 0.726016592102178, ga = 1.7229599395818347,
               de = -0.18570003070547192, ep = 1.2820616702455918, der(th) = 4.0)]
        #[output(out_angle = ep, out_rate = der(ep))]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(3.0)] pub b: f64,
            #[default(2.5)] pub c: f64,
            #[default(3.5)] pub d: f64,
            #[default(3.0)] pub e: f64,
            #[default(2.0)] pub f: f64,
            #[default(5.5)] pub d2: f64,
            #[default(1.0)] pub m: f64,
            #[default(9.81)] pub g: f64,
        }
    };
}
six_bar!(SixBar, jacobian);
six_bar!(SixBarAugmented, jacobian, augmented);

const L: [f64; 5] = [1.0, 3.0, 2.5, 3.0, 2.0];
const D: f64 = 3.5;
const D2: f64 = 5.5;
const G: f64 = 9.81;

/// A model of type `$ty` with the reference's parameters.
macro_rules! reference {
    ($ty:ident) => {
        $ty {
            a: L[0],
            b: L[1],
            c: L[2],
            d: D,
            e: L[3],
            f: L[4],
            d2: D2,
            m: 1.0,
            g: G,
        }
    };
}

fn minimal() -> SixBar {
    reference!(SixBar)
}

fn augmented() -> SixBarAugmented {
    reference!(SixBarAugmented)
}

/// The angles `(AC, DC)` of the point `C` at `r1` from `A` and `r2` from `D`, above `AD`.
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

/// Each bar's `(x, y, angle)` at crank angle `th`.
fn bars(th: f64) -> [[f64; 3]; 5] {
    let [be, ga, de, ep] = close(th);
    let (a, b, c, e, f) = (L[0], L[1], L[2], L[3], L[4]);
    let tip = (D + c * ga.cos(), c * ga.sin());
    [
        [a / 2.0 * th.cos(), a / 2.0 * th.sin(), th],
        [
            a * th.cos() + b / 2.0 * be.cos(),
            a * th.sin() + b / 2.0 * be.sin(),
            be,
        ],
        [D + c / 2.0 * ga.cos(), c / 2.0 * ga.sin(), ga],
        [tip.0 + e / 2.0 * de.cos(), tip.1 + e / 2.0 * de.sin(), de],
        [D2 + f / 2.0 * ep.cos(), f / 2.0 * ep.sin(), ep],
    ]
}

/// First and second derivatives of [`bars`] in `th` by five-point differences.
fn bar_rates(th: f64) -> ([[f64; 3]; 5], [[f64; 3]; 5]) {
    let h = 1e-3;
    let s = [-2.0, -1.0, 1.0, 2.0].map(|k| bars(th + k * h));
    let mid = bars(th);
    let (mut d1, mut d2) = ([[0.0; 3]; 5], [[0.0; 3]; 5]);
    for i in 0..5 {
        for j in 0..3 {
            let (m2, m1, p1, p2) = (s[0][i][j], s[1][i][j], s[2][i][j], s[3][i][j]);
            d1[i][j] = (m2 - 8.0 * m1 + 8.0 * p1 - p2) / (12.0 * h);
            d2[i][j] = (-m2 + 16.0 * m1 - 30.0 * mid[i][j] + 16.0 * p1 - p2) / (12.0 * h * h);
        }
    }
    (d1, d2)
}

/// `th''` by Lagrange's equation in `th`.
fn lagrange(th: f64, thd: f64) -> f64 {
    let (d1, d2) = bar_rates(th);
    let (mut j, mut c, mut q) = (0.0, 0.0, 0.0);
    for (i, len) in L.iter().enumerate() {
        let inertia = len * len / 12.0;
        j += d1[i][0].powi(2) + d1[i][1].powi(2) + inertia * d1[i][2].powi(2);
        c += d1[i][0] * d2[i][0] + d1[i][1] * d2[i][1] + inertia * d1[i][2] * d2[i][2];
        q -= G * d1[i][1];
    }
    (q - c * thd * thd) / j
}

/// `T + V` at `(th, th')`.
fn energy(th: f64, thd: f64) -> f64 {
    let (d1, _) = bar_rates(th);
    let p = bars(th);
    (0..5)
        .map(|i| {
            let inertia = L[i] * L[i] / 12.0;
            let v2 = d1[i][0].powi(2) + d1[i][1].powi(2) + inertia * d1[i][2].powi(2);
            0.5 * v2 * thd * thd + G * p[i][1]
        })
        .sum()
}

#[test]
fn the_init_is_on_the_hand_closure() {
    let want = close(0.5);
    let got = [
        0.726016592102178,
        1.7229599395818347,
        -0.18570003070547192,
        1.2820616702455918,
    ];
    for (w, g) in want.iter().zip(got) {
        assert!((w - g).abs() < 1e-14, "{w} vs {g}");
    }
}

#[test]
fn accelerations_match_lagrange_in_both_forms() {
    let (p, pa) = (minimal(), augmented());
    println!(
        "{:?} / {:?}",
        SixBar::GENERATED.parts,
        SixBarAugmented::GENERATED.parts
    );
    println!("{:?}", SixBar::COORDINATES);
    for th in [0.5, 1.3, 2.2, 3.0, -2.5, -1.0] {
        for thd in [0.0, 3.0, -7.0] {
            let want = lagrange(th, thd);
            let tol = 1e-7 * (1.0 + want.abs());
            // Augmented: the full state from the hand closure and its rates.
            let dep = close(th);
            let (d1, _) = bar_rates(th);
            let q = mbd::Vector::<5>::from([th, dep[0], dep[1], dep[2], dep[3]]);
            let qd = mbd::Vector::<5>::from([1.0, d1[1][2], d1[2][2], d1[3][2], d1[4][2]]) * thd;
            let aug = pa.acceleration(0.0, &q, &qd).unwrap()[0];
            assert!(
                (aug - want).abs() < tol,
                "augmented th = {th}, thd = {thd}: {aug} vs {want}"
            );
            let y = mbd::Vector::<2>::new(th, thd);
            let got = p.rhs(0.0, &y).unwrap()[1];
            assert!(
                (got - want).abs() < tol,
                "minimal th = {th}, thd = {thd}: {got} vs {want}"
            );
        }
    }
}

/// The augmented start: the init's positions, the crank rate held and the others made
/// consistent (the generated `initial_state` leaves them zero).
fn consistent_start(pa: &SixBarAugmented) -> mbd::Vector<10> {
    let y = pa.initial_state();
    let q = y.fixed_rows::<5>(0).into_owned();
    let held = [true, false, false, false, false];
    let qd = mbd::analysis::assembly::consistent_velocities(
        pa,
        0.0,
        &q,
        &y.fixed_rows::<5>(5).into_owned(),
        &held,
    )
    .unwrap();
    let mut out = y;
    out.fixed_rows_mut::<5>(5).copy_from(&qd);
    out
}

/// One method on both forms: `(name, minimal run, augmented run, energy tolerance)`.
type Run = (
    &'static str,
    mbd::Result<Solution<2>>,
    mbd::Result<Solution<10>>,
    f64,
);

/// `method` on both forms, each from its start to `t1`, named, with the energy tolerance.
fn both(name: &'static str, method: impl Integrator, t1: f64, tol: f64) -> Run {
    let (p, pa) = (minimal(), augmented());
    let min = method.solve(&p, 0.0, p.initial_state(), t1, &[]);
    let aug = method.solve(&pa, 0.0, consistent_start(&pa), t1, &[]);
    (name, min, aug, tol)
}

/// Every method, both forms.
fn runs(t1: f64) -> Vec<Run> {
    let tight = || Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    let loose = || Options {
        rtol: 1e-7,
        atol: 1e-7,
        ..Options::default()
    };
    vec![
        both("dopri5", Dopri5::new(tight()), t1, 1e-7),
        both("dop853", Dop853::new(tight()), t1, 1e-7),
        both("vern9", Vern9::new(tight()), t1, 1e-7),
        both("radau5", Radau5::new(loose()), t1, 1e-4),
        both("rk4", Rk4::new(1e-3), t1, 1e-5),
        both("gauss", Gauss::new(2e-3), t1, 1e-5),
        both(
            "generalized-alpha",
            GeneralizedAlpha::new(1.0, 5e-4),
            t1,
            1e-5,
        ),
    ]
}

#[test]
fn every_method_conserves_the_hand_energy_on_both_forms() {
    let (p, pa) = (minimal(), augmented());
    let e0 = energy(0.5, 4.0);
    let rel = |e: f64| (e - e0).abs() / e0.abs().max(1.0);
    for (name, min, aug, tol) in runs(2.0) {
        let min = min.unwrap_or_else(|e| panic!("{name} minimal: {e}"));
        let aug = aug.unwrap_or_else(|e| panic!("{name} augmented: {e}"));
        let mut worst = (0.0f64, 0.0f64, 0.0f64);
        for y in &min.y {
            worst.0 = worst.0.max(rel(energy(y[0], y[1])));
        }
        for (&t, y) in min.t.iter().zip(&min.y).step_by(5) {
            let o = p.outputs(t, y).unwrap();
            let (d1, _) = bar_rates(y[0]);
            let want = close(y[0])[3];
            assert!(
                (o.out_angle - want).abs() < 1e-10,
                "{name}: ep {} vs {want}",
                o.out_angle
            );
            assert!(
                (o.out_rate - d1[4][2] * y[1]).abs() < 1e-7 * (1.0 + y[1].abs()),
                "{name}: ep'"
            );
        }
        for y in &aug.y {
            worst.1 = worst.1.max(rel(energy(y[0], y[5])));
            let dep = close(y[0]);
            for k in 0..4 {
                let wrap = (y[k + 1] - dep[k] + std::f64::consts::PI)
                    .rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                worst.2 = worst.2.max(wrap.abs());
            }
        }
        let _ = &pa;
        println!(
            "{name}: minimal {} steps, energy {:.2e}; augmented {} steps, energy {:.2e}, off the hand closure {:.2e}; ends th = {:.6} / {:.6}",
            min.y.len(),
            worst.0,
            aug.y.len(),
            worst.1,
            worst.2,
            min.y.last().unwrap()[0],
            aug.y.last().unwrap()[0]
        );
        assert!(worst.0 < tol && worst.1 < tol, "{name}: {worst:?}");
        assert!(worst.2 < tol, "{name}: {worst:?}");
    }
}
