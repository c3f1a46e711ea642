//! The derive on the smallest models, checked against equations written by hand.

use approx::assert_relative_eq;
use mbd::Vector;
use mbd::prelude::*;

/// Simple pendulum: a point mass `m` on a massless rod of length `l`, angle `theta` from
/// the downward vertical. By hand: `m l^2 theta'' = -m g l sin(theta)`.
#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[particle(bob, mass = m, at = [l * sin(theta), -l * cos(theta)])]
#[init(theta = PI / 3.0)]
#[output(speed = norm(velocity(bob)))]
#[event(bottom = theta, falling, terminal)]
#[derive(Debug)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn pendulum_equations_match_the_hand_derivation() {
    let p = Pendulum {
        m: 2.0,
        l: 0.7,
        g: 9.81,
    };
    let q = Vector::<1>::new(0.4);
    let qd = Vector::<1>::new(-1.3);
    let mass = p.mass_matrix(0.0, &q).unwrap();
    assert_relative_eq!(mass[(0, 0)], 2.0 * 0.7 * 0.7, max_relative = 1e-15);
    let f = p.forces(0.0, &q, &qd).unwrap();
    assert_relative_eq!(f[0], -2.0 * 9.81 * 0.7 * 0.4f64.sin(), max_relative = 1e-15);
    let qdd = MechanismModel::acceleration(&p, 0.0, &q, &qd).unwrap();
    assert_relative_eq!(qdd[0], -9.81 / 0.7 * 0.4f64.sin(), max_relative = 1e-15);
    // Energy: m l^2 qd^2 / 2 - m g l cos(theta).
    let e = p.energy(0.0, &q, &qd).unwrap();
    assert_relative_eq!(
        e,
        0.5 * 2.0 * 0.49 * 1.69 - 2.0 * 9.81 * 0.7 * 0.4f64.cos(),
        max_relative = 1e-15
    );
    let y = p.initial_state();
    assert_relative_eq!(y[0], std::f64::consts::PI / 3.0);
    let o = p.outputs(0.0, &Vector::<2>::new(0.4, -1.3)).unwrap();
    assert_relative_eq!(o.speed, 0.7 * 1.3, max_relative = 1e-15);
    assert!(!Pendulum::GENERATED.parts.contains(&"phi"));
}
