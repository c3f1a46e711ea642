//! Friction at its extremes, as a demanding user tries them: a cylinder thrown with
//! backspin (slipping, then rolling back), a coefficient of exactly zero against the
//! frictionless model, a normal force of exactly zero, and coefficients of 1e12 and 1e-12.
//! Closed forms derived beside each test.

use mbd::Slip;
use mbd::hybrid;
use mbd::integrate::{Dop853, Dopri5, Integrator, Radau5, Rk4};
use mbd::prelude::*;
use std::f64::consts::PI;

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

/// A uniform cylinder (radius `r`, `I = m r^2 / 2`) on a level floor; `s` is the slip of
/// its contact point, `x = s + r th` its centre, so `s'` is the contact's sliding velocity.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s, th)]
#[rigid(cylinder, mass = m, inertia = 0.5 * m * r * r, at = [s + r * th, r], angle = -th)]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
pub struct Cylinder {
    pub m: f64,
    pub r: f64,
    pub g: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// Thrown at `v0` with spin `w0` (`x' = v0`, `th' = w0`), its contact slides at
/// `u = v0 - r w0`. Kinetic friction `F = -mu_k m g sign(u)` gives `x'' = F / m` and
/// `r th'' = -F r^2 / I = -2 F / m`, so `u'' = 3 F / m`: it rolls from `t* = |u0| / (3 mu_k
/// g)`, at `v = v0 - mu_k g t* sign(u0) = (2 v0 + r w0) / 3`. With backspin (`r w0 < -2
/// v0`) that is negative: it comes back. Rolling on a level floor asks no friction, so from
/// `t*` on it rolls at constant speed with the slip `s` fixed exactly.
#[test]
fn a_cylinder_thrown_with_backspin_rolls_back_from_the_closed_form_instant() {
    let p = Cylinder {
        m: 1.5,
        r: 0.2,
        g: 9.81,
        mu_k: 0.25,
        mu_s: 0.35,
    };
    let (v0, w0) = (2.0, -30.0);
    let u0 = v0 - p.r * w0;
    let t_star = u0 / (3.0 * p.mu_k * p.g);
    let v_f = (2.0 * v0 + p.r * w0) / 3.0;
    assert!(v_f < 0.0);
    let x_star = v0 * t_star - p.mu_k * p.g * t_star * t_star / 2.0;
    let s_star = u0 * t_star - 1.5 * p.mu_k * p.g * t_star * t_star;
    let y0 = Vector::<4>::new(0.0, 0.0, u0, w0);
    let t1 = 5.0;
    let runs = [
        (
            "DOPRI5",
            hybrid::solve(&Dopri5::new(tight()), &p, 0.0, y0, t1, &[]),
        ),
        (
            "DOP853",
            hybrid::solve(&Dop853::new(tight()), &p, 0.0, y0, t1, &[]),
        ),
        (
            "Radau5",
            hybrid::solve(&Radau5::new(tight()), &p, 0.0, y0, t1, &[]),
        ),
        ("RK4", hybrid::solve(&Rk4::new(0.01), &p, 0.0, y0, t1, &[])),
    ];
    for (name, run) in runs {
        let run = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        assert_eq!(run.switches[0].to, [Slip::Stick], "{name}");
        // Every piece is a polynomial of degree 2: exact to rounding.
        assert!((run.switches[0].t - t_star).abs() < 1e-12, "{name}");
        let (_, y) = run.solution.last();
        let x = y[0] + p.r * y[1];
        let want = x_star + v_f * (t1 - t_star);
        assert!((x - want).abs() < 1e-12, "{name}: x off by {:e}", x - want);
        assert!(
            (p.r * y[3] - v_f).abs() < 1e-12,
            "{name}: r th' = {}",
            p.r * y[3]
        );
        assert_eq!(y[2], 0.0, "{name}");
        assert!((y[0] - s_star).abs() < 1e-12, "{name}: s = {}", y[0]);
        // Rolling: the slip is frozen to the bit from the stop on.
        let at_stop = run.solution.at(run.switches[0].t).unwrap();
        assert_eq!(y[0], at_stop[0], "{name}: slipped while rolling");
    }
}

/// A block on a spring with a rough floor (`mu_k`, `mu_s` as parameters) or none.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(tie, from = [0.0, 0.0], to = block, k = k)]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = n)]
pub struct Rough {
    pub m: f64,
    pub k: f64,
    pub n: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(tie, from = [0.0, 0.0], to = block, k = k)]
pub struct Smooth {
    pub m: f64,
    pub k: f64,
}

/// `mu = 0` exactly is the frictionless oscillator `x = x0 cos(w t)`: at rest under the
/// spring's load it slides at once (a zero bound holds no load), it turns at `t = j pi / w`
/// without sticking, and its states agree with the frictionless model's and the closed form.
#[test]
fn a_zero_coefficient_is_the_frictionless_model() {
    let (m, k, x0): (f64, f64, f64) = (0.5, 8.0, 0.3);
    let w: f64 = (k / m).sqrt();
    let p = Rough {
        m,
        k,
        n: m * 9.81,
        mu_k: 0.0,
        mu_s: 0.0,
    };
    let y0 = Vector::<2>::new(x0, 0.0);
    let acc = p.acceleration(0.0, &Vector::<1>::new(x0), &Vector::<1>::zeros());
    assert_eq!(acc.unwrap()[0], -k * x0 / m);
    let t1 = 10.0;
    let run = hybrid::solve(&Dopri5::new(tight()), &p, 0.0, y0, t1, &[]).unwrap();
    let smooth = Dopri5::new(tight())
        .solve(&Smooth { m, k }, 0.0, y0, t1, &[])
        .unwrap();
    assert!(
        run.switches.iter().all(|s| s.to != [Slip::Stick]),
        "{:?}",
        run.switches
    );
    assert_eq!(run.switches.len(), (w * t1 / PI) as usize);
    for (j, s) in run.switches.iter().enumerate() {
        let t = (j + 1) as f64 * PI / w;
        assert!((s.t - t).abs() < 1e-10, "turn {j}: {} vs {t}", s.t);
    }
    let (y, z) = (run.solution.last().1, smooth.last().1);
    let want = x0 * (w * t1).cos();
    assert!((y[0] - want).abs() < 1e-10, "{:e}", y[0] - want);
    assert!((y[0] - z[0]).abs() < 1e-10 && (y[1] - z[1]).abs() < 1e-10);
}

/// A normal force of exactly zero bounds nothing: from rest under the spring it moves as
/// the frictionless oscillator, both signs of a zero normal alike, and a body at rest with
/// no load (at `x = 0`) stays, with zero acceleration.
#[test]
fn a_zero_normal_force_holds_nothing() {
    let (m, k, x0): (f64, f64, f64) = (0.5, 8.0, 0.3);
    let w: f64 = (k / m).sqrt();
    for n in [0.0, -0.0] {
        let p = Rough {
            m,
            k,
            n,
            mu_k: 0.4,
            mu_s: 0.6,
        };
        let run = hybrid::solve(
            &Dopri5::new(tight()),
            &p,
            0.0,
            Vector::<2>::new(x0, 0.0),
            3.0,
            &[],
        )
        .unwrap();
        let want = x0 * (w * 3.0).cos();
        let y = run.solution.last().1;
        assert!((y[0] - want).abs() < 1e-10, "n = {n}: {:e}", y[0] - want);
        let rest = hybrid::solve(
            &Dopri5::new(tight()),
            &p,
            0.0,
            Vector::<2>::zeros(),
            3.0,
            &[],
        )
        .unwrap();
        assert_eq!(rest.solution.last().1, &Vector::<2>::zeros());
        assert_eq!(rest.mode, [Slip::Stick]);
    }
}

/// A block launched at `v0` on a floor (no spring), with `mu = 1e12`: it decelerates at
/// `mu g` and stops after `t = v0 / (mu g)` (about 1e-13 s) at `x = v0^2 / (2 mu g)`, then
/// stays; with `mu = 1e-12` it slides on, `v = v0 - mu g t`.
#[test]
fn huge_and_tiny_coefficients_keep_their_closed_forms() {
    let (m, g, v0) = (2.0, 9.81, 1.0);
    let launched = Vector::<2>::new(0.0, v0);
    let huge = Rough {
        m,
        k: 0.0,
        n: m * g,
        mu_k: 1e12,
        mu_s: 1e12,
    };
    for (name, run) in [
        (
            "DOPRI5",
            hybrid::solve(&Dopri5::new(tight()), &huge, 0.0, launched, 1.0, &[]),
        ),
        (
            "Radau5",
            hybrid::solve(&Radau5::new(tight()), &huge, 0.0, launched, 1.0, &[]),
        ),
        (
            "RK4",
            hybrid::solve(&Rk4::new(1e-3), &huge, 0.0, launched, 1.0, &[]),
        ),
    ] {
        let run = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let t_stop = v0 / (1e12 * g);
        let x_stop = v0 * v0 / (2.0 * 1e12 * g);
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        assert!(
            (run.switches[0].t - t_stop).abs() < 1e-9 * t_stop,
            "{name}: {}",
            run.switches[0].t
        );
        let y = run.solution.last().1;
        // Relative 1e-8 of a distance of 5e-14, far below `atol`: Radau IIA's Newton
        // iteration stops at a fraction of the tolerance (measured 1.9e-9 relative).
        assert!(
            (y[0] - x_stop).abs() < 1e-8 * x_stop,
            "{name}: {:e} vs {x_stop:e}",
            y[0]
        );
        assert_eq!(y[1], 0.0, "{name}");
    }
    let tiny = Rough {
        mu_k: 1e-12,
        mu_s: 1e-12,
        ..huge
    };
    let run = hybrid::solve(&Dopri5::new(tight()), &tiny, 0.0, launched, 10.0, &[]).unwrap();
    assert!(run.switches.is_empty());
    let y = run.solution.last().1;
    let (v, x) = (v0 - 1e-12 * g * 10.0, v0 * 10.0 - 1e-12 * g * 50.0);
    assert!(
        (y[1] - v).abs() < 1e-15 && (y[0] - x).abs() < 1e-13,
        "{:e} {:e}",
        y[1] - v,
        y[0] - x
    );
    assert!(y[1] < v0, "the tiny friction is not lost to rounding");
}
