//! A 32-link chain: generated bodies of tens of thousands of temporaries (Kane's mass
//! matrix and forces, the articulated-body recursion).
//!
//! Regression: each `let` opens a lexical scope nesting the rest of the body, and with debug
//! information rustc (LLVM's DWARF writer) overflowed its stack on this model in the default
//! `dev` profile and in any profile with `debug >= 1`. Long bodies now declare their
//! temporaries in groups; the workspace builds this crate with `debug = "limited"` in release
//! (see the root `Cargo.toml`), so `cargo test --workspace --release` compiles the case that
//! crashed.
//!
//! The check is independent of the layout: the recursion's accelerations equal the solve
//! of the mass-matrix form `M(q) qdd = f(q, qd)`, two separate derivations (Featherstone's
//! recursion vs Kane's projections) through two separately generated bodies.

use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// Thirty-two uniform links hanging from a pin.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 32, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
pub struct Chain32 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn thirty_two_link_recursion_equals_the_mass_matrix_form() {
    let chain = Chain32 {
        m: 1.3,
        l: 0.7,
        g: 9.81,
    };
    assert!(Chain32::GENERATED.parts.contains(&"articulated_body"));
    assert!(Chain32::GENERATED.parts.contains(&"rolled_chain"));
    // A fixed, irregular state: angles in [-1.2, 1.2], rates in [-2, 2].
    let q = Vector::<32>::from_fn(|i, _| 1.2 * (((i * 37) % 17) as f64 / 8.0 - 1.0));
    let qd = Vector::<32>::from_fn(|i, _| 2.0 * (((i * 11) % 13) as f64 / 6.0 - 1.0));
    let qdd = MechanismModel::acceleration(&chain, 0.0, &q, &qd).unwrap();
    let mass: Matrix<32, 32> = chain.mass_matrix(0.0, &q).unwrap();
    let f = chain.forces(0.0, &q, &qd).unwrap();
    assert!((mass - mass.transpose()).norm() <= 1e-13 * mass.norm());
    // Backward error: the recursion's qdd satisfies M qdd = f to rounding (a forward
    // comparison would add M's condition number, 1.7e6 here, to the bound). 1e-13 is about
    // N^2 eps for N = 32; the measured ratio is 2e-17.
    let residual = (mass * qdd - f).amax();
    let size = mass.norm() * qdd.norm() + f.norm();
    assert!(
        residual <= 1e-13 * size,
        "|M qdd - f| = {residual:e}, scale {size:e}"
    );
}
