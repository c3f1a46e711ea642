//! Hunt: a Stephenson six-bar whose dependent links form a triad (an Assur group of class
//! III): a crank `a` about `O1 = (0, 0)` (angle `th`), a link `b` (`be`) from its tip `B` to
//! the vertex `C` of a ternary plate (angle `ps`; vertices `E = C + r1 u(ps)` and
//! `H = C + r2 u(ps + al)`), and two rockers `e` about `O2` (`ep`, tip at `E`) and `h` about
//! `O3` (`et`, tip at `H`); `u(x) = (cos x, sin x)`. The two ternary links (ground and
//! plate) are not adjacent. No pair of loop equations holds only two unknown angles, so the
//! closure has no closed form: the default model is augmented, and `minimal` is refused at
//! compile time (tests/ui/hunt_loops2/stephenson_triad_minimal.rs).
//!
//! Reference, derived here: the closure by Newton's method on the four loop equations (from
//! the init's configuration, continued in small steps), the bodies' mass centres and angles
//! as functions of `th`, five-point derivatives, and Lagrange's equation in `th`:
//! `J th'' + C th'^2 = Q`, `J = sum m |p'|^2 + I phi'^2`, `C = sum m p'.p'' + I phi' phi''`,
//! `Q = -g sum m p'_y`. Energy `T + V` by hand from the full state.

#![allow(
    clippy::needless_range_loop,
    reason = "the references index bodies and components of parallel arrays"
)]

use mbd::integrate::{Ali3, Dop853, Dopri5, GeneralizedAlpha, Integrator, Radau5, Vern9};
use mbd::prelude::*;
use mbd::{Matrix, Vector};
use std::cell::Cell;

macro_rules! stephenson {
    ($name:ident, [$($opt:ident),*]) => {
        /// The Stephenson six-bar above.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism(planar $(, $opt)*)]
        #[gravity(0.0, -g)]
        #[coords(th, be, ps, ep, et)]
        #[constraint(a * cos(th) + b * cos(be) + r1 * cos(ps) == o2x + e * cos(ep))]
        #[constraint(a * sin(th) + b * sin(be) + r1 * sin(ps) == o2y + e * sin(ep))]
        #[constraint(a * cos(th) + b * cos(be) + r2 * cos(ps + al) == o3x + h * cos(et))]
        #[constraint(a * sin(th) + b * sin(be) + r2 * sin(ps + al) == o3y + h * sin(et))]
        #[rigid(crank, mass = 1.0, inertia = a * a / 12.0,
                at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
        #[rigid(link, mass = 1.5, inertia = 1.5 * b * b / 12.0,
                at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
        #[rigid(plate, mass = mt, inertia = it,
                at = [a * cos(th) + b * cos(be) + (r1 * cos(ps) + r2 * cos(ps + al)) / 3.0,
                      a * sin(th) + b * sin(be) + (r1 * sin(ps) + r2 * sin(ps + al)) / 3.0],
                angle = ps)]
        #[rigid(rocker2, mass = 1.2, inertia = 1.2 * e * e / 12.0,
                at = [o2x + e / 2.0 * cos(ep), o2y + e / 2.0 * sin(ep)], angle = ep)]
        #[rigid(rocker3, mass = 0.8, inertia = 0.8 * h * h / 12.0,
                at = [o3x + h / 2.0 * cos(et), o3y + h / 2.0 * sin(et)], angle = et)]
        #[init(th = 1.0, be = 0.3, ps = -0.4, ep = 1.9, et = 0.2, der(th) = 1.0)]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(2.0)] pub b: f64,
            #[default(1.2)] pub r1: f64,
            #[default(1.0)] pub r2: f64,
            #[default(1.2)] pub al: f64,
            #[default(1.5)] pub e: f64,
            #[default(1.3)] pub h: f64,
            #[default(4.041182827218069)] pub o2x: f64,
            #[default(-0.45424074417092675)] pub o2y: f64,
            #[default(1.8735954422729033)] pub o3x: f64,
            #[default(1.8915973589965187)] pub o3y: f64,
            #[default(2.0)] pub mt: f64,
            #[default(0.3)] pub it: f64,
            #[default(-9.81)] pub g: f64,
        }
    };
}
stephenson!(Stephenson, []);
stephenson!(StephensonAugmented, [augmented]);

const A: f64 = 1.0;
const B: f64 = 2.0;
const R1: f64 = 1.2;
const R2: f64 = 1.0;
const AL: f64 = 1.2;
const E: f64 = 1.5;
const H: f64 = 1.3;
const O2: [f64; 2] = [4.041182827218069, -0.45424074417092675];
const O3: [f64; 2] = [1.8735954422729033, 1.8915973589965187];
/// crank, link, plate, rocker2, rocker3.
const MASS: [f64; 5] = [1.0, 1.5, 2.0, 1.2, 0.8];
const INERTIA: [f64; 5] = [
    1.0 / 12.0,
    1.5 * 4.0 / 12.0,
    0.3,
    1.2 * 2.25 / 12.0,
    0.8 * 1.69 / 12.0,
];
/// Gravity along `+y` (`g < 0`): the crank then swings about a stable position near
/// `th = 1.1` (along `-y` that is the top, and the motion falls into a limit position).
const G: f64 = -9.81;

macro_rules! params {
    ($ty:ident) => {
        $ty {
            a: A,
            b: B,
            r1: R1,
            r2: R2,
            al: AL,
            e: E,
            h: H,
            o2x: O2[0],
            o2y: O2[1],
            o3x: O3[0],
            o3y: O3[1],
            mt: MASS[2],
            it: INERTIA[2],
            g: G,
        }
    };
}

/// The loop equations' residual and Jacobian in `x = [be, ps, ep, et]` at `th`.
fn loop_equations(th: f64, x: &Vector<4>) -> (Vector<4>, Matrix<4, 4>) {
    let [be, ps, ep, et] = [x[0], x[1], x[2], x[3]];
    let (cx, cy) = (A * th.cos() + B * be.cos(), A * th.sin() + B * be.sin());
    let r = Vector::<4>::new(
        cx + R1 * ps.cos() - O2[0] - E * ep.cos(),
        cy + R1 * ps.sin() - O2[1] - E * ep.sin(),
        cx + R2 * (ps + AL).cos() - O3[0] - H * et.cos(),
        cy + R2 * (ps + AL).sin() - O3[1] - H * et.sin(),
    );
    #[rustfmt::skip]
    let j = Matrix::<4, 4>::new(
        -B * be.sin(), -R1 * ps.sin(), E * ep.sin(), 0.0,
        B * be.cos(), R1 * ps.cos(), -E * ep.cos(), 0.0,
        -B * be.sin(), -R2 * (ps + AL).sin(), 0.0, H * et.sin(),
        B * be.cos(), R2 * (ps + AL).cos(), 0.0, -H * et.cos(),
    );
    (r, j)
}

thread_local! {
    /// The last closure solved, `(th, x)`: Newton starts there (continuation on the branch).
    static LAST: Cell<(f64, [f64; 4])> = const { Cell::new((1.0, [0.3, -0.4, 1.9, 0.2])) };
}

/// `[be, ps, ep, et]` at `th` by Newton's method, continued from the last solve (in steps of
/// at most 0.05 in `th`), on the init's branch.
fn close(th: f64) -> Vector<4> {
    let (mut t0, x0) = LAST.with(Cell::get);
    let mut x = Vector::<4>::from(x0);
    loop {
        let t = if (th - t0).abs() <= 0.05 {
            th
        } else {
            t0 + 0.05 * (th - t0).signum()
        };
        for _ in 0..50 {
            let (r, j) = loop_equations(t, &x);
            let dx = j.lu().solve(&r).expect("regular");
            x -= dx;
            if dx.amax() < 1e-15 {
                break;
            }
        }
        assert!(loop_equations(t, &x).0.amax() < 1e-13, "closure at {t}");
        t0 = t;
        if t == th {
            break;
        }
    }
    LAST.with(|c| c.set((th, [x[0], x[1], x[2], x[3]])));
    x
}

/// Each body's `(x, y, angle)` at crank angle `th`.
fn bodies(th: f64) -> [[f64; 3]; 5] {
    let x = close(th);
    let [be, ps, ep, et] = [x[0], x[1], x[2], x[3]];
    let (bx, by) = (A * th.cos(), A * th.sin());
    let (cx, cy) = (bx + B * be.cos(), by + B * be.sin());
    [
        [bx / 2.0, by / 2.0, th],
        [bx + B / 2.0 * be.cos(), by + B / 2.0 * be.sin(), be],
        [
            cx + (R1 * ps.cos() + R2 * (ps + AL).cos()) / 3.0,
            cy + (R1 * ps.sin() + R2 * (ps + AL).sin()) / 3.0,
            ps,
        ],
        [O2[0] + E / 2.0 * ep.cos(), O2[1] + E / 2.0 * ep.sin(), ep],
        [O3[0] + H / 2.0 * et.cos(), O3[1] + H / 2.0 * et.sin(), et],
    ]
}

/// `(J, C, Q)` of Lagrange's equation at `th`, by five-point differences (step 1e-3).
fn lagrange_terms(th: f64) -> (f64, f64, f64) {
    let h = 1e-3;
    let s = [-2.0, -1.0, 0.0, 1.0, 2.0].map(|k| bodies(th + k * h));
    let (mut j, mut c, mut q) = (0.0, 0.0, 0.0);
    for b in 0..5 {
        let w = |k: usize| [MASS[b], MASS[b], INERTIA[b]][k];
        for k in 0..3 {
            let v = |i: usize| s[i][b][k];
            let d1 = (v(0) - 8.0 * v(1) + 8.0 * v(3) - v(4)) / (12.0 * h);
            let d2 = (-v(0) + 16.0 * v(1) - 30.0 * v(2) + 16.0 * v(3) - v(4)) / (12.0 * h * h);
            j += w(k) * d1 * d1;
            c += w(k) * d1 * d2;
            if k == 1 {
                q -= G * MASS[b] * d1;
            }
        }
    }
    (j, c, q)
}

fn lagrange(th: f64, thd: f64) -> f64 {
    let (j, c, q) = lagrange_terms(th);
    (q - c * thd * thd) / j
}

/// The full state `[q; qd]` at `(th, th')` from the hand closure, the rates from the loop
/// equations' rate form `J x' = -dF/dth th'`.
fn full_state(th: f64, thd: f64) -> Vector<10> {
    let x = close(th);
    let (_, j) = loop_equations(th, &x);
    let (s, c) = (A * th.sin(), A * th.cos());
    let xd = j
        .lu()
        .solve(&Vector::<4>::new(s * thd, -c * thd, s * thd, -c * thd))
        .unwrap();
    let mut y = Vector::<10>::zeros();
    y[0] = th;
    y[5] = thd;
    for i in 0..4 {
        y[1 + i] = x[i];
        y[6 + i] = xd[i];
    }
    y
}

/// `T + V` by hand from a full state (bodies' velocities from the angles and rates).
fn energy_full(y: &Vector<10>) -> f64 {
    let u = |a: f64| [a.cos(), a.sin()];
    let n = |a: f64| [-a.sin(), a.cos()];
    let [th, be, ps, ep, et] = [y[0], y[1], y[2], y[3], y[4]];
    let [w0, w1, w2, w3, w4] = [y[5], y[6], y[7], y[8], y[9]];
    let add = |terms: &[(f64, [f64; 2])]| {
        terms
            .iter()
            .fold([0.0; 2], |s, (k, v)| [s[0] + k * v[0], s[1] + k * v[1]])
    };
    let vel = [
        add(&[(A / 2.0 * w0, n(th))]),
        add(&[(A * w0, n(th)), (B / 2.0 * w1, n(be))]),
        add(&[
            (A * w0, n(th)),
            (B * w1, n(be)),
            (R1 / 3.0 * w2, n(ps)),
            (R2 / 3.0 * w2, n(ps + AL)),
        ]),
        add(&[(E / 2.0 * w3, n(ep))]),
        add(&[(H / 2.0 * w4, n(et))]),
    ];
    let pos = [
        add(&[(A / 2.0, u(th))]),
        add(&[(A, u(th)), (B / 2.0, u(be))]),
        add(&[
            (A, u(th)),
            (B, u(be)),
            (R1 / 3.0, u(ps)),
            (R2 / 3.0, u(ps + AL)),
        ]),
        add(&[(1.0, O2), (E / 2.0, u(ep))]),
        add(&[(1.0, O3), (H / 2.0, u(et))]),
    ];
    let spin = [w0, w1, w2, w3, w4];
    (0..5)
        .map(|b| {
            0.5 * MASS[b] * (vel[b][0].powi(2) + vel[b][1].powi(2))
                + 0.5 * INERTIA[b] * spin[b] * spin[b]
                + G * MASS[b] * pos[b][1]
        })
        .sum()
}

#[test]
fn the_triad_stays_augmented_and_its_init_is_on_the_hand_closure() {
    assert_eq!(Stephenson::COORDINATES, ["th", "be", "ps", "ep", "et"]);
    assert_eq!(Stephenson::GENERATED.constraints, 4);
    let p = params!(Stephenson);
    let y = p.initial_state();
    let want = full_state(1.0, 1.0);
    assert!((y - want).amax() < 1e-12, "{y} vs {want}");
}

#[test]
fn accelerations_match_lagrange() {
    let (p, pa) = (params!(Stephenson), params!(StephensonAugmented));
    for (th, thd) in [(1.0, 1.0), (1.1, -0.5), (0.9, 2.0), (1.2, 0.0), (0.8, -1.5)] {
        let want = lagrange(th, thd);
        let y = full_state(th, thd);
        let (q, qd) = (
            y.fixed_rows::<5>(0).into_owned(),
            y.fixed_rows::<5>(5).into_owned(),
        );
        for a in [
            p.acceleration(0.0, &q, &qd).unwrap(),
            pa.acceleration(0.0, &q, &qd).unwrap(),
        ] {
            assert!(
                (a[0] - want).abs() < 1e-7 * want.abs().max(1.0),
                "th {th}: {} vs {want}",
                a[0]
            );
        }
    }
}

/// Released at `th' = 1`, the crank swings under gravity about its stable position (between
/// the crank's limit positions, `th = -2.21` and `1.838`); every method keeps the hand energy and the hand closure, and its
/// crank angle at `t = 1.5` is the reference's (Lagrange's equation in `th` by RK4 at
/// `h = 1e-3`, the closure by Newton).
#[test]
fn every_method_keeps_the_energy_and_follows_the_reference() {
    let p = params!(Stephenson);
    let y0 = p.initial_state();
    let e0 = energy_full(&y0);
    let t1: f64 = 1.5;
    // The reference.
    let f = |y: [f64; 2]| [y[1], lagrange(y[0], y[1])];
    let (h, mut r) = (1e-3, [1.0, 1.0]);
    for _ in 0..(t1 / h).round() as usize {
        let k1 = f(r);
        let k2 = f([r[0] + 0.5 * h * k1[0], r[1] + 0.5 * h * k1[1]]);
        let k3 = f([r[0] + 0.5 * h * k2[0], r[1] + 0.5 * h * k2[1]]);
        let k4 = f([r[0] + h * k3[0], r[1] + h * k3[1]]);
        for i in 0..2 {
            r[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    let opts = |tol: f64| Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    };
    let (q0, qd0) = (
        y0.fixed_rows::<5>(0).into_owned(),
        y0.fixed_rows::<5>(5).into_owned(),
    );
    let runs: Vec<(&str, mbd::Result<Solution<10>>, f64)> = vec![
        (
            "dopri5",
            Dopri5::new(opts(1e-10)).solve(&p, 0.0, y0, t1, &[]),
            1e-7,
        ),
        (
            "dop853",
            Dop853::new(opts(1e-10)).solve(&p, 0.0, y0, t1, &[]),
            1e-7,
        ),
        (
            "vern9",
            Vern9::new(opts(1e-10)).solve(&p, 0.0, y0, t1, &[]),
            1e-7,
        ),
        (
            "radau5",
            Radau5::new(opts(1e-9)).solve(&p, 0.0, y0, t1, &[]),
            1e-6,
        ),
        (
            "generalized-alpha index 3",
            GeneralizedAlpha::new(0.9, 1e-3).solve_constrained::<_, 5, 4, 9, 10>(
                &p,
                0.0,
                q0,
                qd0,
                t1,
                &[],
            ),
            1e-3,
        ),
        (
            "ali3",
            Ali3::new(1e-3).solve(&p, 0.0, q0, qd0, t1, &[]),
            1e-3,
        ),
    ];
    for (name, run, tol) in runs {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        for y in &sol.y {
            let phi = Constrained::<5, 4>::phi(&p, 0.0, &y.fixed_rows::<5>(0).into_owned());
            assert!(phi.amax() < 1e-8, "{name}: closure {phi}");
            let e = energy_full(y);
            assert!(
                (e - e0).abs() < tol * e0.abs().max(1.0),
                "{name}: energy {e} vs {e0}"
            );
        }
        let y = sol.y.last().unwrap();
        let th_tol = if tol > 1e-5 { 1e-3 } else { 1e-6 };
        println!("{name}: th {} vs {}", y[0], r[0]);
        assert!(
            (y[0] - r[0]).abs() < th_tol && (y[5] - r[1]).abs() < 10.0 * th_tol,
            "{name}: {y} vs {r:?}"
        );
    }
}

/// Gravity along `-y` (set at run time): from the same start the crank falls into its limit
/// position `th = 1.838` (the triad's configuration folds there; the mechanism is regular),
/// and turns back as the triad moves on. The augmented form must pass it: energy and closure
/// kept, the crank's largest angle the limit.
#[test]
fn gravity_down_passes_the_cranks_limit_position() {
    let p = Stephenson {
        g: 9.81,
        ..params!(Stephenson)
    };
    let y0 = p.initial_state();
    // The hand energy with gravity down: the kinetic part, minus the potential twice over.
    let potential = |y: &Vector<10>| {
        let mut rest = *y;
        rest.fixed_rows_mut::<5>(5).fill(0.0);
        energy_full(&rest)
    };
    let energy = |y: &Vector<10>| energy_full(y) - 2.0 * potential(y);
    let e0 = energy(&y0);
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    let sol = Dopri5::new(opts).solve(&p, 0.0, y0, 3.0, &[]).unwrap();
    let top = sol.y.iter().map(|y| y[0]).fold(f64::MIN, f64::max);
    println!("top th {top}, ends {}", sol.y.last().unwrap());
    assert!((top - 1.838).abs() < 2e-3, "the crank reached {top}");
    assert!(
        sol.y.last().unwrap()[0] < top - 0.1,
        "the crank turned back"
    );
    for y in &sol.y {
        let phi = Constrained::<5, 4>::phi(&p, 0.0, &y.fixed_rows::<5>(0).into_owned());
        assert!(phi.amax() < 1e-8, "closure {phi}");
        assert!(
            (energy(y) - e0).abs() < 1e-6 * e0.abs().max(1.0),
            "energy {} vs {e0}",
            energy(y)
        );
    }
}
