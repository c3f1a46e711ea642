//! Friction in a mechanism with a constraint: the crate of case 05 on its incline, in
//! Cartesian coordinates `(x, y)` held on the slope by `y + x tan(a) = 0`.
//!
//! Friction along `x`: the slope's friction force `mu N` against the sliding, with
//! `N = m g cos(a)`, does virtual work `-mu N sign(s') ds` with `ds = dx / cos(a)`, so its
//! generalised force on `x` is `-(mu / cos a) N sign(x')`: the attribute's coefficient is
//! `mu / cos(a)`. Stuck, the load along `x` is gravity's, `m g tan(a)`, against the bound
//! `mu m g`: it holds when `tan(a) <= mu`. Sliding down at `v0`, the distance along the slope
//! obeys `s'' = g (sin a - mu cos a)` (case 05), so it stops at `t = v0 / |s''|` at
//! `x = cos(a) v0^2 / (2 |s''|)`.

use mbd::Slip;
use mbd::integrate::{Dopri5, Radau5};
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[constraint(y + x * tan(a) == 0.0)]
#[particle(body, mass = m, at = [x, y])]
#[friction(along = x, mu = mu / cos(a), normal = m * g * cos(a))]
#[init(der(x) = v0 * cos(a), der(y) = -v0 * sin(a))]
pub struct OnSlope {
    pub m: f64,
    pub g: f64,
    pub a: f64,
    pub mu: f64,
    pub v0: f64,
}

const SLOPE: OnSlope = OnSlope {
    m: 50.0,
    g: 9.81,
    a: 0.261_799_387_799_149_4,
    mu: 0.4,
    v0: 7.0,
};

#[test]
fn constrained_crate_stops_exactly_and_stays() {
    let acc = 9.81 * (SLOPE.a.sin() - 0.4 * SLOPE.a.cos());
    let (t_stop, s_stop) = (7.0 / -acc, 49.0 / (-2.0 * acc));
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    for (name, run) in [
        (
            "DOPRI5",
            mbd::hybrid::solve(
                &Dopri5::new(opts.clone()),
                &SLOPE,
                0.0,
                SLOPE.initial_state(),
                10.0,
                &[],
            ),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(
                &Radau5::new(opts.clone()),
                &SLOPE,
                0.0,
                SLOPE.initial_state(),
                10.0,
                &[],
            ),
        ),
    ] {
        let run = run.unwrap();
        assert_eq!(run.switches.len(), 1, "{name}");
        let sw = &run.switches[0];
        assert_eq!((sw.from, sw.to), ([Slip::Forward], [Slip::Stick]), "{name}");
        assert!(
            (sw.t - t_stop).abs() <= 1e-11,
            "{name}: {} vs {t_stop}",
            sw.t
        );
        let (t, y) = run.solution.last();
        assert_eq!(t, 10.0);
        assert!(
            (y[0] - s_stop * SLOPE.a.cos()).abs() <= 1e-10 * s_stop,
            "{name}: {y:?}"
        );
        assert!(
            (y[1] + s_stop * SLOPE.a.sin()).abs() <= 1e-10 * s_stop,
            "{name}: {y:?}"
        );
        // Stuck: the sliding coordinate does not move, and the constraint holds it all.
        assert_eq!(y[2], 0.0, "{name}");
        assert!(y[3].abs() <= 1e-14, "{name}: {y:?}");
    }
}

#[test]
fn constrained_crate_at_rest_holds_or_slides_by_the_load() {
    let zero = mbd::Vector::<2>::zeros();
    // tan 15 deg < 0.4: held, no acceleration.
    let qdd = SLOPE.acceleration(0.0, &zero, &zero).unwrap();
    assert_eq!(qdd[0], 0.0);
    assert!(qdd[1].abs() <= 1e-15);
    // tan 30 deg > 0.4: it slides down at g (sin a - mu cos a) along the slope.
    let steep = OnSlope {
        a: 30f64.to_radians(),
        ..SLOPE
    };
    let qdd = steep.acceleration(0.0, &zero, &zero).unwrap();
    let s = 9.81 * (steep.a.sin() - 0.4 * steep.a.cos());
    assert!((qdd[0] - s * steep.a.cos()).abs() <= 1e-13, "{qdd:?}");
    assert!((qdd[1] + s * steep.a.sin()).abs() <= 1e-13, "{qdd:?}");
}

/// A model with both a constraint (a closed loop's bridge, `OdeSystem::passage`) and
/// friction (`OdeSystem::hybrid`): the ordinary solve runs it mode by mode, each mode a raw
/// run (the bridge is not used: `passages` stays empty), exactly as `hybrid::solve` does,
/// so the stop above holds for it too.
#[test]
fn the_ordinary_solve_of_the_constrained_crate_runs_its_modes() {
    use mbd::integrate::Integrator;
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let y0 = SLOPE.initial_state();
    let plain = Dopri5::new(opts.clone())
        .solve(&SLOPE, 0.0, y0, 10.0, &[])
        .unwrap();
    let hybrid = mbd::hybrid::solve(&Dopri5::new(opts), &SLOPE, 0.0, y0, 10.0, &[]).unwrap();
    assert_eq!(plain.y, hybrid.solution.y);
    assert!(plain.passages.is_empty());
    assert_eq!(plain.switches.len(), 1);
    assert_eq!(plain.switches[0].to.get(), Some(&[Slip::Stick]));
    assert_eq!(plain.last().1[2], 0.0);
}
