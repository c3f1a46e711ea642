//! Inverse dynamics of joint trees by recursive Newton-Euler (generated), against the mass-
//! matrix form `M qdd - f` of the same model, a closed form written out below, and forward
//! dynamics (the accelerations a load causes, fed back, give that load).

use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// `|ID(qdd) - (M qdd - f)| <= 1e-12 (|M| |qdd| + |f|)` at each state, for a few `qdd`.
fn equals_mass_matrix_form<const N: usize>(
    model: &impl MechanismModel<N>,
    states: &[([f64; N], [f64; N])],
    t: f64,
) {
    for (k, (q, qd)) in states.iter().enumerate() {
        let (q, qd) = (Vector::<N>::from(*q), Vector::<N>::from(*qd));
        let qdd = Vector::<N>::from_fn(|i, _| ((i + 3 * k) as f64 * 1.7).sin() * 4.0);
        let mass: Matrix<N, N> = model.mass_matrix(t, &q).unwrap();
        let f = model.forces(t, &q, &qd).unwrap();
        let by_mass = mass * qdd - f;
        let rnea = model.inverse_dynamics(t, &q, &qd, &qdd).unwrap();
        let scale = mass.norm() * qdd.norm() + f.norm();
        assert!(
            (rnea - by_mass).norm() <= 1e-12 * scale,
            "Newton-Euler {rnea:?}\nM qdd - f {by_mass:?}"
        );
    }
}

/// A planar chain of 14 uniform links (a run of identical links: the accelerations come
/// from rolled loops, the mass matrix column by column) with a torque at its first joint.
#[derive(Debug, Mechanism)]
#[mechanism(inverse_dynamics)]
#[gravity(0.0, -g)]
#[chain(link, n = 14, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
pub struct Chain14 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn planar_chain_newton_euler_equals_the_mass_matrix_form() {
    assert!(Chain14::GENERATED.parts.contains(&"inverse_dynamics"));
    let p = Chain14 {
        m: 0.8,
        l: 0.3,
        g: 9.81,
    };
    let q: [f64; 14] = std::array::from_fn(|i| (i as f64 * 0.9).sin());
    let qd: [f64; 14] = std::array::from_fn(|i| (i as f64 * 1.3).cos() * 2.0);
    equals_mass_matrix_form(&p, &[(q, qd), ([0.0; 14], [0.0; 14])], 0.0);
}

/// The 7-dof arm of `spatial_tree.rs` (revolute joints about mixed axes with offsets along
/// all three axes, general inertia tensors, a viscous generalised force on `q3`, a driven
/// wrist joint).
#[derive(Debug, Mechanism)]
#[mechanism(spatial, inverse_dynamics)]
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

const ARM_STATES: [([f64; 6], [f64; 6]); 2] = [
    (
        [0.3, -0.7, 1.1, 0.4, -2.0, 0.9],
        [1.2, -0.5, 0.8, -2.2, 1.7, 0.3],
    ),
    (
        [-2.5, 1.3, -0.2, 2.8, 0.6, -1.4],
        [-0.9, 2.1, -1.6, 0.4, -0.3, 2.6],
    ),
];

#[test]
fn seven_dof_arm_newton_euler_equals_the_mass_matrix_form() {
    assert!(Arm7::GENERATED.parts.contains(&"inverse_dynamics"));
    let p = Arm7 {
        m7: 0.4,
        c: 0.7,
        g: 9.81,
    };
    equals_mass_matrix_form(&p, &ARM_STATES, 0.37);
}

/// Forward, then inverse: the arm's accelerations with its damper, fed to the arm without
/// it, need exactly the damper's generalised force `-c qd3` on `q3` and nothing elsewhere;
/// fed to the arm with it, nothing.
#[test]
fn seven_dof_arm_inverse_of_forward_gives_the_applied_force() {
    let (c, t) = (0.7, 0.37);
    let damped = Arm7 {
        m7: 0.4,
        c,
        g: 9.81,
    };
    let free = Arm7 { c: 0.0, ..damped };
    for (q, qd) in ARM_STATES {
        let (q, qd) = (Vector::<6>::from(q), Vector::<6>::from(qd));
        let qdd = damped.acceleration(t, &q, &qd).unwrap();
        let mut applied = Vector::<6>::zeros();
        applied[2] = -c * qd[2];
        let scale = damped.mass_matrix(t, &q).unwrap().norm() * qdd.norm();
        let needed = free.inverse_dynamics(t, &q, &qd, &qdd).unwrap();
        assert!((needed - applied).norm() <= 1e-12 * scale, "{needed:?}");
        let residual = damped.inverse_dynamics(t, &q, &qd, &qdd).unwrap();
        assert!(residual.norm() <= 1e-12 * scale, "{residual:?}");
    }
}

/// Two links on revolute joints (angles from the downward vertical, `q2` relative), with an
/// applied torque at each joint.
#[derive(Debug, Mechanism)]
#[mechanism(inverse_dynamics)]
#[gravity(0.0, -g)]
#[body(upper, joint = revolute(q1), com = [0.0, -c1], mass = m1, inertia = i1)]
#[body(lower, parent = upper, joint = revolute(q2), at = [0.0, -l1], com = [0.0, -c2],
       mass = m2, inertia = i2)]
#[generalized_force(u1, along = q1, value = tau1)]
#[generalized_force(u2, along = q2, value = tau2)]
pub struct TwoLink {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub c1: f64,
    pub c2: f64,
    pub i1: f64,
    pub i2: f64,
    pub g: f64,
    pub tau1: f64,
    pub tau2: f64,
}

/// The textbook closed form of [`TwoLink`] (its own derivation, by Lagrange's equations with
/// `h = m2 l1 c2 sin q2`): `M qdd + C + G - tau`.
fn two_link_by_hand(p: &TwoLink, q: [f64; 2], qd: [f64; 2], qdd: [f64; 2]) -> [f64; 2] {
    let (s1, s12, c2) = (q[0].sin(), (q[0] + q[1]).sin(), q[1].cos());
    let m22 = p.i2 + p.m2 * p.c2 * p.c2;
    let m12 = m22 + p.m2 * p.l1 * p.c2 * c2;
    let m11 = p.i1
        + p.m1 * p.c1 * p.c1
        + p.i2
        + p.m2 * (p.l1 * p.l1 + p.c2 * p.c2)
        + 2.0 * p.m2 * p.l1 * p.c2 * c2;
    let h = p.m2 * p.l1 * p.c2 * q[1].sin();
    let g1 = p.g * ((p.m1 * p.c1 + p.m2 * p.l1) * s1 + p.m2 * p.c2 * s12);
    let g2 = p.g * p.m2 * p.c2 * s12;
    [
        m11 * qdd[0] + m12 * qdd[1] - h * (2.0 * qd[0] * qd[1] + qd[1] * qd[1]) + g1 - p.tau1,
        m12 * qdd[0] + m22 * qdd[1] + h * qd[0] * qd[0] + g2 - p.tau2,
    ]
}

#[test]
fn two_link_newton_euler_equals_the_closed_form() {
    assert!(TwoLink::GENERATED.parts.contains(&"inverse_dynamics"));
    let p = TwoLink {
        m1: 1.3,
        m2: 0.9,
        l1: 0.7,
        c1: 0.3,
        c2: 0.25,
        i1: 0.06,
        i2: 0.03,
        g: 9.81,
        tau1: 0.8,
        tau2: -0.4,
    };
    let states = [
        ([0.4, -1.1], [1.5, -0.8], [2.0, 3.5]),
        ([-2.3, 2.9], [-0.6, 2.4], [-1.2, 0.7]),
    ];
    for (q, qd, qdd) in states {
        let by_hand = Vector::<2>::from(two_link_by_hand(&p, q, qd, qdd));
        let (q, qd, qdd) = (Vector::from(q), Vector::from(qd), Vector::from(qdd));
        let rnea = p.inverse_dynamics(0.0, &q, &qd, &qdd).unwrap();
        assert!(
            (rnea - by_hand).norm() <= 1e-12 * by_hand.norm().max(1.0),
            "{rnea:?} {by_hand:?}"
        );
    }
    equals_mass_matrix_form(&p, &[([0.4, -1.1], [1.5, -0.8])], 0.0);
    // Forward, then inverse: the torques' accelerations, fed to the links without torques,
    // need those torques.
    let free = TwoLink {
        tau1: 0.0,
        tau2: 0.0,
        ..p
    };
    let (q, qd) = (Vector::from([0.4, -1.1]), Vector::from([1.5, -0.8]));
    let qdd = p.acceleration(0.0, &q, &qd).unwrap();
    let needed = free.inverse_dynamics(0.0, &q, &qd, &qdd).unwrap();
    let applied = Vector::<2>::from([p.tau1, p.tau2]);
    assert!(
        (needed - applied).norm() <= 1e-12 * applied.norm(),
        "{needed:?}"
    );
}

/// The same two-link arm without `#[mechanism(inverse_dynamics)]`: the Newton-Euler method
/// is left out (a scene that does not ask for it does not pay for it) and the trait's
/// `M qdd - f` answers, equal to the generated one.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(upper, joint = revolute(q1), com = [0.0, -c1], mass = m1, inertia = i1)]
#[body(lower, parent = upper, joint = revolute(q2), at = [0.0, -l1], com = [0.0, -c2],
       mass = m2, inertia = i2)]
pub struct TwoLinkPlain {
    pub g: f64,
    pub l1: f64,
    pub c1: f64,
    pub c2: f64,
    pub m1: f64,
    pub m2: f64,
    pub i1: f64,
    pub i2: f64,
}

#[test]
fn inverse_dynamics_is_generated_only_when_asked() {
    assert!(!TwoLinkPlain::GENERATED.parts.contains(&"inverse_dynamics"));
    let (g, l1, c1, c2, m1, m2, i1, i2) = (9.81, 1.1, 0.5, 0.45, 2.0, 1.5, 0.2, 0.12);
    let plain = TwoLinkPlain {
        g,
        l1,
        c1,
        c2,
        m1,
        m2,
        i1,
        i2,
    };
    let asked = TwoLink {
        g,
        l1,
        c1,
        c2,
        m1,
        m2,
        i1,
        i2,
        tau1: 0.0,
        tau2: 0.0,
    };
    let (q, qd, qdd) = (
        Vector::<2>::new(0.3, -0.7),
        Vector::<2>::new(1.2, 0.4),
        Vector::<2>::new(-2.0, 3.0),
    );
    let by_default = plain.inverse_dynamics(0.0, &q, &qd, &qdd).unwrap();
    let by_rnea = asked.inverse_dynamics(0.0, &q, &qd, &qdd).unwrap();
    assert!((by_default - by_rnea).norm() <= 1e-12 * (1.0 + by_rnea.norm()));
}
