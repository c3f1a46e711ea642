//! A heavy symmetric top on a spherical joint at its tip, written as a spatial joint tree
//! the way the language reference teaches (`mechanism(spatial)`, `body` with
//! `spherical(a, b, c)` = `rot_z(a) rot_y(b) rot_x(c)`), checked in steady precession.
//!
//! Hand derivation (the heavy top in Euler angles, e.g. Goldstein ch. 5). The symmetry axis
//! is the body's `x` axis, the mass centre at `[l, 0, 0]` on it, the inertia `diag(C, A0, A0)`
//! about the mass centre, so `A = A0 + m l^2` transverse about the tip. The axis
//! `R e_x = (cos a cos b, sin a cos b, -sin b)` makes the polar angle `th` with the vertical,
//! `cos th = -sin b`; `a` is the precession about `z` and `c` the spin about the axis, and at
//! constant `b` the angular velocity is `a' e_z + c' R e_x`, whose component along the axis is
//! `w3 = c' + a' cos th`. With `L = A (th'^2 + a'^2 sin^2 th) / 2 + C w3^2 / 2 - m g l cos th`,
//! the `th` equation at `th' = 0` is `sin th (A a'^2 cos th - C w3 a' + m g l) = 0`: steady
//! precession at `a' = W` with `A cos th W^2 - C w3 W + m g l = 0` (slow root
//! `W = (C w3 - sqrt(C^2 w3^2 - 4 A cos th m g l)) / (2 A cos th)`), every Euler angle rate
//! constant and the mass centre at height `l cos th`.

use mbd::prelude::*;

/// A symmetric top on a spherical joint at the ground's origin.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = spherical(a, b, c), com = [l, 0.0, 0.0], mass = m,
       inertia = diag(ca, at, at))]
#[output(centre = position(top), spin = angular_velocity(top))]
pub struct Top {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub ca: f64,
    pub at: f64,
}

const P: Top = Top {
    m: 1.0,
    l: 0.1,
    g: 9.81,
    ca: 0.004,
    at: 0.002,
};

/// The steady state at polar angle `th` and axial spin `w3`: `(b, W, c')`.
fn steady(p: &Top, th: f64, w3: f64) -> (f64, f64, f64) {
    let big_a = p.at + p.m * p.l * p.l;
    let k = big_a * th.cos();
    let disc = (p.ca * w3).powi(2) - 4.0 * k * p.m * p.g * p.l;
    let w = (p.ca * w3 - disc.sqrt()) / (2.0 * k);
    (th - std::f64::consts::FRAC_PI_2, w, w3 - w * th.cos())
}

#[test]
fn steady_precession_has_no_euler_angle_acceleration() {
    for (th, w3) in [(1.0_f64, 100.0), (0.4, 60.0), (1.4, 150.0)] {
        let (b, w, cd) = steady(&P, th, w3);
        let q = Vector::<3>::new(0.3, b, 0.7);
        let qd = Vector::<3>::new(w, 0.0, cd);
        let acc = P.acceleration(0.0, &q, &qd).unwrap();
        // Each term of the equations is of order C w3 W ~ 1 N m over inertias ~ 0.01 kg m^2.
        assert!(acc.amax() < 1e-10, "th = {th}: {acc:?}");
        // The component of the angular velocity along the axis is w3.
        let y = Vector::<6>::new(q[0], q[1], q[2], qd[0], qd[1], qd[2]);
        let o = P.outputs(0.0, &y).unwrap();
        let axis = [o.centre_x / P.l, o.centre_y / P.l, o.centre_z / P.l];
        let along = o.spin_x * axis[0] + o.spin_y * axis[1] + o.spin_z * axis[2];
        assert!((along - w3).abs() < 1e-11 * w3, "th = {th}: {along}");
        assert!((o.centre_z - P.l * th.cos()).abs() < 1e-15);
    }
}

#[test]
fn the_top_precesses_steadily_for_a_whole_turn() {
    let th: f64 = 1.0;
    let (b, w, cd) = steady(&P, th, 100.0);
    let y0 = Vector::<6>::new(0.0, b, 0.0, w, 0.0, cd);
    let period = 2.0 * std::f64::consts::PI / w;
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let sol = Dopri5::new(opts).solve(&P, 0.0, y0, period, &[]).unwrap();
    for k in 1..=8 {
        let t = period * k as f64 / 8.0;
        let y = sol.at(t).unwrap();
        assert!((y[0] - w * t).abs() < 1e-7, "precession at t = {t}");
        assert!((y[1] - b).abs() < 1e-8, "tilt at t = {t}: {}", y[1] - b);
        assert!((y[2] - cd * t).abs() < 1e-6 * cd * t, "spin at t = {t}");
        let o = P.outputs(t, &y).unwrap();
        let turn = w * t;
        let r = P.l * th.sin();
        assert!((o.centre_x - r * turn.cos()).abs() < 1e-8);
        assert!((o.centre_y - r * turn.sin()).abs() < 1e-8);
    }
}
