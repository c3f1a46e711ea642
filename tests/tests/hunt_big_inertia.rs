//! Hunting silent wrong answers: a spatial inertia of parameters that no body can have (a
//! principal moment above the sum of the other two, or an indefinite tensor) was accepted at
//! run time (`check_parameters` looked at the diagonal's signs only) and integrated as if it
//! were a body; the constant forms were already refused at compile time. Every evaluation
//! now names it. The reference: a mass distribution has `I = tr(S) E - S` with
//! `S = sum m r r^T` positive semi-definite, so `tr(I)/2 E - I` must be too (written out
//! beside each case), and a boundary case (a thin disk, `I_zz = I_xx + I_yy`) is a body.

use mbd::integrate::{Dopri5, Integrator, Radau5};
use mbd::prelude::*;

/// A top on a spherical joint (tree: articulated-body recursion).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = spherical(a, b, c), com = [0.0, 0.0, h], mass = m,
       inertia = [[ix, p, 0.0], [p, iy, 0.0], [0.0, 0.0, iz]])]
pub struct Top {
    pub m: f64,
    pub h: f64,
    pub g: f64,
    pub ix: f64,
    pub iy: f64,
    pub iz: f64,
    pub p: f64,
}

/// A free body turning about `z` (mass-matrix form): `iz psi'' = tau`.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[coords(psi)]
#[rigid3(wheel, mass = m, inertia = diag(ix, iy, iz), at = [0.0, 0.0, 0.0], rotation = rot_z(psi))]
#[torque(motor, on = wheel, value = [0.0, 0.0, tau])]
pub struct Wheel {
    pub m: f64,
    pub ix: f64,
    pub iy: f64,
    pub iz: f64,
    pub tau: f64,
}

fn top(ix: f64, iy: f64, iz: f64, p: f64) -> Top {
    Top {
        m: 2.0,
        h: 0.3,
        g: 9.81,
        ix,
        iy,
        iz,
        p,
    }
}

/// The error every evaluation and every method must give, with the value it names.
fn refused(err: Error, needle: &str) -> f64 {
    match err {
        Error::InvalidParameter { what, value, .. } => {
            assert!(what.contains(needle), "{what}");
            value
        }
        other => panic!("expected the inertia to be named, got {other:?}"),
    }
}

#[test]
fn an_impossible_inertia_of_parameters_is_refused_by_every_evaluation() {
    let q = Vector::<3>::new(0.2, -0.4, 0.3);
    let qd = Vector::<3>::new(1.0, 0.5, -2.0);
    let y = Vector::<6>::new(0.2, -0.4, 0.3, 1.0, 0.5, -2.0);
    // I_zz = 3 > I_xx + I_yy = 2: the margin I_xx + I_yy - I_zz is -1.
    let bad = top(1.0, 1.0, 3.0, 0.0);
    let margin = refused(
        bad.check_parameters().unwrap_err(),
        "`I_xx + I_yy - I_zz` of `top`",
    );
    assert!((margin + 1.0).abs() < 1e-10, "{margin}");
    refused(bad.acceleration(0.0, &q, &qd).unwrap_err(), "of `top`");
    refused(bad.rhs(0.0, &y).unwrap_err(), "of `top`");
    let opts = Options::default();
    refused(
        Dopri5::new(opts.clone())
            .solve(&bad, 0.0, y, 1.0, &[])
            .unwrap_err(),
        "of `top`",
    );
    refused(
        Radau5::new(opts).solve(&bad, 0.0, y, 1.0, &[]).unwrap_err(),
        "of `top`",
    );
    // Diagonal entries all positive, but [[1, 2], [2, 1]] has the eigenvalue -1: no body.
    let indefinite = top(1.0, 1.0, 1.0, 2.0);
    refused(
        indefinite.check_parameters().unwrap_err(),
        "inertia of `top`",
    );
    refused(
        indefinite.acceleration(0.0, &q, &qd).unwrap_err(),
        "inertia of `top`",
    );
    // The free body of the mass-matrix form: its mass matrix [iz] is positive whatever
    // I_xx, I_yy say, so no solve would notice.
    let wheel = Wheel {
        m: 1.0,
        ix: 0.1,
        iy: 0.1,
        iz: 0.5,
        tau: 1.0,
    };
    let (psi, psid) = (Vector::<1>::new(0.3), Vector::<1>::new(0.0));
    refused(
        wheel.acceleration(0.0, &psi, &psid).unwrap_err(),
        "`I_xx + I_yy - I_zz` of `wheel`",
    );
}

#[test]
fn bodies_on_the_boundary_are_bodies() {
    // A thin disk of radius r: I_xx = I_yy = m r^2 / 4, I_zz = m r^2 / 2 = I_xx + I_yy.
    let (m, r) = (3.0, 0.7);
    let disk = Wheel {
        m,
        ix: m * r * r / 4.0,
        iy: m * r * r / 4.0,
        iz: m * r * r / 2.0,
        tau: 1.5,
    };
    disk.check_parameters().unwrap();
    let acc = disk
        .acceleration(0.0, &Vector::<1>::new(0.3), &Vector::<1>::new(2.0))
        .unwrap();
    assert!((acc[0] - 1.5 / (m * r * r / 2.0)).abs() < 1e-14);
    // A thin rod along z: diag(a, a, 0); with a product of inertia, a rod along the
    // diagonal of the xy plane (I = m l^2/12 (E - u u^T), u = (1, -1, 0)/sqrt 2): S = m l^2/12
    // u u^T, semi-definite of rank one.
    top(0.5, 0.5, 0.0, 0.0).check_parameters().unwrap();
    let a = 2.0 * 0.36 / 12.0;
    let rod = top(a / 2.0, a / 2.0, a, a / 2.0);
    rod.check_parameters().unwrap();
    // A solid box 0.1 x 0.2 x 0.3, turned by 30 degrees about z: products of inertia.
    let (bx, by, bz) = (2.0 * 0.13 / 12.0, 2.0 * 0.1 / 12.0, 2.0 * 0.05 / 12.0);
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    let box_ = top(
        c * c * bx + s * s * by,
        s * s * bx + c * c * by,
        bz,
        s * c * (bx - by),
    );
    box_.check_parameters().unwrap();
    let rest = Vector::<3>::zeros();
    assert!(box_.acceleration(0.0, &rest, &rest).unwrap().amax() < 1e-15);
}
