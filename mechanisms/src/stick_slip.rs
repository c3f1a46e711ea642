//! The classical stick-slip oscillator against its closed-form limit cycle.
//!
//! A mass `m` on a spring `k` anchored at `x = 0` rests on a belt moving at constant speed
//! `v`. The belt's position is the driven `b = v t`, the free coordinate `s` is the mass's
//! position relative to the belt, so `x = b + s` and the sliding velocity is `s'`. Friction
//! along `s` with the normal force `m g`: kinetic `mu_k`, static `mu_s > mu_k`.
//!
//! Derivation (write `w^2 = k / m`, `x_s = mu_s g / w^2`, `x_k = mu_k g / w^2`):
//! - Stick (`s' = 0`): the mass rides the belt, `x = x_0 + v t`; the friction must hold the
//!   spring force `-k x`, which it can while `k |x| <= mu_s m g`, i.e. up to `x = x_s`.
//! - Slip: at `x_s` the spring wins and the mass falls back against the belt (`s' < 0`), so
//!   kinetic friction pushes it forward: `x'' = -w^2 x + mu_k g = -w^2 (x - x_k)`, a harmonic
//!   arc about `x_k` starting at `(x, x') = (x_s, v)`. In `(u, z) = (x - x_k, x'/w)` the
//!   state turns clockwise at rate `w` on the circle through `(D, v/w)`, `D = x_s - x_k`.
//!   Sliding ends when `x' = v` again (`s' = 0` from below), at the circle's other point on
//!   the line `z = v/w`: `(-D, v/w)`, i.e. `x_a = 2 x_k - x_s`. The arc below the chord
//!   sweeps `pi + 2 atan(v / (w D))`, so `T_slip = (pi + 2 atan(v / (w D))) / w`.
//! - At `x_a` the spring force `k |x_a| <= k x_s` (as `x_k >= 0`): it sticks again.
//!   `T_stick = (x_s - x_a) / v = 2 D / v`.
//!
//! Started at `x(0) = x_a` stuck, the motion is the limit cycle from the first instant:
//! breakaway at `T_stick + n T`, sticking at `(n + 1) T`, `T = T_stick + T_slip`.

use mbd::Slip;
use mbd::hybrid::HybridSolution;
use mbd::integrate::Integrator;

use crate::workprecision::{
    Failure, Measured, Method, Problem, Quantity, RHO_INF, Setting, solve_mechanism,
};
use mbd::integrate::{Dop853, Dopri5, GeneralizedAlpha, Radau5, Rk4};
use mbd::prelude::*;

/// A mass on a spring dragged by a belt at speed `v` (see the module's derivation).
#[derive(Debug, Mechanism)]
#[coords(s)]
#[drive(b = v * t)]
#[particle(mass, mass = m, at = [b + s, 0.0])]
#[potential(k * (b + s) * (b + s) / 2.0)]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
#[init(s = s0)]
pub struct Belt {
    pub m: f64,
    pub k: f64,
    pub g: f64,
    pub v: f64,
    pub mu_k: f64,
    pub mu_s: f64,
    pub s0: f64,
}

/// The closed form: `(x_a, T_stick, T_slip)`: where the cycle sticks, how long it sticks,
/// how long it slips.
pub fn limit_cycle(b: &Belt) -> (f64, f64, f64) {
    let w = (b.k / b.m).sqrt();
    let (x_s, x_k) = (b.mu_s * b.g / (w * w), b.mu_k * b.g / (w * w));
    let d = x_s - x_k;
    let t_slip = (std::f64::consts::PI + 2.0 * (b.v / (w * d)).atan()) / w;
    (2.0 * x_k - x_s, 2.0 * d / b.v, t_slip)
}

/// The report's and tests' belt (`w = 2 rad/s`, `v = 0.5 m/s`), started on its limit cycle.
pub fn belt() -> Belt {
    let b = Belt {
        m: 1.0,
        k: 4.0,
        g: 9.81,
        v: 0.5,
        mu_k: 0.3,
        mu_s: 0.4,
        s0: 0.0,
    };
    Belt {
        s0: limit_cycle(&b).0,
        ..b
    }
}

/// The same mass and spring on the same belt without friction (a harmonic oscillator in
/// `x = b + s`): the baseline of the cost comparison.
#[derive(Debug, Mechanism)]
#[coords(s)]
#[drive(b = v * t)]
#[particle(mass, mass = m, at = [b + s, 0.0])]
#[potential(k * (b + s) * (b + s) / 2.0)]
#[init(s = s0)]
pub struct BeltFree {
    pub m: f64,
    pub k: f64,
    pub v: f64,
    pub s0: f64,
}

/// The frictionless twin of `b`.
pub fn without_friction(b: &Belt) -> BeltFree {
    BeltFree {
        m: b.m,
        k: b.k,
        v: b.v,
        s0: b.s0,
    }
}

/// Run `periods` periods of the limit cycle (and half a stick phase more) mode by mode.
pub fn run<I: Integrator>(
    integrator: &I,
    b: &Belt,
    periods: usize,
    polish: bool,
) -> mbd::Result<HybridSolution<2, [Slip; 1]>> {
    let (_, t_stick, t_slip) = limit_cycle(b);
    let t1 = periods as f64 * (t_stick + t_slip) + 0.5 * t_stick;
    let settings = mbd::hybrid::Settings {
        polish,
        ..Default::default()
    };
    mbd::hybrid::solve_with(integrator, b, 0.0, b.initial_state(), t1, &[], &settings)
}

/// The exact time of switch `i` of the cycle started stuck at `x_a` (breakaways at
/// `T_stick + n T`, stops at `(n + 1) T`), and the modes it goes between.
pub fn exact_switch(b: &Belt, i: usize) -> (f64, [Slip; 1], [Slip; 1]) {
    let (_, t_stick, t_slip) = limit_cycle(b);
    let (n, period) = ((i / 2) as f64, t_stick + t_slip);
    if i.is_multiple_of(2) {
        (t_stick + n * period, [Slip::Stick], [Slip::Backward])
    } else {
        ((n + 1.0) * period, [Slip::Backward], [Slip::Stick])
    }
}

/// The largest relative error of the switch times against the closed form, or `None` if a
/// switch goes between the wrong modes.
pub fn switch_error(b: &Belt, run: &HybridSolution<2, [Slip; 1]>) -> Option<f64> {
    run.switches
        .iter()
        .enumerate()
        .try_fold(0.0f64, |worst, (i, sw)| {
            let (exact, from, to) = exact_switch(b, i);
            ((sw.from, sw.to) == (from, to)).then(|| worst.max((sw.t - exact).abs() / exact))
        })
}

/// Periods of the work-precision runs (20 switches).
pub const WP_PERIODS: usize = 10;

/// The work-precision rows: the limit cycle mode by mode with each method, and the same
/// belt without friction over the same time (its cost is the smooth one's).
pub fn problems() -> Vec<Problem> {
    vec![
        Problem {
            name: "stick-slip",
            title: "stick-slip oscillator, 10 periods mode by mode (20 switches): last stop, last stick time, final s",
            methods: &Method::MBD,
            run: wp_friction,
        },
        Problem {
            name: "stick-slip (no friction)",
            title: "the same belt without friction over the same time: final s, s'",
            methods: &Method::MBD,
            run: wp_free,
        },
    ]
}

/// The end of the work-precision runs: half a stick phase after the last stop.
fn wp_end(b: &Belt) -> f64 {
    let (_, t_stick, t_slip) = limit_cycle(b);
    WP_PERIODS as f64 * (t_stick + t_slip) + 0.5 * t_stick
}

/// The cycle from its start to `t1`, mode by mode.
fn cycle<I: Integrator>(i: &I, b: &Belt, t1: f64) -> mbd::Result<HybridSolution<2, [Slip; 1]>> {
    mbd::hybrid::solve(i, b, 0.0, b.initial_state(), t1, &[])
}

fn wp_friction(s: &Setting) -> Result<Measured, Failure> {
    let b = std::hint::black_box(belt());
    let opts = Options {
        rtol: s.value,
        atol: s.value,
        ..Options::default()
    };
    let t1 = wp_end(&b);
    let run = match s.method {
        Method::Rk4 => cycle(&Rk4::new(s.value), &b, t1),
        Method::Dopri5 => cycle(&Dopri5::new(opts), &b, t1),
        Method::Dop853 => cycle(&Dop853::new(opts), &b, t1),
        Method::Vern9 => cycle(&mbd::integrate::Vern9::new(opts), &b, t1),
        Method::Radau5 => cycle(&Radau5::new(opts), &b, t1),
        Method::GeneralizedAlpha => cycle(&GeneralizedAlpha::new(RHO_INF, s.value), &b, t1),
        _ => return Err(Failure::Unsupported("mbd's methods only".into())),
    }?;
    let sw = &run.switches;
    if sw.len() != 2 * WP_PERIODS || switch_error(&b, &run).is_none() {
        return Err(Failure::Failed(format!(
            "{} switches instead of the cycle's {}",
            sw.len(),
            2 * WP_PERIODS
        )));
    }
    let (x_a, t_stick, _) = limit_cycle(&b);
    let last = exact_switch(&b, 2 * WP_PERIODS - 1).0;
    let mut stats = run.solution.stats;
    if s.method == Method::Radau5 {
        // Radau5 counts its own calls only; each forward-difference Jacobian makes D + 1 more.
        stats.n_rhs += stats.n_jac * 3;
    }
    Ok(Measured {
        quantities: vec![
            Quantity {
                name: "t_stop",
                value: sw[sw.len() - 1].t,
                reference: last,
            },
            Quantity {
                name: "t_stick",
                value: sw[sw.len() - 2].t - sw[sw.len() - 3].t,
                reference: t_stick,
            },
            // Stuck at x_a since the last stop: s = x_a - v t_stop.
            Quantity {
                name: "s_end",
                value: run.solution.last().1[0],
                reference: x_a - b.v * last,
            },
        ],
        stats,
        span: t1,
    })
}

fn wp_free(s: &Setting) -> Result<Measured, Failure> {
    let b = belt();
    let free = std::hint::black_box(without_friction(&b));
    let t1 = wp_end(&b);
    let sol = solve_mechanism(s, &free, 0.0, free.initial_state(), t1, &[])?;
    // x = b + s is harmonic, x(0) = x_a, x'(0) = v (s' = 0): x = x_a cos wt + (v / w) sin wt.
    let w = (b.k / b.m).sqrt();
    let (t, y) = sol.last();
    let x = b.s0 * (w * t).cos() + b.v / w * (w * t).sin();
    let xd = -b.s0 * w * (w * t).sin() + b.v * (w * t).cos();
    Ok(Measured {
        quantities: vec![
            Quantity {
                name: "s_end",
                value: y[0],
                reference: x - b.v * t,
            },
            Quantity {
                name: "s'_end",
                value: y[1],
                reference: xd - b.v,
            },
        ],
        stats: sol.stats,
        span: t1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use mbd::integrate::{Dopri5, Radau5};

    #[test]
    fn the_limit_cycle_has_the_closed_form_switch_times_stick_time_and_period() {
        let b = belt();
        let (_, t_stick, t_slip) = limit_cycle(&b);
        let period = t_stick + t_slip;
        let opts = Options {
            rtol: 1e-12,
            atol: 1e-12,
            ..Options::default()
        };
        let periods = 10;
        let dopri = Dopri5::new(opts.clone());
        let radau = Radau5::new(opts);
        // (name, run, largest relative switch-time error allowed)
        let runs = [
            ("DOPRI5", run(&dopri, &b, periods, false).unwrap(), 1e-9),
            ("Radau5", run(&radau, &b, periods, false).unwrap(), 1e-9),
            // Polished: the switches from step ends, as accurate as the tolerance.
            (
                "DOPRI5 polished",
                run(&dopri, &b, periods, true).unwrap(),
                1e-11,
            ),
            (
                "Radau5 polished",
                run(&radau, &b, periods, true).unwrap(),
                1e-11,
            ),
        ];
        for (name, run, allowed) in &runs {
            assert_eq!(run.switches.len(), 2 * periods, "{name}");
            let err = switch_error(&b, run).expect("switches between the cycle's modes");
            assert!(
                err <= *allowed,
                "{name}: switch times off by {err:.1e} (relative)"
            );
            // Stick time and period from the located switches.
            let sw = &run.switches;
            let (stick, per) = (sw[2].t - sw[1].t, sw[3].t - sw[1].t);
            assert!(
                (stick - t_stick).abs() <= 1e-9 * t_stick,
                "{name}: {stick} vs {t_stick}"
            );
            assert!(
                (per - period).abs() <= 1e-9 * period,
                "{name}: {per} vs {period}"
            );
            // While stuck the mass rides the belt exactly: s' = 0 at the end (half a stick in).
            assert_eq!(run.solution.last().1[1], 0.0, "{name}");
        }
    }

    /// Generalized-alpha (second order, fixed step) driven mode by mode through its
    /// `Integrator` implementation: the switches go between the cycle's modes, their times
    /// converge to the closed form at second order (the error falls by 4 when `h` halves),
    /// and the mass rides the belt exactly while stuck.
    #[test]
    fn generalized_alpha_converges_to_the_limit_cycle_at_second_order() {
        let b = belt();
        let errors: Vec<f64> = [2e-3, 1e-3]
            .into_iter()
            .map(|h| {
                let run =
                    run(&mbd::integrate::GeneralizedAlpha::new(0.8, h), &b, 3, false).unwrap();
                assert_eq!(run.switches.len(), 6, "h = {h}");
                assert_eq!(run.solution.last().1[1], 0.0, "h = {h}");
                switch_error(&b, &run).expect("switches between the cycle's modes")
            })
            .collect();
        let ratio = errors[0] / errors[1];
        assert!((3.8..=4.2).contains(&ratio), "{errors:?}");
        assert!(errors[1] < 1e-6, "{errors:?}");
    }

    /// The closed form itself, against an independent check: the slip arc from `(x_s, v)`
    /// integrated as the harmonic motion `x_k + D cos(w t) + (v / w) sin(w t)` reaches
    /// `x' = v` at `T_slip` and there `x = x_a`.
    #[test]
    fn the_closed_form_slip_arc_ends_where_it_says() {
        let b = belt();
        let (x_a, _, t_slip) = limit_cycle(&b);
        let w = (b.k / b.m).sqrt();
        let (x_s, x_k) = (b.mu_s * b.g / (w * w), b.mu_k * b.g / (w * w));
        let d = x_s - x_k;
        let x = |t: f64| x_k + d * (w * t).cos() + b.v / w * (w * t).sin();
        let xd = |t: f64| -d * w * (w * t).sin() + b.v * (w * t).cos();
        assert!((xd(t_slip) - b.v).abs() < 1e-14);
        assert!((x(t_slip) - x_a).abs() < 1e-14);
        // and not before: the relative velocity stays negative inside the arc.
        assert!((1..100).all(|i| xd(t_slip * i as f64 / 100.0) < b.v));
    }
}
