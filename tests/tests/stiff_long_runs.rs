//! Stress suite, part 3: long runs (docs/STABILITY.md, row "long runs").
//!
//! A simple pendulum for 1e4 periods and a double pendulum for 100 s, every method, with
//! the energy as the truth: both models are conservative, so the exact energy is the
//! initial one, written out by hand below. What is measured is how each method's energy
//! error grows: linearly in time for the non-symplectic methods (RK4, DOPRI5, Radau IIA,
//! the damped generalized-α), bounded for the symmetric, symplectic Gauss method that
//! these measurements are the reason for (mbd-core/src/integrate/gauss.rs).

use mbd::integrate::{Dopri5, Gauss, GeneralizedAlpha, Integrator, Radau5, Rk4};
use mbd::prelude::*;
use std::f64::consts::PI;

/// Simple pendulum: a point mass on a massless rod, `theta` from the downward vertical.
#[derive(Debug, Mechanism)]
#[mechanism(planar, jacobian)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[particle(bob, mass = m, at = [l * sin(theta), -l * cos(theta)])]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// Double pendulum of two point masses on massless rods, both angles from the vertical.
#[derive(Debug, Mechanism)]
#[mechanism(planar, jacobian)]
#[gravity(0.0, -g)]
#[coords(a, b)]
#[particle(p1, mass = m1, at = [l1 * sin(a), -l1 * cos(a)])]
#[particle(p2, mass = m2, at = [l1 * sin(a) + l2 * sin(b), -l1 * cos(a) - l2 * cos(b)])]
pub struct DoublePendulum {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}

const PENDULUM: Pendulum = Pendulum {
    m: 1.0,
    l: 1.0,
    g: 9.81,
};
const THETA0: f64 = 1.0;

/// `m l^2 theta'^2 / 2 - m g l cos(theta)`, by hand.
fn pendulum_energy(y: &Vector<2>) -> f64 {
    let Pendulum { m, l, g } = PENDULUM;
    0.5 * m * l * l * y[1] * y[1] - m * g * l * y[0].cos()
}

/// The period `4 sqrt(l/g) K(sin(theta0/2))`, `K(s) = pi / (2 AGM(1, sqrt(1 - s^2)))`.
fn period() -> f64 {
    let s = (THETA0 / 2.0).sin();
    let (mut a, mut b) = (1.0f64, (1.0 - s * s).sqrt());
    while (a - b).abs() > 4.0 * f64::EPSILON * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    4.0 * (PENDULUM.l / PENDULUM.g).sqrt() * PI / (2.0 * a)
}

/// One integration from `(t0, y0)` to `t1`.
type Run<'a> = dyn Fn(f64, Vector<2>, f64) -> mbd::Result<mbd::Solution<2>> + 'a;

/// Energy error relative to `m g l` after 10, 100, 1000 and 10000 periods, running in
/// chunks of at most 1000 periods (the record stays small): the largest error seen up to
/// each checkpoint.
fn pendulum_run(solve: &Run<'_>) -> ([f64; 4], usize) {
    let t_p = period();
    let scale = PENDULUM.m * PENDULUM.g * PENDULUM.l;
    let mut y = Vector::<2>::new(THETA0, 0.0);
    let e0 = pendulum_energy(&y);
    let (mut worst, mut steps) = (0.0f64, 0usize);
    let mut out = [0.0; 4];
    let mut done = 0.0f64;
    for (i, target) in [10.0, 100.0, 1000.0, 10000.0].into_iter().enumerate() {
        while done < target {
            let chunk = (target - done).min(1000.0);
            let sol = solve(done * t_p, y, (done + chunk) * t_p).unwrap();
            steps += sol.stats.n_steps;
            for yk in &sol.y {
                worst = worst.max((pendulum_energy(yk) - e0).abs() / scale);
            }
            y = *sol.last().1;
            done += chunk;
        }
        out[i] = worst;
    }
    (out, steps)
}

fn opts(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        max_steps: 10_000_000,
        dense: false,
        ..Options::default()
    }
}

/// The simple pendulum from rest at 1 rad (period 2.13 s) for 1e4 periods (21,300 s).
///
/// Measured (docs/STABILITY.md), |dE| / (m g l) after 10 and 1e4 periods: RK4 (h = T/100)
/// 4.3e-7 -> 4.2e-4, DOPRI5 (tol 1e-10) 1.9e-9 -> 1.9e-6, Radau IIA (tol 1e-10)
/// 1.1e-9 -> 1.1e-6: exactly linear growth, a factor 10 per decade of run time;
/// generalized-α with rho_inf = 0.9 8.2e-5 -> 1.1e-3 (dissipative by design), with
/// rho_inf = 1 (the trapezoidal rule, symmetric) bounded at 7.9e-5; Gauss (h = T/100)
/// bounded at 7.6e-9, the same after 10 periods as after 1e4.
///
/// Asserted: Gauss's error after 1e4 periods is at most 1.5 times what it is after 10
/// (bounded: the energy of a symplectic method oscillates about a modified energy, GNI
/// Sect. IX.8) and a hundredth of DOPRI5's; DOPRI5's and Radau IIA's grow by at least 100
/// from 10 to 1e4 periods (linear drift over a factor 1000 in time) and stay below 1e-5 at
/// rtol = 1e-10.
#[test]
fn simple_pendulum_for_ten_thousand_periods() {
    let t_p = period();
    let h = t_p / 100.0;
    let sys = &PENDULUM;
    let rk4 = |t0: f64, y0: Vector<2>, t1: f64| Rk4::new(h).solve(sys, t0, y0, t1, &[]);
    let dopri =
        |t0: f64, y0: Vector<2>, t1: f64| Dopri5::new(opts(1e-10)).solve(sys, t0, y0, t1, &[]);
    let radau =
        |t0: f64, y0: Vector<2>, t1: f64| Radau5::new(opts(1e-10)).solve(sys, t0, y0, t1, &[]);
    let alpha = |rho: f64| {
        move |t0: f64, y0: Vector<2>, t1: f64| {
            GeneralizedAlpha::new(rho, h).solve::<_, 1, 2>(
                sys,
                t0,
                y0.fixed_rows::<1>(0).into_owned(),
                y0.fixed_rows::<1>(1).into_owned(),
                t1,
                &[],
            )
        }
    };
    let gauss = |t0: f64, y0: Vector<2>, t1: f64| {
        Gauss {
            dense: false,
            ..Gauss::new(h)
        }
        .solve(sys, t0, y0, t1, &[])
    };
    let alpha09 = alpha(0.9);
    let alpha10 = alpha(1.0);
    let runs: [(&str, &Run<'_>); 6] = [
        ("RK4 h = T/100", &rk4),
        ("DOPRI5 tol 1e-10", &dopri),
        ("Radau5 tol 1e-10", &radau),
        ("gen-alpha 0.9 h = T/100", &alpha09),
        ("gen-alpha 1.0 h = T/100", &alpha10),
        ("Gauss h = T/100", &gauss),
    ];
    let mut results = Vec::new();
    for (name, run) in runs {
        let (e, steps) = pendulum_run(run);
        eprintln!(
            "pendulum {name}: |dE|/(m g l) after 1e1, 1e2, 1e3, 1e4 periods: {:.2e} {:.2e} {:.2e} {:.2e}; steps {steps}",
            e[0], e[1], e[2], e[3]
        );
        results.push(e);
    }
    let [_, dopri, radau, _, _, gauss] = results[..] else {
        unreachable!()
    };
    assert!(
        gauss[3] <= 1.5 * gauss[0] && gauss[3] < 0.01 * dopri[3],
        "{gauss:?} {dopri:?}"
    );
    for e in [dopri, radau] {
        assert!(e[3] >= 100.0 * e[0] && e[3] < 1e-5, "{e:?}");
    }
}

/// `T + V` of the double pendulum, by hand: `v1 = l1 a'`, `v2^2 = l1^2 a'^2 + l2^2 b'^2 +
/// 2 l1 l2 a' b' cos(a - b)`, heights `-l1 cos a` and `-l1 cos a - l2 cos b`.
fn double_energy(p: &DoublePendulum, y: &Vector<4>) -> f64 {
    let (a, b, ad, bd) = (y[0], y[1], y[2], y[3]);
    let v2 =
        p.l1 * p.l1 * ad * ad + p.l2 * p.l2 * bd * bd + 2.0 * p.l1 * p.l2 * ad * bd * (a - b).cos();
    0.5 * p.m1 * p.l1 * p.l1 * ad * ad + 0.5 * p.m2 * v2
        - p.m1 * p.g * p.l1 * a.cos()
        - p.m2 * p.g * (p.l1 * a.cos() + p.l2 * b.cos())
}

/// The double pendulum from rest at (pi/2, pi/2), a chaotic motion, for 100 s.
///
/// Measured, max |dE| / ((m1 + m2) g l1) over the first 10 s and over 100 s: RK4
/// (h = 1e-3) 1.6e-9 / 2.7e-9, DOPRI5 (tol 1e-9) 4.2e-9 / 3.9e-8, Radau IIA (tol 1e-9)
/// 2.5e-9 / 7.9e-8 (growing about linearly), generalized-α 0.9 (h = 1e-3) 7.2e-5 / 1.1e-4,
/// Gauss (h = 1e-3) 2.2e-10 / 3.9e-10.
///
/// Asserted: DOPRI5 and Radau IIA keep the energy within 100 tol over the 100 s
/// (rtol = atol = 1e-9); Gauss keeps it below 1e-8 with an error that does not grow from
/// the first 10 s to the whole run by more than a factor 3 (its mass matrix depends on the
/// angles, so in (q, q') it is symmetric but not exactly symplectic; it behaves as if it
/// were, GNI Sect. XI.3).
#[test]
fn double_pendulum_for_a_hundred_seconds() {
    let p = DoublePendulum {
        m1: 1.0,
        m2: 1.0,
        l1: 1.0,
        l2: 1.0,
        g: 9.81,
    };
    let y0 = Vector::<4>::new(PI / 2.0, PI / 2.0, 0.0, 0.0);
    let e0 = double_energy(&p, &y0);
    let scale = (p.m1 + p.m2) * p.g * p.l1;
    let track = |sol: &mbd::Solution<4>| -> (f64, f64) {
        let mut early: f64 = 0.0;
        let mut all: f64 = 0.0;
        for (t, y) in sol.t.iter().zip(&sol.y) {
            let e = (double_energy(&p, y) - e0).abs() / scale;
            all = all.max(e);
            if *t <= 10.0 {
                early = early.max(e);
            }
        }
        (early, all)
    };
    let tol = 1e-9;
    let h = 1e-3;
    let report = |name: &str, sol: mbd::Solution<4>| -> (f64, f64) {
        let (early, all) = track(&sol);
        eprintln!(
            "double pendulum {name}: |dE|/((m1+m2) g l1) max over 10 s {early:.2e}, over 100 s {all:.2e}; steps {}",
            sol.stats.n_steps
        );
        (early, all)
    };
    let o = opts(tol);
    let (_, rk4) = report(
        "RK4 h = 1e-3",
        Rk4::new(h).solve(&p, 0.0, y0, 100.0, &[]).unwrap(),
    );
    let (_, dopri) = report(
        "DOPRI5 tol 1e-9",
        Dopri5::new(o.clone())
            .solve(&p, 0.0, y0, 100.0, &[])
            .unwrap(),
    );
    let (_, radau) = report(
        "Radau5 tol 1e-9",
        Radau5::new(o.clone())
            .solve(&p, 0.0, y0, 100.0, &[])
            .unwrap(),
    );
    let q0 = y0.fixed_rows::<2>(0).into_owned();
    let qd0 = y0.fixed_rows::<2>(2).into_owned();
    let (_, alpha) = report(
        "gen-alpha 0.9 h = 1e-3",
        GeneralizedAlpha::new(0.9, h)
            .solve::<_, 2, 4>(&p, 0.0, q0, qd0, 100.0, &[])
            .unwrap(),
    );
    let (g_early, gauss) = report(
        "Gauss h = 1e-3",
        Gauss {
            dense: false,
            ..Gauss::new(h)
        }
        .solve(&p, 0.0, y0, 100.0, &[])
        .unwrap(),
    );
    eprintln!("(RK4 {rk4:.1e}, gen-alpha {alpha:.1e})");
    assert!(
        dopri < 100.0 * tol && radau < 100.0 * tol,
        "{dopri} {radau}"
    );
    assert!(gauss < 1e-8 && gauss <= 3.0 * g_early, "{g_early} {gauss}");
}
