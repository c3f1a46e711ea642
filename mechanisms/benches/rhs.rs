//! Generated vs hand-written right-hand sides, same run: simple pendulum, double pendulum,
//! and a constrained slider-crank (index-1 form with the augmented solve), each against a
//! *same-algorithm* twin; then the *expert* comparisons: the double pendulum against
//! Cramer's rule, and the free slider-crank written with three coordinates and two closure
//! constraints (which the derive turns into minimal coordinates) against its one-coordinate
//! twin with the closure solved by hand. Every printed ratio says which.
//!
//! `cargo bench -p mechanisms --bench rhs`. The models and their hand-written twins are in
//! `mechanisms::handwritten`: the closed-form acceleration for the pendulum, M and f written
//! out with the same mass-matrix solve for the double pendulum, and M, f, Phi_q, gamma with
//! the same augmented LU for the slider-crank, so the ratio measures the generated code, not
//! a different algorithm. The `work-precision` report compares whole integrations.

use criterion::{Criterion, criterion_group, criterion_main};
use mbd::prelude::*;
use mechanisms::handwritten::{
    DOUBLE_PENDULUM, DoublePendulumByHand, DoublePendulumCramer, FREE_SLIDER_CRANK, PENDULUM,
    PendulumByHand, SLIDER_CRANK, SliderCrankByHand, SliderCrankClosedByHand, slider_crank_state,
};
use std::hint::black_box;
use std::time::Instant;

/// The least time per call of `generated` and `hand` over interleaved batches (generated,
/// hand, generated, ...): on a shared machine criterion's figures drift between benchmarks
/// run one after the other, the interleaved minimum is the robust ratio.
fn interleaved(name: &str, kind: &str, generated: &dyn Fn(), hand: &dyn Fn()) {
    let batch = |run: &dyn Fn()| {
        let start = Instant::now();
        for _ in 0..1000 {
            run();
        }
        start.elapsed().as_secs_f64() * 1e9 / 1000.0
    };
    let (mut g, mut h) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..2000 {
        g = g.min(batch(generated));
        h = h.min(batch(hand));
    }
    println!(
        "{name}: min over interleaved batches: generated {g:.2} ns, hand-written {h:.2} ns, ratio {:.3} ({kind})",
        g / h
    );
}

fn benches(c: &mut Criterion) {
    let p = PENDULUM;
    let ph = PendulumByHand::from(&p);
    let y = Vector::<2>::new(0.7, 0.3);
    assert!((p.rhs(0.0, &y).unwrap() - ph.rhs(0.0, &y).unwrap()).norm() < 1e-14);
    interleaved(
        "pendulum",
        "same algorithm",
        &|| drop(black_box(p.rhs(0.0, black_box(&y)))),
        &|| drop(black_box(ph.rhs(0.0, black_box(&y)))),
    );
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
    interleaved(
        "double_pendulum",
        "same algorithm",
        &|| drop(black_box(d.rhs(0.0, black_box(&y)))),
        &|| drop(black_box(dh.rhs(0.0, black_box(&y)))),
    );
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
    interleaved(
        "slider_crank",
        "same algorithm",
        &|| drop(black_box(s.rhs(0.0, black_box(&y)))),
        &|| drop(black_box(sh.rhs(0.0, black_box(&y)))),
    );
    c.bench_function("slider_crank/generated", |b| {
        b.iter(|| s.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("slider_crank/hand-written", |b| {
        b.iter(|| sh.rhs(0.0, black_box(&y)).unwrap())
    });

    // Expert twins.
    let dc = DoublePendulumCramer(dh);
    let y = Vector::<4>::new(0.7, -0.4, 0.3, 1.1);
    assert!((d.rhs(0.0, &y).unwrap() - dc.rhs(0.0, &y).unwrap()).norm() < 1e-12);
    interleaved(
        "double_pendulum vs Cramer",
        "expert",
        &|| drop(black_box(d.rhs(0.0, black_box(&y)))),
        &|| drop(black_box(dc.rhs(0.0, black_box(&y)))),
    );
    let f = FREE_SLIDER_CRANK;
    let fh = SliderCrankClosedByHand::from(&f);
    let y = Vector::<2>::new(0.6, 5.0);
    assert!((f.rhs(0.0, &y).unwrap() - fh.rhs(0.0, &y).unwrap()).norm() < 1e-12);
    interleaved(
        "free_slider_crank (minimal) vs closed by hand",
        "expert",
        &|| drop(black_box(f.rhs(0.0, black_box(&y)))),
        &|| drop(black_box(fh.rhs(0.0, black_box(&y)))),
    );
    c.bench_function("free_slider_crank/generated", |b| {
        b.iter(|| f.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("free_slider_crank/expert", |b| {
        b.iter(|| fh.rhs(0.0, black_box(&y)).unwrap())
    });
}

criterion_group!(rhs, benches);
criterion_main!(rhs);
