//! Generated vs hand-written right-hand sides, same run: simple pendulum, double pendulum,
//! and a constrained slider-crank (index-1 form with the augmented solve).
//!
//! `cargo bench -p mechanisms --bench rhs`. The models and their hand-written twins are in
//! `mechanisms::handwritten`: the closed-form acceleration for the pendulum, M and f written
//! out with the same mass-matrix solve for the double pendulum, and M, f, Phi_q, gamma with
//! the same augmented LU for the slider-crank, so the ratio measures the generated code, not
//! a different algorithm. The `work-precision` report compares whole integrations.

use criterion::{Criterion, criterion_group, criterion_main};
use mbd::prelude::*;
use mechanisms::handwritten::{
    DOUBLE_PENDULUM, DoublePendulumByHand, PENDULUM, PendulumByHand, SLIDER_CRANK,
    SliderCrankByHand, slider_crank_state,
};
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let p = PENDULUM;
    let ph = PendulumByHand::from(&p);
    let y = Vector::<2>::new(0.7, 0.3);
    assert!((p.rhs(0.0, &y).unwrap() - ph.rhs(0.0, &y).unwrap()).norm() < 1e-14);
    c.bench_function("pendulum/generated", |b| {
        b.iter(|| p.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("pendulum/hand-written", |b| {
        b.iter(|| ph.rhs(0.0, black_box(&y)).unwrap())
    });

    let d = DOUBLE_PENDULUM;
    let dh = DoublePendulumByHand::from(&d);
    let y = Vector::<4>::new(0.7, -0.4, 0.3, 1.1);
    assert!((d.rhs(0.0, &y).unwrap() - dh.rhs(0.0, &y).unwrap()).norm() < 1e-12);
    c.bench_function("double_pendulum/generated", |b| {
        b.iter(|| d.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("double_pendulum/hand-written", |b| {
        b.iter(|| dh.rhs(0.0, black_box(&y)).unwrap())
    });

    let s = SLIDER_CRANK;
    let sh = SliderCrankByHand::from(&s);
    let y = slider_crank_state(&s, 0.6, 5.0);
    assert!((s.rhs(0.0, &y).unwrap() - sh.rhs(0.0, &y).unwrap()).norm() < 1e-9);
    c.bench_function("slider_crank/generated", |b| {
        b.iter(|| s.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("slider_crank/hand-written", |b| {
        b.iter(|| sh.rhs(0.0, black_box(&y)).unwrap())
    });
}

criterion_group!(rhs, benches);
criterion_main!(rhs);
