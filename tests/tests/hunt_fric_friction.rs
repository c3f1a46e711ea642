//! Hunting friction defects as a new user: Coulomb friction with viscous damping, a normal
//! force that vanishes at rest (a bead in a turning slot) or changes sign in time, a block
//! on an accelerating platform, static and kinetic coefficients at the friction angle, a
//! stick-slip belt over thousands of switches, a tiny coefficient over hundreds of turning
//! points with the energy it takes, and two contacts tied by a rigid link. Each closed form
//! is derived beside its test; every run goes through `mbd::hybrid::solve`.

use mbd::Slip;
use mbd::integrate::{Dop853, Dopri5, Radau5, Vern9};
use mbd::prelude::*;
use std::f64::consts::PI;

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

/// Runs the body with four adaptive methods at tight tolerances, naming each and giving
/// the accuracy its runs reach here (`acc`, in the state's units): 1e-10 for the explicit
/// methods; Radau IIA's error estimate is of order 3 and its dense output of degree 3, so
/// at the same tolerances its global error on these runs is a few 1e-10 to 2e-9: 1e-8.
macro_rules! each_method {
    (|$name:ident, $m:ident, $acc:ident| $body:block) => {{
        {
            let ($name, $m, $acc) = ("DOPRI5", Dopri5::new(tight()), 1e-10);
            $body
        }
        {
            let ($name, $m, $acc) = ("DOP853", Dop853::new(tight()), 1e-10);
            $body
        }
        {
            let ($name, $m, $acc) = ("Vern9", Vern9::new(tight()), 1e-10);
            $body
        }
        {
            let ($name, $m, $acc) = ("Radau5", Radau5::new(tight()), 1e-8);
            $body
        }
    }};
}

/// A block launched at `v0` along a rough floor with a viscous damper `c` to the wall
/// behind it (the block stays ahead of the wall, so the damper's rate is `x'`).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[point(wall, at = [0.0, 0.0])]
#[particle(block, mass = m, at = [x, 0.0])]
#[damper(d, from = wall, to = block, c = c)]
#[friction(along = x, mu = mu, normal = m * g)]
#[init(x = x0, der(x) = v0)]
pub struct ViscousCoulomb {
    pub m: f64,
    pub g: f64,
    pub c: f64,
    pub mu: f64,
    pub x0: f64,
    pub v0: f64,
}

/// `m v' = -c v - mu m g` while sliding: with `b = mu m g / c` and `tau = m / c`,
/// `v = (v0 + b) e^{-t / tau} - b`, zero at `t* = tau ln(1 + v0 / b)`, and
/// `x = x0 + tau (v0 + b)(1 - e^{-t / tau}) - b t`. After the stop nothing loads it.
#[test]
fn viscous_and_coulomb_friction_stop_at_the_closed_form_instant() {
    let p = ViscousCoulomb {
        m: 2.0,
        g: 9.81,
        c: 3.0,
        mu: 0.15,
        x0: 0.5,
        v0: 4.0,
    };
    let (b, tau) = (p.mu * p.m * p.g / p.c, p.m / p.c);
    let t_stop = tau * (1.0 + p.v0 / b).ln();
    let x = |t: f64| p.x0 + tau * (p.v0 + b) * (1.0 - (-t / tau).exp()) - b * t;
    each_method!(|name, method, acc| {
        let run = mbd::hybrid::solve(&method, &p, 0.0, p.initial_state(), 3.0, &[]).unwrap();
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        assert_eq!(run.switches[0].to, [Slip::Stick]);
        assert!((run.switches[0].t - t_stop).abs() < acc, "{name}");
        for t in [0.3, 0.9, t_stop] {
            let y = run.solution.at(t).unwrap();
            assert!(
                (y[0] - x(t)).abs() < acc,
                "{name}: x({t}) off by {:e}",
                y[0] - x(t)
            );
        }
        let (_, y) = run.solution.last();
        assert!((y[0] - x(t_stop)).abs() < acc, "{name}");
        assert_eq!(y[1], 0.0, "{name}");
    });
}

/// A bead in a slot of a rod turned at constant `w` in a horizontal plane (no gravity in
/// it). `r` along the slot, `n` across it, relaxed: `reaction(n)` is the slot's push on
/// the bead, which gives it the Coriolis acceleration, `N = 2 m w r'`.
#[derive(Debug, Mechanism)]
#[coords(r)]
#[relaxed(n)]
#[drive(th = w * t)]
#[particle(bead, mass = m, at = [r * cos(th) - n * sin(th), r * sin(th) + n * cos(th)])]
#[friction(along = r, mu = mu, normal = reaction(n))]
#[init(r = r0, der(r) = v0)]
pub struct Slot {
    pub m: f64,
    pub w: f64,
    pub mu: f64,
    pub r0: f64,
    pub v0: f64,
}

/// Along the slot `m r'' = m w^2 r - mu |N| sign(r')` with `|N| = 2 m w |r'|`, so in either
/// direction `r'' + 2 mu w r' - w^2 r = 0`: `r = A e^{l1 t} + B e^{l2 t}`,
/// `l1,2 = w (-mu +- sqrt(1 + mu^2))`. At rest the normal force, hence the friction bound,
/// is zero while the centrifugal load `m w^2 r` is not: the bead cannot stick, and a bead
/// thrown inward stops at `t* = ln(-l2 B / (l1 A)) / (l1 - l2)` and slides back out on the
/// same curve.
fn slot_reference(p: &Slot) -> (impl Fn(f64) -> f64, f64) {
    let s = (1.0 + p.mu * p.mu).sqrt();
    let (l1, l2) = (p.w * (s - p.mu), p.w * (-s - p.mu));
    let a = (p.v0 - l2 * p.r0) / (l1 - l2);
    let b = p.r0 - a;
    let t_stop = (-l2 * b / (l1 * a)).ln() / (l1 - l2);
    (
        move |t: f64| a * (l1 * t).exp() + b * (l2 * t).exp(),
        t_stop,
    )
}

#[test]
fn a_bead_in_a_turning_slot_cannot_stick_where_its_normal_force_vanishes() {
    for (v0, turns) in [(0.0, false), (-1.2, true)] {
        let p = Slot {
            m: 0.3,
            w: 2.0,
            mu: 0.4,
            r0: 1.0,
            v0,
        };
        let (r, t_stop) = slot_reference(&p);
        // At rest the bead slides out at once, under no friction.
        let at_rest = p
            .acceleration(0.0, &Vector::<1>::new(p.r0), &Vector::<1>::zeros())
            .unwrap();
        assert!((at_rest[0] - p.w * p.w * p.r0).abs() < 1e-14);
        each_method!(|name, method, acc| {
            let run = mbd::hybrid::solve(&method, &p, 0.0, p.initial_state(), 1.5, &[]).unwrap();
            assert!(run.switches.iter().all(|s| s.to != [Slip::Stick]), "{name}");
            if turns {
                assert!(t_stop > 0.0 && r(t_stop) > 0.0);
                assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
                assert!((run.switches[0].t - t_stop).abs() < acc, "{name}");
                assert_eq!(run.switches[0].to, [Slip::Forward], "{name}");
            } else {
                assert!(run.switches.is_empty(), "{name}: {:?}", run.switches);
            }
            for t in [0.2, 0.7, 1.5] {
                let y = run.solution.at(t).unwrap();
                let want = r(t);
                assert!(
                    (y[0] - want).abs() < acc * want,
                    "{name}: r({t}) off by {:e}",
                    y[0] - want
                );
            }
        });
    }
}

/// A block at rest, pushed by a constant `p`, with a normal force that falls linearly in
/// time through zero and grows again on the other side (`|n|` is what bounds friction).
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = p)]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = n0 - c * t)]
pub struct Unloading {
    pub m: f64,
    pub p: f64,
    pub n0: f64,
    pub c: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// Held while `p <= mu_s |n0 - c t|`: breakaway at `t1 = (n0 - p / mu_s) / c`. Then
/// `m v' = p - mu_k |n0 - c t|`: up to `t0 = n0 / c`,
/// `m v = (p - mu_k n0)(t - t1) + mu_k c (t^2 - t1^2) / 2`; after it, with `s = t - t0`,
/// `m v = m v0 + p s - mu_k c s^2 / 2`, zero at `s* = (p + sqrt(p^2 + 2 mu_k c m v0)) /
/// (mu_k c)`, where `mu_s |n| = mu_s c s* > p` holds it for good. The distance is the
/// integral of each.
#[test]
fn a_normal_force_through_zero_releases_and_recaptures_the_block() {
    let p = Unloading {
        m: 1.0,
        p: 2.0,
        n0: 10.0,
        c: 4.0,
        mu_k: 0.4,
        mu_s: 0.5,
    };
    let t1 = (p.n0 - p.p / p.mu_s) / p.c;
    let t0 = p.n0 / p.c;
    let a = p.p - p.mu_k * p.n0;
    let cc = p.mu_k * p.c;
    let x_at_t0 = (a * (t0 - t1).powi(2) / 2.0
        + cc / 2.0 * ((t0.powi(3) - t1.powi(3)) / 3.0 - t1 * t1 * (t0 - t1)))
        / p.m;
    let mv0 = a * (t0 - t1) + cc * (t0 * t0 - t1 * t1) / 2.0;
    let s_star = (p.p + (p.p * p.p + 2.0 * cc * mv0).sqrt()) / cc;
    let t_stop = t0 + s_star;
    let x_stop =
        x_at_t0 + (mv0 * s_star + p.p * s_star.powi(2) / 2.0 - cc * s_star.powi(3) / 6.0) / p.m;
    // The numbers by hand: t1 = 1.5, t0 = 2.5, m v0 = 1.2, s* = 3, x = 7 / 15 + 5.4.
    assert!((t1 - 1.5).abs() < 1e-15 && (s_star - 3.0).abs() < 1e-14);
    assert!((x_stop - (7.0 / 15.0 + 5.4)).abs() < 1e-13);
    each_method!(|name, method, acc| {
        let y0 = Vector::<2>::zeros();
        let run = mbd::hybrid::solve(&method, &p, 0.0, y0, 8.0, &[]).unwrap();
        let seen: Vec<_> = run.switches.iter().map(|s| (s.to, s.t)).collect();
        assert_eq!(run.switches.len(), 2, "{name}: {seen:?}");
        assert_eq!(run.switches[0].to, [Slip::Forward], "{name}");
        assert!((run.switches[0].t - t1).abs() < 1e-10, "{name}: {seen:?}");
        assert_eq!(run.switches[1].to, [Slip::Stick], "{name}");
        assert!((run.switches[1].t - t_stop).abs() < acc, "{name}: {seen:?}");
        let y = run.solution.at(t0).unwrap();
        assert!((y[0] - x_at_t0).abs() < acc, "{name}: x(t0) = {}", y[0]);
        assert!((y[1] - mv0 / p.m).abs() < acc, "{name}: v(t0) = {}", y[1]);
        let (_, y) = run.solution.last();
        // The normal force's zero at t0 is a kink in mu_k |n|: the driver locates it and
        // restarts there (`Hybrid::kink`), so no step crosses it (before, DOPRI5 at rtol
        // 1e-12 came to rest 1.8e-10 off).
        assert!(
            (y[0] - x_stop).abs() < acc,
            "{name}: rests off by {:e}",
            y[0] - x_stop
        );
        assert_eq!(y[1], 0.0, "{name}");
    });
}

/// A block on a platform whose position is driven, `xp = c t^3 / 6` (acceleration `c t`);
/// `s` is the block's place on the platform, so its sliding velocity is `s'`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[drive(xp = c * t * t * t / 6.0)]
#[particle(block, mass = m, at = [xp + s, 0.0])]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
pub struct Platform {
    pub m: f64,
    pub g: f64,
    pub c: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// Riding along, the block needs the force `m c t`: it holds to `t1 = mu_s g / c`. Then it
/// slips back (`s' < 0`) with `s'' = -c t + mu_k g`:
/// `s' = -c (t^2 - t1^2) / 2 + mu_k g (t - t1)`,
/// `s = -c ((t^3 - t1^3) / 3 - t1^2 (t - t1)) / 2 + mu_k g (t - t1)^2 / 2`; `s'` stays
/// negative (it would vanish again at `(2 mu_k - mu_s) g / c < t1`).
#[test]
fn a_block_on_an_accelerating_platform_slips_at_the_static_limit() {
    let p = Platform {
        m: 3.0,
        g: 9.81,
        c: 2.5,
        mu_k: 0.25,
        mu_s: 0.35,
    };
    let t1 = p.mu_s * p.g / p.c;
    let s = |t: f64| {
        -p.c * ((t.powi(3) - t1.powi(3)) / 3.0 - t1 * t1 * (t - t1)) / 2.0
            + p.mu_k * p.g * (t - t1).powi(2) / 2.0
    };
    each_method!(|name, method, acc| {
        let run = mbd::hybrid::solve(&method, &p, 0.0, Vector::<2>::zeros(), 3.0, &[]).unwrap();
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        assert_eq!(run.switches[0].to, [Slip::Backward]);
        assert!((run.switches[0].t - t1).abs() < 1e-10, "{name}");
        let held = run.solution.at(0.9 * t1).unwrap();
        assert_eq!((held[0], held[1]), (0.0, 0.0), "{name}: crept while held");
        for t in [1.5, 2.2, 3.0] {
            let y = run.solution.at(t).unwrap();
            assert!(
                (y[0] - s(t)).abs() < acc,
                "{name}: s({t}) = {} vs {}",
                y[0],
                s(t)
            );
        }
    });
}

/// A block on an incline of angle `a` (`s` down the slope, `n` across it, relaxed), with
/// `mu_k < mu_s`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[relaxed(n)]
#[particle(block, mass = m, at = [s * cos(a) + n * sin(a), -s * sin(a) + n * cos(a)])]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = reaction(n))]
pub struct Slope {
    pub m: f64,
    pub g: f64,
    pub a: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// From rest the block holds while `tan a <= mu_s` (the load `m g sin a` within
/// `mu_s m g cos a`), even above the kinetic angle `atan(mu_k)`; a hair above the static
/// angle it slides with the full kinetic acceleration `g (sin a - mu_k cos a)`, not a
/// small one: `s = g (sin a - mu_k cos a) t^2 / 2`.
#[test]
fn a_block_at_rest_holds_to_the_static_angle_and_jumps_past_it() {
    let (mu_k, mu_s) = (0.3, 0.5);
    let base = Slope {
        m: 4.0,
        g: 9.81,
        a: 0.0,
        mu_k,
        mu_s,
    };
    let (kinetic, fixed) = (mu_k.atan(), mu_s.atan());
    for (a, holds) in [
        (0.5 * kinetic, true),
        (kinetic, true),
        (0.5 * (kinetic + fixed), true),
        (fixed - 1e-9, true),
        (fixed + 1e-9, false),
        (fixed + 0.1, false),
    ] {
        let p = Slope { a, ..base };
        let down = p.g * (a.sin() - mu_k * a.cos());
        each_method!(|name, method, _acc| {
            let run = mbd::hybrid::solve(&method, &p, 0.0, Vector::<2>::zeros(), 2.0, &[]).unwrap();
            let (_, y) = run.solution.last();
            if holds {
                assert_eq!((y[0], y[1]), (0.0, 0.0), "{name} a = {a}");
                assert_eq!(run.mode, [Slip::Stick], "{name} a = {a}");
            } else {
                assert_eq!(run.mode, [Slip::Forward], "{name} a = {a}");
                assert!(
                    (y[0] - down * 2.0).abs() < 1e-11,
                    "{name} a = {a}: {}",
                    y[0]
                );
                assert!(
                    (y[1] - down * 2.0).abs() < 1e-11,
                    "{name} a = {a}: {}",
                    y[1]
                );
            }
        });
    }
}

/// The classical stick-slip oscillator: a mass on a spring `k` to a wall, on a belt moving
/// at `v`; `s` is the mass's place on the belt (`x = v t + s`), friction along `s` with
/// normal force `m g`.
#[derive(Debug, Mechanism)]
#[coords(s)]
#[drive(b = v * t)]
#[particle(mass, mass = m, at = [b + s, 0.0])]
#[point(wall, at = [0.0, 0.0])]
#[spring(spring, from = wall, to = mass, k = k)]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
pub struct Belt {
    pub m: f64,
    pub k: f64,
    pub g: f64,
    pub v: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// The limit cycle by hand (`w^2 = k / m`, `x_s = mu_s g / w^2`, `x_k = mu_k g / w^2`). Stuck,
/// the mass rides the belt (`x' = v`) until the spring's pull `k x` reaches `mu_s m g` at
/// `x_s`. Slipping back (`s' < 0`), kinetic friction pushes it forward:
/// `x'' = -w^2 (x - x_k)`, a circle in `(x - x_k, x' / w)` through `(D, v / w)`,
/// `D = x_s - x_k`, turned clockwise at rate `w`; slipping ends where `x' = v` again, at the
/// mirror point `x_a = 2 x_k - x_s`, after the arc `2 pi - 2 atan(w D / v)`, i.e.
/// `T_slip = (pi + 2 atan(v / (w D))) / w`. There `k |x_a| < mu_s m g`: it sticks, and rides
/// `2 D` back to `x_s` in `T_stick = 2 D / v`. Started stuck at `x_a`, breakaways fall at
/// `T_stick + n T` and sticks at `(n + 1) T`, `T = T_stick + T_slip`.
fn belt_cycle(p: &Belt) -> (f64, f64, f64) {
    let w = (p.k / p.m).sqrt();
    let (x_s, x_k) = (p.mu_s * p.g / (w * w), p.mu_k * p.g / (w * w));
    let d = x_s - x_k;
    let t_slip = (PI + 2.0 * (p.v / (w * d)).atan()) / w;
    (2.0 * x_k - x_s, 2.0 * d / p.v, t_slip)
}

/// Ten thousand switches (5000 periods): every switch in its mode, every period of the
/// closed-form length. Each period restarts from the same stuck state, so errors do not
/// compound; but the belt coordinate grows (`s = x - v t`, to 8500 m here) and the
/// tolerance is relative, `rtol |s|` per step, so a period's error may grow as `rtol t`
/// (in seconds: the position error over `v`, times `v`): each period is held to
/// `100 rtol (1 + t)` (about 25 steps a period), and the sum of them bounds the drift.
#[test]
fn a_belt_driven_stick_slip_oscillator_keeps_its_limit_cycle_over_ten_thousand_switches() {
    let p = Belt {
        m: 1.0,
        k: 4.0,
        g: 9.81,
        v: 0.5,
        mu_k: 0.3,
        mu_s: 0.4,
    };
    let (x_a, t_stick, t_slip) = belt_cycle(&p);
    let period = t_stick + t_slip;
    let periods = 5000;
    let t1 = period * periods as f64 + 0.5 * t_stick;
    let opts = Options {
        max_steps: 10_000_000,
        dense: false,
        ..tight()
    };
    let rtol = opts.rtol;
    let method = Dop853::new(opts);
    let run = mbd::hybrid::solve(&method, &p, 0.0, Vector::<2>::new(x_a, 0.0), t1, &[]).unwrap();
    assert_eq!(run.switches.len(), 2 * periods);
    let (mut drift_bound, mut last_stick) = (0.0, 0.0);
    for (i, sw) in run.switches.iter().enumerate() {
        let n = (i / 2) as f64;
        let (want, mode) = if i % 2 == 0 {
            (t_stick + n * period, [Slip::Backward])
        } else {
            ((n + 1.0) * period, [Slip::Stick])
        };
        assert_eq!(sw.to, mode, "switch {i}");
        if i % 2 == 1 {
            let bound = 100.0 * rtol * (1.0 + sw.t);
            let err = (sw.t - last_stick - period).abs();
            assert!(err <= bound, "period {n}: off by {err:e} (bound {bound:e})");
            drift_bound += bound;
            last_stick = sw.t;
        }
        assert!((sw.t - want).abs() <= drift_bound + 1e-10, "switch {i}");
    }
    let (_, y) = run.solution.last();
    assert_eq!(run.mode, [Slip::Stick]);
    // Riding the belt since the last stick, which was at `x_a`.
    let x = y[0] + p.v * t1;
    let want = x_a + p.v * (t1 - last_stick);
    assert!(
        (x - want).abs() < 100.0 * rtol * p.v * t1,
        "at {x} vs {want}"
    );
}

/// Two blocks on one rough floor joined by a rigid bar of length `d` (a constraint,
/// augmented form), each with its own contact: the contacts' coordinates are tied, so
/// both cannot be "stuck" as independent rows (with the constraint that is three equations
/// for two accelerations; the split of the holding force between them is indeterminate,
/// the motion is not). Pushed by `p` on the first, the pair moves as one body of mass
/// `M = m1 + m2`: at rest it holds while `p <= mu_s M g`; else it slides at
/// `(p - mu_k M g) / M`. Launched at `v0` unpushed, it stops after `v0 / (mu_k g)` and stays.
#[derive(Debug, Mechanism)]
#[mechanism(augmented)]
#[gravity(0.0, -g)]
#[coords(x1, x2)]
#[constraint(x2 - x1 == d)]
#[particle(b1, mass = m1, at = [x1, 0.0])]
#[particle(b2, mass = m2, at = [x2, 0.0])]
#[generalized_force(push, along = x1, value = p)]
#[friction(along = x1, mu_k = mu_k, mu_s = mu_s, normal = m1 * g)]
#[friction(along = x2, mu_k = mu_k, mu_s = mu_s, normal = m2 * g)]
pub struct Linked {
    pub m1: f64,
    pub m2: f64,
    pub g: f64,
    pub d: f64,
    pub p: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

const LINKED: Linked = Linked {
    m1: 1.0,
    m2: 3.0,
    g: 9.81,
    d: 0.5,
    p: 0.0,
    mu_k: 0.2,
    mu_s: 0.3,
};

#[test]
fn two_contacts_tied_by_a_bar_move_as_one_block() {
    let total = LINKED.m1 + LINKED.m2;
    let q = Vector::<2>::new(0.0, LINKED.d);
    let rest = Vector::<2>::zeros();
    for (p, holds) in [
        (0.0, true),
        (5.0, true),
        (11.0, true),
        (11.9, false),
        (20.0, false),
    ] {
        let m = Linked { p, ..LINKED };
        let qdd = m.acceleration(0.0, &q, &rest).unwrap();
        let want = if holds {
            0.0
        } else {
            (p - m.mu_k * total * m.g) / total
        };
        assert_eq!(p <= m.mu_s * total * m.g, holds);
        for (i, a) in qdd.iter().enumerate() {
            assert!(
                (a - want).abs() < 1e-12,
                "p = {p}: qdd[{i}] = {a} vs {want}"
            );
        }
        each_method!(|name, method, acc| {
            let y0 = Vector::<4>::new(0.0, m.d, 0.0, 0.0);
            let run = mbd::hybrid::solve(&method, &m, 0.0, y0, 1.0, &[]).unwrap();
            let (_, y) = run.solution.last();
            assert!((y[0] - want / 2.0).abs() < acc, "{name} p = {p}: {}", y[0]);
            assert!((y[1] - y[0] - m.d).abs() < acc, "{name} p = {p}");
        });
    }
    // Launched, it stops at v0 / (mu_k g), at v0^2 / (2 mu_k g), and stays.
    let v0 = 1.5;
    let t_stop = v0 / (LINKED.mu_k * LINKED.g);
    each_method!(|name, method, acc| {
        let y0 = Vector::<4>::new(0.0, LINKED.d, v0, v0);
        let run = mbd::hybrid::solve(&method, &LINKED, 0.0, y0, 1.5, &[]).unwrap();
        let stuck = run.switches.iter().find(|s| s.to == [Slip::Stick; 2]);
        let stuck = stuck.unwrap_or_else(|| panic!("{name}: {:?}", run.switches));
        assert!((stuck.t - t_stop).abs() < acc, "{name}: {}", stuck.t);
        let (_, y) = run.solution.last();
        assert!((y[0] - v0 * t_stop / 2.0).abs() < acc, "{name}: {}", y[0]);
        assert_eq!((y[2], y[3]), (0.0, 0.0), "{name}");
    });
}

/// A mass on a spring on a rough floor with a tiny coefficient (`mu = 2e-5`): hundreds of
/// half-swings before it sticks.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[point(wall, at = [0.0, 0.0])]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(s, from = wall, to = block, k = k)]
#[friction(along = x, mu = mu, normal = m * g)]
#[init(x = x0)]
pub struct Slippery {
    pub m: f64,
    pub k: f64,
    pub g: f64,
    pub mu: f64,
    pub x0: f64,
}

/// Released at rest from `x0`, each half-swing is a half cosine of duration `pi / w`
/// (`w^2 = k / m`) about the shifted centre `c = sign(x_j) x_f`, `x_f = mu g / w^2`, to the
/// turning point `2 c - x_j`, until one lies within `x_f` (the spring then pulls less than
/// `mu m g`: it sticks). Energy: friction takes `mu m g` per metre slid, so at any time
/// `m x'^2 / 2 + k x^2 / 2 = k x0^2 / 2 - mu m g (distance slid)`.
#[test]
fn a_tiny_coefficient_damps_hundreds_of_swings_by_the_friction_work() {
    let p = Slippery {
        m: 1.0,
        k: 4.0,
        g: 9.81,
        mu: 2e-5,
        x0: 0.01,
    };
    let w = (p.k / p.m).sqrt();
    let x_f = p.mu * p.g / (w * w);
    let mut turns = vec![p.x0];
    while turns.last().unwrap().abs() > x_f {
        let x = *turns.last().unwrap();
        turns.push(2.0 * x.signum() * x_f - x);
    }
    let n = turns.len() - 1;
    assert!(n > 100, "{n} half-swings");
    let half = PI / w;
    let t1 = half * (n as f64 + 1.5);
    let energy = |y: &Vector<2>| 0.5 * p.m * y[1] * y[1] + 0.5 * p.k * y[0] * y[0];
    each_method!(|name, method, acc| {
        let run = mbd::hybrid::solve(&method, &p, 0.0, p.initial_state(), t1, &[]).unwrap();
        assert_eq!(run.switches.len(), n, "{name}");
        for (j, sw) in run.switches.iter().enumerate() {
            let want = half * (j + 1) as f64;
            // Each half-swing adds at most the method's error: they accumulate.
            let bound = acc * (j + 1) as f64;
            assert!((sw.t - want).abs() < bound, "{name}: turn {j} at {}", sw.t);
        }
        assert_eq!(run.switches[n - 1].to, [Slip::Stick], "{name}");
        let (_, y) = run.solution.last();
        assert!((y[0] - turns[n]).abs() < acc, "{name}: rests at {}", y[0]);
        assert_eq!(y[1], 0.0, "{name}");
        // Energy against the friction work, mid-swing: the distance slid is the sum of the
        // completed half-swings and the part of the current one.
        for j in [0, n / 2, n - 1] {
            let t = half * (j as f64 + 0.37);
            let y = run.solution.at(t).unwrap();
            let slid: f64 = turns
                .windows(2)
                .take(j)
                .map(|s| (s[1] - s[0]).abs())
                .sum::<f64>()
                + (y[0] - turns[j]).abs();
            let want = 0.5 * p.k * p.x0 * p.x0 - p.mu * p.m * p.g * slid;
            assert!(
                (energy(&y) - want).abs() < acc * p.k * p.x0,
                "{name}: energy at swing {j}: {} vs {want}",
                energy(&y)
            );
        }
    });
}

/// A ball (mass `m`, radius `r`, inertia `2 m r^2 / 5`) on a rough floor. `th` is its
/// rolling angle (clockwise) and `s` the slip of its contact point, so its centre is at
/// `x = s + r th` and the contact slides at `s'`: friction acts along `s` only (the contact
/// force does work on the slip alone).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s, th)]
#[rigid(ball, mass = m, inertia = 0.4 * m * r * r, at = [s + r * th, r], angle = -th)]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g)]
#[init(der(s) = v0)]
pub struct Bowling {
    pub m: f64,
    pub r: f64,
    pub g: f64,
    pub mu_k: f64,
    pub mu_s: f64,
    pub v0: f64,
}

/// Thrown without spin at `v0`: sliding, `x'' = -mu_k g` and `I th'' = mu_k m g r`, so the
/// slip `s' = x' - r th'` falls at `mu_k g (1 + m r^2 / I) = 7 mu_k g / 2`: it rolls from
/// `t* = 2 v0 / (7 mu_k g)` at `5 v0 / 7`, at `x* = v0 t* - mu_k g t*^2 / 2`, and rolling
/// needs no friction, so it rolls on: `x = x* + 5 v0 (t - t*) / 7`.
#[test]
fn a_bowled_ball_starts_rolling_at_the_closed_form_instant() {
    let p = Bowling {
        m: 7.0,
        r: 0.11,
        g: 9.81,
        mu_k: 0.2,
        mu_s: 0.25,
        v0: 8.0,
    };
    let t_roll = 2.0 * p.v0 / (7.0 * p.mu_k * p.g);
    let x_roll = p.v0 * t_roll - p.mu_k * p.g * t_roll * t_roll / 2.0;
    let t1 = 2.0;
    each_method!(|name, method, acc| {
        let run = mbd::hybrid::solve(&method, &p, 0.0, p.initial_state(), t1, &[]).unwrap();
        assert_eq!(run.switches.len(), 1, "{name}: {:?}", run.switches);
        assert_eq!(run.switches[0].to, [Slip::Stick]);
        assert!((run.switches[0].t - t_roll).abs() < acc, "{name}");
        let (_, y) = run.solution.last();
        let x = y[0] + p.r * y[1];
        let v = y[2] + p.r * y[3];
        assert_eq!(y[2], 0.0, "{name}: slipping at the end");
        assert!((v - 5.0 * p.v0 / 7.0).abs() < acc, "{name}: v = {v}");
        let want = x_roll + 5.0 * p.v0 / 7.0 * (t1 - t_roll);
        assert!((x - want).abs() < acc, "{name}: x = {x} vs {want}");
    });
}

/// The ball at rest on an incline of angle `a` (gravity turned with it): rolling needs the
/// friction `m g sin a * I / (I + m r^2) = 2 m g sin a / 7`, so it rolls without slipping
/// while `tan a <= 7 mu_s / 2`, at `x'' = 5 g sin a / 7`; beyond, it slips with
/// `x'' = g (sin a - mu_k cos a)`, `r th'' = 5 mu_k g cos a / 2`.
#[derive(Debug, Mechanism)]
#[gravity(g * sin(a), -g * cos(a))]
#[coords(s, th)]
#[rigid(ball, mass = m, inertia = 0.4 * m * r * r, at = [s + r * th, r], angle = -th)]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = m * g * cos(a))]
pub struct RollingDown {
    pub m: f64,
    pub r: f64,
    pub g: f64,
    pub a: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

#[test]
fn a_ball_on_an_incline_rolls_below_its_angle_and_slips_above() {
    let base = RollingDown {
        m: 2.0,
        r: 0.3,
        g: 9.81,
        a: 0.0,
        mu_k: 0.1,
        mu_s: 0.12,
    };
    let limit = (3.5 * base.mu_s).atan();
    let rest = Vector::<2>::zeros();
    for a in [0.2, limit - 1e-6, limit + 1e-6, 0.9] {
        let p = RollingDown { a, ..base };
        let qdd = p.acceleration(0.0, &rest, &rest).unwrap();
        let (x_dd, th_dd) = (qdd[0] + p.r * qdd[1], qdd[1]);
        if a < limit {
            let want = 5.0 * p.g * a.sin() / 7.0;
            assert_eq!(qdd[0], 0.0, "a = {a}: slips");
            assert!((x_dd - want).abs() < 1e-13, "a = {a}: {x_dd} vs {want}");
        } else {
            let want = p.g * (a.sin() - p.mu_k * a.cos());
            let spin = 2.5 * p.mu_k * p.g * a.cos() / p.r;
            assert!((x_dd - want).abs() < 1e-13, "a = {a}: {x_dd} vs {want}");
            assert!((th_dd - spin).abs() < 1e-12, "a = {a}: {th_dd} vs {spin}");
        }
    }
}

/// Three blocks in a train joined by two rigid bars (two constraints, augmented form),
/// each on the floor with its own coefficients: the holding loads have two free
/// combinations. Pushed at the first, the train holds while the push is within the sum of
/// the three static bounds, `P_s = sum mu_s_i m_i g`, and otherwise slides at
/// `(p - sum mu_k_i m_i g) / (m1 + m2 + m3)`.
#[derive(Debug, Mechanism)]
#[mechanism(augmented)]
#[gravity(0.0, -g)]
#[coords(x1, x2, x3)]
#[constraint(x2 - x1 == d)]
#[constraint(x3 - x2 == d)]
#[particle(b1, mass = m1, at = [x1, 0.0])]
#[particle(b2, mass = m2, at = [x2, 0.0])]
#[particle(b3, mass = m3, at = [x3, 0.0])]
#[generalized_force(push, along = x1, value = p)]
#[friction(along = x1, mu_k = k1, mu_s = s1, normal = m1 * g)]
#[friction(along = x2, mu_k = k2, mu_s = s2, normal = m2 * g)]
#[friction(along = x3, mu_k = k3, mu_s = s3, normal = m3 * g)]
pub struct Train {
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub g: f64,
    pub d: f64,
    pub p: f64,
    pub k1: f64,
    pub s1: f64,
    pub k2: f64,
    pub s2: f64,
    pub k3: f64,
    pub s3: f64,
}

#[test]
fn a_train_of_three_tied_blocks_holds_to_the_sum_of_its_static_bounds() {
    let base = Train {
        m1: 1.0,
        m2: 2.0,
        m3: 0.5,
        g: 9.81,
        d: 0.4,
        p: 0.0,
        k1: 0.1,
        s1: 0.5,
        k2: 0.2,
        s2: 0.25,
        k3: 0.3,
        s3: 0.6,
    };
    let total = base.m1 + base.m2 + base.m3;
    let hold = (base.s1 * base.m1 + base.s2 * base.m2 + base.s3 * base.m3) * base.g;
    let kinetic = (base.k1 * base.m1 + base.k2 * base.m2 + base.k3 * base.m3) * base.g;
    let q = Vector::<3>::new(0.0, base.d, 2.0 * base.d);
    let rest = Vector::<3>::zeros();
    for (p, holds) in [
        (3.0, true),
        (0.99 * hold, true),
        (1.01 * hold, false),
        (-0.99 * hold, true),
    ] {
        let m = Train { p, ..base };
        let qdd = m.acceleration(0.0, &q, &rest).unwrap();
        let want = if holds { 0.0 } else { (p - kinetic) / total };
        for (i, a) in qdd.iter().enumerate() {
            assert!(
                (a - want).abs() < 1e-12,
                "p = {p}: qdd[{i}] = {a} vs {want}"
            );
        }
    }
    // Launched unpushed at v0, it decelerates at `sum mu_k_i m_i g / M` and stops together.
    let v0 = 1.2;
    let t_stop = v0 * total / kinetic;
    each_method!(|name, method, acc| {
        let y0 = Vector::<6>::new(0.0, base.d, 2.0 * base.d, v0, v0, v0);
        let run = mbd::hybrid::solve(&method, &base, 0.0, y0, 1.0, &[]).unwrap();
        assert_eq!(run.mode, [Slip::Stick; 3], "{name}: {:?}", run.switches);
        let stuck = run.switches.last().unwrap();
        assert!((stuck.t - t_stop).abs() < acc, "{name}: {}", stuck.t);
        let (_, y) = run.solution.last();
        assert_eq!((y[3], y[4], y[5]), (0.0, 0.0, 0.0), "{name}");
        assert!((y[0] - v0 * t_stop / 2.0).abs() < acc, "{name}: {}", y[0]);
    });
}

/// A double pendulum (point masses on massless links, a joint tree in relative angles)
/// with a friction torque bound at each joint (`mu` the torque, normal 1).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(b1, joint = revolute(q1), com = [0.0, -l1], mass = m1)]
#[body(b2, parent = b1, joint = revolute(q2), at = [0.0, -l1], com = [0.0, -l2], mass = m2)]
#[friction(along = q1, mu = t1, normal = 1.0)]
#[friction(along = q2, mu = t2, normal = 1.0)]
pub struct StiffJoints {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
    pub t1: f64,
    pub t2: f64,
}

/// At rest, by hand: `M = [[m1 l1^2 + m2 (l1^2 + l2^2 + 2 l1 l2 cos q2), m2 (l2^2 + l1 l2
/// cos q2)], [.., m2 l2^2]]`, gravity's torques `f2 = -m2 g l2 sin(q1 + q2)`,
/// `f1 = -g (m1 + m2) l1 sin q1 + f2`. Every combination of stick and slip is solved
/// (stuck: `q_i'' = 0`, its holding torque the residual; sliding in `d`: torque `-d t_i`) and
/// the strictly consistent ones kept (a holding torque within its bound, a slide
/// accelerating its way); the configurations below have exactly one.
fn stiff_joints_at_rest(p: &StiffJoints, q1: f64, q2: f64) -> [f64; 2] {
    let c = q2.cos();
    let m11 = p.m1 * p.l1 * p.l1 + p.m2 * (p.l1 * p.l1 + p.l2 * p.l2 + 2.0 * p.l1 * p.l2 * c);
    let m12 = p.m2 * (p.l2 * p.l2 + p.l1 * p.l2 * c);
    let m22 = p.m2 * p.l2 * p.l2;
    let f2 = -p.m2 * p.g * p.l2 * (q1 + q2).sin();
    let f1 = -(p.m1 + p.m2) * p.g * p.l1 * q1.sin() + f2;
    let mut found = Vec::new();
    for d1 in [0.0, 1.0, -1.0] {
        for d2 in [0.0, 1.0, -1.0] {
            let (g1, g2) = (f1 - d1 * p.t1, f2 - d2 * p.t2);
            let qdd = match (d1 == 0.0, d2 == 0.0) {
                (true, true) => [0.0, 0.0],
                (true, false) => [0.0, g2 / m22],
                (false, true) => [g1 / m11, 0.0],
                (false, false) => {
                    let det = m11 * m22 - m12 * m12;
                    [(m22 * g1 - m12 * g2) / det, (m11 * g2 - m12 * g1) / det]
                }
            };
            let h1 = g1 - m11 * qdd[0] - m12 * qdd[1];
            let h2 = g2 - m12 * qdd[0] - m22 * qdd[1];
            let ok1 = if d1 == 0.0 {
                h1.abs() < p.t1
            } else {
                d1 * qdd[0] > 0.0
            };
            let ok2 = if d2 == 0.0 {
                h2.abs() < p.t2
            } else {
                d2 * qdd[1] > 0.0
            };
            if ok1 && ok2 {
                found.push(qdd);
            }
        }
    }
    assert_eq!(found.len(), 1, "({q1}, {q2}): {found:?}");
    found[0]
}

#[test]
fn joint_friction_of_a_double_pendulum_at_rest_takes_the_consistent_modes() {
    let p = StiffJoints {
        m1: 1.0,
        m2: 0.6,
        l1: 0.5,
        l2: 0.4,
        g: 9.81,
        t1: 1.5,
        t2: 0.4,
    };
    let rest = Vector::<2>::zeros();
    let mut kinds = std::collections::BTreeSet::new();
    for (q1, q2) in [
        (0.05, 0.02),
        (0.2, 1.0),
        (0.6, -0.6),
        (1.2, 0.9),
        (-0.3, -0.5),
    ] {
        let want = stiff_joints_at_rest(&p, q1, q2);
        kinds.insert((want[0] != 0.0, want[1] != 0.0));
        let got = p
            .acceleration(0.0, &Vector::<2>::new(q1, q2), &rest)
            .unwrap();
        for i in 0..2 {
            assert!(
                (got[i] - want[i]).abs() < 1e-12,
                "({q1}, {q2}): qdd = {got} vs {want:?}"
            );
        }
    }
    // Both held, one slipping, the other slipping, both slipping: all four seen.
    assert_eq!(kinds.len(), 4, "{kinds:?}");
}

/// A parallelogram four-bar hanging from pivots `(0, 0)` and `(d, 0)`: massless cranks of
/// length `r` at `phi`, `psi` from the downward vertical, a coupler of length `d` with its
/// mass `m` lumped half at each pin; the loop closes by one distance constraint (augmented
/// form). Pin friction at both ground pivots, torque bounds `t1`, `t2` (normal 1): two
/// contacts on a one-degree-of-freedom loop, tied through a nonlinear constraint.
#[derive(Debug, Mechanism)]
#[mechanism(augmented)]
#[gravity(0.0, -g)]
#[coords(phi, psi)]
#[constraint((d + r * sin(psi) - r * sin(phi)) * (d + r * sin(psi) - r * sin(phi))
    + (r * cos(phi) - r * cos(psi)) * (r * cos(phi) - r * cos(psi)) == d * d)]
#[particle(pin_a, mass = 0.5 * m, at = [r * sin(phi), -r * cos(phi)])]
#[particle(pin_b, mass = 0.5 * m, at = [d + r * sin(psi), -r * cos(psi)])]
#[friction(along = phi, mu = t1, normal = 1.0)]
#[friction(along = psi, mu = t2, normal = 1.0)]
pub struct RoughParallelogram {
    pub m: f64,
    pub r: f64,
    pub d: f64,
    pub g: f64,
    pub t1: f64,
    pub t2: f64,
}

/// On the parallelogram branch `psi = phi`: `T = m r^2 phi'^2 / 2`, `V = -m g r cos phi`,
/// and the two pins turn together, so the friction torques add: at rest at `phi0` it holds
/// while `m g r |sin phi0| <= t1 + t2` (some split of the load holds), and otherwise falls
/// back with `m r^2 phi'' = -m g r sin phi0 + (t1 + t2) sign(phi0)`, both cranks alike.
#[test]
fn a_parallelogram_with_two_rough_pivots_holds_by_their_sum() {
    let base = RoughParallelogram {
        m: 2.0,
        r: 0.5,
        d: 1.5,
        g: 9.81,
        t1: 1.0,
        t2: 2.0,
    };
    let limit = ((base.t1 + base.t2) / (base.m * base.g * base.r)).asin();
    let rest = Vector::<2>::zeros();
    for phi0 in [0.1, 0.9 * limit, -0.9 * limit, 1.1 * limit, -1.2 * limit] {
        let q = Vector::<2>::new(phi0, phi0);
        let qdd = base.acceleration(0.0, &q, &rest).unwrap();
        let want = if phi0.abs() <= limit {
            0.0
        } else {
            (-base.m * base.g * base.r * phi0.sin() + (base.t1 + base.t2) * phi0.signum())
                / (base.m * base.r * base.r)
        };
        for i in 0..2 {
            assert!(
                (qdd[i] - want).abs() < 1e-11 * want.abs().max(1.0),
                "phi0 = {phi0}: qdd = {qdd} vs {want}"
            );
        }
    }
    // Either pivot alone could not hold 0.9 of the limit (each bound is below the load).
    let load = base.m * base.g * base.r * (0.9 * limit).sin();
    assert!(load > base.t1 && load > base.t2);
}
