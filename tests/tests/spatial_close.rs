//! Loops of spatial joint trees closed by prismatic, universal and revolute `close` joints,
//! against a closed form and an independent planar model.
//!
//! The mechanism is a centred slider-crank moving in the ground's `yz` plane, built in space
//! so that no constraint row is trivially zero: a crank turning about `x` at the origin
//! (length `r`, along its `y`), a connecting rod on a spherical joint at the crank's tip
//! (length `l`, along its `z`) and a slider on the `z` axis. Two ways of closing it:
//!
//! - `Rsup`: the slider hangs on the rod's far end by a universal joint (`rot_x(u1) rot_y(u2)`,
//!   a tree joint) and a **prismatic `close`** keeps it on the ground's `z` axis with its
//!   orientation locked (axis `z`, normal `x` in both frames): 6 coordinates, 5 equations.
//! - `Rspu`: the slider is a tree body on a prismatic joint along `z`, and a **universal
//!   `close`** joins the rod's far end to it (the rod's `x` pin perpendicular to the slider's
//!   `y` pin): 5 coordinates, 4 equations.
//! - `Rspr`: the same with a **revolute `close`** about `x`: 5 coordinates, 5 equations of
//!   rank 4 (Grübler's `6 * 3 - (5 + 3 + 5 + 5) = 0` misses the redundant one).
//!
//! The first two have one degree of freedom (Grübler: `6 * 3 - (5 + 3 + 4 + 5) = 1`), and no
//! equation is redundant: the universal joint's two pins (the rod's `x`, the slider's `y`) and the rod's own
//! axis are independent unless the rod lies along `y`, which needs `r >= l`. So the motion is the
//! planar slider-crank, and the spherical joint's other two angles stay zero.
//!
//! **Closed form** (crank angle `theta` from `y` towards `z`): the crank tip is
//! `(0, r cos theta, r sin theta)`; the rod's direction `(0, -sin phi, cos phi)` with
//! `phi = theta + c` (its absolute angle) and the slider on the `z` axis give
//! `r cos theta = l sin phi`, so `phi = asin(r cos theta / l)` (slider above the crank) and the
//! slider's height `z = r sin theta + sqrt(l^2 - r^2 cos^2 theta)`. In `Rsup` the slider's
//! frame is the ground's: `u1 = -phi`, `u2 = 0`.
//!
//! **Reference dynamics**: the same slider-crank as a planar model of one coordinate, its
//! kinematics written with the closed form above (`(y, z)` of space are `(x, y)` of the plane,
//! and a body's inertia about `x` is the planar one). Lagrange's equation of that model and the
//! augmented spatial equations share no code but the derive's Kane projection of explicit
//! positions.

use mbd::prelude::*;
use mbd::{Constrained, Vector};

/// Prismatic `close`: the slider on a universal joint at the rod's end, kept on the `z` axis.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(crank, joint = revolute(th, x), com = [0.0, r / 2.0, 0.0], mass = mc,
       inertia = diag(ic, 0.001, ic))]
#[body(rod, parent = crank, joint = spherical(a, b, c), at = [0.0, r, 0.0],
       com = [0.0, 0.0, l / 2.0], mass = mr, inertia = diag(ir, ir, 0.002))]
#[body(slider, parent = rod, joint = universal(u1, u2), at = [0.0, 0.0, l], mass = ms,
       inertia = diag(0.01, 0.02, 0.025))]
#[close(slot, joint = prismatic, a = slider, axis_a = [0.0, 0.0, 1.0], normal_a = [1.0, 0.0, 0.0],
        b = ground, axis_b = [0.0, 0.0, 2.0], normal_b = [1.0, 0.0, 0.5])]
pub struct Rsup {
    pub r: f64,
    pub l: f64,
    pub mc: f64,
    pub mr: f64,
    pub ms: f64,
    pub ic: f64,
    pub ir: f64,
    pub g: f64,
}

/// Universal `close`: the slider a tree body on a prismatic joint, joined to the rod's end.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(crank, joint = revolute(th, x), com = [0.0, r / 2.0, 0.0], mass = mc,
       inertia = diag(ic, 0.001, ic))]
#[body(rod, parent = crank, joint = spherical(a, b, c), at = [0.0, r, 0.0],
       com = [0.0, 0.0, l / 2.0], mass = mr, inertia = diag(ir, ir, 0.002))]
#[body(slider, joint = prismatic(s, [0.0, 0.0, 1.0]), mass = ms)]
#[close(cross, joint = universal, a = rod, at_a = [0.0, 0.0, l], axis_a = [1.0, 0.0, 0.0],
        b = slider, axis_b = [0.0, 1.0, 0.0])]
pub struct Rspu {
    pub r: f64,
    pub l: f64,
    pub mc: f64,
    pub mr: f64,
    pub ms: f64,
    pub ic: f64,
    pub ir: f64,
    pub g: f64,
}

/// Revolute `close`: the slider a tree body on a prismatic joint, pinned to the rod's end
/// about `x` in both frames: 5 coordinates and 5 equations, one of them redundant (the
/// mechanism still moves: the revolute joint's rows lock the rod's tilt and spin, which the
/// points already fix but for one combination), so rank 4.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(crank, joint = revolute(th, x), com = [0.0, r / 2.0, 0.0], mass = mc,
       inertia = diag(ic, 0.001, ic))]
#[body(rod, parent = crank, joint = spherical(a, b, c), at = [0.0, r, 0.0],
       com = [0.0, 0.0, l / 2.0], mass = mr, inertia = diag(ir, ir, 0.002))]
#[body(slider, joint = prismatic(s, [0.0, 0.0, 1.0]), mass = ms)]
#[close(pin, joint = revolute, a = rod, at_a = [0.0, 0.0, l], axis_a = [1.0, 0.0, 0.0],
        b = slider, axis_b = [-1.0, 0.0, 0.0])]
pub struct Rspr {
    pub r: f64,
    pub l: f64,
    pub mc: f64,
    pub mr: f64,
    pub ms: f64,
    pub ic: f64,
    pub ir: f64,
    pub g: f64,
}

/// The planar slider-crank in its crank angle, the closure solved by hand.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[rigid(crank, mass = mc, inertia = ic, at = [0.5 * r * cos(theta), 0.5 * r * sin(theta)],
        angle = theta)]
#[rigid(rod, mass = mr, inertia = ir,
        at = [0.5 * r * cos(theta), r * sin(theta) + 0.5 * sqrt(l * l - r * r * cos(theta) * cos(theta))],
        angle = asin(r * cos(theta) / l))]
#[particle(slider, mass = ms, at = [0.0, r * sin(theta) + sqrt(l * l - r * r * cos(theta) * cos(theta))])]
pub struct Planar {
    pub r: f64,
    pub l: f64,
    pub mc: f64,
    pub mr: f64,
    pub ms: f64,
    pub ic: f64,
    pub ir: f64,
    pub g: f64,
}

const R: f64 = 0.3;
const L: f64 = 1.0;

fn planar() -> Planar {
    Planar {
        r: R,
        l: L,
        mc: 2.0,
        mr: 3.0,
        ms: 1.5,
        ic: 0.02,
        ir: 0.25,
        g: 9.81,
    }
}

/// `(phi, phi', z, z')` of the closed form at `(theta, theta')`.
fn closed_form(th: f64, thd: f64) -> (f64, f64, f64, f64) {
    let phi = (R * th.cos() / L).asin();
    let phid = -R * th.sin() * thd / (L * phi.cos());
    let z = R * th.sin() + L * phi.cos();
    let zd = R * th.cos() * thd - L * phi.sin() * phid;
    (phi, phid, z, zd)
}

const STATES: [(f64, f64); 6] = [
    (0.0, 0.0),
    (0.4, 1.5),
    (1.3, -2.0),
    (2.5, 0.7),
    (-2.0, 3.0),
    (4.0, -0.3),
];

#[test]
fn prismatic_close_moves_as_the_planar_slider_crank() {
    let p = planar();
    let m = Rsup {
        r: p.r,
        l: p.l,
        mc: p.mc,
        mr: p.mr,
        ms: p.ms,
        ic: p.ic,
        ir: p.ir,
        g: p.g,
    };
    for (th, thd) in STATES {
        let (phi, phid, _, _) = closed_form(th, thd);
        let q = Vector::<6>::from([th, 0.0, 0.0, phi - th, -phi, 0.0]);
        let qd = Vector::<6>::from([thd, 0.0, 0.0, phid - thd, -phid, 0.0]);
        let phi_res = Constrained::<6, 5>::phi(&m, 0.0, &q);
        assert!(phi_res.amax() < 1e-15, "closure {phi_res}");
        let rate_res = Constrained::<6, 5>::phi_q(&m, 0.0, &q) * qd;
        assert!(rate_res.amax() < 1e-14, "rates {rate_res}");
        let (rank, redundant) = mbd::analysis::rank_and_redundant(&m.phi_q(0.0, &q));
        assert_eq!((rank, redundant.len()), (5, 0));
        let qdd = m.acceleration(0.0, &q, &qd).unwrap();
        let want = p
            .acceleration(0.0, &Vector::from([th]), &Vector::from([thd]))
            .unwrap()[0];
        eprintln!(
            "theta = {th}: theta'' {} vs planar {want}, difference {:e}",
            qdd[0],
            (qdd[0] - want).abs()
        );
        assert!(
            (qdd[0] - want).abs() < 1e-10 * want.abs().max(1.0),
            "theta'' {} vs planar {want} at {th}",
            qdd[0]
        );
        // The spherical joint's out-of-plane angles and the slider's second pin stay at rest.
        for k in [1, 2, 5] {
            assert!(qdd[k].abs() < 1e-10, "q''[{k}] = {}", qdd[k]);
        }
    }
}

#[test]
fn universal_close_moves_as_the_planar_slider_crank() {
    let p = planar();
    let m = Rspu {
        r: p.r,
        l: p.l,
        mc: p.mc,
        mr: p.mr,
        ms: p.ms,
        ic: p.ic,
        ir: p.ir,
        g: p.g,
    };
    for (th, thd) in STATES {
        let (phi, phid, z, zd) = closed_form(th, thd);
        let q = Vector::<5>::from([th, 0.0, 0.0, phi - th, z]);
        let qd = Vector::<5>::from([thd, 0.0, 0.0, phid - thd, zd]);
        let phi_res = Constrained::<5, 4>::phi(&m, 0.0, &q);
        assert!(phi_res.amax() < 1e-15, "closure {phi_res}");
        let rate_res = Constrained::<5, 4>::phi_q(&m, 0.0, &q) * qd;
        assert!(rate_res.amax() < 1e-14, "rates {rate_res}");
        let (rank, redundant) = mbd::analysis::rank_and_redundant(&m.phi_q(0.0, &q));
        assert_eq!((rank, redundant.len()), (4, 0));
        let qdd = m.acceleration(0.0, &q, &qd).unwrap();
        let want = p
            .acceleration(0.0, &Vector::from([th]), &Vector::from([thd]))
            .unwrap()[0];
        eprintln!(
            "theta = {th}: theta'' {} vs planar {want}, difference {:e}",
            qdd[0],
            (qdd[0] - want).abs()
        );
        assert!(
            (qdd[0] - want).abs() < 1e-10 * want.abs().max(1.0),
            "theta'' {} vs planar {want} at {th}",
            qdd[0]
        );
        for k in [1, 2] {
            assert!(qdd[k].abs() < 1e-10, "q''[{k}] = {}", qdd[k]);
        }
    }
}

/// The redundant row does not change the motion: the accelerations are unique (the
/// multipliers are not; the augmented solve returns the minimum-norm ones). `axis_b` points
/// along `-x`: antiparallel axes are the same revolute joint.
#[test]
fn revolute_close_moves_as_the_planar_slider_crank() {
    let p = planar();
    let m = Rspr {
        r: p.r,
        l: p.l,
        mc: p.mc,
        mr: p.mr,
        ms: p.ms,
        ic: p.ic,
        ir: p.ir,
        g: p.g,
    };
    for (th, thd) in STATES {
        let (phi, phid, z, zd) = closed_form(th, thd);
        let q = Vector::<5>::from([th, 0.0, 0.0, phi - th, z]);
        let qd = Vector::<5>::from([thd, 0.0, 0.0, phid - thd, zd]);
        assert!(Constrained::<5, 5>::phi(&m, 0.0, &q).amax() < 1e-15);
        assert!((Constrained::<5, 5>::phi_q(&m, 0.0, &q) * qd).amax() < 1e-14);
        let (rank, redundant) = mbd::analysis::rank_and_redundant(&m.phi_q(0.0, &q));
        assert_eq!((rank, redundant.len()), (4, 1));
        let qdd = m.acceleration(0.0, &q, &qd).unwrap();
        let want = p
            .acceleration(0.0, &Vector::from([th]), &Vector::from([thd]))
            .unwrap()[0];
        eprintln!(
            "revolute, theta = {th}: difference {:e}",
            (qdd[0] - want).abs()
        );
        assert!((qdd[0] - want).abs() < 1e-10 * want.abs().max(1.0));
        for k in [1, 2] {
            assert!(qdd[k].abs() < 1e-10, "q''[{k}] = {}", qdd[k]);
        }
    }
}
