//! The hand-written spatial articulated-body chain against the derive's model of the same
//! chain in its mass-matrix form (Kane's projections of the composed kinematics, an LU
//! solve): an independent derivation, so the scaling report's timings compare like with like.

use mbd::prelude::*;
use mbd::{Matrix, Vector};
use mechanisms::spatial_chain_by_hand::{SpatialChainByHand, spatial_chain_source};

#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(u1, joint = universal(a1, b1), com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u2, parent = u1, joint = universal(a2, b2), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u3, parent = u2, joint = universal(a3, b3), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
pub struct Universal3 {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

#[test]
fn the_source_writer_writes_this_model() {
    let written = spatial_chain_source("Universal3", 3, "mass_matrix");
    let here = include_str!("spatial_chain_by_hand.rs");
    // The attributes, in order (rustfmt lays out the struct's fields).
    let attributes: Vec<&str> = written.lines().filter(|l| l.starts_with("#[")).collect();
    assert_eq!(attributes.len(), 6);
    assert!(here.contains(&attributes.join("\n")), "{written}");
    assert!(written.contains("pub struct Universal3 {"));
}

#[test]
fn hand_written_recursion_equals_the_mass_matrix_form() {
    let (m, l, i, j, g) = (1.3, 0.7, 0.06, 0.004, 9.81);
    let model = Universal3 { m, l, i, j, g };
    let hand = SpatialChainByHand::<3>::new(m, l, i, j, g);
    for (q, qd) in [
        (
            [0.3, -0.4, 0.9, 0.2, -1.1, 0.7],
            [1.0, -0.3, 0.6, -1.4, 0.8, 0.2],
        ),
        (
            [-2.0, 1.2, 0.1, -0.8, 2.6, -1.5],
            [-0.5, 2.2, -1.7, 0.3, 1.1, -2.4],
        ),
    ] {
        let (qv, qdv) = (Vector::<6>::from(q), Vector::<6>::from(qd));
        let mass: Matrix<6, 6> = model.mass_matrix(0.0, &qv).unwrap();
        let f = model.forces(0.0, &qv, &qdv).unwrap();
        let reference = mbd::solve::solve_mass(0.0, &mass, &f).unwrap();
        let by_hand = hand.acceleration(&q, &qd).unwrap();
        for k in 0..6 {
            assert!(
                (by_hand[k] - reference[k]).abs() <= 1e-12 * reference.norm(),
                "qdd[{k}]: by hand {}, mass-matrix form {}",
                by_hand[k],
                reference[k]
            );
        }
        // The first-order form carries the same accelerations.
        let y = Vector::<12>::from_fn(|r, _| if r < 6 { q[r] } else { qd[r - 6] });
        let dy = hand.rhs(0.0, &y).unwrap();
        assert_eq!(dy.rows(6, 6).iter().copied().collect::<Vec<_>>(), by_hand);
    }
}

#[test]
fn a_massless_chain_is_refused() {
    let hand = SpatialChainByHand::<2>::new(0.0, 0.7, 0.06, 0.004, 9.81);
    assert!(hand.acceleration(&[0.0; 4], &[0.0; 4]).is_err());
}
