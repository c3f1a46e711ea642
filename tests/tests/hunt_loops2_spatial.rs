//! Hunt: a spatial RSSR four-bar written with coordinates and one loop equation: a crank `a`
//! about the ground `z` axis (`th`), a rocker `c` about the ground `x` direction through
//! `D = (dx, dy, dz)` (`ps`), and a coupler of length `b` on ball joints between the tips
//! `A = a (cos th, sin th, 0)` and `C = D + c (0, cos ps, sin ps)`, modelled as a point mass
//! at its middle (its spin about its own axis carries nothing). Gravity along `-z`.
//!
//! Reference, by hand: the closure `|A - C| = b` is `P cos ps + Q sin ps = K` with
//! `P = A_y - dy`, `Q = A_z - dz`, `K = (|A - D|^2 + c^2 - b^2) / (2 c)`, so
//! `ps = atan2(Q, P) + acos(K / hypot(P, Q))` (the init's branch); then Lagrange's equation
//! in `th`, `J th'' + C th'^2 = Q_g`, from the mass points and the two rotations
//! (`J = sum m |p'|^2 + Iz + Ix ps'^2`, five-point differences in `th`).

#![allow(
    clippy::needless_range_loop,
    reason = "the references index bodies and components of parallel arrays"
)]

use mbd::integrate::{Dop853, Dopri5, Integrator, Radau5, Vern9};
use mbd::prelude::*;
use std::f64::consts::PI;

#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[coords(th, ps)]
#[constraint(dot([a * cos(th) - dx, a * sin(th) - dy - c * cos(ps), -dz - c * sin(ps)],
                 [a * cos(th) - dx, a * sin(th) - dy - c * cos(ps), -dz - c * sin(ps)]) == b * b)]
#[rigid3(crank, mass = 1.0, inertia = diag(0.01, 0.1, 0.1), at = [a / 2.0 * cos(th), a / 2.0 * sin(th), 0.0],
         rotation = rot_z(th))]
#[rigid3(rocker, mass = 1.5, inertia = diag(0.2, 0.05, 0.2),
         at = [dx, dy + c / 2.0 * cos(ps), dz + c / 2.0 * sin(ps)], rotation = rot_x(ps))]
#[particle(coupler, mass = 2.0, at = [(a * cos(th) + dx) / 2.0, (a * sin(th) + dy + c * cos(ps)) / 2.0,
                                      (dz + c * sin(ps)) / 2.0])]
#[init(th = 0.0, ps = -0.628696650643876, der(th) = 3.0)]
pub struct Rssr {
    #[default(1.0)]
    pub a: f64,
    #[default(2.0)]
    pub b: f64,
    #[default(1.2)]
    pub c: f64,
    #[default(0.2)]
    pub dx: f64,
    #[default(0.5)]
    pub dy: f64,
    #[default(1.8)]
    pub dz: f64,
    #[default(9.81)]
    pub g: f64,
}

const P: Rssr = Rssr {
    a: 1.0,
    b: 2.0,
    c: 1.2,
    dx: 0.2,
    dy: 0.5,
    dz: 1.8,
    g: 9.81,
};
const MASS: [f64; 3] = [1.0, 1.5, 2.0];
/// The crank's inertia about `z`, the rocker's about `x`.
const IZ: f64 = 0.1;
const IX: f64 = 0.2;

/// `ps` at `th` for coupler length `b`; `None` where the loop cannot close.
fn close(th: f64, b: f64) -> Option<f64> {
    let (ax, ay) = (P.a * th.cos(), P.a * th.sin());
    let (p, q) = (ay - P.dy, -P.dz);
    let ad2 = (ax - P.dx).powi(2) + p * p + q * q;
    let k = (ad2 + P.c * P.c - b * b) / (2.0 * P.c);
    let u = k / p.hypot(q);
    (u.abs() < 1.0).then(|| q.atan2(p) + u.acos())
}

/// The three mass points and the rocker angle at `th` (coupler length `P.b`).
fn points(th: f64) -> [[f64; 3]; 4] {
    let ps = close(th, P.b).expect("closes");
    let a = [P.a * th.cos(), P.a * th.sin(), 0.0];
    let c = [P.dx, P.dy + P.c * ps.cos(), P.dz + P.c * ps.sin()];
    [
        [a[0] / 2.0, a[1] / 2.0, 0.0],
        [
            P.dx,
            P.dy + P.c / 2.0 * ps.cos(),
            P.dz + P.c / 2.0 * ps.sin(),
        ],
        [
            (a[0] + c[0]) / 2.0,
            (a[1] + c[1]) / 2.0,
            (a[2] + c[2]) / 2.0,
        ],
        [ps, 0.0, 0.0],
    ]
}

/// `(J, C, Q)` of Lagrange's equation at `th`.
fn lagrange_terms(th: f64) -> (f64, f64, f64) {
    let h = 1e-3;
    let s = [-2.0, -1.0, 0.0, 1.0, 2.0].map(|k| points(th + k * h));
    let d = |b: usize, k: usize| {
        let v = |i: usize| s[i][b][k];
        (
            (v(0) - 8.0 * v(1) + 8.0 * v(3) - v(4)) / (12.0 * h),
            (-v(0) + 16.0 * v(1) - 30.0 * v(2) + 16.0 * v(3) - v(4)) / (12.0 * h * h),
        )
    };
    let (mut j, mut c, mut q) = (IZ, 0.0, 0.0);
    for b in 0..3 {
        for k in 0..3 {
            let (d1, d2) = d(b, k);
            j += MASS[b] * d1 * d1;
            c += MASS[b] * d1 * d2;
        }
        q -= P.g * MASS[b] * d(b, 2).0;
    }
    let (d1, d2) = d(3, 0);
    (j + IX * d1 * d1, c + IX * d1 * d2, q)
}

fn energy(th: f64, thd: f64) -> f64 {
    let (j, _, _) = lagrange_terms(th);
    0.5 * j * thd * thd
        + P.g
            * points(th)
                .iter()
                .take(3)
                .zip(MASS)
                .map(|(p, m)| m * p[2])
                .sum::<f64>()
}

#[test]
fn the_spatial_loop_is_reduced_to_the_crank_angle_on_the_inits_branch() {
    assert_eq!(Rssr::COORDINATES, ["th"]);
    assert!(Rssr::GENERATED.parts.contains(&"minimal_closed_form"));
    assert!((close(0.0, P.b).unwrap() + 0.628696650643876).abs() < 1e-14);
}

#[test]
fn accelerations_match_lagrange_over_a_turn() {
    for k in 0..24 {
        let th = k as f64 * PI / 12.0;
        for thd in [0.0, 3.0] {
            let (j, c, q) = lagrange_terms(th);
            let want = (q - c * thd * thd) / j;
            let got = P
                .acceleration(0.0, &Vector::<1>::new(th), &Vector::<1>::new(thd))
                .unwrap()[0];
            assert!(
                (got - want).abs() < 1e-7 * want.abs().max(1.0),
                "th {th}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn turning_crank_keeps_the_hand_energy_on_every_adaptive_method() {
    // Fast enough to turn round against gravity.
    let y0 = Vector::<2>::new(0.0, 8.0);
    let e0 = energy(0.0, 8.0);
    let opts = |tol: f64| Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    };
    let t1 = 4.0;
    for (name, run) in [
        (
            "dopri5",
            Dopri5::new(opts(1e-10)).solve(&P, 0.0, y0, t1, &[]),
        ),
        (
            "dop853",
            Dop853::new(opts(1e-10)).solve(&P, 0.0, y0, t1, &[]),
        ),
        ("vern9", Vern9::new(opts(1e-10)).solve(&P, 0.0, y0, t1, &[])),
        (
            "radau5",
            Radau5::new(opts(1e-9)).solve(&P, 0.0, y0, t1, &[]),
        ),
    ] {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let y = sol.y.last().unwrap();
        assert!(y[0] > 2.0 * PI, "{name}: the crank turned to {}", y[0]);
        for y in &sol.y {
            let e = energy(y[0], y[1]);
            assert!((e - e0).abs() < 1e-6 * e0, "{name}: {e} vs {e0}");
        }
    }
}

/// A coupler set shorter at run time (`b = 1.3`) cannot reach round: the rocker's angle
/// `acos` argument reaches 1 at the crank's limit. From rest at `th = 0` under gravity the
/// crank, started at `th' = 4`, reaches that limit (`th = 2.82`): the run must stop there
/// with a typed `SingularPosition`.
#[test]
fn a_short_coupler_stops_at_the_cranks_limit() {
    let b = 1.3;
    let p = Rssr { b, ..P };
    let limit = (0..=3600)
        .map(|k| k as f64 * PI / 1800.0)
        .find(|&th| close(th, b).is_none());
    let limit = limit.expect("the crank has a limit");
    let y0 = Vector::<2>::new(0.0, 4.0);
    assert!(close(0.0, b).is_some());
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    match Dopri5::new(opts).solve(&p, 0.0, y0, 3.0, &[]) {
        Err(mbd::Error::SingularPosition { t, detail }) => {
            println!("stopped at t = {t}: {detail} (limit th {limit})");
            let sol = Dopri5::new(Options {
                rtol: 1e-10,
                atol: 1e-10,
                ..Options::default()
            })
            .solve(&p, 0.0, y0, 0.999 * t, &[])
            .unwrap();
            let th = sol.y.last().unwrap()[0];
            assert!(
                (th - limit).abs() < 2e-2,
                "stopped at th = {th}, limit {limit}"
            );
        }
        Ok(sol) => panic!(
            "Ok, crank reached {}",
            sol.y.iter().map(|y| y[0]).fold(f64::MIN, f64::max)
        ),
        Err(e) => panic!("{e}"),
    }
}
