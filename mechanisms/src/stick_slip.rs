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
                let run = run(&mbd::integrate::GeneralizedAlpha::new(0.8, h), &b, 3, false)
                    .unwrap();
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
