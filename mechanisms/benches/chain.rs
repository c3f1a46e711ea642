//! The planar chains' right-hand sides, generated (`#[chain]`, the articulated-body
//! recursion with its run of identical links rolled into loops) against the hand-written
//! same algorithm (`mechanisms::chain_by_hand`, Featherstone's three passes over 2x2
//! blocks, the platform's `sin_cos`), 8 and 32 links: the least time per call over
//! interleaved batches, for independent calls (throughput) and for calls in a dependent
//! chain, each argument made from the last result as an integrator's stages are
//! (latency); then criterion's figures for the generated ones.
//!
//! `cargo bench -p mechanisms --bench chain`.

use criterion::{Criterion, criterion_group, criterion_main};
use mbd::prelude::*;
use mechanisms::accuracy::{Chain8, Chain32};
use mechanisms::chain_by_hand::ChainByHand;
use std::hint::black_box;
use std::time::Instant;

/// 64 states near the time-to-accuracy runs' (every joint about 0.3 rad, rates about 1).
fn states<const N: usize, const D: usize>() -> Vec<Vector<D>> {
    (0..64)
        .map(|k| {
            Vector::<D>::from_fn(|i, _| {
                let wobble = 0.05 * (((k * 7 + i * 3) % 11) as f64 - 5.0);
                if i < N { 0.3 + wobble } else { 2.0 * wobble }
            })
        })
        .collect()
}

/// Nanoseconds per call of `f` over the states, independent and in a dependent chain
/// (adding `0 * sum(f)` makes every argument wait for the whole last result).
fn per_call<S: OdeSystem<D>, const D: usize>(sys: &S, ys: &[Vector<D>]) -> [f64; 2] {
    let time = |run: &dyn Fn()| {
        let start = Instant::now();
        for _ in 0..20 {
            run();
        }
        start.elapsed().as_secs_f64() * 1e9 / (20 * ys.len()) as f64
    };
    let independent = time(&|| {
        for y in ys {
            drop(black_box(sys.rhs(0.0, black_box(y))));
        }
    });
    let chained = time(&|| {
        let mut f = Vector::<D>::zeros();
        for y in ys {
            f = sys.rhs(0.0, &y.add_scalar(f.sum() * 0.0)).unwrap_or(f);
        }
        black_box(f);
    });
    [independent, chained]
}

/// Interleaved minima of the generated model and its hand-written same-algorithm twin,
/// after checking that they agree (relative 1e-12 of the largest acceleration).
fn compare<G: OdeSystem<D>, const N: usize, const D: usize>(name: &str, generated: &G) {
    let hand: ChainByHand<N> = black_box(ChainByHand::new(1.0, 0.5, 9.81));
    let ys = states::<N, D>();
    for y in &ys {
        let (a, b) = (generated.rhs(0.0, y).unwrap(), hand.rhs(0.0, y).unwrap());
        assert!(
            (a - b).amax() <= 1e-12 * b.amax(),
            "{name}: the twins disagree"
        );
    }
    let (mut g, mut h) = ([f64::INFINITY; 2], [f64::INFINITY; 2]);
    for _ in 0..300 {
        let (tg, th) = (per_call(generated, &ys), per_call(&hand, &ys));
        for i in 0..2 {
            g[i] = g[i].min(tg[i]);
            h[i] = h[i].min(th[i]);
        }
    }
    println!(
        "{name}: min over interleaved batches: generated {:.1} ns ({:.1} ns chained), \
         hand-written {:.1} ns ({:.1} ns chained), ratio {:.3} ({:.3} chained) (same algorithm)",
        g[0],
        g[1],
        h[0],
        h[1],
        g[0] / h[0],
        g[1] / h[1]
    );
}

fn benches(c: &mut Criterion) {
    let c8 = black_box(Chain8 {
        m: 1.0,
        l: 0.5,
        g: 9.81,
    });
    let c32 = black_box(Chain32 {
        m: 1.0,
        l: 0.5,
        g: 9.81,
    });
    compare::<Chain8, 8, 16>("chain of 8 links", &c8);
    compare::<Chain32, 32, 64>("chain of 32 links", &c32);
    let y8 = states::<8, 16>()[0];
    let y32 = states::<32, 64>()[0];
    c.bench_function("chain8/generated", |b| {
        b.iter(|| c8.rhs(0.0, black_box(&y8)).unwrap())
    });
    c.bench_function("chain32/generated", |b| {
        b.iter(|| c32.rhs(0.0, black_box(&y32)).unwrap())
    });
}

criterion_group!(chain, benches);
criterion_main!(chain);
