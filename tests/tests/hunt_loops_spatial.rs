//! Hunt: a spatial RSUR linkage (a crank about `z`, a coupler on a spherical joint at its tip,
//! a rocker about `y`, the coupler's far end joined to the rocker's tip by a universal
//! `close`), one degree of freedom, free under gravity along `-z`, in both forms and on every
//! method. Every body has an isotropic inertia `j 1` (so `T = sum m |v|^2 / 2 + j |w|^2 / 2`
//! needs no body axes).
//!
//! References, derived here: the loop's length condition by hand from the two joint angles
//! (`A = a (cos th, sin th, 0)`, `C = P + c (sin ps, 0, cos ps)`, `|C - A| = b`); the energy
//! `T + V` summed here from the mass centres' velocities and positions and the bodies'
//! angular velocities (kinematic outputs: the dynamics, `M` and the forces, are not used), which
//! the motion must conserve.

use mbd::Vector;
use mbd::integrate::{
    Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;

macro_rules! rsur {
    ($name:ident, $($opt:ident),*) => {
        /// RSUR: crank `th`, coupler `s1 s2 s3`, rocker `ps`.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism(spatial, $($opt),*)]
        #[gravity(0.0, 0.0, -g)]
        #[body(crank, joint = revolute(th, z), com = [a / 2.0, 0.0, 0.0], mass = m, inertia = diag(j, j, j))]
        #[body(coupler, parent = crank, joint = spherical(s1, s2, s3), at = [a, 0.0, 0.0],
               com = [b / 2.0, 0.0, 0.0], mass = m, inertia = diag(j, j, j))]
        #[body(rocker, joint = revolute(ps, y), at = [px, py, 0.0], com = [0.0, 0.0, c / 2.0],
               mass = m, inertia = diag(j, j, j))]
        #[close(cross, joint = universal, a = coupler, at_a = [b, 0.0, 0.0], axis_a = [0.0, 0.0, 1.0],
                b = rocker, at_b = [0.0, 0.0, c], axis_b = [0.0, 1.0, 0.0])]
        #[output(v1 = velocity(crank), v2 = velocity(coupler), v3 = velocity(rocker),
                 w1 = angular_velocity(crank), w2 = angular_velocity(coupler), w3 = angular_velocity(rocker),
                 z1 = position(crank)[2], z2 = position(coupler)[2], z3 = position(rocker)[2])]
        pub struct $name {
            pub a: f64, pub b: f64, pub c: f64, pub px: f64, pub py: f64,
            pub m: f64, pub j: f64, pub g: f64,
        }
    };
}
rsur!(RsurAugmented, jacobian, augmented);

const P: [f64; 8] = [1.0, 2.5, 1.5, 0.5, 2.5, 1.0, 0.05, 9.81];

fn augmented() -> RsurAugmented {
    let [a, b, c, px, py, m, j, g] = P;
    RsurAugmented {
        a,
        b,
        c,
        px,
        py,
        m,
        j,
        g,
    }
}

/// `|C - A| - b` from the crank and rocker angles alone.
fn length_residual(th: f64, ps: f64) -> f64 {
    let [a, b, c, px, py, ..] = P;
    let (ax, ay) = (a * th.cos(), a * th.sin());
    let (cx, cy, cz) = (px + c * ps.sin(), py, c * ps.cos());
    ((cx - ax).powi(2) + (cy - ay).powi(2) + cz * cz).sqrt() - b
}

/// The assembled start at `th = 0.3`, at rest: `[th, s1, s2, s3, ps]`.
fn start() -> Vector<5> {
    let pa = augmented();
    let guess = Vector::<5>::from([0.3, 0.95, -0.38, 0.0, 0.9]);
    let held = [true, false, false, false, false];
    mbd::analysis::assembly::assemble(&pa, 0.0, &guess, &held, &Default::default()).unwrap()
}

fn energy(o: &[f64], m: f64, j: f64, g: f64) -> f64 {
    // o: v1 v2 v3 (3 each), w1 w2 w3 (3 each), z1 z2 z3.
    let sq = |k: usize| o[k] * o[k] + o[k + 1] * o[k + 1] + o[k + 2] * o[k + 2];
    let t = 0.5 * m * (sq(0) + sq(3) + sq(6)) + 0.5 * j * (sq(9) + sq(12) + sq(15));
    t + m * g * (o[18] + o[19] + o[20])
}

#[test]
fn the_start_closes_the_loop_by_hand() {
    let q = start();
    assert!(length_residual(q[0], q[4]).abs() < 1e-12);
    assert!(q[0] == 0.3);
}

/// The start at rest, and what each method keeps of the energy and of the loop.
fn check_runs<S>(
    p: &S,
    outputs: impl Fn(f64, &Vector<10>) -> [f64; 21],
    runs: Vec<(&str, mbd::Result<Solution<10>>, f64)>,
) where
    S: Mechanism<5>,
{
    let [.., m, j, g] = P;
    let y0 = runs_start();
    let e0 = energy(&outputs(0.0, &y0), m, j, g);
    let _ = p;
    for (name, run, tol) in runs {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut worst = (0.0f64, 0.0f64);
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            worst.0 = worst.0.max((energy(&outputs(t, y), m, j, g) - e0).abs());
            worst.1 = worst.1.max(length_residual(y[0], y[4]).abs());
        }
        let last = sol.y.last().unwrap();
        println!(
            "{name}: {} steps, energy {:.2e}, length {:.2e}, th {:.4} -> {:.6}",
            sol.y.len(),
            worst.0,
            worst.1,
            y0[0],
            last[0]
        );
        assert!(
            worst.0 < tol && worst.1 < tol.max(1e-9),
            "{name}: {worst:?}"
        );
        assert!((last[0] - y0[0]).abs() > 0.05, "{name}: it moved");
    }
}

fn runs_start() -> Vector<10> {
    let q = start();
    Vector::<10>::from_fn(|i, _| if i < 5 { q[i] } else { 0.0 })
}

fn all_methods<S: OdeSystem<10>>(p: &S) -> Vec<(&'static str, mbd::Result<Solution<10>>, f64)> {
    let y0 = runs_start();
    let tight = || Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    vec![
        (
            "dopri5",
            Dopri5::new(tight()).solve(p, 0.0, y0, 1.5, &[]),
            1e-7,
        ),
        (
            "dop853",
            Dop853::new(tight()).solve(p, 0.0, y0, 1.5, &[]),
            1e-7,
        ),
        (
            "vern9",
            Vern9::new(tight()).solve(p, 0.0, y0, 1.5, &[]),
            1e-7,
        ),
        (
            "radau5",
            Radau5::new(Options {
                rtol: 1e-8,
                atol: 1e-8,
                ..Options::default()
            })
            .solve(p, 0.0, y0, 1.5, &[]),
            1e-5,
        ),
        ("rk4", Rk4::new(2e-3).solve(p, 0.0, y0, 1.5, &[]), 1e-6),
        ("gauss", Gauss::new(4e-3).solve(p, 0.0, y0, 1.5, &[]), 1e-6),
        (
            "generalized-alpha",
            Integrator::solve(&GeneralizedAlpha::new(1.0, 5e-4), p, 0.0, y0, 1.5, &[]),
            1e-4,
        ),
    ]
}

#[test]
fn augmented_form_conserves_energy_and_closes_the_loop_on_every_method() {
    let p = augmented();
    let out = |t: f64, y: &Vector<10>| p.output_values(t, y).unwrap();
    check_runs(&p, out, all_methods(&p));
}
