//! Repeated cells: the 40-loop four-bar assembly (IFToMM A02) written with one
//! `#[repeat(..)]` (three stamped attributes and the last crank, 5 lines of attributes)
//! must be the very model the written-out one is (`mechanisms`' 121 attribute lines by a
//! `macro_rules!` table): the same coordinates, generated statements and constraints, and
//! bit-for-bit the same right-hand side and multipliers.

use mbd::prelude::*;
use mbd::{OdeSystem, Vector};

/// The written-out model, as `mechanisms` declares it (its own source file).
#[allow(dead_code)]
#[path = "../../mechanisms/src/fourbar_assembly.rs"]
mod written_out;

use written_out::{D, FourBarAssembly, N};

/// The same assembly, its 40 identical loops as one repeated cell.
#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[repeat(i in 0..40,
    body(crank[i], joint = revolute(c[i]), at = [i * l, 0.0], com = [0.5 * l, 0.0],
         mass = m, inertia = m * l * l / 12.0),
    body(coupler[i], parent = crank[i], joint = revolute(k[i]), at = [l, 0.0],
         com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0),
    close(pin[i], a = coupler[i], at_a = [l, 0.0], b = crank[i + 1], at_b = [l, 0.0]))]
#[body(crank40, joint = revolute(c40), at = [40.0 * l, 0.0], com = [0.5 * l, 0.0],
       mass = m, inertia = m * l * l / 12.0)]
pub struct CompactAssembly {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// Three loops written out by hand beside the same three as a cell, small enough to read.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(crank0, joint = revolute(c0), at = [0.0 * l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0)]
#[body(coupler0, parent = crank0, joint = revolute(k0), at = [l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0)]
#[close(pin0, a = coupler0, at_a = [l, 0.0], b = crank1, at_b = [l, 0.0])]
#[body(crank1, joint = revolute(c1), at = [1.0 * l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0)]
#[body(coupler1, parent = crank1, joint = revolute(k1), at = [l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0)]
#[close(pin1, a = coupler1, at_a = [l, 0.0], b = crank2, at_b = [l, 0.0])]
#[body(crank2, joint = revolute(c2), at = [2.0 * l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0)]
pub struct TwoLoopsByHand {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// [`TwoLoopsByHand`] as a repeated cell (`..=` includes the end).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[repeat(i in 0..=1,
    body(crank[i], joint = revolute(c[i]), at = [i * l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0),
    body(coupler[i], parent = crank[i], joint = revolute(k[i]), at = [l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0),
    close(pin[i], a = coupler[i], at_a = [l, 0.0], b = crank[i + 1], at_b = [l, 0.0]))]
#[body(crank2, joint = revolute(c2), at = [2.0 * l, 0.0], com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0)]
pub struct TwoLoops {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn a_repeated_cell_is_the_model_written_out() -> Result<(), mbd::Error> {
    assert_eq!(TwoLoops::COORDINATES, TwoLoopsByHand::COORDINATES);
    assert_eq!(
        TwoLoops::GENERATED.statements,
        TwoLoopsByHand::GENERATED.statements
    );
    assert_eq!(TwoLoops::GENERATED.parts, TwoLoopsByHand::GENERATED.parts);
    let (a, b) = (
        TwoLoops {
            m: 1.2,
            l: 0.9,
            g: 9.81,
        },
        TwoLoopsByHand {
            m: 1.2,
            l: 0.9,
            g: 9.81,
        },
    );
    let y = Vector::<10>::from_fn(|i, _| 0.3 + 0.17 * i as f64);
    assert_eq!(a.rhs(0.0, &y)?, b.rhs(0.0, &y)?);
    Ok(())
}

#[test]
fn the_compact_40_loop_assembly_is_the_written_out_one() -> Result<(), mbd::Error> {
    assert_eq!(CompactAssembly::COORDINATES, FourBarAssembly::COORDINATES);
    let (c, w) = (CompactAssembly::GENERATED, FourBarAssembly::GENERATED);
    assert_eq!(
        (c.parts, c.statements, c.constraints),
        (w.parts, w.statements, w.constraints)
    );
    let written = FourBarAssembly::benchmark();
    let compact = CompactAssembly {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let start = written.benchmark_state(1.0);
    // The benchmark's start and a perturbed, non-parallelogram state (the rhs projects
    // nothing: both solve the same augmented system at the same point).
    let skew = Vector::<D>::from_fn(|i, _| start[i] + 1e-3 * ((i * 7919) % 13) as f64);
    for y in [start, skew] {
        assert_eq!(compact.rhs(0.0, &y)?, written.rhs(0.0, &y)?);
        let (q, qd) = (y.fixed_rows::<N>(0).into(), y.fixed_rows::<N>(N).into());
        let a = compact.acceleration_and_multipliers(0.0, &q, &qd)?;
        let b = written.acceleration_and_multipliers(0.0, &q, &qd)?;
        assert_eq!(a, b);
    }
    Ok(())
}
