//! Hunting big models: a long spatial tree whose mass matrix is formed at run time (12 or
//! more free coordinates: `M qdd` by Newton-Euler instead of the written-out composite
//! rigid bodies, which made the derive's expansion quadratic in the bodies) and whose root
//! joint is driven, a known function of time. The driven joint's known acceleration enters
//! the free coordinates' forces as `-(M a_driven)`, now through the same `M qdd` code;
//! checked against Kane's form of the same model (`#[mechanism(mass_matrix)]`: `M` and `f`
//! by the bodies' projections, an independent derivation) at spread states and times.

use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// One driven revolute joint at the root, then 12 free ones about alternating axes with
/// offsets, masses and inertias that differ from link to link (no rolled tail).
macro_rules! arm {
    ($name:ident, $($form:ident)?) => {
        #[derive(Debug, Mechanism)]
        #[mechanism(spatial $(, $form)?)]
        #[gravity(0.0, 0.0, -g)]
        #[drive(q0 = 0.5 * sin(2.0 * t))]
        #[body(b0, joint = revolute(q0, z), com = [0.05, 0.0, 0.1], mass = 3.0, inertia = diag(0.05, 0.04, 0.03))]
        #[body(b1, parent = b0, joint = revolute(q1, y), at = [0.1, 0.0, 0.2], com = [0.2, 0.01, 0.0], mass = 2.0, inertia = diag(0.01, 0.03, 0.03))]
        #[body(b2, parent = b1, joint = revolute(q2, x), at = [0.4, 0.0, 0.0], com = [0.1, 0.0, 0.02], mass = 1.9, inertia = diag(0.02, 0.01, 0.02))]
        #[body(b3, parent = b2, joint = revolute(q3, y), at = [0.2, 0.03, 0.0], com = [0.15, 0.0, 0.0], mass = 1.8, inertia = [[0.004, 0.0, 0.001], [0.0, 0.015, 0.0], [0.001, 0.0, 0.014]])]
        #[body(b4, parent = b3, joint = revolute(q4, z), at = [0.3, 0.0, -0.05], com = [0.05, 0.0, 0.02], mass = 1.7, inertia = diag(0.003, 0.004, 0.003))]
        #[body(b5, parent = b4, joint = revolute(q5, x), at = [0.1, 0.02, 0.0], com = [0.04, 0.0, 0.0], mass = 1.6, inertia = diag(0.002, 0.003, 0.003))]
        #[body(b6, parent = b5, joint = revolute(q6, y), at = [0.2, 0.0, 0.01], com = [0.1, 0.01, 0.0], mass = 1.5, inertia = diag(0.002, 0.005, 0.004))]
        #[body(b7, parent = b6, joint = revolute(q7, z), at = [0.25, 0.0, 0.0], com = [0.1, 0.0, 0.03], mass = 1.4, inertia = diag(0.003, 0.003, 0.002))]
        #[body(b8, parent = b7, joint = revolute(q8, x), at = [0.2, 0.01, 0.0], com = [0.08, 0.0, 0.0], mass = 1.3, inertia = diag(0.002, 0.002, 0.003))]
        #[body(b9, parent = b8, joint = revolute(q9, y), at = [0.15, 0.0, 0.02], com = [0.07, 0.02, 0.0], mass = 1.2, inertia = diag(0.001, 0.003, 0.002))]
        #[body(b10, parent = b9, joint = revolute(q10, z), at = [0.2, 0.0, 0.0], com = [0.1, 0.0, 0.01], mass = 1.1, inertia = diag(0.002, 0.002, 0.001))]
        #[body(b11, parent = b10, joint = revolute(q11, x), at = [0.1, 0.02, 0.0], com = [0.05, 0.0, 0.0], mass = 1.0, inertia = diag(0.001, 0.002, 0.002))]
        #[body(b12, parent = b11, joint = revolute(q12, y), at = [0.12, 0.0, 0.01], com = [0.06, 0.01, 0.0], mass = m12, inertia = diag(0.001, 0.001, 0.002))]
        pub struct $name {
            pub m12: f64,
            pub g: f64,
        }
    };
}

arm!(Recursive,);
arm!(Kane, mass_matrix);

fn state(seed: f64) -> (Vector<12>, Vector<12>) {
    let q = Vector::<12>::from_fn(|i, _| (1.7 * i as f64 + seed).sin() * 2.5);
    let qd = Vector::<12>::from_fn(|i, _| (2.3 * i as f64 - seed).cos() * 3.0);
    (q, qd)
}

#[test]
fn a_driven_long_tree_equals_kanes_form() {
    assert!(Recursive::GENERATED.parts.contains(&"articulated_body"));
    assert!(!Kane::GENERATED.parts.contains(&"articulated_body"));
    let (rec, kane) = (Recursive { m12: 0.7, g: 9.81 }, Kane { m12: 0.7, g: 9.81 });
    for (k, t) in [0.0, 0.4, 1.3, 2.9].into_iter().enumerate() {
        let (q, qd) = state(k as f64 * 0.9);
        let m_rec: Matrix<12, 12> = rec.mass_matrix(t, &q).unwrap();
        let m_kane: Matrix<12, 12> = kane.mass_matrix(t, &q).unwrap();
        assert!(
            (m_rec - m_kane).norm() <= 1e-12 * m_kane.norm(),
            "M at t = {t}"
        );
        let (f_rec, f_kane) = (
            rec.forces(t, &q, &qd).unwrap(),
            kane.forces(t, &q, &qd).unwrap(),
        );
        assert!(
            (f_rec - f_kane).norm() <= 1e-12 * f_kane.norm().max(1.0),
            "f at t = {t}: {f_rec:?}\n{f_kane:?}"
        );
        let (a_rec, a_kane) = (
            rec.acceleration(t, &q, &qd).unwrap(),
            kane.acceleration(t, &q, &qd).unwrap(),
        );
        assert!(
            (a_rec - a_kane).norm() <= 1e-10 * a_kane.norm().max(1.0),
            "qdd at t = {t}: {a_rec:?}\n{a_kane:?}"
        );
    }
}
