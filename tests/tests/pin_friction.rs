//! A pendulum with pin friction comes to rest at a located time, against an independent
//! reference.
//!
//! A point mass `m` on a massless rod `l` about a pin of friction radius `r` with
//! coefficient `mu`: the friction torque is `c |N|`, `c = mu r`, with `N` the pin's
//! reaction along the rod, `N = m (g cos th + l th'^2)` (the polar coordinate `u` along the
//! rod is relaxed, so `reaction(u)` is that force; it does not depend on `th''`). So
//! `m l^2 th'' = -m g l sin th - c N sign(th')`.
//!
//! Reference. With `w^2 = g / l`, `k = c / l` and `s = sign(th')` in one swing, `U = th'^2`
//! as a function of `th` obeys the linear equation `dU/dth + a U = -2 w^2 (sin th + s k cos th)`,
//! `a = 2 s k`, whose solution from a turning point `th0` (`U = 0`) is
//! `U(th) = -2 w^2 e^(-a th) (J(th) - J(th0))`,
//! `J(p) = e^(a p) ((a sin p - cos p) + s k (a cos p + sin p)) / (a^2 + 1)`.
//! The next turning point is the root of `U` (bisection to adjacent doubles), and the swing
//! takes `int dth / sqrt(U)`, computed with `th = mid - half cos(p)`, `p` in `[0, pi]`, which
//! removes the inverse square roots at both ends, by composite Gauss-Legendre quadrature. At
//! a turning point the pendulum sticks when the gravity torque is within static friction,
//! `m g l |sin th| <= c m g cos th`, i.e. `l |tan th| <= c`; otherwise it swings back.

use mbd::Slip;
use mbd::integrate::{Dopri5, Radau5};
use mbd::prelude::*;
use std::f64::consts::PI;

/// The pendulum with pin friction; `u` along the rod is relaxed so that `reaction(u)` is the
/// pin's force along it.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(th)]
#[relaxed(u)]
#[particle(bob, mass = m, at = [(l + u) * sin(th), -(l + u) * cos(th)])]
#[friction(along = th, mu = c, normal = reaction(u))]
#[init(th = th0)]
pub struct PinPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
    pub th0: f64,
}

const P: PinPendulum = PinPendulum {
    m: 1.5,
    l: 1.0,
    g: 9.81,
    c: 0.05,
    th0: 0.53,
};

/// `U(th)` of the swing from the turning point `th0` in direction `s`.
fn u_of(p: &PinPendulum, s: f64, th0: f64, th: f64) -> f64 {
    let (w2, k) = (p.g / p.l, p.c / p.l);
    let a = 2.0 * s * k;
    let j = |x: f64| {
        (a * x).exp() * ((a * x.sin() - x.cos()) + s * k * (a * x.cos() + x.sin())) / (a * a + 1.0)
    };
    -2.0 * w2 * (-a * th).exp() * (j(th) - j(th0))
}

/// The next turning point after `th0` in direction `s`: `U > 0` just past `th0`, zero there.
fn turning_point(p: &PinPendulum, s: f64, th0: f64) -> f64 {
    // U grows from th0, then falls back to zero before -s th0 (friction only takes energy).
    let (mut a, mut b) = (th0 + s * 1e-6, -th0);
    assert!(u_of(p, s, th0, a) > 0.0 && u_of(p, s, th0, b) < 0.0);
    loop {
        let c = 0.5 * (a + b);
        if c == a || c == b {
            return a;
        }
        if u_of(p, s, th0, c) > 0.0 {
            a = c;
        } else {
            b = c;
        }
    }
}

/// Gauss-Legendre nodes and weights on `[-1, 1]` (Newton on `P_n`).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            loop {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let kf = k as f64;
                    (p0, p1) = (p1, ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf);
                }
                let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-15 {
                    let (mut p0, mut p1) = (1.0, x);
                    for k in 2..=n {
                        let kf = k as f64;
                        (p0, p1) = (p1, ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf);
                    }
                    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                    return (x, 2.0 / ((1.0 - x * x) * dp * dp));
                }
            }
        })
        .collect()
}

/// The duration of the swing from `th0` to `th1` in direction `s`.
fn swing_time(p: &PinPendulum, s: f64, th0: f64, th1: f64) -> f64 {
    let (mid, half) = (0.5 * (th0 + th1), 0.5 * (th0 - th1).abs());
    let nodes = gauss_legendre(20);
    let panels = 40;
    let mut total = 0.0;
    for k in 0..panels {
        let (lo, hi) = (
            PI * k as f64 / panels as f64,
            PI * (k + 1) as f64 / panels as f64,
        );
        for &(x, w) in &nodes {
            let phi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x;
            // th runs from th0 to th1 as phi runs over [0, pi].
            let th = mid + s * (-half * phi.cos());
            total += 0.5 * (hi - lo) * w * half * phi.sin() / u_of(p, s, th0, th).sqrt();
        }
    }
    total
}

/// The reference: the turning points and the times at them, to the one where it sticks.
fn reference(p: &PinPendulum) -> Vec<(f64, f64)> {
    reference_until(p, |th| p.l * th.tan().abs() <= p.c)
}

/// [`reference`] with the rule `sticks(th)` at a turning point.
fn reference_until(p: &PinPendulum, sticks: impl Fn(f64) -> bool) -> Vec<(f64, f64)> {
    let (mut th, mut t, mut out) = (p.th0, 0.0, Vec::new());
    loop {
        let s = -th.signum();
        let next = turning_point(p, s, th);
        t += swing_time(p, s, th, next);
        out.push((t, next));
        if sticks(next) {
            return out;
        }
        th = next;
    }
}

#[test]
fn the_reference_is_consistent() {
    // Without friction the swing time tends to half the period of the free pendulum
    // (an independent series: T/2 = pi sqrt(l/g) (1 + th0^2/16 + 11 th0^4/3072 + ...)).
    let free = PinPendulum {
        c: 1e-12,
        th0: 0.1,
        ..P
    };
    let s = -1.0;
    let th1 = turning_point(&free, s, 0.1);
    assert!((th1 + 0.1).abs() < 1e-9);
    let half = PI * (1.0f64 / 9.81).sqrt() * (1.0 + 0.01 / 16.0 + 11.0 * 1e-4 / 3072.0);
    assert!((swing_time(&free, s, 0.1, th1) - half).abs() < 1e-7 * half);
}

#[test]
fn the_pendulum_comes_to_rest_at_the_located_time() {
    let reference = reference(&P);
    assert_eq!(reference.len(), 5, "{reference:?}");
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let (t_rest, th_rest) = *reference.last().unwrap();
    for (name, run) in [
        (
            "DOPRI5",
            mbd::hybrid::solve(
                &Dopri5::new(opts.clone()),
                &P,
                0.0,
                P.initial_state(),
                6.0,
                &[],
            ),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(
                &Radau5::new(opts.clone()),
                &P,
                0.0,
                P.initial_state(),
                6.0,
                &[],
            ),
        ),
    ] {
        let run = run.unwrap();
        assert_eq!(run.switches.len(), reference.len(), "{name}");
        for (sw, &(t, th)) in run.switches.iter().zip(&reference) {
            let y = run.solution.at(sw.t).unwrap();
            assert!((sw.t - t).abs() <= 1e-9 * t, "{name}: {} vs {t}", sw.t);
            assert!((y[0] - th).abs() <= 1e-9, "{name}: {} vs {th}", y[0]);
        }
        let last = run.switches.last().unwrap();
        assert_eq!(last.to, [Slip::Stick], "{name}");
        assert!((last.t - t_rest).abs() <= 1e-9 * t_rest);
        // At rest from then on: the angle where it stuck, no velocity.
        let (t, y) = run.solution.last();
        assert_eq!(t, 6.0);
        assert_eq!(y[1], 0.0);
        assert!((y[0] - th_rest).abs() <= 1e-9);
    }
}

/// The same pendulum written as a joint tree: a massless arm with the bob at its end on a
/// revolute joint whose pivot force is asked for with `reaction` (ground axes). Its
/// component along the rod, `rx sin(th) - ry cos(th)` (minus the rod's tension), is the
/// normal force of the pin friction: the reaction's tangential part, which carries `th''`,
/// drops out of that projection (the derive checks that its derivatives by the
/// accelerations vanish), so the friction stays explicit.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(th), com = [0.0, -l], mass = m, inertia = 0.0, reaction)]
#[friction(along = th, mu = c, normal = reaction(arm_rx) * sin(th) - reaction(arm_ry) * cos(th))]
#[init(th = th0)]
pub struct JointPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
    pub th0: f64,
}

/// Friction on the revolute joint of a joint tree: the same turning points and rest as the
/// polar model and its reference.
#[test]
fn revolute_joint_friction_matches_the_pin_reference() {
    let j = JointPendulum {
        m: P.m,
        l: P.l,
        g: P.g,
        c: P.c,
        th0: P.th0,
    };
    let reference = reference(&P);
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let run = mbd::hybrid::solve(&Dopri5::new(opts), &j, 0.0, j.initial_state(), 6.0, &[]).unwrap();
    assert_eq!(run.switches.len(), reference.len());
    for (sw, &(t, th)) in run.switches.iter().zip(&reference) {
        let y = run.solution.at(sw.t).unwrap();
        assert!((sw.t - t).abs() <= 1e-9 * t, "{} vs {t}", sw.t);
        assert!((y[0] - th).abs() <= 1e-9, "{} vs {th}", y[0]);
    }
    assert_eq!(run.mode, [Slip::Stick]);
}

/// Pin friction on the full magnitude of the joint's reaction, `c |R|` with
/// `|R| = hypot(R_x, R_y)`: implicit, since `R` carries `th''`, which carries the friction.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(th), com = [0.0, -l], mass = m, inertia = 0.0, reaction)]
#[friction(along = th, mu = c, normal = hypot(reaction(arm_rx), reaction(arm_ry)))]
#[init(th = th0)]
pub struct FullPin {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
    pub th0: f64,
}

/// Independent derivation. The pin's force on the bob is `R = m a - m g`: along the rod
/// (towards the pin) `R_r = m (g cos th + l th'^2)`, across it `R_t = m l th'' + m g sin th`,
/// and the moments about the pin give `m l^2 th'' = -m g l sin th + tau`, so `R_t = tau / l`.
/// Sliding, `tau = -c |R| sign(th')`, so `|R|^2 = R_r^2 + (c / l)^2 |R|^2`:
/// `|R| = R_r / sqrt(1 - (c / l)^2)` (`R_r > 0`). The motion is the radial-only pendulum's
/// with `c / sqrt(1 - (c / l)^2)` in place of `c`. At rest (`th' = th'' = 0`), `tau` must
/// hold `m g l sin th` and `|R| = m g`: it sticks where `l |sin th| <= c`.
fn full_pin_effective(p: &FullPin) -> PinPendulum {
    let k = p.c / p.l;
    PinPendulum {
        m: p.m,
        l: p.l,
        g: p.g,
        c: p.c / (1.0 - k * k).sqrt(),
        th0: p.th0,
    }
}

/// The implicit friction at one sliding state and at rest, against the closed forms above.
#[test]
fn full_reaction_friction_has_the_closed_form_acceleration() {
    let p = FullPin {
        m: 1.5,
        l: 0.8,
        g: 9.81,
        c: 0.3,
        th0: 0.4,
    };
    let eff = full_pin_effective(&p);
    for (th, w) in [(0.3, 1.2), (-0.7, -0.4), (1.1, -2.0)] {
        let s: f64 = if w > 0.0 { 1.0 } else { -1.0 };
        let r_r = p.m * (p.g * f64::cos(th) + p.l * w * w);
        let expected = (-p.m * p.g * p.l * f64::sin(th) - s * eff.c * r_r) / (p.m * p.l * p.l);
        let a = p
            .acceleration(0.0, &nalgebra::Vector1::new(th), &nalgebra::Vector1::new(w))
            .unwrap()[0];
        assert!(
            (a - expected).abs() <= 1e-13 * expected.abs(),
            "{a} vs {expected}"
        );
    }
    // At rest: held exactly where l |sin th| <= c (here 0.3 / 0.8 = sin 0.3844), else slides.
    let at_rest = |th: f64| {
        p.acceleration(
            0.0,
            &nalgebra::Vector1::new(th),
            &nalgebra::Vector1::new(0.0),
        )
        .unwrap()[0]
    };
    assert_eq!(at_rest(0.38), 0.0);
    assert_eq!(at_rest(-0.38), 0.0);
    assert!(at_rest(0.39) < 0.0 && at_rest(-0.39) > 0.0);
    let y = nalgebra::Vector2::new(0.38, 0.0);
    assert!(p.th_sticks(0.0, &y).unwrap());
    assert!(
        !p.th_sticks(0.0, &nalgebra::Vector2::new(0.39, 0.0))
            .unwrap()
    );
}

/// The pendulum with friction on the full reaction comes to rest at the located time: every
/// turning point and the rest against the derivation beside `full_pin_effective`.
#[test]
fn full_reaction_pendulum_comes_to_rest_at_the_located_time() {
    let p = FullPin {
        m: P.m,
        l: P.l,
        g: P.g,
        c: 0.1,
        th0: P.th0,
    };
    let eff = full_pin_effective(&p);
    let reference = reference_until(&eff, |th| p.l * th.sin().abs() <= p.c);
    assert!(reference.len() >= 2, "{reference:?}");
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let (t_rest, th_rest) = *reference.last().unwrap();
    for (name, run) in [
        (
            "DOPRI5",
            mbd::hybrid::solve(
                &Dopri5::new(opts.clone()),
                &p,
                0.0,
                p.initial_state(),
                6.0,
                &[],
            ),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(
                &Radau5::new(opts.clone()),
                &p,
                0.0,
                p.initial_state(),
                6.0,
                &[],
            ),
        ),
    ] {
        let run = run.unwrap();
        assert_eq!(run.switches.len(), reference.len(), "{name}");
        for (sw, &(t, th)) in run.switches.iter().zip(&reference) {
            let y = run.solution.at(sw.t).unwrap();
            assert!((sw.t - t).abs() <= 1e-9 * t, "{name}: {} vs {t}", sw.t);
            assert!((y[0] - th).abs() <= 1e-9, "{name}: {} vs {th}", y[0]);
        }
        assert_eq!(run.mode, [Slip::Stick], "{name}");
        assert!((run.switches.last().unwrap().t - t_rest).abs() <= 1e-9 * t_rest);
        let (t, y) = run.solution.last();
        assert_eq!(t, 6.0);
        assert_eq!(y[1], 0.0);
        assert!((y[0] - th_rest).abs() <= 1e-9);
    }
}
