//! Bricard's mechanism (the IFToMM multibody benchmark A04): five rods of length 1 m and mass
//! 1 kg (square section 0.1 m) and the ground, joined in one loop by six revolute joints
//! whose axes lie on edges of a unit cube; gravity along `-y`.
//!
//! **Geometry** (the benchmark's initial position): the joints sit at `(0,0,0)`, `(1,0,0)`,
//! `(1,-1,0)`, `(1,-1,1)`, `(0,-1,1)` and `(0,0,1)`; the rods run between consecutive joints
//! and the ground closes the loop from `(0,0,1)` back to the origin along `z`. Each joint
//! axis is perpendicular to both rods it joins: `y`, `z`, `x`, `y`, `z` and, at the closing
//! joint, `x`. (A 6R loop with equal links, zero offsets and right-angle twists: Bricard's
//! mobile over-constrained linkage.)
//!
//! **Model.** The five rods are a spatial joint tree from the origin, one relative angle per
//! joint, all zero at the initial position. The sixth (closing) joint is a revolute `close`
//! between rod 5's tip and the ground's `(0,0,1)`, about rod 5's `x` axis and the ground's
//! `x` axis: five equations (the tip stays at `(0,0,1)`, and rod 5's `x` axis stays normal to
//! the ground's `y` and `z`). Five coordinates and five equations: Grübler's count is zero,
//! yet the mechanism moves with one degree of freedom because one equation is dependent on
//! the others (found at run time by `mbd::analysis::rank_and_redundant`; the augmented solve
//! returns minimum-norm multipliers).

use mbd::prelude::*;

/// Rod inertia about its mass centre: axial `m (a^2 + a^2) / 12`, transverse
/// `m (l^2 + a^2) / 12`, for length `l = 1` and section side `a = 0.1` (the benchmark's).
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
#[close(hinge, joint = revolute, a = rod5, at_a = [0.0, 1.0, 0.0], axis_a = [1.0, 0.0, 0.0],
        b = ground, at_b = [0.0, 0.0, 1.0], axis_b = [1.0, 0.0, 0.0])]
pub struct Bricard {
    /// Rod mass (1 kg in the benchmark).
    pub m: f64,
    /// Axial moment of inertia of a rod.
    pub ia: f64,
    /// Transverse moment of inertia of a rod about its mass centre.
    pub it: f64,
    /// Gravity.
    pub g: f64,
}

impl Bricard {
    /// The benchmark's data: 1 kg rods of 1 m with a 0.1 m square section, `g = 9.81`.
    pub fn benchmark() -> Self {
        let (m, l, a) = (1.0, 1.0, 0.1);
        Bricard {
            m,
            ia: m * (a * a + a * a) / 12.0,
            it: m * (l * l + a * a) / 12.0,
            g: 9.81,
        }
    }
}
