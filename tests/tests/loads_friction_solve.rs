//! A plain `Integrator::solve` of a model with Coulomb friction: where the body stops and
//! sticks, the right-hand side jumps. The ordinary solve runs the model mode by mode (as
//! `mbd::hybrid::solve` does), so it stops the body at the closed form and holds it there
//! exactly, at tight and loose tolerances alike (it used to fail with `Error::ModeSwitch`,
//! or chatter across `v = 0` within loose tolerances).
//!
//! Closed form: a block launched at `v0` on a rough level floor decelerates at `mu g`
//! (friction `-mu m g sign(v)`, normal force `m g`), so `v = v0 - mu g t` until
//! `t_stop = v0 / (mu g)`, where `x = v0^2 / (2 mu g)`; then it stays (no load moves it).

use mbd::integrate::{Dop853, Dopri5, Integrator, Radau5, Vern9};
use mbd::prelude::*;

#[path = "support/floor.rs"]
mod floor;
use floor::FLOOR;

fn opts() -> Options {
    Options {
        rtol: 1e-10,
        atol: 1e-10,
        max_steps: 20_000,
        ..Options::default()
    }
}

fn t_stop() -> f64 {
    FLOOR.v0 / (FLOOR.mu * FLOOR.g)
}

/// The ordinary solve past the stop: one switch at the stop, then exactly at rest.
fn stops_and_stays<I: Integrator>(method: &I) {
    let (mu, g, v0) = (FLOOR.mu, FLOOR.g, FLOOR.v0);
    let x_stop = v0 * v0 / (2.0 * mu * g);
    let sol = method
        .solve(&FLOOR, 0.0, FLOOR.initial_state(), 3.0, &[])
        .unwrap();
    assert_eq!(
        sol.switches.len(),
        1,
        "{}: {:?}",
        method.name(),
        sol.switches
    );
    let sw = &sol.switches[0];
    assert!(
        (sw.t - t_stop()).abs() < 1e-9 * t_stop(),
        "{}",
        method.name()
    );
    assert_eq!(sw.to.get(), Some(&[mbd::Slip::Stick]), "{}", method.name());
    let (t, y) = sol.last();
    assert_eq!(t, 3.0);
    assert!(
        (y[0] - x_stop).abs() < 1e-9 * x_stop,
        "{}: {y}",
        method.name()
    );
    assert_eq!(y[1], 0.0, "{}", method.name());
}

#[test]
fn plain_solve_of_a_sticking_block_stops_it_and_holds_it() {
    stops_and_stays(&Dopri5::new(opts()));
    stops_and_stays(&Dop853::new(opts()));
    stops_and_stays(&Vern9::new(opts()));
    stops_and_stays(&Radau5::new(opts()));
}

/// At loose tolerances (`Options::default()`: 1e-6), where the plain right-hand side used
/// to chatter across `v = 0` within them: the same exact stop, and `v == 0` after it.
#[test]
fn plain_solve_at_loose_tolerances_does_not_chatter() {
    stops_and_stays(&Dopri5::new(Options::default()));
    stops_and_stays(&Radau5::new(Options::default()));
}

/// Before the stop the plain solve is smooth and right.
#[test]
fn plain_solve_before_the_stop_is_the_closed_form() {
    let (mu, g, v0) = (FLOOR.mu, FLOOR.g, FLOOR.v0);
    let t1 = 0.5 * t_stop();
    let sol = Dopri5::new(opts())
        .solve(&FLOOR, 0.0, FLOOR.initial_state(), t1, &[])
        .unwrap();
    let (_, y) = sol.last();
    assert!((y[0] - (v0 * t1 - 0.5 * mu * g * t1 * t1)).abs() < 1e-9);
    assert!((y[1] - (v0 - mu * g * t1)).abs() < 1e-9);
}

/// The hybrid driver: the stop at `v0 / (mu g)`, at `v0^2 / (2 mu g)`, and the block stays.
#[test]
fn hybrid_solve_stops_the_block_where_the_closed_form_says_and_it_stays() {
    let (mu, g, v0) = (FLOOR.mu, FLOOR.g, FLOOR.v0);
    let x_stop = v0 * v0 / (2.0 * mu * g);
    let y0 = FLOOR.initial_state();
    let runs = [
        mbd::hybrid::solve(&Dopri5::new(opts()), &FLOOR, 0.0, y0, 3.0, &[]).unwrap(),
        mbd::hybrid::solve(&Radau5::new(opts()), &FLOOR, 0.0, y0, 3.0, &[]).unwrap(),
    ];
    for run in runs {
        assert_eq!(run.switches.len(), 1, "{:?}", run.switches);
        assert!((run.switches[0].t - t_stop()).abs() < 1e-9 * t_stop());
        assert_eq!(run.mode, [mbd::Slip::Stick]);
        let (t, y) = run.solution.last();
        assert_eq!(t, 3.0);
        assert!((y[0] - x_stop).abs() < 1e-9 * x_stop, "{y}");
        assert_eq!(y[1], 0.0);
    }
}
