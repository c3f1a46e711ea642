//! `Options::stiffness_check` on a stiff flyball governor: with the test on (Hairer's
//! `NSTIFF`, every 1000 accepted steps) DOPRI5 stops with [`Error::Stiff`] at loose
//! tolerances, where its step is held at the stability limit; with it off (`None`) the same
//! runs finish, slowly, and agree with a Radau5 reference.
//!
//! # The governor
//! A Watt governor reduced by its symmetry: a spindle turned at a constant rate `w` about
//! the vertical; two massless arms of length `l` hinged at the spindle's top (the origin),
//! at the angle `phi` from the downward vertical, each carrying a ball of mass `m`; a sleeve
//! of mass `ms` sliding on the spindle at height `z` (negative: below the hinge), joined to
//! each ball by a link of free length `l` that is a stiff spring (`k = 8e5 N/m`) with a
//! damper `c` in parallel. In the frame turning with the spindle, ball
//! `(l sin phi, -l cos phi)`, sleeve `(0, z)`, link length
//! `d = sqrt(l^2 sin^2 phi + (l cos phi + z)^2)`, with
//! `d_phi = -z l sin(phi) / d` and `d_z = (l cos phi + z) / d`.
//!
//! Lagrange's equations of `T = m l^2 phi'^2 + m w^2 l^2 sin^2 phi + ms z'^2 / 2` and
//! `V = -2 m g l cos phi + ms g z + k (d - l)^2`, with the link force
//! `F = k (d - l) + c d'` (`d' = d_phi phi' + d_z z'`):
//!
//! `2 m l^2 phi'' = 2 m l^2 w^2 sin phi cos phi - 2 m g l sin phi - 2 F d_phi`,
//! `ms z'' = -ms g - 2 F d_z`.
//!
//! At the release the largest eigenvalue of the Jacobian has `|lambda| = 1.5e4 s^-1`
//! (the links' stretch, damped by `c = 1e4 N s/m`), far from the slow swing of the arms:
//! DOPRI5's step is then held near `3.3 / 1.5e4 s` whatever a loose tolerance asks, which is
//! what stiffness means and what the detector is for.

use mbd_core::integrate::{Dopri5, Integrator, Options, Radau5, Record};
use mbd_core::{Error, OdeSystem, Result, Vector};

/// The governor of the module docs; state `[phi, z, phi', z']`.
struct Flyball {
    m: f64,
    ms: f64,
    l: f64,
    w: f64,
    g: f64,
    k: f64,
    c: f64,
}

impl OdeSystem<4> for Flyball {
    fn rhs(&self, _t: f64, y: &Vector<4>) -> Result<Vector<4>> {
        let (phi, z, phid, zd) = (y[0], y[1], y[2], y[3]);
        let (s, c) = phi.sin_cos();
        let l = self.l;
        let dy = l * c + z;
        let d = (l * l * s * s + dy * dy).sqrt();
        let (d_phi, d_z) = (-z * l * s / d, dy / d);
        let force = self.k * (d - l) + self.c * (d_phi * phid + d_z * zd);
        let ml2 = self.m * l * l;
        let phidd = (2.0 * ml2 * self.w * self.w * s * c
            - 2.0 * self.m * self.g * l * s
            - 2.0 * force * d_phi)
            / (2.0 * ml2);
        let zdd = -self.g - 2.0 * force * d_z / self.ms;
        Ok(Vector::<4>::new(phid, zd, phidd, zdd))
    }
}

const GOVERNOR: Flyball = Flyball {
    m: 1.0,
    ms: 2.0,
    l: 0.3,
    w: 10.0,
    g: 9.81,
    k: 8e5,
    c: 1e4,
};

/// Released at rest with the arms at 0.5 rad and the links at their free length.
fn y0() -> Vector<4> {
    let phi0: f64 = 0.5;
    Vector::<4>::new(phi0, -2.0 * GOVERNOR.l * phi0.cos(), 0.0, 0.0)
}

const T1: f64 = 2.0;

fn opts(tol: f64, stiffness_check: Option<usize>) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        dense: false,
        record: Record::Final,
        max_steps: 10_000_000,
        stiffness_check,
        ..Options::default()
    }
}

/// The largest `|lambda|` of the Jacobian at `y` (central differences).
fn largest_eigenvalue(y: &Vector<4>) -> f64 {
    let mut jac = mbd_core::Matrix::<4, 4>::zeros();
    for j in 0..4 {
        let dy = 1e-7 * y[j].abs().max(1.0);
        let mut e = Vector::<4>::zeros();
        e[j] = dy;
        let col = (GOVERNOR.rhs(0.0, &(y + e)).unwrap() - GOVERNOR.rhs(0.0, &(y - e)).unwrap())
            / (2.0 * dy);
        jac.set_column(j, &col);
    }
    jac.complex_eigenvalues()
        .iter()
        .map(|l| l.norm())
        .fold(0.0, f64::max)
}

/// Largest difference of the final states.
fn distance(a: &Vector<4>, b: &Vector<4>) -> f64 {
    (a - b).abs().max()
}

/// Truths checked: (1) the Radau5 reference agrees with itself one decade looser to 1e-9;
/// (2) at 1e-4 and 1e-6, with the test on, DOPRI5 stops with `Error::Stiff` (before `t1`),
/// and with it off it finishes within 10 tol of the reference; (3) those runs are
/// stiff in the sense of the theory: their mean step times the largest `|lambda|` at the
/// start is near DOPRI5's stability limit on the real axis (3.3; accepted in [2.5, 5]),
/// and the two tolerances, a factor 100 apart, take nearly the same number of steps (within
/// 10%, where accuracy alone would ask `100^(1/5) = 2.5` times more); (4) at 1e-8 the
/// tolerance asks for smaller steps than stability, the test finds nothing, and the run
/// with it on is the run with it off, within 10 tol of the reference.
#[test]
fn flyball_stops_as_stiff_only_with_the_check_on() {
    let reference = Radau5::new(opts(1e-12, None))
        .solve(&GOVERNOR, 0.0, y0(), T1, &[])
        .unwrap();
    let looser = Radau5::new(opts(1e-11, None))
        .solve(&GOVERNOR, 0.0, y0(), T1, &[])
        .unwrap();
    assert!(distance(&reference.y_end, &looser.y_end) < 1e-9);
    let lambda = largest_eigenvalue(&y0());
    let mut steps = Vec::new();
    for tol in [1e-4, 1e-6] {
        let on = Dopri5::new(opts(tol, Some(Dopri5::NSTIFF))).solve(&GOVERNOR, 0.0, y0(), T1, &[]);
        match on {
            Err(Error::Stiff { t }) => assert!(t > 0.0 && t < T1, "tol {tol:e}: t = {t}"),
            other => panic!("tol {tol:e}: expected Error::Stiff, got {other:?}"),
        }
        let off = Dopri5::new(opts(tol, None))
            .solve(&GOVERNOR, 0.0, y0(), T1, &[])
            .unwrap();
        let err = distance(&off.y_end, &reference.y_end);
        let h_lambda = T1 / off.stats.n_accepted as f64 * lambda;
        eprintln!(
            "tol {tol:.0e}, check off: {} steps, error {err:.1e}, mean h |lambda| {h_lambda:.2}",
            off.stats.n_steps
        );
        assert!(err < 10.0 * tol, "tol {tol:e}: error {err:e}");
        assert!(
            (2.5..5.0).contains(&h_lambda),
            "tol {tol:e}: h |lambda| = {h_lambda}"
        );
        steps.push(off.stats.n_steps as f64);
    }
    assert!(steps[1] / steps[0] < 1.1, "steps {steps:?}");
    let tol = 1e-8;
    let on = Dopri5::new(opts(tol, Some(Dopri5::NSTIFF)))
        .solve(&GOVERNOR, 0.0, y0(), T1, &[])
        .unwrap();
    let off = Dopri5::new(opts(tol, None))
        .solve(&GOVERNOR, 0.0, y0(), T1, &[])
        .unwrap();
    assert_eq!(on.stats, off.stats);
    assert_eq!(on.y_end, off.y_end);
    let err = distance(&on.y_end, &reference.y_end);
    eprintln!("tol 1e-8: {} steps, error {err:.1e}", on.stats.n_steps);
    assert!(err < 10.0 * tol, "error {err:e}");
}
