//! Spatial joint trees, generated against hand-written, same run: the right-hand side of 10
//! bars on universal joints (20 coordinates) against the hand-written spatial
//! articulated-body algorithm (`mechanisms::spatial_chain_by_hand`, the same algorithm), and
//! the forward dynamics of a 7-dof arm of revolute joints about mixed axes with offsets.
//! Also the smallest recursive tree (two bodies) against its own mass-matrix form: the
//! threshold from which the derive takes the recursion (`RECURSIVE_FROM_BODIES`). And the
//! arm's inverse dynamics: generated recursive Newton-Euler against `M qdd - f` (the trait's
//! default, from the same model's generated `M` and `f`).
//!
//! `cargo bench -p mechanisms --bench spatial`

use criterion::{Criterion, criterion_group, criterion_main};
use mbd::Vector;
use mbd::prelude::*;
use mechanisms::spatial_chain_by_hand::{SpatialChainByHand, spatial_chain_source};
use std::hint::black_box;
use std::time::Instant;

/// Ten bars on universal joints: what `spatial_chain_source("Universal10", 10, "")` writes.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(u1, joint = universal(a1, b1), com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u2, parent = u1, joint = universal(a2, b2), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u3, parent = u2, joint = universal(a3, b3), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u4, parent = u3, joint = universal(a4, b4), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u5, parent = u4, joint = universal(a5, b5), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u6, parent = u5, joint = universal(a6, b6), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u7, parent = u6, joint = universal(a7, b7), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u8, parent = u7, joint = universal(a8, b8), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u9, parent = u8, joint = universal(a9, b9), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
#[body(u10, parent = u9, joint = universal(a10, b10), at = [0.0, 0.0, -l], com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(i, i, j))]
pub struct Universal10 {
    pub m: f64,
    pub l: f64,
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

/// A 7-dof arm: revolute joints about z, y, x, y, z, x, y with offsets along all three axes,
/// mass centres off the joint axes, two general inertia tensors.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial, inverse_dynamics)]
#[gravity(0.0, 0.0, -g)]
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
       mass = 0.4, inertia = diag(0.0005, 0.0008, 0.0007))]
pub struct Arm7 {
    pub g: f64,
}

/// A spatial double pendulum (universal joint, then a revolute joint about `x`): the
/// smallest tree the derive evaluates by the recursion; [`CardanMassMatrix`] is the same
/// model through the mass-matrix solve.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(upper, joint = universal(a, b), com = [0.0, 0.0, -0.45], mass = 1.3,
       inertia = diag(0.09, 0.09, 0.004))]
#[body(lower, parent = upper, joint = revolute(c, x), at = [0.0, 0.0, -0.9],
       com = [0.0, 0.0, -0.3], mass = 0.7, inertia = diag(0.021, 0.021, 0.002))]
pub struct Cardan {
    pub g: f64,
}

/// [`Cardan`] through the mass-matrix solve.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(upper, joint = universal(a, b), com = [0.0, 0.0, -0.45], mass = 1.3,
       inertia = diag(0.09, 0.09, 0.004))]
#[body(lower, parent = upper, joint = revolute(c, x), at = [0.0, 0.0, -0.9],
       com = [0.0, 0.0, -0.3], mass = 0.7, inertia = diag(0.021, 0.021, 0.002))]
pub struct CardanMassMatrix {
    pub g: f64,
}

/// The least time per call of `generated` and `hand` over interleaved batches.
fn interleaved(name: &str, (first, second): (&str, &str), generated: &dyn Fn(), hand: &dyn Fn()) {
    let batch = |run: &dyn Fn()| {
        let start = Instant::now();
        for _ in 0..1000 {
            run();
        }
        start.elapsed().as_secs_f64() * 1e9 / 1000.0
    };
    let (mut g, mut h) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..300 {
        g = g.min(batch(generated));
        h = h.min(batch(hand));
    }
    println!(
        "{name}: min over interleaved batches: {first} {g:.1} ns, {second} {h:.1} ns, ratio {:.3}",
        g / h
    );
}

fn benches(c: &mut Criterion) {
    assert!(spatial_chain_source("Universal10", 10, "").contains("joint = universal(a10, b10)"));
    let (m, l, g) = (1.3, 0.7, 9.81);
    let (i, j) = (m * l * l / 12.0, 0.004);
    let model = Universal10 { m, l, i, j, g };
    let hand = SpatialChainByHand::<10>::new(m, l, i, j, g);
    let y = Vector::<40>::from_fn(|r, _| 0.9 * (((r * 37) % 17) as f64 / 8.0 - 1.0));
    let (a, b) = (model.rhs(0.0, &y).unwrap(), hand.rhs(0.0, &y).unwrap());
    assert!(
        (a - b).amax() <= 1e-12 * b.amax(),
        "generated and hand-written differ"
    );
    interleaved(
        "universal10 rhs",
        ("generated", "hand-written"),
        &|| drop(black_box(model.rhs(0.0, black_box(&y)))),
        &|| drop(black_box(hand.rhs(0.0, black_box(&y)))),
    );
    c.bench_function("universal10 rhs generated", |bch| {
        bch.iter(|| model.rhs(0.0, black_box(&y)))
    });
    c.bench_function("universal10 rhs hand-written", |bch| {
        bch.iter(|| hand.rhs(0.0, black_box(&y)))
    });

    let (cr, cm) = (Cardan { g }, CardanMassMatrix { g });
    let yc = Vector::<6>::from([0.4, -0.9, 1.3, 1.1, -0.7, 2.3]);
    let (a, b) = (cr.rhs(0.0, &yc).unwrap(), cm.rhs(0.0, &yc).unwrap());
    assert!(
        (a - b).amax() <= 1e-12 * b.amax(),
        "recursion and mass-matrix form differ"
    );
    interleaved(
        "cardan rhs (both generated)",
        ("recursion", "mass-matrix solve"),
        &|| drop(black_box(cr.rhs(0.0, black_box(&yc)))),
        &|| drop(black_box(cm.rhs(0.0, black_box(&yc)))),
    );

    let arm = Arm7 { g };
    assert!(Arm7::GENERATED.parts.contains(&"articulated_body"));
    let q = Vector::<7>::from([0.3, -0.7, 1.1, 0.4, -2.0, 0.9, -0.5]);
    let qd = Vector::<7>::from([1.2, -0.5, 0.8, -2.2, 1.7, 0.3, 0.6]);
    let least = (0..300)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..1000 {
                drop(black_box(MechanismModel::acceleration(
                    &arm,
                    0.0,
                    black_box(&q),
                    black_box(&qd),
                )));
            }
            start.elapsed().as_secs_f64() * 1e9 / 1000.0
        })
        .fold(f64::INFINITY, f64::min);
    println!("arm7 forward dynamics: least over batches {least:.1} ns");
    c.bench_function("arm7 forward dynamics", |bch| {
        bch.iter(|| MechanismModel::acceleration(&arm, 0.0, black_box(&q), black_box(&qd)))
    });

    assert!(Arm7::GENERATED.parts.contains(&"inverse_dynamics"));
    let qdd = Vector::<7>::from([2.0, -1.5, 0.7, 3.1, -0.4, 1.9, -2.6]);
    let by_mass = |q: &Vector<7>, qd: &Vector<7>, qdd: &Vector<7>| {
        arm.mass_matrix(0.0, q).unwrap() * qdd - arm.forces(0.0, q, qd).unwrap()
    };
    let rnea = arm.inverse_dynamics(0.0, &q, &qd, &qdd).unwrap();
    assert!((rnea - by_mass(&q, &qd, &qdd)).amax() <= 1e-12 * rnea.amax());
    interleaved(
        "arm7 inverse dynamics (both generated)",
        ("Newton-Euler", "M qdd - f"),
        &|| {
            black_box(
                arm.inverse_dynamics(0.0, black_box(&q), black_box(&qd), black_box(&qdd))
                    .unwrap(),
            );
        },
        &|| {
            black_box(by_mass(black_box(&q), black_box(&qd), black_box(&qdd)));
        },
    );
    c.bench_function("arm7 inverse dynamics newton-euler", |bch| {
        bch.iter(|| {
            arm.inverse_dynamics(0.0, black_box(&q), black_box(&qd), black_box(&qdd))
                .unwrap()
        })
    });
    c.bench_function("arm7 inverse dynamics M qdd - f", |bch| {
        bch.iter(|| by_mass(black_box(&q), black_box(&qd), black_box(&qdd)))
    });
}

criterion_group!(spatial, benches);
criterion_main!(spatial);
