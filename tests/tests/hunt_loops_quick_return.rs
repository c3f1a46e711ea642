//! Hunt: a quick-return mechanism (the inverted slider-crank): a crank `a` about the origin
//! carries a block at its tip that slides in a slotted lever pivoted at `(0, -d)`, `d > a`,
//! so the lever rocks while the crank turns. Coordinates `th` (crank), `phi` (lever), `s`
//! (the block's distance along the lever); loop: `a cos th = s cos phi`,
//! `a sin th + d = s sin phi`. Free and driven (`th = w t`), in both forms, with gravity.
//!
//! Reference, derived here: `phi = atan2(a sin th + d, a cos th)`, `s = hypot(..)`; the
//! bodies' mass centres and angles as functions of `th`, their derivatives by five-point
//! differences, and Lagrange's equation in `th` (`J th'' + C th'^2 = Q`, see
//! `hunt_loops_sixbar.rs`). Driven at `th' = w`, the drive's effort is `C w^2 - Q`.

use mbd::integrate::{
    Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;

macro_rules! quick_return {
    ($name:ident, [$($rate:tt)*], $($opt:ident),*) => {
        /// The free quick-return under gravity.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[gravity(0.0, -g)]
        #[coords(th, phi, s)]
        #[constraint(a * cos(th) == s * cos(phi))]
        #[constraint(a * sin(th) + d == s * sin(phi))]
        #[rigid(crank, mass = m, inertia = m * a * a / 12.0,
                at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
        #[rigid(lever, mass = ml, inertia = ml * l * l / 12.0,
                at = [l / 2.0 * cos(phi), -d + l / 2.0 * sin(phi)], angle = phi)]
        #[rigid(block, mass = mb, inertia = ib, at = [a * cos(th), a * sin(th)], angle = phi)]
        #[init(th = 0.3, phi = 1.0818256619128643, s = 2.0338536377979657, $($rate)*)]
        #[output(lever_rate = der(phi), slide = s, slide_rate = der(s))]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(1.5)] pub d: f64,
            #[default(3.0)] pub l: f64,
            #[default(1.0)] pub m: f64,
            #[default(2.0)] pub ml: f64,
            #[default(0.5)] pub mb: f64,
            #[default(0.01)] pub ib: f64,
            #[default(9.81)] pub g: f64,
        }
    };
}
quick_return!(QuickReturn, [der(th) = 6.0], jacobian);
quick_return!(
    QuickReturnMinimal,
    [der(s) = 4.227456805318331],
    jacobian,
    minimal
);
quick_return!(QuickReturnAugmented, [der(th) = 6.0], jacobian, augmented);

macro_rules! driven {
    ($name:ident, $($opt:ident),*) => {
        /// The same, its crank driven at `w`.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[gravity(0.0, -g)]
        #[drive(th = 0.3 + w * t)]
        #[coords(phi, s)]
        #[constraint(a * cos(th) == s * cos(phi))]
        #[constraint(a * sin(th) + d == s * sin(phi))]
        #[rigid(crank, mass = m, inertia = m * a * a / 12.0,
                at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
        #[rigid(lever, mass = ml, inertia = ml * l * l / 12.0,
                at = [l / 2.0 * cos(phi), -d + l / 2.0 * sin(phi)], angle = phi)]
        #[rigid(block, mass = mb, inertia = ib, at = [a * cos(th), a * sin(th)], angle = phi)]
        #[init(phi = 1.0818256619128643, s = 2.0338536377979657)]
        #[output(motor = reaction(th), lever = phi)]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(1.5)] pub d: f64,
            #[default(3.0)] pub l: f64,
            #[default(1.0)] pub m: f64,
            #[default(2.0)] pub ml: f64,
            #[default(0.5)] pub mb: f64,
            #[default(0.01)] pub ib: f64,
            #[default(9.81)] pub g: f64,
            #[default(3.0)] pub w: f64,
        }
    };
}
driven!(Driven, jacobian);
driven!(DrivenAugmented, jacobian, augmented);

const A: f64 = 1.0;
const D: f64 = 1.5;
const LL: f64 = 3.0;
const MASS: [f64; 3] = [1.0, 2.0, 0.5];
const INERTIA: [f64; 3] = [1.0 / 12.0, 2.0 * 9.0 / 12.0, 0.01];
const G: f64 = 9.81;
const W: f64 = 3.0;

/// A model of type `$ty` with the reference's parameters (and any `field: value` more).
macro_rules! reference {
    ($ty:ident $(, $field:ident: $value:expr)*) => {
        $ty {
            a: A,
            d: D,
            l: LL,
            m: MASS[0],
            ml: MASS[1],
            mb: MASS[2],
            ib: INERTIA[2],
            g: G,
            $($field: $value,)*
        }
    };
}

/// `(phi, s)` at crank angle `th`.
fn close(th: f64) -> (f64, f64) {
    let (x, y) = (A * th.cos(), A * th.sin() + D);
    (y.atan2(x), x.hypot(y))
}

/// Each body's `(x, y, angle)` at crank angle `th`: crank, lever, block.
fn bodies(th: f64) -> [[f64; 3]; 3] {
    let (phi, _) = close(th);
    [
        [A / 2.0 * th.cos(), A / 2.0 * th.sin(), th],
        [LL / 2.0 * phi.cos(), -D + LL / 2.0 * phi.sin(), phi],
        [A * th.cos(), A * th.sin(), phi],
    ]
}

/// Five-point first and second derivatives in `th` of `f`.
fn diff<const K: usize>(f: impl Fn(f64) -> [f64; K], th: f64) -> ([f64; K], [f64; K]) {
    let h = 1e-3;
    let s = [-2.0, -1.0, 1.0, 2.0].map(|k| f(th + k * h));
    let mid = f(th);
    let (mut d1, mut d2) = ([0.0; K], [0.0; K]);
    for j in 0..K {
        let (m2, m1, p1, p2) = (s[0][j], s[1][j], s[2][j], s[3][j]);
        d1[j] = (m2 - 8.0 * m1 + 8.0 * p1 - p2) / (12.0 * h);
        d2[j] = (-m2 + 16.0 * m1 - 30.0 * mid[j] + 16.0 * p1 - p2) / (12.0 * h * h);
    }
    (d1, d2)
}

fn flat(th: f64) -> [f64; 9] {
    let b = bodies(th);
    [
        b[0][0], b[0][1], b[0][2], b[1][0], b[1][1], b[1][2], b[2][0], b[2][1], b[2][2],
    ]
}

/// `(J, C, Q)` of Lagrange's equation `J th'' + C th'^2 = Q`; `with_crank` false leaves the
/// crank's own inertia and weight out (a driven crank's are carried by the drive too).
fn lagrange_terms(th: f64, with_crank: bool) -> (f64, f64, f64) {
    let (d1, d2) = diff(flat, th);
    let (mut j, mut c, mut q) = (0.0, 0.0, 0.0);
    for b in 0..3 {
        if b == 0 && !with_crank {
            continue;
        }
        let (m, i) = (MASS[b], INERTIA[b]);
        let k = 3 * b;
        j += m * (d1[k].powi(2) + d1[k + 1].powi(2)) + i * d1[k + 2].powi(2);
        c += m * (d1[k] * d2[k] + d1[k + 1] * d2[k + 1]) + i * d1[k + 2] * d2[k + 2];
        q -= m * G * d1[k + 1];
    }
    (j, c, q)
}

fn energy(th: f64, thd: f64) -> f64 {
    let (d1, _) = diff(flat, th);
    let b = bodies(th);
    (0..3)
        .map(|k| {
            let v2 = MASS[k] * (d1[3 * k].powi(2) + d1[3 * k + 1].powi(2))
                + INERTIA[k] * d1[3 * k + 2].powi(2);
            0.5 * v2 * thd * thd + MASS[k] * G * b[k][1]
        })
        .sum()
}

fn free() -> QuickReturn {
    reference!(QuickReturn)
}

fn free_augmented() -> QuickReturnAugmented {
    reference!(QuickReturnAugmented)
}

#[test]
fn the_init_is_on_the_closure() {
    let (phi, s) = close(0.3);
    assert!((phi - 1.0818256619128643).abs() < 1e-15 && (s - 2.0338536377979657).abs() < 1e-15);
}

#[test]
fn free_accelerations_match_lagrange_in_both_forms() {
    let (p, pa) = (free(), free_augmented());
    for th in [0.3, 1.0, 2.0, 3.5, 5.0, -0.4] {
        for thd in [0.0, 2.0, -5.0] {
            let (j, c, q) = lagrange_terms(th, true);
            let want = (q - c * thd * thd) / j;
            let tol = 1e-7 * (1.0 + want.abs());
            let (phi, s) = close(th);
            let (d, _) = diff(
                |t| {
                    let (f, s) = close(t);
                    [f, s]
                },
                th,
            );
            let y = mbd::Vector::<6>::from([th, phi, s, thd, d[0] * thd, d[1] * thd]);
            let got = pa.rhs(0.0, &y).unwrap()[3];
            assert!(
                (got - want).abs() < tol,
                "augmented th = {th}: {got} vs {want}"
            );
            let _ = &p;
        }
    }
}

/// Defect found: the derive solved the loop for `th` and `phi` from the slide `s` (the only
/// closed form it has), so the default form's state was `s`, whose extremes `s = d -+ a`
/// (the crank at `-+pi/2`) are limit positions of that chart though the mechanism is regular
/// there: the run stopped with `SingularPosition` at t = 1.13. The state is now the
/// first-listed coordinate, and the loop stays augmented where that has no closed form.
#[test]
fn the_default_form_keeps_the_crank_angle() {
    assert_eq!(QuickReturn::COORDINATES, ["th", "phi", "s"]);
    assert_eq!(QuickReturnMinimal::COORDINATES, ["s"]);
}

/// `init(der(th) = 6)` alone: the other rates follow from the closure in both forms.
#[test]
fn the_initial_rates_follow_the_closure_in_both_forms() {
    let (d, _) = diff(
        |t| {
            let (f, s) = close(t);
            [f, s]
        },
        0.3,
    );
    for y in [free().initial_state(), free_augmented().initial_state()] {
        assert_eq!(y[3], 6.0);
        assert!(
            (y[4] - 6.0 * d[0]).abs() < 1e-10 && (y[5] - 6.0 * d[1]).abs() < 1e-10,
            "{y}"
        );
    }
}

/// Several crank turns, through both extremes of the slide, on every method: the energy by
/// hand is conserved and the state stays on the hand closure.
#[test]
fn crank_turns_through_the_slide_extremes_on_every_method() {
    let p = free();
    let y0 = p.initial_state();
    let e0 = energy(0.3, 6.0);
    let tight = || Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    let runs: Vec<(&str, mbd::Result<Solution<6>>, f64)> = vec![
        (
            "dopri5",
            Dopri5::new(tight()).solve(&p, 0.0, y0, 3.0, &[]),
            1e-8,
        ),
        (
            "dop853",
            Dop853::new(tight()).solve(&p, 0.0, y0, 3.0, &[]),
            1e-8,
        ),
        (
            "vern9",
            Vern9::new(tight()).solve(&p, 0.0, y0, 3.0, &[]),
            1e-8,
        ),
        (
            "radau5",
            Radau5::new(Options {
                rtol: 1e-8,
                atol: 1e-8,
                ..Options::default()
            })
            .solve(&p, 0.0, y0, 3.0, &[]),
            1e-5,
        ),
        ("rk4", Rk4::new(1e-3).solve(&p, 0.0, y0, 3.0, &[]), 1e-7),
        ("gauss", Gauss::new(2e-3).solve(&p, 0.0, y0, 3.0, &[]), 1e-7),
        (
            "generalized-alpha",
            Integrator::solve(&GeneralizedAlpha::new(1.0, 2.5e-4), &p, 0.0, y0, 3.0, &[]),
            1e-4,
        ),
    ];
    for (name, run, tol) in runs {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let last = sol.y.last().unwrap();
        assert!(
            last[0] > 0.3 + 4.0 * std::f64::consts::PI,
            "{name}: th = {}",
            last[0]
        );
        let mut worst = (0.0f64, 0.0f64);
        for y in &sol.y {
            worst.0 = worst.0.max((energy(y[0], y[3]) - e0).abs() / e0.abs());
            let (phi, s) = close(y[0]);
            let wrap = (y[1] - phi + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            worst.1 = worst.1.max(wrap.abs()).max((y[2] - s).abs());
        }
        println!(
            "{name}: {} steps, energy {:.2e}, closure {:.2e}",
            sol.y.len(),
            worst.0,
            worst.1
        );
        assert!(
            worst.0 < tol && worst.1 < tol.max(1e-9),
            "{name}: {worst:?}"
        );
    }
}

/// Asked for `minimal`, the derive keeps the slide (the only closed form): its chart ends
/// where the slide turns back, and the run says so with a typed error there (`th = -pi/2`,
/// the slide at `d - a`), not with a wrong motion.
#[test]
fn the_minimal_form_on_the_slide_stops_where_the_slide_turns() {
    let p = reference!(QuickReturnMinimal);
    let y0 = p.initial_state();
    match Dopri5::new(Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    })
    .solve(&p, 0.0, y0, 3.0, &[])
    {
        Err(mbd::Error::SingularPosition { detail, .. }) => {
            assert!(detail.contains("s = "), "{detail}")
        }
        other => panic!("{other:?}"),
    }
}

/// Driven at `th = 0.3 + w t`: no free coordinate is left, the motion is the closure's, and
/// the drive's effort `reaction(th)` is `C w^2 - Q` (with `th'' = 0`), in both forms.
#[test]
fn driven_quick_return_drive_effort_matches_lagrange() {
    let p = reference!(Driven, w: W);
    let pa = reference!(DrivenAugmented, w: W);
    let opts = || Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    let runs = [
        Dopri5::new(opts())
            .solve(&p, 0.0, p.initial_state(), 2.0, &[])
            .map(|s| (s, "minimal")),
        Radau5::new(opts())
            .solve(&pa, 0.0, pa.initial_state(), 2.0, &[])
            .map(|s| (s, "augmented")),
    ];
    for run in runs {
        let (sol, form) = run.unwrap();
        for (&t, y) in sol.t.iter().zip(&sol.y).step_by(3) {
            let th = 0.3 + W * t;
            let (phi, s) = close(th);
            let wrap = (y[0] - phi + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            assert!(
                wrap.abs() < 1e-8 && (y[1] - s).abs() < 1e-8,
                "{form} t = {t}"
            );
            let (_, c, q) = lagrange_terms(th, true);
            let want = c * W * W - q;
            let got = if form == "minimal" {
                p.outputs(t, y).unwrap().motor
            } else {
                pa.outputs(t, y).unwrap().motor
            };
            assert!(
                (got - want).abs() < 1e-6 * (1.0 + want.abs()),
                "{form} t = {t}: {got} vs {want}"
            );
        }
    }
}
