//! Bricard's closing revolute joint written with the language's `close(joint = revolute)`
//! (`mechanisms::bricard::Bricard`) against the same joint written by hand: a spherical
//! `close` plus two axis-alignment constraints that repeat rod 5's rotation chain (the form
//! the model had before revolute `close` joints existed).

use mbd::prelude::*;
use mbd::{Constrained, Vector};
use mechanisms::bricard::Bricard;

#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial, augmented)]
#[gravity(0.0, -g, 0.0)]
#[body(rod1, joint = revolute(q1, y), com = [0.5, 0.0, 0.0], mass = m,
       inertia = diag(ia, it, it))]
#[body(rod2, parent = rod1, joint = revolute(q2, z), at = [1.0, 0.0, 0.0],
       com = [0.0, -0.5, 0.0], mass = m, inertia = diag(it, ia, it))]
#[body(rod3, parent = rod2, joint = revolute(q3, x), at = [0.0, -1.0, 0.0],
       com = [0.0, 0.0, 0.5], mass = m, inertia = diag(it, it, ia))]
#[body(rod4, parent = rod3, joint = revolute(q4, y), at = [0.0, 0.0, 1.0],
       com = [-0.5, 0.0, 0.0], mass = m, inertia = diag(ia, it, it))]
#[body(rod5, parent = rod4, joint = revolute(q5, z), at = [-1.0, 0.0, 0.0],
       com = [0.0, 0.5, 0.0], mass = m, inertia = diag(it, ia, it))]
#[close(tip, a = rod5, at_a = [0.0, 1.0, 0.0], b = ground, at_b = [0.0, 0.0, 1.0])]
#[point(axis5, at = rot_y(q1) * rot_z(q2) * rot_x(q3) * rot_y(q4) * rot_z(q5) * [1.0, 0.0, 0.0])]
#[constraint(axis5[1] == 0.0)]
#[constraint(axis5[2] == 0.0)]
pub struct BricardByHand {
    pub m: f64,
    pub ia: f64,
    pub it: f64,
    pub g: f64,
}

/// The revolute `close` about `x` in both frames has rows `d` (3) and `u_a . n1`, `u_a . n2`
/// with `(n1, n2) = (z, -y)` (the normals picked for the axis `x`: `x × y` from the least
/// aligned coordinate axis, then `x × z`), i.e. the hand-written rows `axis5[2]` and
/// `-axis5[1]`, at any configuration (on the loop or off it).
#[test]
fn revolute_close_rows_equal_the_hand_written_ones() {
    let b = Bricard::benchmark();
    let h = BricardByHand {
        m: b.m,
        ia: b.ia,
        it: b.it,
        g: b.g,
    };
    // The hand-written model lists its two `constraint`s before the `close`'s three rows.
    let sign = [1.0, 1.0, 1.0, 1.0, -1.0];
    let order = [2, 3, 4, 1, 0];
    for q in [
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [0.3, -0.7, 1.1, 0.2, -0.4],
        [2.0, 1.0, -2.5, 0.9, 3.0],
    ] {
        let q = Vector::<5>::from(q);
        let (pc, ph) = (
            Constrained::<5, 5>::phi(&b, 0.0, &q),
            Constrained::<5, 5>::phi(&h, 0.0, &q),
        );
        let (jc, jh) = (
            Constrained::<5, 5>::phi_q(&b, 0.0, &q),
            Constrained::<5, 5>::phi_q(&h, 0.0, &q),
        );
        for (k, &o) in order.iter().enumerate() {
            assert!((pc[k] - sign[k] * ph[o]).abs() < 1e-15, "{pc} vs {ph}");
            for j in 0..5 {
                assert!(
                    (jc[(k, j)] - sign[k] * jh[(o, j)]).abs() < 1e-14,
                    "{jc} vs {jh}"
                );
            }
        }
    }
}
