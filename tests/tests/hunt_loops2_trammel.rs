//! Hunt: an elliptic trammel (a double slider): a bar of length `l` whose end `A` slides on
//! the ground's `x` axis and end `B` on its `y` axis, the bar at `th` from `x`:
//! `A = (l cos th, 0)`, `B = (0, l sin th)`. Gravity along `-y`; sliders of masses `ma`,
//! `mb`, a uniform bar `m`. The mechanism is regular at every `th`; the slider positions are
//! charts that end where the bar lies along an axis (`xa = l` at `th = 0`).
//!
//! Reference, by hand: `T = J(th) th'^2 / 2`, `J = l^2 (ma sin^2 th + mb cos^2 th + m / 3)`,
//! `V = g l (mb + m / 2) sin th`, so Lagrange's equation is
//! `J th'' + l^2 (ma - mb) sin th cos th th'^2 + g l (mb + m / 2) cos th = 0`, integrated
//! here by a separately written RK4 at a small step.

#![allow(
    clippy::needless_range_loop,
    reason = "the references index bodies and components of parallel arrays"
)]

use mbd::integrate::{
    Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;

macro_rules! trammel {
    ($name:ident, [$($coord:ident),*], [$($opt:ident),*], [$($init:tt)*]) => {
        /// The trammel with coordinates in the order given.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism(planar $(, $opt)*)]
        #[gravity(0.0, -g)]
        #[coords($($coord),*)]
        #[constraint(xa == l * cos(th))]
        #[constraint(yb == l * sin(th))]
        #[particle(slider_a, mass = ma, at = [xa, 0.0])]
        #[particle(slider_b, mass = mb, at = [0.0, yb])]
        #[rigid(bar, mass = m, inertia = m * l * l / 12.0,
                at = [l / 2.0 * cos(th), l / 2.0 * sin(th)], angle = -th)]
        #[init($($init)*)]
        pub struct $name {
            #[default(1.0)] pub l: f64,
            #[default(1.0)] pub ma: f64,
            #[default(2.0)] pub mb: f64,
            #[default(0.5)] pub m: f64,
            #[default(9.81)] pub g: f64,
        }
    };
}

// Starting at th = 0.5 turning towards the x axis at th' = -3:
// xa = cos 0.5, yb = sin 0.5, xa' = -l sin(th) th' = 3 sin 0.5.
trammel!(
    ByAngle,
    [th, xa, yb],
    [],
    [
        th = 0.5,
        xa = 0.8775825618903728,
        yb = 0.479425538604203,
        der(th) = -3.0
    ]
);
trammel!(
    BySlider,
    [xa, yb, th],
    [],
    [
        xa = 0.8775825618903728,
        yb = 0.479425538604203,
        th = 0.5,
        der(xa) = 1.438276615812609
    ]
);
trammel!(
    Augmented,
    [th, xa, yb],
    [augmented],
    [
        th = 0.5,
        xa = 0.8775825618903728,
        yb = 0.479425538604203,
        der(th) = -3.0
    ]
);

const L: f64 = 1.0;
const MA: f64 = 1.0;
const MB: f64 = 2.0;
const M: f64 = 0.5;
const G: f64 = 9.81;

macro_rules! params {
    ($ty:ident) => {
        $ty {
            l: L,
            ma: MA,
            mb: MB,
            m: M,
            g: G,
        }
    };
}

/// `th''` by Lagrange's equation (above).
fn lagrange(th: f64, thd: f64) -> f64 {
    let (s, c) = th.sin_cos();
    let j = L * L * (MA * s * s + MB * c * c + M / 3.0);
    -(L * L * (MA - MB) * s * c * thd * thd + G * L * (MB + M / 2.0) * c) / j
}

/// `T + V` at `(th, th')`.
fn energy(th: f64, thd: f64) -> f64 {
    let (s, c) = th.sin_cos();
    let j = L * L * (MA * s * s + MB * c * c + M / 3.0);
    0.5 * j * thd * thd + G * L * (MB + M / 2.0) * s
}

/// The hand equation from `(0.5, -3)` by RK4 at `h = 1e-5`: `(t, th, th')` every 1e-3.
fn reference(t1: f64) -> Vec<(f64, f64, f64)> {
    let f = |y: [f64; 2]| [y[1], lagrange(y[0], y[1])];
    let (h, mut y, mut t) = (1e-5, [0.5, -3.0], 0.0);
    let mut out = vec![(t, y[0], y[1])];
    let steps = (t1 / h).round() as usize;
    for k in 1..=steps {
        let k1 = f(y);
        let k2 = f([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
        let k3 = f([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
        let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
        for i in 0..2 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        t += h;
        if k % 100 == 0 {
            out.push((t, y[0], y[1]));
        }
    }
    out
}

/// The first time the reference reaches `th = 0` (the bar along the `x` axis: `xa = l`).
fn time_on_axis() -> f64 {
    let r = reference(1.0);
    let k = r.iter().position(|s| s.1 <= 0.0).expect("reaches the axis");
    let ((t0, a0, _), (t1, a1, _)) = (r[k - 1], r[k]);
    t0 + (t1 - t0) * a0 / (a0 - a1)
}

fn opts(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    }
}

/// Every integrator from `y0` to `t1`, named.
fn every_method<S: MechanismModel<1> + OdeSystem<2>>(
    p: &S,
    y0: Vector<2>,
    t1: f64,
) -> Vec<(&'static str, mbd::Result<Solution<2>>)> {
    let (q0, qd0) = (Vector::<1>::new(y0[0]), Vector::<1>::new(y0[1]));
    vec![
        (
            "dopri5",
            Dopri5::new(opts(1e-10)).solve(p, 0.0, y0, t1, &[]),
        ),
        (
            "dop853",
            Dop853::new(opts(1e-10)).solve(p, 0.0, y0, t1, &[]),
        ),
        ("vern9", Vern9::new(opts(1e-10)).solve(p, 0.0, y0, t1, &[])),
        ("auto", Auto::new(opts(1e-10)).solve(p, 0.0, y0, t1, &[])),
        ("radau5", Radau5::new(opts(1e-8)).solve(p, 0.0, y0, t1, &[])),
        ("rk4", Rk4::new(1e-3).solve(p, 0.0, y0, t1, &[])),
        ("gauss", Gauss::new(1e-3).solve(p, 0.0, y0, t1, &[])),
        (
            "generalized-alpha",
            GeneralizedAlpha::new(0.9, 1e-3).solve(p, 0.0, q0, qd0, t1, &[]),
        ),
    ]
}

#[test]
fn the_state_is_the_first_listed_coordinate() {
    assert_eq!(ByAngle::COORDINATES, ["th"]);
    assert_eq!(BySlider::COORDINATES, ["xa"]);
    assert_eq!(Augmented::COORDINATES, ["th", "xa", "yb"]);
    assert_eq!(
        (
            ByAngle::GENERATED.constraints,
            Augmented::GENERATED.constraints
        ),
        (0, 2)
    );
}

#[test]
fn accelerations_match_lagrange_in_every_chart() {
    let (by_angle, by_slider, aug) = (params!(ByAngle), params!(BySlider), params!(Augmented));
    for &(th, thd) in &[
        (0.5, -3.0),
        (1.2, 0.7),
        (2.5, 2.0),
        (-0.4, 1.0),
        (-2.0, -1.5),
    ] {
        let want = lagrange(th, thd);
        let a = by_angle
            .acceleration(0.0, &Vector::<1>::new(th), &Vector::<1>::new(thd))
            .unwrap()[0];
        assert!(
            (a - want).abs() < 1e-12 * want.abs().max(1.0),
            "th {th}: {a} vs {want}"
        );
        let (s, c) = th.sin_cos();
        let q = Vector::<3>::new(th, L * c, L * s);
        let qd = Vector::<3>::new(thd, -L * s * thd, L * c * thd);
        let a = aug.acceleration(0.0, &q, &qd).unwrap()[0];
        assert!(
            (a - want).abs() < 1e-11 * want.abs().max(1.0),
            "augmented th {th}: {a} vs {want}"
        );
        // The slider chart covers 0 < th < pi (the init's branch): xa'' = -l (s th'' + c th'^2).
        if th > 0.0 && th < std::f64::consts::PI {
            let xdd = by_slider
                .acceleration(
                    0.0,
                    &Vector::<1>::new(L * c),
                    &Vector::<1>::new(-L * s * thd),
                )
                .unwrap()[0];
            let want_x = -L * (s * want + c * thd * thd);
            assert!(
                (xdd - want_x).abs() < 1e-11 * want_x.abs().max(1.0),
                "slider th {th}: {xdd} vs {want_x}"
            );
        }
    }
}

#[test]
fn the_angle_chart_and_the_augmented_form_pass_the_axes_with_the_reference() {
    let t1 = 1.0;
    let r = reference(t1);
    let (_, th_ref, thd_ref) = *r.last().unwrap();
    let crossed = r.iter().any(|s| s.1 < -0.2);
    assert!(crossed, "the reference must pass the x axis");
    let p = params!(ByAngle);
    for (name, run) in every_method(&p, p.initial_state(), t1) {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let y = sol.y.last().unwrap();
        let tol = if name == "radau5" { 1e-5 } else { 1e-6 };
        assert!(
            (y[0] - th_ref).abs() < tol && (y[1] - thd_ref).abs() < 10.0 * tol,
            "{name}: {y:?} vs ({th_ref}, {thd_ref})"
        );
    }
    let pa = params!(Augmented);
    let sol = Dopri5::new(opts(1e-11))
        .solve(&pa, 0.0, pa.initial_state(), t1, &[])
        .unwrap();
    let y = sol.y.last().unwrap();
    assert!(
        (y[0] - th_ref).abs() < 1e-7 && (y[3] - thd_ref).abs() < 1e-6,
        "{y:?}"
    );
    let e0 = energy(0.5, -3.0);
    for y in &sol.y {
        assert!((energy(y[0], y[3]) - e0).abs() < 1e-7 * e0.abs(), "{y:?}");
        assert!((y[1] - L * y[0].cos()).abs() < 1e-9 && (y[2] - L * y[0].sin()).abs() < 1e-9);
    }
}

/// In the slider chart (state `xa`, `th = acos(xa / l)` on the init's branch `th > 0`) the
/// bar reaching the `x` axis is the chart's edge: the motion goes on to `th < 0`, which the
/// chart cannot represent. Every method must stop there with a typed error, never return a
/// motion reflected back into `th > 0`.
#[test]
fn the_slider_chart_stops_where_the_bar_reaches_the_axis() {
    let t_axis = time_on_axis();
    let p = params!(BySlider);
    let y0 = p.initial_state();
    assert!((y0[0] - 0.5f64.cos()).abs() < 1e-15 && (y0[1] - 3.0 * 0.5f64.sin()).abs() < 1e-12);
    for (name, run) in every_method(&p, y0, 1.0) {
        match run {
            Err(mbd::Error::SingularPosition { t, detail }) => {
                println!("{name}: t = {t} (axis at {t_axis}): {detail}");
                assert!(
                    (t - t_axis).abs() < 1e-3,
                    "{name}: stopped at {t}, axis at {t_axis}"
                );
            }
            Ok(sol) => panic!("{name}: Ok, ends at {:?}", sol.y.last().unwrap()),
            Err(e) => panic!("{name}: {e}"),
        }
    }
}
