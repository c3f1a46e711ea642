//! Spatial joint trees (`body` in a `#[mechanism(spatial)]`): revolute joints about a named
//! axis, universal and spherical joints, frames composed by the macro. Checked against the
//! same mechanisms written out body by body with `rigid3` (kinematics by hand), and against
//! the conservation of energy and of the vertical angular momentum of a heavy body on a
//! spherical joint (physics, computed here from the state by hand).

use approx::assert_relative_eq;
use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// A spatial double pendulum: a bar on a universal joint at the ground, a second bar on a
/// revolute joint about its `x` axis at the first bar's lower end.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(upper, joint = universal(a, b), com = [0.0, 0.0, -l1 / 2.0], mass = m1,
       inertia = diag(i1, i1, j1))]
#[body(lower, parent = upper, joint = revolute(c, x), at = [0.0, 0.0, -l1],
       com = [0.0, 0.0, -l2 / 2.0], mass = m2, inertia = diag(i2, i2, j2))]
pub struct CardanPendulum {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub i1: f64,
    pub j1: f64,
    pub i2: f64,
    pub j2: f64,
    pub g: f64,
}

/// [`CardanPendulum`] written out: `R1 = rot_x(a) rot_y(b)`, `R2 = R1 rot_x(c)`, the lower
/// bar's joint at `R1 (0, 0, -l1)`.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[coords(a, b, c)]
#[rigid3(upper, mass = m1, inertia = diag(i1, i1, j1),
         at = rot_x(a) * rot_y(b) * [0.0, 0.0, -l1 / 2.0], rotation = rot_x(a) * rot_y(b))]
#[rigid3(lower, mass = m2, inertia = diag(i2, i2, j2),
         at = rot_x(a) * rot_y(b) * [0.0, 0.0, -l1]
            + rot_x(a) * rot_y(b) * rot_x(c) * [0.0, 0.0, -l2 / 2.0],
         rotation = rot_x(a) * rot_y(b) * rot_x(c))]
pub struct CardanPendulumByHand {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub i1: f64,
    pub j1: f64,
    pub i2: f64,
    pub j2: f64,
    pub g: f64,
}

/// A cart on a prismatic joint along a slanted horizontal axis, a weight welded to it, and an
/// arm on a revolute joint about the cart's `y` axis.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(cart, joint = prismatic(s, [0.6, 0.8, 0.0]), mass = mc)]
#[body(weight, parent = cart, joint = fixed, at = [0.0, 0.0, 0.1], com = [0.02, 0.0, 0.0],
       mass = mw, inertia = diag(0.01, 0.02, 0.03))]
#[body(arm, parent = cart, joint = revolute(u, y), com = [0.0, 0.0, -l], mass = ma,
       inertia = diag(ia, ia, ja))]
pub struct CartArm {
    pub mc: f64,
    pub mw: f64,
    pub ma: f64,
    pub l: f64,
    pub ia: f64,
    pub ja: f64,
    pub g: f64,
}

/// [`CartArm`] written out.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[coords(s, u)]
#[particle(cart, mass = mc, at = [0.6 * s, 0.8 * s, 0.0])]
#[rigid3(weight, mass = mw, inertia = diag(0.01, 0.02, 0.03),
         at = [0.6 * s + 0.02, 0.8 * s, 0.1], rotation = rot_z(0.0))]
#[rigid3(arm, mass = ma, inertia = diag(ia, ia, ja),
         at = [0.6 * s, 0.8 * s, 0.0] + rot_y(u) * [0.0, 0.0, -l], rotation = rot_y(u))]
pub struct CartArmByHand {
    pub mc: f64,
    pub mw: f64,
    pub ma: f64,
    pub l: f64,
    pub ia: f64,
    pub ja: f64,
    pub g: f64,
}

#[test]
fn prismatic_fixed_and_revolute_joints_equal_the_explicit_twin() {
    let p = CartArm {
        mc: 3.0,
        mw: 0.5,
        ma: 1.1,
        l: 0.7,
        ia: 0.05,
        ja: 0.003,
        g: 9.81,
    };
    let by_hand = CartArmByHand {
        mc: p.mc,
        mw: p.mw,
        ma: p.ma,
        l: p.l,
        ia: p.ia,
        ja: p.ja,
        g: p.g,
    };
    for (q, qd) in [([0.4, 0.9], [1.3, -2.1]), ([-1.5, -2.5], [0.2, 0.7])] {
        let (q, qd) = (Vector::<2>::from(q), Vector::<2>::from(qd));
        let (m, m_hand): (Matrix<2, 2>, Matrix<2, 2>) =
            (p.mass_matrix(0.0, &q), by_hand.mass_matrix(0.0, &q));
        assert_relative_eq!(m, m_hand, epsilon = 1e-14, max_relative = 1e-13);
        assert_relative_eq!(
            p.forces(0.0, &q, &qd),
            by_hand.forces(0.0, &q, &qd),
            epsilon = 1e-13,
            max_relative = 1e-13
        );
    }
}

/// A heavy body on a spherical joint (yaw `psi`, pitch `theta`, roll `phi`), its mass
/// centre `h` below the joint, off its symmetry axis by `e` (so every coordinate moves it),
/// with a general inertia tensor.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = spherical(psi, theta, phi), com = [e, 0.0, -h], mass = m,
       inertia = [[ia, 0.01, 0.0], [0.01, ib, 0.02], [0.0, 0.02, ic]])]
#[output(omega_x = angular_velocity(top)[0])]
#[output(omega_y = angular_velocity(top)[1])]
#[output(omega_z = angular_velocity(top)[2])]
#[output(x = position(top)[0])]
#[output(y = position(top)[1])]
#[output(vx = velocity(top)[0])]
#[output(vy = velocity(top)[1])]
pub struct HeavyBody {
    pub m: f64,
    pub e: f64,
    pub h: f64,
    pub ia: f64,
    pub ib: f64,
    pub ic: f64,
    pub g: f64,
}

const CARDAN: CardanPendulum = CardanPendulum {
    m1: 1.3,
    m2: 0.7,
    l1: 0.9,
    l2: 0.6,
    i1: 0.09,
    j1: 0.004,
    i2: 0.021,
    j2: 0.002,
    g: 9.81,
};

#[test]
fn cardan_pendulum_equals_its_explicit_twin() {
    let p = &CARDAN;
    let by_hand = CardanPendulumByHand {
        m1: p.m1,
        m2: p.m2,
        l1: p.l1,
        l2: p.l2,
        i1: p.i1,
        j1: p.j1,
        i2: p.i2,
        j2: p.j2,
        g: p.g,
    };
    for (q, qd) in [
        ([0.3, -0.2, 0.5], [0.4, 1.1, -0.7]),
        ([1.2, 0.9, -2.0], [-2.0, 0.3, 1.5]),
        ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
    ] {
        let (q, qd) = (Vector::<3>::from(q), Vector::<3>::from(qd));
        let (m, m_hand): (Matrix<3, 3>, Matrix<3, 3>) =
            (p.mass_matrix(0.0, &q), by_hand.mass_matrix(0.0, &q));
        assert_relative_eq!(m, m_hand, epsilon = 1e-14, max_relative = 1e-13);
        assert_relative_eq!(
            p.forces(0.0, &q, &qd),
            by_hand.forces(0.0, &q, &qd),
            epsilon = 1e-13,
            max_relative = 1e-13
        );
        assert_relative_eq!(
            p.energy(0.0, &q, &qd),
            by_hand.energy(0.0, &q, &qd),
            max_relative = 1e-14
        );
    }
    // Hanging straight down, released: it stays there.
    let rest = Vector::<3>::zeros();
    assert_eq!(p.acceleration(0.0, &rest, &rest).unwrap(), rest);
}

/// `rot_z(psi) rot_y(theta) rot_x(phi)`, written out here apart from the macro.
fn zyx(psi: f64, theta: f64, phi: f64) -> Matrix<3, 3> {
    let (sz, cz) = psi.sin_cos();
    let (sy, cy) = theta.sin_cos();
    let (sx, cx) = phi.sin_cos();
    let rz = Matrix::<3, 3>::new(cz, -sz, 0.0, sz, cz, 0.0, 0.0, 0.0, 1.0);
    let ry = Matrix::<3, 3>::new(cy, 0.0, sy, 0.0, 1.0, 0.0, -sy, 0.0, cy);
    let rx = Matrix::<3, 3>::new(1.0, 0.0, 0.0, 0.0, cx, -sx, 0.0, sx, cx);
    rz * ry * rx
}

/// Gravity along `-z` and a fixed joint: its torque about the joint is horizontal, so the
/// angular momentum about the vertical through the joint, `m (r x v)_z + (R I R^T w)_z`, is
/// conserved, and so is the energy.
#[test]
fn heavy_body_on_a_spherical_joint_conserves_energy_and_vertical_momentum() {
    let p = HeavyBody {
        m: 2.0,
        e: 0.05,
        h: 0.4,
        ia: 0.12,
        ib: 0.1,
        ic: 0.03,
        g: 9.81,
    };
    let inertia = Matrix::<3, 3>::new(p.ia, 0.01, 0.0, 0.01, p.ib, 0.02, 0.0, 0.02, p.ic);
    let vertical_momentum = |y: &Vector<6>| {
        let o = p.outputs(0.0, y).unwrap();
        let rot = zyx(y[0], y[1], y[2]);
        let w = Vector::<3>::new(o.omega_x, o.omega_y, o.omega_z);
        let spin = rot * inertia * rot.transpose() * w;
        p.m * (o.x * o.vy - o.y * o.vx) + spin[2]
    };
    let energy = |y: &Vector<6>| {
        let (q, qd) = (
            y.fixed_rows::<3>(0).into_owned(),
            y.fixed_rows::<3>(3).into_owned(),
        );
        p.energy(0.0, &q, &qd)
    };
    // Pitch stays well inside (-pi/2, pi/2), away from the coordinates' singularity.
    let y0 = Vector::<6>::from([0.1, 0.35, -0.2, 1.5, -0.4, 3.0]);
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        dense: false,
        ..Default::default()
    };
    let sol = Dopri5::new(opts).solve(&p, 0.0, y0, 2.0, &[]).unwrap();
    let (_, y1) = sol.last();
    assert!(y1[1].abs() < 1.2, "pitch reached {}", y1[1]);
    let (e0, l0) = (energy(&y0), vertical_momentum(&y0));
    assert!(
        l0.abs() > 0.1,
        "a test of a zero momentum would be weak: {l0}"
    );
    assert_relative_eq!(energy(y1), e0, max_relative = 1e-9);
    assert_relative_eq!(vertical_momentum(y1), l0, max_relative = 1e-9);
    // The motion is not trivial: the body turned and the roll moved.
    assert!((y1[0] - y0[0]).abs() > 0.1 && (y1[2] - y0[2]).abs() > 0.1);
}
