//! Rolled runs of identical spatial links (`spatial/roll.rs`): a long chain's tail
//! generated once, as three loops over the links. The rolled articulated-body recursion
//! is checked against Kane's form of the same chain (`#[mechanism(mass_matrix)]`: the
//! mass matrix and forces by projections, an independent derivation) for links of one step
//! (revolute), two (universal) and three (Euler spherical), with a branch off the chain
//! before the run; and a rolled chain's energy is conserved along a motion.

use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// Ten bars on universal joints (the `scaling` report's spatial chain, with offsets and
/// products of inertia): the first bar hangs from the ground, the other nine are a run.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(link1, joint = universal(a1, b1), com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link2, parent = link1, joint = universal(a2, b2), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link3, parent = link2, joint = universal(a3, b3), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link4, parent = link3, joint = universal(a4, b4), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link5, parent = link4, joint = universal(a5, b5), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link6, parent = link5, joint = universal(a6, b6), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link7, parent = link6, joint = universal(a7, b7), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link8, parent = link7, joint = universal(a8, b8), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link9, parent = link8, joint = universal(a9, b9), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link10, parent = link9, joint = universal(a10, b10), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
pub struct Universal10 {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// [`Universal10`] by Kane's projections.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(link1, joint = universal(a1, b1), com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link2, parent = link1, joint = universal(a2, b2), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link3, parent = link2, joint = universal(a3, b3), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link4, parent = link3, joint = universal(a4, b4), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link5, parent = link4, joint = universal(a5, b5), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link6, parent = link5, joint = universal(a6, b6), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link7, parent = link6, joint = universal(a7, b7), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link8, parent = link7, joint = universal(a8, b8), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link9, parent = link8, joint = universal(a9, b9), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link10, parent = link9, joint = universal(a10, b10), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
pub struct Universal10Kane {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// Seven bodies on Euler spherical joints (three steps a link), the first off the ground.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(link1, joint = spherical(a1, b1, c1), at = [0.0, 0.0, 0.3], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link2, parent = link1, joint = spherical(a2, b2, c2), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link3, parent = link2, joint = spherical(a3, b3, c3), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link4, parent = link3, joint = spherical(a4, b4, c4), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link5, parent = link4, joint = spherical(a5, b5, c5), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link6, parent = link5, joint = spherical(a6, b6, c6), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link7, parent = link6, joint = spherical(a7, b7, c7), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
pub struct Spherical7 {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// [`Spherical7`] by Kane's projections.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(link1, joint = spherical(a1, b1, c1), at = [0.0, 0.0, 0.3], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link2, parent = link1, joint = spherical(a2, b2, c2), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link3, parent = link2, joint = spherical(a3, b3, c3), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link4, parent = link3, joint = spherical(a4, b4, c4), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link5, parent = link4, joint = spherical(a5, b5, c5), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link6, parent = link5, joint = spherical(a6, b6, c6), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link7, parent = link6, joint = spherical(a7, b7, c7), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
pub struct Spherical7Kane {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// Eight bodies on hinges about `x` with a side body on a hinge about `z` off the first,
/// declared before the rest (a run is the tail of the declarations): the run is the last
/// seven.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(link1, joint = revolute(a1, x), com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(side, parent = link1, joint = revolute(c, z), at = [0.1, 0.0, -0.2], com = [0.05, 0.0, 0.0], mass = m,
       inertia = diag(0.002, 0.003, 0.004))]
#[body(link2, parent = link1, joint = revolute(a2, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link3, parent = link2, joint = revolute(a3, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link4, parent = link3, joint = revolute(a4, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link5, parent = link4, joint = revolute(a5, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link6, parent = link5, joint = revolute(a6, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link7, parent = link6, joint = revolute(a7, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link8, parent = link7, joint = revolute(a8, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
pub struct Hinges8 {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// [`Hinges8`] by Kane's projections.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(link1, joint = revolute(a1, x), com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(side, parent = link1, joint = revolute(c, z), at = [0.1, 0.0, -0.2], com = [0.05, 0.0, 0.0], mass = m,
       inertia = diag(0.002, 0.003, 0.004))]
#[body(link2, parent = link1, joint = revolute(a2, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link3, parent = link2, joint = revolute(a3, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link4, parent = link3, joint = revolute(a4, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link5, parent = link4, joint = revolute(a5, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link6, parent = link5, joint = revolute(a6, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link7, parent = link6, joint = revolute(a7, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
#[body(link8, parent = link7, joint = revolute(a8, x), at = [0.0, 0.01, -l], com = [0.02, 0.0, -l / 2.0], mass = m,
       inertia = [[i, 0.001, 0.0], [0.001, i, 0.002], [0.0, 0.002, j]])]
pub struct Hinges8Kane {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// `|M qdd - f| <= 1e-12 (|M| |qdd| + |f|)` (backward error: the forward one would add
/// `M`'s condition number), with `M`, `f` from the Kane twin, at fixed irregular states.
fn rolled_equals_kane<const N: usize>(
    rolled: &impl MechanismModel<N>,
    kane: &impl MechanismModel<N>,
) {
    for seed in [3usize, 7, 11] {
        let q =
            Vector::<N>::from_fn(|i, _| 1.2 * ((((i + 1) * seed * 37) % 17) as f64 / 8.0 - 1.0));
        let qd =
            Vector::<N>::from_fn(|i, _| 2.0 * ((((i + 2) * seed * 11) % 13) as f64 / 6.0 - 1.0));
        let qdd = rolled.acceleration(0.0, &q, &qd).unwrap();
        let mass: Matrix<N, N> = kane.mass_matrix(0.0, &q).unwrap();
        let f = kane.forces(0.0, &q, &qd).unwrap();
        let residual = (mass * qdd - f).amax();
        let size = mass.norm() * qdd.norm() + f.norm();
        assert!(
            residual <= 1e-12 * size,
            "|M qdd - f| = {residual:e}, scale {size:e}"
        );
        assert!(qdd.norm() > 1.0, "a trivial state");
    }
}

const M: f64 = 1.3;
const L: f64 = 0.7;
const I: f64 = M * L * L / 12.0;
const J: f64 = 0.004;
const G: f64 = 9.81;

#[test]
fn universal_chain_rolled_equals_kanes_form() {
    assert!(Universal10::GENERATED.parts.contains(&"rolled_chain"));
    let p = Universal10 {
        m: M,
        l: L,
        i: I,
        j: J,
        g: G,
    };
    let k = Universal10Kane {
        m: M,
        l: L,
        i: I,
        j: J,
        g: G,
    };
    rolled_equals_kane::<20>(&p, &k);
}

#[test]
fn spherical_chain_rolled_equals_kanes_form() {
    assert!(Spherical7::GENERATED.parts.contains(&"rolled_chain"));
    let p = Spherical7 {
        m: M,
        l: L,
        i: I,
        j: J,
        g: G,
    };
    let k = Spherical7Kane {
        m: M,
        l: L,
        i: I,
        j: J,
        g: G,
    };
    rolled_equals_kane::<21>(&p, &k);
}

#[test]
fn hinge_chain_with_a_branch_rolled_equals_kanes_form() {
    assert!(Hinges8::GENERATED.parts.contains(&"rolled_chain"));
    let p = Hinges8 {
        m: M,
        l: L,
        i: I,
        j: J,
        g: G,
    };
    let k = Hinges8Kane {
        m: M,
        l: L,
        i: I,
        j: J,
        g: G,
    };
    rolled_equals_kane::<9>(&p, &k);
}

/// No damping, no loads: the rolled chain conserves its energy along 1 s of motion
/// (DOPRI5 at 1e-11).
#[test]
fn rolled_universal_chain_conserves_energy() {
    let p = Universal10 {
        m: M,
        l: L,
        i: I,
        j: J,
        g: G,
    };
    let y0 = Vector::<40>::from_fn(|i, _| {
        if i < 20 {
            0.3 * (((i * 7) % 5) as f64 - 2.0)
        } else {
            0.0
        }
    });
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        dense: false,
        ..Default::default()
    };
    let sol = Dopri5::new(opts).solve(&p, 0.0, y0, 1.0, &[]).unwrap();
    let energy = |y: &Vector<40>| {
        p.energy(
            0.0,
            &y.fixed_rows::<20>(0).into_owned(),
            &y.fixed_rows::<20>(20).into_owned(),
        )
        .unwrap()
    };
    let (e0, (_, y1)) = (energy(&y0), sol.last());
    assert!(
        (energy(y1) - e0).abs() <= 1e-9 * e0.abs(),
        "{} against {e0}",
        energy(y1)
    );
    assert!((y1 - y0).norm() > 1.0, "it moved");
}
