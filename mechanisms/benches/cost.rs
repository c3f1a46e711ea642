//! Cost per mechanism, so that a regression shows: the right-hand side, the mass matrix, and
//! one adaptive step (DOPRI5, and Radau5 with its Jacobian and factorisations), for every
//! model of the `work-precision` report.
//!
//! `cargo bench -p mechanisms --bench cost` (about a minute: short samples on purpose).

use criterion::{Criterion, criterion_group, criterion_main};
use mbd::analysis::{NewtonOptions, kinematics};
use mbd::integrate::{Dopri5, Integrator, Radau5};
use mbd::prelude::*;
use mechanisms::handwritten::{
    DOUBLE_PENDULUM, DoublePendulumByHand, PENDULUM, PendulumByHand, SLIDER_CRANK,
    SliderCrankByHand, slider_crank_state,
};
use mechanisms::{
    case01_vertical_throw as c01, case05_crate_on_incline as c05, case07_collar_spring as c07,
    case08_slider_bumper as c08, case09_rotating_tube as c09, case10_pendulum_on_cart as c10,
    case19_slider_crank_max_speed as c19, case20_pendulum_bearing as c20,
    case23_block_reversing_torque as c23, case26_crank_bar_released as c26,
    case27_bar_spring_released as c27, case28_falling_bar_spring as c28,
    case30_damped_vibration as c30,
};
use std::hint::black_box;
use std::time::Duration;

/// The step of the one-step benchmarks.
const H: f64 = 1e-3;

fn one_step_options() -> Options {
    Options {
        rtol: 1e-8,
        atol: 1e-8,
        h0: Some(H),
        dense: false,
        ..Options::default()
    }
}

/// `rhs`, `mass_matrix`, `dopri5_step` and `radau5_step` of one model at state `y`.
fn bench_model<S: OdeSystem<D>, Mm: mbd::Mechanism<N>, const N: usize, const D: usize>(
    c: &mut Criterion,
    name: &str,
    sys: &S,
    mech: &Mm,
    y: Vector<D>,
) {
    assert!(
        sys.rhs(0.0, &y).is_ok(),
        "{name}: rhs fails at the benchmark state"
    );
    let q = y.fixed_rows::<N>(0).into_owned();
    let mut g = c.benchmark_group(name);
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(100))
        .measurement_time(Duration::from_millis(300));
    g.bench_function("rhs", |b| b.iter(|| sys.rhs(0.0, black_box(&y))));
    g.bench_function("mass_matrix", |b| {
        b.iter(|| mech.mass_matrix(0.0, black_box(&q)).unwrap())
    });
    g.bench_function("dopri5_step", |b| {
        b.iter(|| Dopri5::new(one_step_options()).solve(sys, 0.0, black_box(y), H, &[]))
    });
    g.bench_function("radau5_step", |b| {
        b.iter(|| Radau5::new(one_step_options()).solve(sys, 0.0, black_box(y), H, &[]))
    });
    g.finish();
}

fn benches(c: &mut Criterion) {
    bench_model::<_, _, 1, 2>(
        c,
        "case01",
        &c01::MODEL,
        &c01::MODEL,
        c01::MODEL.initial_state(),
    );
    let crate_model = c05::MODEL;
    let sliding = crate_model.sliding([1.0]);
    bench_model::<_, _, 1, 2>(
        c,
        "case05",
        &sliding,
        &crate_model,
        crate_model.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case07",
        &c07::MODEL,
        &c07::MODEL,
        c07::MODEL.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case08",
        &c08::MODEL,
        &c08::MODEL,
        c08::MODEL.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case09",
        &c09::MODEL,
        &c09::MODEL,
        c09::MODEL.initial_state(),
    );
    bench_model::<_, _, 2, 4>(
        c,
        "case10",
        &c10::MODEL,
        &c10::MODEL,
        c10::MODEL.initial_state(),
    );
    let driven = c19::MODEL;
    let guess = driven.initial_state().fixed_rows::<2>(0).into_owned();
    let k = kinematics(&driven, 0.0, &guess, &NewtonOptions::default())
        .expect("case 19 assembles at t = 0");
    let y19 = Vector::<4>::new(k.q[0], k.q[1], k.qd[0], k.qd[1]);
    bench_model::<_, _, 2, 4>(c, "case19", &driven, &driven, y19);
    bench_model::<_, _, 1, 2>(
        c,
        "case20",
        &c20::MODEL,
        &c20::MODEL,
        c20::MODEL.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case23",
        &c23::MODEL,
        &c23::MODEL,
        c23::MODEL.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case26",
        &c26::MODEL,
        &c26::MODEL,
        c26::MODEL.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case27",
        &c27::MODEL,
        &c27::MODEL,
        c27::MODEL.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case28",
        &c28::MODEL,
        &c28::MODEL,
        c28::MODEL.initial_state(),
    );
    bench_model::<_, _, 1, 2>(
        c,
        "case30",
        &c30::MODEL,
        &c30::MODEL,
        c30::MODEL.initial_state(),
    );

    let p = PENDULUM;
    let ph = PendulumByHand::from(&p);
    let y = Vector::<2>::new(2.0, 0.0);
    bench_model::<_, _, 1, 2>(c, "pendulum/generated", &p, &p, y);
    bench_model::<_, _, 1, 2>(c, "pendulum/hand-written", &ph, &ph, y);
    let d = DOUBLE_PENDULUM;
    let dh = DoublePendulumByHand::from(&d);
    let y = Vector::<4>::new(0.9, -0.5, 0.4, 1.2);
    bench_model::<_, _, 2, 4>(c, "double_pendulum/generated", &d, &d, y);
    bench_model::<_, _, 2, 4>(c, "double_pendulum/hand-written", &dh, &dh, y);
    let s = SLIDER_CRANK;
    let sh = SliderCrankByHand::from(&s);
    let y = slider_crank_state(&s, 0.6, 5.0);
    bench_model::<_, _, 3, 6>(c, "slider_crank/generated", &s, &s, y);
    bench_model::<_, _, 3, 6>(c, "slider_crank/hand-written", &sh, &sh, y);
}

criterion_group!(cost, benches);
criterion_main!(cost);
