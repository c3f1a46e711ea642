//! Cost of the generic DOPRI5 (`mbd_core::Dopri5`) against a minimal hand-written
//! Dormand–Prince loop on plain `[f64; 2]` arrays with the same tableau, the same error norm
//! and the same PI controller (so both take the same steps), on the harmonic oscillator
//! x'' = -x over [0, 20] at rtol = atol = 1e-8. The hand loop records t and y per step, as
//! `Solution` does; the difference is the price of genericity, dense output and events.

use criterion::{Criterion, criterion_group, criterion_main};
use mbd_core::integrate::{Dopri5, Integrator, Options};
use mbd_core::{OdeSystem, Result, Vector};
use std::hint::black_box;
use std::time::Instant;

const T_END: f64 = 20.0;
const TOL: f64 = 1e-8;
const H0: f64 = 1e-3;

struct Oscillator;

impl OdeSystem<2> for Oscillator {
    #[inline]
    fn rhs(&self, _t: f64, y: &Vector<2>) -> Result<Vector<2>> {
        Ok(Vector::<2>::new(y[1], -y[0]))
    }
}

#[inline]
fn f(_t: f64, y: &[f64; 2]) -> [f64; 2] {
    [y[1], -y[0]]
}

/// y + h sum_j a_j k_j on arrays.
#[inline]
fn axpy(y: &[f64; 2], h: f64, a: &[f64], k: &[[f64; 2]]) -> [f64; 2] {
    let mut out = [0.0; 2];
    for i in 0..2 {
        let mut acc = 0.0;
        for (aj, kj) in a.iter().zip(k) {
            acc += aj * kj[i];
        }
        out[i] = y[i] + h * acc;
    }
    out
}

/// The minimal Dormand–Prince loop: dopri5.f's step, norm and controller, nothing else.
fn hand_dopri5(y0: [f64; 2]) -> (Vec<f64>, Vec<[f64; 2]>) {
    const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
    const A2: [f64; 1] = [0.2];
    const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
    const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
    const A5: [f64; 4] = [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ];
    const A6: [f64; 5] = [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ];
    const A7: [f64; 6] = [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ];
    const E: [f64; 7] = [
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ];
    let (mut t, mut y) = (0.0, y0);
    let (mut ts, mut ys) = (vec![t], vec![y]);
    let mut k = [[0.0; 2]; 7];
    k[0] = f(t, &y);
    let mut h = H0;
    let (mut err_old, mut rejected, mut last) = (1e-4f64, false, false);
    loop {
        if t + 1.01 * h - T_END > 0.0 {
            h = T_END - t;
            last = true;
        }
        k[1] = f(t + C[1] * h, &axpy(&y, h, &A2, &k[..1]));
        k[2] = f(t + C[2] * h, &axpy(&y, h, &A3, &k[..2]));
        k[3] = f(t + C[3] * h, &axpy(&y, h, &A4, &k[..3]));
        k[4] = f(t + C[4] * h, &axpy(&y, h, &A5, &k[..4]));
        k[5] = f(t + h, &axpy(&y, h, &A6, &k[..5]));
        let y1 = axpy(&y, h, &A7, &k[..6]);
        k[6] = f(t + h, &y1);
        let e = axpy(&[0.0; 2], h, &E, &k);
        let mut sum = 0.0;
        for i in 0..2 {
            let sk = TOL + TOL * y[i].abs().max(y1[i].abs());
            sum += (e[i] / sk).powi(2);
        }
        let err = (sum / 2.0).sqrt();
        let fac11 = err.powf(0.17);
        if err <= 1.0 {
            let fac = (fac11 / err_old.powf(0.04) / 0.9).clamp(0.1, 5.0);
            let mut h_new = h / fac;
            err_old = err.max(1e-4);
            if rejected {
                h_new = h_new.min(h);
            }
            rejected = false;
            k[0] = k[6];
            t = if last { T_END } else { t + h };
            y = y1;
            ts.push(t);
            ys.push(y);
            if last {
                break;
            }
            h = h_new;
        } else {
            h /= (fac11 / 0.9).min(5.0);
            rejected = true;
            last = false;
        }
    }
    (ts, ys)
}

fn bench(c: &mut Criterion) {
    let y0 = Vector::<2>::new(1.0, 0.0);
    let solver = |dense| {
        Dopri5::new(Options {
            rtol: TOL,
            atol: TOL,
            h0: Some(H0),
            dense,
            ..Options::default()
        })
    };
    // Same steps, same answer (to rounding order).
    let generic = solver(false)
        .solve(&Oscillator, 0.0, y0, T_END, &[])
        .unwrap();
    let (ts, ys) = hand_dopri5([1.0, 0.0]);
    assert_eq!(generic.t.len(), ts.len());
    let (yg, yh) = (generic.last().1, ys.last().unwrap());
    assert!((yg[0] - yh[0]).abs() < 1e-12 && (yg[1] - yh[1]).abs() < 1e-12);

    // On a shared, loaded machine criterion's means drift between groups; the minimum over
    // interleaved batches (hand, generic, dense, hand, ...) is the robust ratio.
    let batch = |run: &dyn Fn()| {
        let start = Instant::now();
        for _ in 0..20 {
            run();
        }
        start.elapsed().as_secs_f64() / 20.0
    };
    let (plain, dense) = (solver(false), solver(true));
    let mut best = [f64::INFINITY; 3];
    for _ in 0..300 {
        let runs: [&dyn Fn(); 3] = [
            &|| drop(black_box(hand_dopri5(black_box([1.0, 0.0])))),
            &|| {
                drop(black_box(plain.solve(
                    &Oscillator,
                    0.0,
                    black_box(y0),
                    T_END,
                    &[],
                )))
            },
            &|| {
                drop(black_box(dense.solve(
                    &Oscillator,
                    0.0,
                    black_box(y0),
                    T_END,
                    &[],
                )))
            },
        ];
        for (b, run) in best.iter_mut().zip(runs) {
            *b = b.min(batch(run));
        }
    }
    println!(
        "min over interleaved batches: hand {:.2} us, Dopri5 {:.2} us (ratio {:.3}), \
         Dopri5 dense {:.2} us (ratio {:.3}); {} steps",
        best[0] * 1e6,
        best[1] * 1e6,
        best[1] / best[0],
        best[2] * 1e6,
        best[2] / best[0],
        ts.len() - 1
    );

    let mut group = c.benchmark_group("dopri5_oscillator_rtol1e-8");
    group.bench_function("hand_written_arrays", |b| {
        b.iter(|| hand_dopri5(black_box([1.0, 0.0])))
    });
    for dense in [false, true] {
        let s = solver(dense);
        let name = if dense { "Dopri5_dense" } else { "Dopri5" };
        group.bench_function(name, |b| {
            b.iter(|| {
                s.solve(&Oscillator, 0.0, black_box(y0), T_END, &[])
                    .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
