//! The ordinary `Integrator::solve` of a model with Coulomb friction, the way a new user
//! calls it, runs the model mode by mode (as `mbd::hybrid::solve` does): a stuck body is
//! held exactly (`v == 0`, `x` constant to the bit) and every stop and breakaway is located.
//! Every method, against closed forms derived beside each test:
//!
//! - a block on a level floor launched at `v0`: friction `-mu m g sign(v)` decelerates it at
//!   `mu g`, so it stops at `t = v0 / (mu g)`, `x = v0^2 / (2 mu g)`, and no load moves it;
//! - a block at rest on an incline below its friction angle (`tan a < mu`): the load down the
//!   slope `m g sin a` is within the bound `mu m g cos a`, so it never moves;
//! - a block on a floor pushed by `F = c t`: it holds while `c t <= mu m g` and breaks away at
//!   `t_b = mu m g / c`, after which `m x'' = c (t - t_b)`, so `v = c (t - t_b)^2 / (2 m)`,
//!   `x = c (t - t_b)^3 / (6 m)`;
//! - a Coulomb-damped oscillator `m x'' + k x = -mu m g sign(x')` released from `x0 > 0` at
//!   rest: each half period it swings about `+-d`, `d = mu m g / k`, so the turning points are
//!   at `t_j = j pi / w` (`w^2 = k / m`) with `|x_j| = x0 - 2 j d` (a loss of `4 d` per
//!   cycle), and it stops at the first turning point inside the dead band `|x| <= d`, where
//!   the spring force `k |x|` no longer exceeds static friction.
//!
//! Adaptive methods run at `rtol = atol = 1e-12`; fixed-step ones with a step for which their
//! order makes the error small (RK4 `1e-3`, Gauss `1e-3`, generalized-alpha `1e-4`). The
//! bounds are per method: the floor and the pushed block's sliding phases are polynomials of
//! degree 2 and 3 that every method but generalized-alpha (second order) integrates exactly.

use mbd::integrate::{
    Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Radau5, Record, Rk4, Solution, Vern9,
};
use mbd::prelude::*;
use mbd::{Slip, Vector};

#[path = "support/floor.rs"]
mod floor;
use floor::{FLOOR, Floor};

/// A block on an incline of angle `a`, `s` down the slope.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[particle(block, mass = m, at = [s * cos(a), -s * sin(a)])]
#[friction(along = s, mu = mu, normal = m * g * cos(a))]
pub struct Incline {
    pub m: f64,
    pub g: f64,
    pub a: f64,
    pub mu: f64,
}

/// A block on a floor pushed by `c t`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g)]
#[generalized_force(push, along = x, value = c * t)]
pub struct Pushed {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
    pub c: f64,
}

/// A block on a spring (`k`, rest at `x = 0`) on a rough floor.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(s, from = [0.0, 0.0], to = block, k = k)]
#[friction(along = x, mu = mu, normal = m * g)]
#[init(x = x0)]
pub struct Damped {
    pub m: f64,
    pub g: f64,
    pub k: f64,
    pub mu: f64,
    pub x0: f64,
}

const DAMPED: Damped = Damped {
    m: 1.0,
    g: 9.81,
    k: 100.0,
    mu: 0.3,
    x0: 0.2,
};

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        max_steps: 1_000_000,
        ..Options::default()
    }
}

/// What a check sees of one method's run: its name and the ordinary solve's result.
type Run = (&'static str, Solution<2>);

/// The ordinary solve of `sys` from `y0` to `t1` with every method: DOPRI5, DOP853, Vern9,
/// Auto and Radau IIA with `opts`; RK4 and Gauss with step `h`, generalized-alpha with
/// `h / 10` (second order), each through `Integrator::solve`.
fn every_method<S: OdeSystem<2>>(
    sys: &S,
    y0: Vector<2>,
    t1: f64,
    opts: &Options,
    h: f64,
) -> Vec<Run> {
    fn run<I: Integrator, S: OdeSystem<2>>(
        name: &'static str,
        method: I,
        sys: &S,
        y0: Vector<2>,
        t1: f64,
    ) -> Run {
        let sol = method
            .solve(sys, 0.0, y0, t1, &[])
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        (name, sol)
    }
    vec![
        run("DOPRI5", Dopri5::new(opts.clone()), sys, y0, t1),
        run("DOP853", Dop853::new(opts.clone()), sys, y0, t1),
        run("VERN9", Vern9::new(opts.clone()), sys, y0, t1),
        run("Auto", Auto::new(opts.clone()), sys, y0, t1),
        run("Radau5", Radau5::new(opts.clone()), sys, y0, t1),
        run("RK4", Rk4::new(h), sys, y0, t1),
        run("Gauss", Gauss::new(h), sys, y0, t1),
        run(
            "generalized-alpha",
            GeneralizedAlpha::new(0.9, h / 10.0),
            sys,
            y0,
            t1,
        ),
    ]
}

/// Every recorded state from `t_s` on is the stuck state `y_s`, bit for bit, and so is the
/// end: the body does not creep.
fn held_from(name: &str, sol: &Solution<2>, t_s: f64, y_s: &Vector<2>) {
    assert_eq!(y_s[1], 0.0, "{name}: stuck with v = {}", y_s[1]);
    for (t, y) in sol.t.iter().zip(&sol.y).filter(|(t, _)| **t >= t_s) {
        assert_eq!(y, y_s, "{name}: moved while stuck, at t = {t}");
    }
    assert_eq!(sol.last().1, y_s, "{name}: moved while stuck");
}

/// The switch times and modes of a run.
fn switches(sol: &Solution<2>) -> Vec<(f64, [Slip; 1], [Slip; 1])> {
    sol.switches
        .iter()
        .map(|w| {
            let mode = |m: &mbd::hybrid::AnyMode| *m.get::<[Slip; 1]>().expect("a friction mode");
            (w.t, mode(&w.from), mode(&w.to))
        })
        .collect()
}

#[test]
fn a_sliding_block_stops_at_the_closed_form_and_stays_exactly() {
    let (mu, g, v0) = (FLOOR.mu, FLOOR.g, FLOOR.v0);
    let (t_stop, x_stop) = (v0 / (mu * g), v0 * v0 / (2.0 * mu * g));
    for (name, sol) in every_method(&FLOOR, FLOOR.initial_state(), 10.0, &tight(), 1e-2) {
        let sw = switches(&sol);
        assert_eq!(sw.len(), 1, "{name}: {sw:?}");
        let (t_s, from, to) = sw[0];
        assert_eq!((from, to), ([Slip::Forward], [Slip::Stick]), "{name}");
        // v = v0 - mu g t is linear: every method's dense output has it exactly.
        assert!(
            (t_s - t_stop).abs() <= 1e-12 * t_stop,
            "{name}: {t_s} vs {t_stop}"
        );
        let y_s = sol.at(t_s).unwrap();
        assert!((y_s[0] - x_stop).abs() <= 1e-12 * x_stop, "{name}: {y_s}");
        held_from(name, &sol, t_s, &y_s);
        assert_eq!(sol.last().0, 10.0, "{name}");
        println!(
            "{name:>18}: stop {:.1e} s off, x {:.1e} m off",
            t_s - t_stop,
            y_s[0] - x_stop
        );
    }
}

/// At loose tolerances too (where the plain right-hand side chattered within them): the
/// stop is exact and the block stays.
#[test]
fn loose_tolerances_hold_the_stop_exactly_too() {
    let (mu, g, v0) = (FLOOR.mu, FLOOR.g, FLOOR.v0);
    let (t_stop, x_stop) = (v0 / (mu * g), v0 * v0 / (2.0 * mu * g));
    for tol in [1e-3, 1e-6] {
        let opts = Options {
            rtol: tol,
            atol: tol,
            ..Options::default()
        };
        for (name, sol) in every_method(&FLOOR, FLOOR.initial_state(), 3.0, &opts, 0.1) {
            let sw = switches(&sol);
            assert_eq!(sw.len(), 1, "{name} {tol:e}: {sw:?}");
            let t_s = sw[0].0;
            // Still a polynomial every method integrates exactly, whatever the tolerance.
            assert!(
                (t_s - t_stop).abs() <= 1e-12 * t_stop,
                "{name} {tol:e}: {t_s}"
            );
            let y_s = sol.at(t_s).unwrap();
            assert!(
                (y_s[0] - x_stop).abs() <= 1e-12 * x_stop,
                "{name} {tol:e}: {y_s}"
            );
            held_from(name, &sol, t_s, &y_s);
        }
    }
}

/// 15 degrees, `mu = 0.4 > tan 15 deg = 0.268`: at rest it holds, displacement exactly zero
/// over 10 s, at every tolerance and step.
#[test]
fn a_block_on_an_incline_below_its_friction_angle_never_creeps() {
    let incline = Incline {
        m: 50.0,
        g: 9.81,
        a: 15f64.to_radians(),
        mu: 0.4,
    };
    assert!(incline.a.tan() < incline.mu);
    let zero = Vector::<2>::zeros();
    for (tol, h) in [(1e-3, 1.0), (1e-6, 0.1), (1e-12, 1e-2)] {
        let opts = Options {
            rtol: tol,
            atol: tol,
            ..Options::default()
        };
        for (name, sol) in every_method(&incline, zero, 10.0, &opts, h) {
            assert!(sol.switches.is_empty(), "{name}: {:?}", sol.switches);
            held_from(name, &sol, 0.0, &zero);
            assert_eq!(sol.last().0, 10.0, "{name}");
        }
    }
}

#[test]
fn a_block_under_a_rising_push_breaks_away_at_mu_m_g() {
    let p = Pushed {
        m: 2.0,
        g: 9.81,
        mu: 0.3,
        c: 2.0,
    };
    let t_b = p.mu * p.m * p.g / p.c;
    let v = |t: f64| p.c * (t - t_b).powi(2) / (2.0 * p.m);
    let x = |t: f64| p.c * (t - t_b).powi(3) / (6.0 * p.m);
    let zero = Vector::<2>::zeros();
    for (name, sol) in every_method(&p, zero, 5.0, &tight(), 1e-2) {
        let sw = switches(&sol);
        assert_eq!(sw.len(), 1, "{name}: {sw:?}");
        let (t_s, from, to) = sw[0];
        assert_eq!((from, to), ([Slip::Stick], [Slip::Forward]), "{name}");
        // The holding force c t is linear and the state constant: located to rounding.
        assert!((t_s - t_b).abs() <= 1e-12 * t_b, "{name}: {t_s} vs {t_b}");
        // Held exactly before.
        for (t, y) in sol.t.iter().zip(&sol.y).filter(|(t, _)| **t <= t_s) {
            assert_eq!(*y, zero, "{name}: moved at t = {t} before breakaway");
        }
        // Then the cubic: exact for every method of order >= 3; generalized-alpha is of
        // order 2 (error O(h^2) with h = 1e-3, relative to x ~ 0.7 m).
        let tol = if name == "generalized-alpha" {
            1e-5
        } else {
            1e-11
        };
        let (t1, y1) = sol.last();
        assert_eq!(t1, 5.0);
        assert!(
            (y1[0] - x(5.0)).abs() <= tol * x(5.0),
            "{name}: {y1} vs {}",
            x(5.0)
        );
        assert!(
            (y1[1] - v(5.0)).abs() <= tol * v(5.0),
            "{name}: {y1} vs {}",
            v(5.0)
        );
        println!(
            "{name:>18}: breakaway {:.1e} s off, x(5) {:.1e}, v(5) {:.1e} relative",
            t_s - t_b,
            (y1[0] - x(5.0)) / x(5.0),
            (y1[1] - v(5.0)) / v(5.0)
        );
    }
}

#[test]
fn a_coulomb_damped_oscillator_turns_at_k_pi_over_omega_and_stops_in_its_dead_band() {
    let Damped { m, g, k, mu, x0 } = DAMPED;
    let (w, d) = ((k / m).sqrt(), mu * m * g / k);
    // Turning points: |x_j| = x0 - 2 j d while outside the dead band, alternating in sign.
    let mut turns = vec![x0];
    while turns.last().unwrap().abs() > d {
        let x = *turns.last().unwrap();
        turns.push(-x.signum() * (x.abs() - 2.0 * d));
    }
    assert_eq!(turns.len(), 4, "{turns:?}");
    // Four d lost per full cycle.
    assert!((turns[0] - turns[2] - 4.0 * d).abs() < 1e-15);
    for (name, sol) in every_method(&DAMPED, DAMPED.initial_state(), 5.0, &tight(), 1e-3) {
        let sw = switches(&sol);
        assert_eq!(sw.len(), turns.len() - 1, "{name}: {sw:?}");
        // Time and position errors by method: tolerance-bound adaptive ones (Radau IIA's
        // dense output is of degree 3), RK4 (order 4, h = 1e-3), generalized-alpha (order
        // 2, h = 1e-4: a phase error (w h)^2 w t / 12 ~ 1e-6).
        let tol = match name {
            "generalized-alpha" => 1e-5,
            "RK4" => 1e-9,
            "Radau5" => 1e-8,
            _ => 1e-10,
        };
        let mut worst: (f64, f64) = (0.0, 0.0);
        for (j, &(t_s, from, to)) in sw.iter().enumerate() {
            let t_j = (j + 1) as f64 * std::f64::consts::PI / w;
            let x_j = sol.at(t_s).unwrap()[0];
            assert!(
                (t_s - t_j).abs() <= tol,
                "{name}: turn {j} at {t_s} vs {t_j}"
            );
            assert!(
                (x_j - turns[j + 1]).abs() <= tol,
                "{name}: turn {j} at {x_j}"
            );
            worst = (
                worst.0.max((t_s - t_j).abs()),
                worst.1.max((x_j - turns[j + 1]).abs()),
            );
            let moving = if j % 2 == 0 {
                Slip::Backward
            } else {
                Slip::Forward
            };
            let next = if j + 1 == sw.len() {
                Slip::Stick
            } else if moving == Slip::Backward {
                Slip::Forward
            } else {
                Slip::Backward
            };
            assert_eq!((from, to), ([moving], [next]), "{name}: turn {j}");
        }
        // Stuck for good inside the dead band.
        let (t_s, _, _) = *sw.last().unwrap();
        let y_s = sol.at(t_s).unwrap();
        assert!(
            y_s[0].abs() <= d,
            "{name}: stopped at {} outside +-{d}",
            y_s[0]
        );
        held_from(name, &sol, t_s, &y_s);
        println!(
            "{name:>18}: turning times {:.1e} s, positions {:.1e} m off (worst)",
            worst.0, worst.1
        );
    }
}

/// The ordinary solve is `hybrid::solve` with its default settings: the same states, bit
/// for bit, and the same switches.
#[test]
fn the_ordinary_solve_is_the_hybrid_driver() {
    fn same<I: Integrator>(method: &I) {
        let y0 = DAMPED.initial_state();
        let plain = method.solve(&DAMPED, 0.0, y0, 2.0, &[]).unwrap();
        let hybrid = mbd::hybrid::solve(method, &DAMPED, 0.0, y0, 2.0, &[]).unwrap();
        assert_eq!(plain.t, hybrid.solution.t, "{}", method.name());
        assert_eq!(plain.y, hybrid.solution.y, "{}", method.name());
        assert_eq!(plain.stats, hybrid.solution.stats, "{}", method.name());
        let erased: Vec<_> = hybrid.switches.iter().map(|w| w.erased()).collect();
        assert_eq!(plain.switches, erased, "{}", method.name());
        assert_eq!(
            plain.switches.last().and_then(|w| w.to.get::<[Slip; 1]>()),
            Some(&hybrid.mode)
        );
    }
    same(&Dopri5::new(tight()));
    same(&Radau5::new(tight()));
    same(&Rk4::new(1e-3));
    same(&GeneralizedAlpha::new(0.9, 1e-3));
}

/// The user's events keep their indices and a terminal one ends the run: the oscillator's
/// first swing is about `+d`, `x = d + (x0 - d) cos(w t)`, so it first passes `x = 0` at
/// `t = acos(-d / (x0 - d)) / w`, before its first turning point.
#[test]
fn user_events_work_through_the_modes() {
    let Damped { m, g, k, mu, x0 } = DAMPED;
    let (w, d) = ((k / m).sqrt(), mu * m * g / k);
    let t_zero = (-d / (x0 - d)).acos() / w;
    let events = [mbd::integrate::Event::new(
        "x = 0",
        |_t: f64, y: &Vector<2>| y[0],
        mbd::integrate::Direction::Falling,
    )
    .terminal()];
    let sol = Dopri5::new(tight())
        .solve(&DAMPED, 0.0, DAMPED.initial_state(), 5.0, &events)
        .unwrap();
    assert_eq!(sol.stopped_by, Some(0));
    assert!(sol.switches.is_empty());
    assert!(
        (sol.last().0 - t_zero).abs() <= 1e-10,
        "{} vs {t_zero}",
        sol.last().0
    );
}

/// Generalized-alpha's own second-order form, `ga.solve(&model, t0, q0, qd0, t1, ..)`, takes
/// any `Mechanism` and so cannot see the modes (its `Integrator::solve` above runs them): on
/// the plain model its Newton iteration meets the jump of the friction force at the stop and
/// fails there with the typed error, never a wrong `Ok`.
#[test]
fn generalized_alpha_in_mechanism_form_refuses_the_stop() {
    let (mu, g, v0) = (FLOOR.mu, FLOOR.g, FLOOR.v0);
    let t_stop = v0 / (mu * g);
    for h in [1e-2, 1e-3] {
        let (q0, qd0) = (Vector::<1>::new(0.0), Vector::<1>::new(v0));
        let run = GeneralizedAlpha::new(0.9, h).solve::<_, 1, 2>(&FLOOR, 0.0, q0, qd0, 3.0, &[]);
        match run {
            Err(mbd::Error::NewtonFailed { t, .. }) => {
                assert!((t - t_stop).abs() <= 2.0 * h, "h = {h}: failed at {t}")
            }
            other => panic!("h = {h}: {other:?}"),
        }
    }
}

/// A block on a floor under a periodic push `p sin(w t)` just above static friction
/// (`r = mu m g / p = 0.99`).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g)]
#[generalized_force(push, along = x, value = p * sin(w * t))]
pub struct Shaken {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
    pub p: f64,
    pub w: f64,
}

/// Stuck from rest, the state is constant and the steps grow tenfold at a time, so the
/// breakaway window (`sin(w t) > r`, about `0.094 s` wide around `pi / (2 w)`) lies inside
/// one step: it is found inside the step, with or without dense output kept. Closed form:
/// breakaway at `t_b = asin(r) / w`; then `m v = p (cos(w t_b) - cos(w t)) / w - mu m g (t -
/// t_b)`, which must vanish at the stop the run reports. Without dense output (`dense:
/// false` with `Record::Final` or output times: what ensembles and reports use) the
/// switches and the final state are the dense run's, bit for bit, and the output times
/// are the states at those times (at rest before the breakaway and after the stop).
#[test]
fn a_breakaway_inside_one_long_step_is_found_without_dense_output() {
    let b = Shaken {
        m: 1.0,
        g: 9.81,
        mu: 0.3,
        p: 0.3 * 9.81 / 0.99,
        w: 3.0,
    };
    let (mg, w) = (b.m * b.g, b.w);
    let t_b = (b.mu * mg / b.p).asin() / w;
    let v = |t: f64| (b.p * ((w * t_b).cos() - (w * t).cos()) / w - b.mu * mg * (t - t_b)) / b.m;
    let zero = Vector::<2>::zeros();
    let lean = |record| Options {
        dense: false,
        record,
        ..tight()
    };
    let times = vec![0.25, 0.5, 0.75, 1.0, 1.25];
    for name in ["DOPRI5", "Radau5"] {
        let run = |opts: Options| match name {
            "DOPRI5" => Dopri5::new(opts).solve(&b, 0.0, zero, 1.5, &[]).unwrap(),
            _ => Radau5::new(opts).solve(&b, 0.0, zero, 1.5, &[]).unwrap(),
        };
        let dense = run(tight());
        let sw = switches(&dense);
        assert_eq!(sw.len(), 2, "{name}: {sw:?}");
        assert_eq!((sw[0].1, sw[0].2), ([Slip::Stick], [Slip::Forward]));
        assert_eq!((sw[1].1, sw[1].2), ([Slip::Forward], [Slip::Stick]));
        assert!(
            (sw[0].0 - t_b).abs() <= 1e-12,
            "{name}: {} vs {t_b}",
            sw[0].0
        );
        // v' = p sin(w t) / m - mu g ~ -0.09 m/s^2 at the stop: 1e-11 m/s is 1e-10 s.
        // Radau IIA's dense output is of degree 3 (`hybrid::Settings::polish` is for it):
        // 1e-10 m/s, 1e-9 s, as its stops are held at this tolerance elsewhere.
        let v_tol = if name == "Radau5" { 1e-10 } else { 1e-11 };
        assert!(v(sw[1].0).abs() <= v_tol, "{name}: v = {}", v(sw[1].0));
        let (t, y) = dense.last();
        assert_eq!((t, y[1]), (1.5, 0.0), "{name}: {y}");
        for record in [Record::Final, Record::Times(times.clone())] {
            let sol = run(lean(record.clone()));
            assert_eq!(sol.switches, dense.switches, "{name} {record:?}");
            assert_eq!(sol.last(), dense.last(), "{name} {record:?}");
            assert!(sol.t.windows(2).all(|w| w[0] < w[1]), "{name}: {:?}", sol.t);
            for (t, y) in sol.t.iter().zip(&sol.y) {
                if *t <= sw[0].0 {
                    assert_eq!(*y, zero, "{name} {record:?}: moved at {t}");
                } else if *t >= sw[1].0 {
                    assert_eq!(y, dense.last().1, "{name} {record:?}: moved at {t}");
                }
            }
        }
    }
}

/// An ensemble (its members run through the ordinary solve, here without dense output)
/// of blocks launched at different speeds: each stops at `v0^2 / (2 mu g)` and stays.
#[test]
fn an_ensemble_of_sliding_blocks_stops_each_at_its_closed_form() {
    let (mu, g) = (FLOOR.mu, FLOOR.g);
    let members: Vec<_> = [1.0, 2.5, 4.0, 6.0]
        .iter()
        .map(|&v0| {
            let block = Floor { v0, ..FLOOR };
            let y0 = block.initial_state();
            ensemble::Member::new(block, y0)
        })
        .collect();
    let lean = Options {
        dense: false,
        record: Record::Final,
        ..tight()
    };
    let ends = ensemble::final_states(&Dopri5::new(lean), &members, 0.0, 5.0);
    for (m, end) in members.iter().zip(ends) {
        let (t, y) = end.unwrap();
        let x_stop = m.model.v0 * m.model.v0 / (2.0 * mu * g);
        assert_eq!(t, 5.0);
        assert!(
            (y[0] - x_stop).abs() <= 1e-12 * x_stop,
            "v0 = {}: {y}",
            m.model.v0
        );
        assert_eq!(y[1], 0.0, "v0 = {}", m.model.v0);
    }
}
