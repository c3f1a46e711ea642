//! Hunt: a parallelogram with a redundant third crank written as a new user writes it, with
//! coordinates and loop equations (`#[coords]` and four `#[constraint]`s of rank three), hanging
//! and swinging gently (never near a flat, singular position), on every method.
//!
//! Three cranks of length `l` (mass `m`, uniform) pinned at `x = 0, l, 2 l`, their tips on one
//! coupler (length `2 l`, mass `mc`) at angle `be`. **Reference, by hand:** the cranks turn
//! together by `th` and the coupler translates, so
//! `T = (3 m l^2 / 3 + mc l^2) th'^2 / 2`, `V = (3 m / 2 + mc) g l sin th`, and
//! `(m + mc) l^2 th'' = -(3 m / 2 + mc) g l cos th`, integrated here by DOPRI5 at 1e-13.

use mbd::integrate::{
    Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;
use mbd::{OdeSystem, Vector};
use std::f64::consts::FRAC_PI_2;

/// Cranks `t0`, `t1`, `t2` (absolute angles), coupler `be`.
#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[coords(t0, t1, t2, be)]
#[constraint(l * cos(t0) + l * cos(be) == l + l * cos(t1))]
#[constraint(l * sin(t0) + l * sin(be) == l * sin(t1))]
#[constraint(l * cos(t0) + 2.0 * l * cos(be) == 2.0 * l + l * cos(t2))]
#[constraint(l * sin(t0) + 2.0 * l * sin(be) == l * sin(t2))]
#[rigid(crank0, mass = m, inertia = m * l * l / 12.0, at = [l / 2.0 * cos(t0), l / 2.0 * sin(t0)], angle = t0)]
#[rigid(crank1, mass = m, inertia = m * l * l / 12.0, at = [l + l / 2.0 * cos(t1), l / 2.0 * sin(t1)], angle = t1)]
#[rigid(crank2, mass = m, inertia = m * l * l / 12.0, at = [2.0 * l + l / 2.0 * cos(t2), l / 2.0 * sin(t2)], angle = t2)]
#[rigid(coupler, mass = mc, inertia = mc * 4.0 * l * l / 12.0,
        at = [l * cos(t0) + l * cos(be), l * sin(t0) + l * sin(be)], angle = be)]
#[output(spread = t2 - t0)]
pub struct ThreeCranks {
    pub m: f64,
    pub mc: f64,
    pub l: f64,
    pub g: f64,
}

const S: ThreeCranks = ThreeCranks {
    m: 1.0,
    mc: 2.0,
    l: 1.0,
    g: 9.81,
};

struct Reduced;

impl OdeSystem<2> for Reduced {
    fn rhs(&self, _t: f64, y: &Vector<2>) -> mbd::Result<Vector<2>> {
        let (s, j) = ((1.5 * S.m + S.mc) * S.g * S.l, (S.m + S.mc) * S.l * S.l);
        Ok(Vector::<2>::new(y[1], -s * y[0].cos() / j))
    }
}

const W0: f64 = 0.5;

/// The one-coordinate reduction from the bottom at `th' = W0` to `t1`, by DOPRI5 at 1e-13.
fn reference(t1: f64) -> Solution<2> {
    let tight = Options {
        rtol: 1e-13,
        atol: 1e-13,
        ..Options::default()
    };
    Dopri5::new(tight)
        .solve(&Reduced, 0.0, Vector::<2>::new(-FRAC_PI_2, W0), t1, &[])
        .unwrap()
}

fn start() -> Vector<8> {
    Vector::<8>::from_row_slice(&[-FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2, 0.0, W0, W0, W0, 0.0])
}

#[test]
fn redundancy_is_found_and_the_multipliers_are_finite() {
    let q = start().fixed_rows::<4>(0).into_owned();
    let qd = start().fixed_rows::<4>(4).into_owned();
    let (rank, redundant) = mbd::analysis::rank_and_redundant(&S.phi_q(0.0, &q));
    assert_eq!((rank, redundant.len()), (3, 1));
    let (qdd, lambda) = S.acceleration_and_multipliers(0.0, &q, &qd).unwrap();
    // At the bottom, th'' = 0 (cos th = 0): every crank's, the coupler's too.
    assert!(qdd.amax() < 1e-10, "{qdd}");
    assert!(lambda.iter().all(|v| v.is_finite()));
}

/// The end of every run.
const T1: f64 = 3.0;

/// A run of `method` from `start()` to `T1`, named, with the tolerance its check allows.
fn follow(
    name: &'static str,
    method: impl Integrator,
    check: f64,
) -> (&'static str, mbd::Result<Solution<8>>, f64) {
    (name, method.solve(&S, 0.0, start(), T1, &[]), check)
}

#[test]
fn every_method_follows_the_one_coordinate_reduction() {
    let t1 = T1;
    let opts = |tol: f64| Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    };
    let reference = reference(t1);
    let y0 = start();
    let runs: Vec<(&str, mbd::Result<Solution<8>>, f64)> = vec![
        follow("dopri5 1e-6", Dopri5::new(opts(1e-6)), 1e-5),
        follow("dopri5 1e-9", Dopri5::new(opts(1e-9)), 1e-8),
        follow("dopri5 1e-12", Dopri5::new(opts(1e-12)), 1e-10),
        follow("dop853 1e-10", Dop853::new(opts(1e-10)), 1e-8),
        follow("vern9 1e-12", Vern9::new(opts(1e-12)), 1e-10),
        follow("radau5 1e-6", Radau5::new(opts(1e-6)), 1e-4),
        follow("radau5 1e-9", Radau5::new(opts(1e-9)), 1e-7),
        follow("rk4 1e-2", Rk4::new(1e-2), 1e-6),
        follow("gauss 1e-2", Gauss::new(1e-2), 1e-6),
        follow(
            "generalized-alpha 1e-3",
            GeneralizedAlpha::new(0.9, 1e-3),
            1e-4,
        ),
        (
            "ali3 1e-3",
            mbd::integrate::Ali3::new(1e-3).solve::<_, 4, 4, 8>(
                &S,
                0.0,
                y0.fixed_rows::<4>(0).into_owned(),
                y0.fixed_rows::<4>(4).into_owned(),
                t1,
                &[],
            ),
            1e-4,
        ),
    ];
    let mut failures = vec![];
    for (name, run, tol) in runs {
        let sol = match run {
            Ok(sol) => sol,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let mut worst = (0.0f64, 0.0f64);
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            let r = reference.at(t).unwrap();
            worst.0 = worst.0.max((y[0] - r[0]).abs());
            worst.1 = worst
                .1
                .max((y[1] - y[0]).abs())
                .max((y[2] - y[0]).abs())
                .max(y[3].abs());
        }
        println!(
            "{name}: {} steps, crank error {:.2e}, off the parallelogram {:.2e}",
            sol.y.len(),
            worst.0,
            worst.1
        );
        if !(worst.0 < tol && worst.1 < tol) {
            failures.push(format!("{name}: {worst:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Generalized-alpha's index-3 form (`solve_constrained`) factors `[M, Phi_q^T; Phi_q, 0]`-like
/// Newton matrices, singular with a redundant row (it stopped at its first step); the row found
/// redundant at the start leaves Newton's system (its multiplier zero) and the run follows the
/// one-coordinate reduction like the same method through `Integrator::solve` and ALI3-P (above).
#[test]
fn generalized_alpha_index_three_runs_with_a_redundant_crank() {
    let t1 = 3.0;
    let y0 = start();
    let reference = reference(t1);
    let sol = GeneralizedAlpha::new(0.9, 1e-3)
        .solve_constrained::<_, 4, 4, 8, 8>(
            &S,
            0.0,
            y0.fixed_rows::<4>(0).into_owned(),
            y0.fixed_rows::<4>(4).into_owned(),
            t1,
            &[],
        )
        .unwrap();
    for (&t, y) in sol.t.iter().zip(&sol.y) {
        assert!((y[0] - reference.at(t).unwrap()[0]).abs() < 1e-4, "t = {t}");
    }
}
