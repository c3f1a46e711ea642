//! A change-point four-bar (crank a = 1, coupler b = 2, rocker c = 1.5, ground d = 2.5:
//! s + l = p + q = 3.5) driven through its change point by `phi = phi0 + omega t`.
//!
//! At `phi = pi` the crank points away from the rocker's pivot, `|A D| = a + d = b + c`,
//! and all four links lie on one line: the coupler along `+x` (`theta = 0`) and the rocker
//! along `-x` (`psi = pi`). There `Phi_q` with respect to `(theta, psi)`,
//! `[[-b sin theta, c sin psi], [b cos theta, -c cos psi]]`, has determinant
//! `b c sin(theta - psi) = 0`: the two assembly branches cross, and the driven mechanism
//! (no degree of freedom) may continue on either. Started at `phi0 = pi - 0.5` with
//! `omega = 1`, the change point is at `t = 0.5`. Whatever the method, the run must not
//! pass it silently: [`check_passages`] reports it as [`Error::SingularPosition`] at the
//! first recorded time at or after `t = 0.5` (DOPRI5 and Radau5 creep up to it and turn
//! back on the reflected branch, RK4 steps onto it and across), and finds nothing on a run that stops before it.

use mbd::analysis::{NewtonOptions, check_passages, kinematics};
use mbd::integrate::{Ali3, Integrator, Radau5, Rk4};
use mbd::prelude::*;
use mbd::{Dopri5, Error, Options, Solution};
use std::f64::consts::PI;

#[derive(Debug, Mechanism)]
#[mechanism(planar)]
#[coords(theta, psi)]
#[drive(phi = phi0 + omega * t)]
#[constraint(a * cos(phi) + b * cos(theta) == d + c * cos(psi))]
#[constraint(a * sin(phi) + b * sin(theta) == c * sin(psi))]
#[rigid(crank, mass = m, inertia = m * a * a / 12.0,
        at = [a / 2.0 * cos(phi), a / 2.0 * sin(phi)], angle = phi)]
#[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
        at = [a * cos(phi) + b / 2.0 * cos(theta), a * sin(phi) + b / 2.0 * sin(theta)],
        angle = theta)]
#[rigid(rocker, mass = m, inertia = m * c * c / 12.0,
        at = [d + c / 2.0 * cos(psi), c / 2.0 * sin(psi)], angle = psi)]
pub struct ChangePoint {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub phi0: f64,
    pub omega: f64,
    pub m: f64,
}

const T_CHANGE: f64 = 0.5;

fn mechanism() -> ChangePoint {
    ChangePoint {
        a: 1.0,
        b: 2.0,
        c: 1.5,
        d: 2.5,
        phi0: PI - T_CHANGE,
        omega: 1.0,
        m: 1.0,
    }
}

/// The assembled start on the branch with the coupler above the ground line.
fn start(m: &ChangePoint) -> (mbd::Vector<2>, mbd::Vector<2>) {
    let k = kinematics(
        m,
        0.0,
        &mbd::Vector::<2>::new(0.3, 2.6),
        &NewtonOptions::default(),
    )
    .unwrap();
    assert!(m.phi(0.0, &k.q).amax() < 1e-12);
    (k.q, k.qd)
}

fn runs(t1: f64) -> Vec<(&'static str, mbd::Result<Solution<4>>)> {
    let m = mechanism();
    let (q0, qd0) = start(&m);
    let y0 = mbd::Vector::<4>::new(q0[0], q0[1], qd0[0], qd0[1]);
    let o = Options {
        rtol: 1e-8,
        atol: 1e-8,
        ..Default::default()
    };
    vec![
        ("DOPRI5", Dopri5::new(o.clone()).solve(&m, 0.0, y0, t1, &[])),
        ("Radau5", Radau5::new(o).solve(&m, 0.0, y0, t1, &[])),
        ("RK4", Rk4::new(1e-3).solve(&m, 0.0, y0, t1, &[])),
        (
            "ALI3-P",
            Ali3::new(1e-3).solve::<_, 2, 2, 4>(&m, 0.0, q0, qd0, t1, &[]),
        ),
    ]
}

#[test]
fn every_method_reports_the_change_point() {
    let m = mechanism();
    for (name, run) in runs(1.0) {
        let verdict = run.and_then(|sol| check_passages::<_, 2, 2, 4>(&m, &sol));
        eprintln!("{name}: {verdict:?}");
        match verdict {
            Err(Error::SingularPosition { t, detail }) => {
                assert!(
                    (T_CHANGE..T_CHANGE + 0.2).contains(&t),
                    "{name}: at t = {t}"
                );
                // Found along the solution, the report names the configuration; found by
                // the right-hand side (the solve cannot meet the constraints there), the
                // residual it reached.
                assert!(
                    detail.contains("q = ")
                        || detail.contains("constraint equations are met only to"),
                    "{detail}"
                );
            }
            other => panic!("{name}: expected SingularPosition, got {other:?}"),
        }
    }
}

#[test]
fn no_passage_before_the_change_point() {
    let m = mechanism();
    for (name, run) in runs(0.45) {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(check_passages::<_, 2, 2, 4>(&m, &sol), Ok(()), "{name}");
    }
}

/// Through the bridge of `mbd::passage` (which carries a mobile loop across its singular
/// positions), the driven change-point four-bar has no degree of freedom to be carried
/// by: every method, the index-3 generalized-α included, ends with the same typed error
/// at the change point, naming the configuration.
#[test]
fn the_bridge_reports_the_change_point_on_every_method() {
    use mbd::integrate::GeneralizedAlpha;
    use mbd::passage::{self, Settings};
    let m = mechanism();
    let (q0, qd0) = start(&m);
    let y0 = mbd::Vector::<4>::new(q0[0], q0[1], qd0[0], qd0[1]);
    let o = Options {
        rtol: 1e-8,
        atol: 1e-8,
        ..Default::default()
    };
    let s = Settings::new(1e-8);
    let runs = vec![
        (
            "DOPRI5",
            passage::solve(&Dopri5::new(o.clone()), &m, 0.0, y0, 1.0, &[], &s),
        ),
        (
            "Radau5",
            passage::solve(&Radau5::new(o), &m, 0.0, y0, 1.0, &[], &s),
        ),
        (
            "RK4",
            passage::solve(&Rk4::new(1e-3), &m, 0.0, y0, 1.0, &[], &s),
        ),
        (
            "generalized-alpha",
            passage::solve_generalized_alpha::<_, 2, 2, 4, 4>(
                &GeneralizedAlpha::new(0.9, 1e-3),
                &m,
                0.0,
                y0,
                1.0,
                &[],
                &s,
            ),
        ),
    ];
    for (name, run) in runs {
        match run.map(|p| p.passages.len()) {
            Err(Error::SingularPosition { t, detail }) => {
                eprintln!("{name}: t = {t}: {detail}");
                assert!(
                    (T_CHANGE..T_CHANGE + 0.2).contains(&t),
                    "{name}: at t = {t}"
                );
                assert!(detail.contains("q = "), "{name}: {detail}");
            }
            other => panic!("{name}: expected SingularPosition, got {other:?}"),
        }
    }
}

/// The ordinary `solve` of every method (no `passage` call written) runs through the
/// bridge of a closed loop: the driven change-point four-bar, without a degree of freedom
/// to be carried by, ends with the same typed error at the change point on each, naming
/// the configuration, instead of an `Ok` on one branch or the other.
#[test]
fn the_ordinary_solve_reports_the_change_point_on_every_method() {
    use mbd::integrate::{Auto, Dop853, GeneralizedAlpha};
    let m = mechanism();
    let (q0, qd0) = start(&m);
    let y0 = mbd::Vector::<4>::new(q0[0], q0[1], qd0[0], qd0[1]);
    let o = Options {
        rtol: 1e-8,
        atol: 1e-8,
        ..Default::default()
    };
    let runs = vec![
        (
            "DOPRI5",
            Dopri5::new(o.clone()).solve(&m, 0.0, y0, 1.0, &[]),
        ),
        (
            "DOP853",
            Dop853::new(o.clone()).solve(&m, 0.0, y0, 1.0, &[]),
        ),
        ("Auto", Auto::new(o.clone()).solve(&m, 0.0, y0, 1.0, &[])),
        ("Radau5", Radau5::new(o).solve(&m, 0.0, y0, 1.0, &[])),
        ("RK4", Rk4::new(1e-3).solve(&m, 0.0, y0, 1.0, &[])),
        (
            "generalized-alpha",
            GeneralizedAlpha::new(0.9, 1e-3).solve_constrained::<_, 2, 2, 4, 4>(
                &m,
                0.0,
                q0,
                qd0,
                1.0,
                &[],
            ),
        ),
    ];
    for (name, run) in runs {
        match run {
            Err(Error::SingularPosition { t, detail }) => {
                eprintln!("{name}: t = {t}: {detail}");
                // A right-hand side refuses the accelerations in a window around the
                // change point, so a stop may come just before it (DOP853: 1.3e-7 s).
                assert!(
                    (T_CHANGE - 1e-6..T_CHANGE + 0.2).contains(&t),
                    "{name}: at t = {t}"
                );
                assert!(detail.contains("q = "), "{name}: {detail}");
            }
            other => panic!("{name}: expected SingularPosition, got {other:?}"),
        }
    }
}
