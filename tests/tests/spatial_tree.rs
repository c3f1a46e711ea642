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
        let (m, m_hand): (Matrix<2, 2>, Matrix<2, 2>) = (
            p.mass_matrix(0.0, &q).unwrap(),
            by_hand.mass_matrix(0.0, &q).unwrap(),
        );
        assert_relative_eq!(m, m_hand, epsilon = 1e-14, max_relative = 1e-13);
        assert_relative_eq!(
            p.forces(0.0, &q, &qd).unwrap(),
            by_hand.forces(0.0, &q, &qd).unwrap(),
            epsilon = 1e-13,
            max_relative = 1e-13
        );
    }
}

/// A spatial four-bar (revolute, universal, spherical, revolute): a crank turning about `z`,
/// a coupler on a universal joint at the crank's tip, standing up along its `z`, and a rocker
/// turning about `x` at `(r, -s, l)`; the coupler's top is closed onto the rocker's tip by a
/// spherical joint (`close`, three equations). Assembled at all angles zero; one degree of
/// freedom.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(crank, joint = revolute(a, z), com = [r / 2.0, 0.0, 0.0], mass = mc,
       inertia = diag(0.001, 0.01, 0.01))]
#[body(coupler, parent = crank, joint = universal(b1, b2), at = [r, 0.0, 0.0],
       com = [0.0, 0.0, l / 2.0], mass = mk, inertia = diag(0.02, 0.02, 0.001))]
#[body(rocker, joint = revolute(c, x), at = [r, -s, l], com = [0.0, s / 2.0, 0.0], mass = mr,
       inertia = diag(0.01, 0.001, 0.01))]
#[close(ball, a = coupler, at_a = [0.0, 0.0, l], b = rocker, at_b = [0.0, s, 0.0])]
pub struct SpatialFourBar {
    pub r: f64,
    pub l: f64,
    pub s: f64,
    pub mc: f64,
    pub mk: f64,
    pub mr: f64,
    pub g: f64,
}

/// [`SpatialFourBar`] written out, its loop closed by three hand-written constraints.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[coords(a, b1, b2, c)]
#[rigid3(crank, mass = mc, inertia = diag(0.001, 0.01, 0.01), at = rot_z(a) * [r / 2.0, 0.0, 0.0],
         rotation = rot_z(a))]
#[rigid3(coupler, mass = mk, inertia = diag(0.02, 0.02, 0.001),
         at = rot_z(a) * [r, 0.0, 0.0] + rot_z(a) * rot_x(b1) * rot_y(b2) * [0.0, 0.0, l / 2.0],
         rotation = rot_z(a) * rot_x(b1) * rot_y(b2))]
#[rigid3(rocker, mass = mr, inertia = diag(0.01, 0.001, 0.01),
         at = [r, -s, l] + rot_x(c) * [0.0, s / 2.0, 0.0], rotation = rot_x(c))]
#[point(top, at = rot_z(a) * [r, 0.0, 0.0] + rot_z(a) * rot_x(b1) * rot_y(b2) * [0.0, 0.0, l])]
#[point(tip, at = [r, -s, l] + rot_x(c) * [0.0, s, 0.0])]
#[constraint(top[0] == tip[0])]
#[constraint(top[1] == tip[1])]
#[constraint(top[2] == tip[2])]
pub struct SpatialFourBarByHand {
    pub r: f64,
    pub l: f64,
    pub s: f64,
    pub mc: f64,
    pub mk: f64,
    pub mr: f64,
    pub g: f64,
}

#[test]
fn spatial_closure_equals_hand_written_constraints_and_keeps_the_loop_closed() {
    let p = SpatialFourBar {
        r: 0.2,
        l: 0.5,
        s: 0.3,
        mc: 0.4,
        mk: 1.0,
        mr: 0.6,
        g: 9.81,
    };
    let by_hand = SpatialFourBarByHand {
        r: p.r,
        l: p.l,
        s: p.s,
        mc: p.mc,
        mk: p.mk,
        mr: p.mr,
        g: p.g,
    };
    for q in [[0.3, -0.2, 0.5, 0.1], [1.1, 0.4, -0.3, -0.8]] {
        let q = Vector::<4>::from(q);
        assert_relative_eq!(
            Constrained::<4, 3>::phi(&p, 0.0, &q),
            Constrained::<4, 3>::phi(&by_hand, 0.0, &q),
            epsilon = 1e-15
        );
        assert_relative_eq!(
            Constrained::<4, 3>::phi_q(&p, 0.0, &q),
            Constrained::<4, 3>::phi_q(&by_hand, 0.0, &q),
            epsilon = 1e-14
        );
        assert_relative_eq!(
            p.mass_matrix(0.0, &q).unwrap(),
            by_hand.mass_matrix(0.0, &q).unwrap(),
            epsilon = 1e-14,
            max_relative = 1e-13
        );
    }
    // Released from the assembled configuration with the crank turning: the loop stays
    // closed and the energy stays put (gravity only).
    let rest = Vector::<4>::zeros();
    assert!(Constrained::<4, 3>::phi(&p, 0.0, &rest).norm() < 1e-15);
    // A velocity on the constraint manifold: crank rate 2, the others from Phi_q qd = 0.
    let jac = Constrained::<4, 3>::phi_q(&p, 0.0, &rest);
    let others = jac.fixed_columns::<3>(1).into_owned();
    let rest_rates = -others.lu().solve(&(jac.column(0) * 2.0)).unwrap();
    let qd = Vector::<4>::new(2.0, rest_rates[0], rest_rates[1], rest_rates[2]);
    let y0 = Vector::<8>::from_fn(|i, _| if i < 4 { 0.0 } else { qd[i - 4] });
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        dense: false,
        ..Default::default()
    };
    let sol = Dopri5::new(opts).solve(&p, 0.0, y0, 1.0, &[]).unwrap();
    let (_, y1) = sol.last();
    let (q1, qd1) = (
        y1.fixed_rows::<4>(0).into_owned(),
        y1.fixed_rows::<4>(4).into_owned(),
    );
    assert!(Constrained::<4, 3>::phi(&p, 1.0, &q1).norm() < 1e-10);
    assert!((Constrained::<4, 3>::phi_q(&p, 1.0, &q1) * qd1).norm() < 1e-9);
    let (e0, e1) = (
        p.energy(0.0, &rest, &qd).unwrap(),
        p.energy(1.0, &q1, &qd1).unwrap(),
    );
    assert_relative_eq!(e1, e0, max_relative = 1e-8);
    assert!((q1[0] - 0.0).abs() > 0.1, "the crank moved: {}", q1[0]);
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
        let (m, m_hand): (Matrix<3, 3>, Matrix<3, 3>) = (
            p.mass_matrix(0.0, &q).unwrap(),
            by_hand.mass_matrix(0.0, &q).unwrap(),
        );
        assert_relative_eq!(m, m_hand, epsilon = 1e-14, max_relative = 1e-13);
        assert_relative_eq!(
            p.forces(0.0, &q, &qd).unwrap(),
            by_hand.forces(0.0, &q, &qd).unwrap(),
            epsilon = 1e-13,
            max_relative = 1e-13
        );
        assert_relative_eq!(
            p.energy(0.0, &q, &qd).unwrap(),
            by_hand.energy(0.0, &q, &qd).unwrap(),
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
        p.energy(0.0, &q, &qd).unwrap()
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

/// [`HeavyBody`] with its joint's force asked for: `reaction` frees the joint origin along
/// the ground's `x`, `y`, `z`.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = spherical(psi, theta, phi), com = [e, 0.0, -h], mass = m,
       inertia = [[ia, 0.01, 0.0], [0.01, ib, 0.02], [0.0, 0.02, ic]], reaction)]
#[output(fx = reaction(top_rx))]
#[output(fy = reaction(top_ry))]
#[output(fz = reaction(top_rz))]
#[output(ax = acceleration(top)[0])]
#[output(ay = acceleration(top)[1])]
#[output(az = acceleration(top)[2])]
pub struct HeavyBodyForce {
    pub m: f64,
    pub e: f64,
    pub h: f64,
    pub ia: f64,
    pub ib: f64,
    pub ic: f64,
    pub g: f64,
}

/// Newton for the whole body: the joint's force plus its weight is mass times the
/// acceleration of its mass centre, `F = m (a + g e_z)`, at any state.
#[test]
fn spherical_joint_reaction_is_newtons_force_on_the_body() {
    let p = HeavyBodyForce {
        m: 2.0,
        e: 0.05,
        h: 0.4,
        ia: 0.12,
        ib: 0.1,
        ic: 0.03,
        g: 9.81,
    };
    for y in [
        [0.1, 0.35, -0.2, 1.5, -0.4, 3.0],
        [-1.0, -0.6, 2.0, -0.3, 2.2, 0.8],
        [0.0; 6],
    ] {
        let o = p.outputs(0.0, &Vector::<6>::from(y)).unwrap();
        let newton = [p.m * o.ax, p.m * o.ay, p.m * (o.az + p.g)];
        for (f, n) in [o.fx, o.fy, o.fz].into_iter().zip(newton) {
            assert_relative_eq!(f, n, epsilon = 1e-12, max_relative = 1e-12);
        }
    }
    // At rest with the mass centre under the joint (pitched by atan(e / h)): the joint
    // carries the weight, and nothing else.
    let hanging = Vector::<6>::new(0.0, p.e.atan2(p.h), 0.0, 0.0, 0.0, 0.0);
    let o = p.outputs(0.0, &hanging).unwrap();
    assert_relative_eq!(o.fz, p.m * p.g, max_relative = 1e-14);
    assert!(o.fx.abs() < 1e-14 && o.fy.abs() < 1e-14);
}

// The spatial articulated-body recursion against the mass-matrix form of the same model: two
// algorithms (the articulated-body recursion, one step per joint axis, vs the
// composite-rigid-body mass matrix and Newton-Euler forces at zero acceleration) through
// separately generated bodies. The mass-matrix form itself equals the body-by-body twins'
// (Kane's projections of kinematics written out) in the tests above.

/// `|qdd - M^-1 f| <= 1e-12 |qdd|` and `|M qdd - f| <= 1e-12 (|M| |qdd| + |f|)` at each state.
fn recursion_equals_mass_matrix_form<const N: usize>(
    model: &impl MechanismModel<N>,
    states: &[([f64; N], [f64; N])],
    t: f64,
) {
    for (q, qd) in states {
        let (q, qd) = (Vector::<N>::from(*q), Vector::<N>::from(*qd));
        let qdd = model.acceleration(t, &q, &qd).unwrap();
        let mass: Matrix<N, N> = model.mass_matrix(t, &q).unwrap();
        let f = model.forces(t, &q, &qd).unwrap();
        let solved = mbd::solve::solve_mass(t, &mass, &f).unwrap();
        let scale = qdd.norm().max(1.0);
        assert!(
            (qdd - solved).norm() <= 1e-12 * scale,
            "recursion {qdd:?}\nmass-matrix form {solved:?}"
        );
        let residual = (mass * qdd - f).norm();
        assert!(residual <= 1e-12 * (mass.norm() * qdd.norm() + f.norm()));
    }
}

#[test]
fn cardan_pendulum_recursion_equals_its_mass_matrix_form() {
    assert!(
        CardanPendulum::GENERATED
            .parts
            .contains(&"articulated_body")
    );
    recursion_equals_mass_matrix_form(
        &CARDAN,
        &[
            ([0.4, -0.9, 1.3], [1.1, -0.7, 2.3]),
            ([-2.1, 0.3, -0.4], [-0.2, 3.1, -1.7]),
        ],
        0.0,
    );
}

#[test]
fn prismatic_fixed_and_revolute_recursion_equals_the_mass_matrix_form() {
    assert!(CartArm::GENERATED.parts.contains(&"articulated_body"));
    let p = CartArm {
        mc: 3.0,
        mw: 0.5,
        ma: 1.1,
        l: 0.7,
        ia: 0.05,
        ja: 0.003,
        g: 9.81,
    };
    recursion_equals_mass_matrix_form(
        &p,
        &[([0.4, 0.9], [1.3, -2.1]), ([-1.5, -2.5], [0.2, 0.7])],
        0.0,
    );
}

/// [`HeavyBody`]'s spherical joint through the recursion (one body: by default the mass
/// matrix), as three steps `z`, `y`, `x`.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, recursive)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = spherical(psi, theta, phi), com = [e, 0.0, -h], mass = m,
       inertia = [[ia, 0.01, 0.0], [0.01, ib, 0.02], [0.0, 0.02, ic]])]
pub struct HeavyBodyRecursive {
    pub m: f64,
    pub e: f64,
    pub h: f64,
    pub ia: f64,
    pub ib: f64,
    pub ic: f64,
    pub g: f64,
}

#[test]
fn spherical_joint_recursion_equals_the_mass_matrix_form() {
    // A body's inertia: with the products 0.01 and 0.02 the moments (0.04, 0.05, 0.02) had no
    // mass distribution (`tr(I)/2 - I` indefinite), refused at run time since.
    let p = HeavyBodyRecursive {
        m: 2.0,
        e: 0.05,
        h: 0.3,
        ia: 0.06,
        ib: 0.05,
        ic: 0.04,
        g: 9.81,
    };
    // Away from the Euler-angle singularity `theta = +-pi/2` (shared by both forms).
    recursion_equals_mass_matrix_form(
        &p,
        &[
            ([0.3, 0.6, -0.8], [2.0, -1.0, 0.5]),
            ([-2.7, -1.2, 2.9], [-0.4, 1.8, -3.0]),
        ],
        0.0,
    );
}

/// A 7-dof arm: revolute joints about mixed axes with offsets along all three axes, bodies
/// with general inertia tensors off their joint axes, a viscous generalised force on one
/// joint and a driven wrist joint (a known function of time).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[drive(q7 = 0.4 * sin(3.0 * t))]
#[body(b1, joint = revolute(q1, z), at = [0.0, 0.0, 0.3], com = [0.01, 0.02, 0.1], mass = 4.0,
       inertia = [[0.05, 0.001, 0.0], [0.001, 0.04, 0.002], [0.0, 0.002, 0.03]])]
#[body(b2, parent = b1, joint = revolute(q2, y), at = [0.05, 0.0, 0.2], com = [0.2, 0.0, 0.01],
       mass = 3.0, inertia = diag(0.01, 0.06, 0.05))]
#[body(b3, parent = b2, joint = revolute(q3, x), at = [0.4, 0.03, 0.0], com = [0.1, 0.01, 0.0],
       mass = 2.0, inertia = diag(0.008, 0.02, 0.02))]
#[body(b4, parent = b3, joint = revolute(q4, y), at = [0.2, 0.0, -0.05], com = [0.15, 0.0, 0.0],
       mass = 1.5, inertia = [[0.004, 0.0, 0.001], [0.0, 0.015, 0.0], [0.001, 0.0, 0.014]])]
#[body(b5, parent = b4, joint = revolute(q5, z), at = [0.3, 0.0, 0.0], com = [0.05, 0.0, 0.02],
       mass = 1.0, inertia = diag(0.002, 0.003, 0.003))]
#[body(b6, parent = b5, joint = revolute(q6, x), at = [0.1, 0.02, 0.0], com = [0.04, 0.0, 0.0],
       mass = 0.6, inertia = diag(0.001, 0.0015, 0.0015))]
#[body(b7, parent = b6, joint = revolute(q7, y), at = [0.08, 0.0, 0.01], com = [0.03, 0.01, 0.0],
       mass = m7, inertia = diag(0.0005, 0.0008, 0.0007))]
#[generalized_force(damping, along = q3, value = -c * der(q3))]
pub struct Arm7 {
    pub m7: f64,
    pub c: f64,
    pub g: f64,
}

#[test]
fn seven_dof_arm_recursion_equals_the_mass_matrix_form() {
    assert!(Arm7::GENERATED.parts.contains(&"articulated_body"));
    let p = Arm7 {
        m7: 0.4,
        c: 0.7,
        g: 9.81,
    };
    recursion_equals_mass_matrix_form(
        &p,
        &[
            (
                [0.3, -0.7, 1.1, 0.4, -2.0, 0.9],
                [1.2, -0.5, 0.8, -2.2, 1.7, 0.3],
            ),
            (
                [-2.5, 1.3, -0.2, 2.8, 0.6, -1.4],
                [-0.9, 2.1, -1.6, 0.4, -0.3, 2.6],
            ),
        ],
        0.37,
    );
}

/// Four bodies on universal joints in a chain (eight coordinates).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(u1, joint = universal(a1, b1), com = [0.0, 0.0, -l / 2.0], mass = m,
       inertia = diag(i, i, j))]
#[body(u2, parent = u1, joint = universal(a2, b2), at = [0.0, 0.0, -l],
       com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u3, parent = u2, joint = universal(a3, b3), at = [0.0, 0.0, -l],
       com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u4, parent = u3, joint = universal(a4, b4), at = [0.0, 0.0, -l],
       com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
pub struct UniversalChain4 {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

#[test]
fn universal_chain_recursion_equals_the_mass_matrix_form() {
    let p = UniversalChain4 {
        m: 1.2,
        l: 0.5,
        i: 0.03,
        j: 0.002,
        g: 9.81,
    };
    recursion_equals_mass_matrix_form(
        &p,
        &[(
            [0.3, -0.4, 0.9, 0.2, -1.1, 0.7, 0.5, -0.6],
            [1.0, -0.3, 0.6, -1.4, 0.8, 0.2, -0.9, 1.5],
        )],
        0.0,
    );
}

/// Six bodies on universal joints (12 coordinates): long enough that the mass matrix is
/// formed at run time, column by column from Newton-Euler (`M e_j`), not written out.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(u1, joint = universal(a1, b1), com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u2, parent = u1, joint = universal(a2, b2), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u3, parent = u2, joint = universal(a3, b3), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u4, parent = u3, joint = universal(a4, b4), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u5, parent = u4, joint = universal(a5, b5), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u6, parent = u5, joint = universal(a6, b6), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
pub struct UniversalChain6 {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// [`UniversalChain6`] in the mass-matrix form: Kane's projections, written out.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(u1, joint = universal(a1, b1), com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u2, parent = u1, joint = universal(a2, b2), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u3, parent = u2, joint = universal(a3, b3), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u4, parent = u3, joint = universal(a4, b4), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u5, parent = u4, joint = universal(a5, b5), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
#[body(u6, parent = u5, joint = universal(a6, b6), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0],
       mass = m, inertia = diag(i, i, j))]
pub struct UniversalChain6Kane {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

#[test]
fn a_long_trees_mass_matrix_by_columns_equals_kanes() {
    let (m, l, i, j, g) = (1.2, 0.5, 0.03, 0.002, 9.81);
    let p = UniversalChain6 { m, l, i, j, g };
    let kane = UniversalChain6Kane { m, l, i, j, g };
    assert!(
        UniversalChain6::GENERATED
            .parts
            .contains(&"articulated_body")
    );
    assert!(
        !UniversalChain6Kane::GENERATED
            .parts
            .contains(&"articulated_body")
    );
    let q = Vector::<12>::from_fn(|r, _| 1.1 * (((r * 37) % 17) as f64 / 8.0 - 1.0));
    let qd = Vector::<12>::from_fn(|r, _| 1.7 * (((r * 11) % 13) as f64 / 6.0 - 1.0));
    let (mass, mass_kane): (Matrix<12, 12>, Matrix<12, 12>) = (
        p.mass_matrix(0.0, &q).unwrap(),
        kane.mass_matrix(0.0, &q).unwrap(),
    );
    assert!((mass - mass_kane).norm() <= 1e-13 * mass_kane.norm());
    let (f, f_kane) = (
        p.forces(0.0, &q, &qd).unwrap(),
        kane.forces(0.0, &q, &qd).unwrap(),
    );
    assert!((f - f_kane).norm() <= 1e-13 * f_kane.norm());
    let (a, a_kane) = (
        p.acceleration(0.0, &q, &qd).unwrap(),
        kane.acceleration(0.0, &q, &qd).unwrap(),
    );
    assert!(
        (a - a_kane).norm() <= 1e-12 * a_kane.norm(),
        "{a:?}\n{a_kane:?}"
    );
}
