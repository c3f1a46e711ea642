//! Coulomb friction whose normal force is a reaction, and a terminal event at rest.

use approx::assert_relative_eq;
use mbd::Slip;
use mbd::integrate::{Dopri5, Gauss, GeneralizedAlpha, Integrator, Radau5, Rk4};
use mbd::nalgebra;
use mbd::prelude::*;

/// A block sliding down a slope of angle `slope`; `s` along the slope (downhill positive),
/// `n` normal to it, relaxed so that `reaction(n)` is the normal force.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[relaxed(n)]
#[particle(block, mass = m, at = [s * cos(slope) + n * sin(slope), -s * sin(slope) + n * cos(slope)])]
#[friction(along = s, mu = mu, normal = reaction(n))]
#[init(s = 0.0, der(s) = v0)]
#[output(normal = reaction(n))]
#[event(stops = der(s), falling, terminal)]
pub struct Slope {
    pub m: f64,
    pub g: f64,
    pub slope: f64,
    pub mu: f64,
    pub v0: f64,
}

#[test]
fn block_stops_where_constant_deceleration_says() {
    let b = Slope {
        m: 50.0,
        g: 9.81,
        slope: 15f64.to_radians(),
        mu: 0.4,
        v0: 7.0,
    };
    // Sliding: a = g (sin th - mu cos th) < 0; stops at t = v0/|a|, s = v0^2 / (2 |a|).
    let a = 9.81 * (b.slope.sin() - 0.4 * b.slope.cos());
    let (t_stop, s_stop) = (-7.0 / a, 49.0 / (-2.0 * a));
    let y0 = b.initial_state();
    let normal = b.outputs(0.0, &y0).unwrap().normal;
    assert_relative_eq!(normal, 50.0 * 9.81 * b.slope.cos(), max_relative = 1e-14);
    let events = b.events();
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    // The sliding view keeps the friction against downhill motion through the stop, so the
    // stop is an event on a smooth solution, for the implicit and the explicit method alike.
    let sliding = b.sliding([1.0]);
    let radau = Radau5::new(opts.clone())
        .solve(&sliding, 0.0, y0, 20.0, &events)
        .unwrap();
    let dopri = Dopri5::new(opts)
        .solve(&sliding, 0.0, y0, 20.0, &events)
        .unwrap();
    for sol in [&radau, &dopri] {
        assert_eq!(sol.stopped_by, Some(0));
        assert_relative_eq!(sol.events[0].t, t_stop, max_relative = 1e-11);
        assert_relative_eq!(sol.events[0].y[0], s_stop, max_relative = 1e-11);
    }
    let hit = &radau.events[0];
    // At rest the static friction holds it: tan(15 deg) < 0.4.
    assert!(b.s_sticks(hit.t, &hit.y).unwrap());
    // On a 30 degree slope it would not: tan(30 deg) > 0.4.
    let steep = Slope {
        slope: 30f64.to_radians(),
        ..b
    };
    assert!(
        !steep
            .s_sticks(0.0, &nalgebra::Vector2::new(0.0, 0.0))
            .unwrap()
    );
}

/// A block on a level floor pushed along it by a constant `push`: the normal force is
/// `m g`, so it stays put while `|push| <= mu_s m g` and otherwise accelerates at
/// `(push - mu_k m g sign(push)) / m`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[relaxed(n)]
#[particle(block, mass = m, at = [s, n])]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = reaction(n))]
#[generalized_force(push, along = s, value = push)]
pub struct Floor {
    pub m: f64,
    pub g: f64,
    pub mu_k: f64,
    pub mu_s: f64,
    pub push: f64,
}

const FLOOR: Floor = Floor {
    m: 2.0,
    g: 9.81,
    mu_k: 0.4,
    mu_s: 0.5,
    push: 0.0,
};

#[test]
fn at_rest_the_load_decides_not_the_sign_of_zero() {
    let q = nalgebra::Vector1::new(0.0);
    for zero in [0.0, -0.0] {
        let qd = nalgebra::Vector1::new(zero);
        // Unloaded: zero acceleration (the sign bit of the zero velocity plays no part).
        assert_eq!(FLOOR.acceleration(0.0, &q, &qd).unwrap()[0], 0.0);
        // Pushed within the static bound mu_s m g = 9.81 N: still zero.
        for push in [3.0, -9.0, 9.8, -9.8] {
            let f = Floor { push, ..FLOOR };
            assert_eq!(f.acceleration(0.0, &q, &qd).unwrap()[0], 0.0, "push {push}");
            // M qdd = f holds with the holding force in `forces`.
            assert_eq!(f.forces(0.0, &q, &qd).unwrap()[0], 0.0);
        }
        // Beyond it, or at it (where sticking would leave no margin to see the load grow):
        // it breaks away in the direction of the push, under kinetic friction.
        for push in [12.0, -12.0, 9.81, -9.81] {
            let f = Floor { push, ..FLOOR };
            let a = (push - push.signum() * 0.4 * 2.0 * 9.81) / 2.0;
            assert_relative_eq!(
                f.acceleration(0.0, &q, &qd).unwrap()[0],
                a,
                max_relative = 1e-15
            );
        }
    }
    // Sliding, kinetic friction opposes the velocity whatever the load.
    let f = Floor { push: 3.0, ..FLOOR };
    let a = f
        .acceleration(0.0, &q, &nalgebra::Vector1::new(-1e-300))
        .unwrap()[0];
    assert_relative_eq!(a, (3.0 + 0.4 * 2.0 * 9.81) / 2.0, max_relative = 1e-15);
}

#[test]
fn coefficients_outside_their_domain_are_a_typed_error() {
    let q = nalgebra::Vector1::new(0.0);
    for (mu_k, mu_s) in [(0.5, 0.4), (-0.1, 0.4), (0.4, f64::NAN)] {
        let f = Floor {
            mu_k,
            mu_s,
            ..FLOOR
        };
        // A sign or NaN is named by the generated parameter check, `mu_s < mu_k` by the
        // friction solve.
        assert!(matches!(
            f.acceleration(0.0, &q, &q),
            Err(mbd::Error::InvalidInput { .. } | mbd::Error::InvalidParameter { .. })
        ));
    }
}

const AT_REST: Slope = Slope {
    m: 50.0,
    g: 9.81,
    slope: 0.261_799_387_799_149_4, // 15 degrees
    mu: 0.4,
    v0: 0.0,
};

/// At rest on a 15 degree incline, `tan 15 deg = 0.268 < 0.4`: the block must stay, exactly.
#[test]
fn block_at_rest_on_an_incline_stays_with_every_method() {
    let y0 = AT_REST.initial_state();
    assert_eq!(y0, nalgebra::Vector2::zeros());
    for zero in [0.0, -0.0] {
        let (q, qd) = (nalgebra::Vector1::new(0.0), nalgebra::Vector1::new(zero));
        assert_eq!(AT_REST.acceleration(0.0, &q, &qd).unwrap()[0], 0.0);
    }
    let rest = |y: &nalgebra::Vector2<f64>| assert_eq!(*y, nalgebra::Vector2::zeros());
    for tol in [1e-3, 1e-6, 1e-10, 1e-13] {
        let opts = Options {
            rtol: tol,
            atol: tol,
            ..Options::default()
        };
        let dopri = Dopri5::new(opts.clone());
        let radau = Radau5::new(opts);
        // Mode by mode, and the plain model through the ordinary solve.
        rest(
            mbd::hybrid::solve(&dopri, &AT_REST, 0.0, y0, 10.0, &[])
                .unwrap()
                .solution
                .last()
                .1,
        );
        rest(
            mbd::hybrid::solve(&radau, &AT_REST, 0.0, y0, 10.0, &[])
                .unwrap()
                .solution
                .last()
                .1,
        );
        rest(dopri.solve(&AT_REST, 0.0, y0, 10.0, &[]).unwrap().last().1);
        rest(radau.solve(&AT_REST, 0.0, y0, 10.0, &[]).unwrap().last().1);
    }
    for h in [1.0, 1e-2, 1e-4] {
        rest(
            Rk4::new(h)
                .solve(&AT_REST, 0.0, y0, 10.0, &[])
                .unwrap()
                .last()
                .1,
        );
        rest(
            mbd::hybrid::solve(&Gauss::new(h), &AT_REST, 0.0, y0, 1.0, &[])
                .unwrap()
                .solution
                .last()
                .1,
        );
        let ga = GeneralizedAlpha::new(0.8, h);
        let (q0, qd0) = (nalgebra::Vector1::new(0.0), nalgebra::Vector1::new(0.0));
        let sol = ga
            .solve::<_, 1, 2>(&AT_REST, 0.0, q0, qd0, 1.0, &[])
            .unwrap();
        rest(sol.last().1);
        // Mode by mode through its `Integrator` implementation.
        rest(
            mbd::hybrid::solve(&ga, &AT_REST, 0.0, y0, 1.0, &[])
                .unwrap()
                .solution
                .last()
                .1,
        );
    }
}

/// Launched down the incline: slides to the exact stop of constant deceleration, sticks
/// there, and stays, with the ordinary solve of each method driven mode by mode.
#[test]
fn block_stops_and_stays_on_the_plain_model() {
    let b = Slope { v0: 7.0, ..AT_REST };
    let a = 9.81 * (b.slope.sin() - 0.4 * b.slope.cos());
    let (t_stop, s_stop) = (-7.0 / a, 49.0 / (-2.0 * a));
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let check = |run: mbd::hybrid::HybridSolution<2, [Slip; 1]>, what: &str| {
        assert_eq!(run.switches.len(), 1, "{what}");
        let sw = &run.switches[0];
        assert_eq!((sw.from, sw.to), ([Slip::Forward], [Slip::Stick]), "{what}");
        assert!(
            (sw.t - t_stop).abs() <= 1e-12,
            "{what}: {} vs {t_stop}",
            sw.t
        );
        let (t, y) = run.solution.last();
        assert_eq!(t, 20.0);
        assert_relative_eq!(y[0], s_stop, max_relative = 1e-12);
        assert_eq!(y[1], 0.0, "{what}");
    };
    check(
        mbd::hybrid::solve(
            &Dopri5::new(opts.clone()),
            &b,
            0.0,
            b.initial_state(),
            20.0,
            &[],
        )
        .unwrap(),
        "DOPRI5",
    );
    check(
        mbd::hybrid::solve(
            &Radau5::new(opts.clone()),
            &b,
            0.0,
            b.initial_state(),
            20.0,
            &[],
        )
        .unwrap(),
        "Radau5",
    );
    check(
        mbd::hybrid::solve(&Rk4::new(0.01), &b, 0.0, b.initial_state(), 20.0, &[]).unwrap(),
        "RK4",
    );
    // Constant deceleration: generalized-alpha's steps and its cubic Hermite segments
    // reproduce the parabola, so the stop is as exact as with the others.
    check(
        mbd::hybrid::solve(
            &GeneralizedAlpha::new(0.8, 0.01),
            &b,
            0.0,
            b.initial_state(),
            20.0,
            &[],
        )
        .unwrap(),
        "generalized-alpha",
    );
    // The user's events pass through: the model's terminal `stops` (s' falling through 0)
    // ends the run at the stop, reported with its own index.
    let events = b.events();
    let run = mbd::hybrid::solve(
        &Dopri5::new(opts.clone()),
        &b,
        0.0,
        b.initial_state(),
        20.0,
        &events,
    )
    .unwrap();
    assert_eq!(run.solution.stopped_by, Some(0));
    assert_eq!(run.solution.events.len(), 1);
    assert!((run.solution.events[0].t - t_stop).abs() <= 1e-11 * t_stop);
    assert!((run.solution.last().0 - t_stop).abs() <= 1e-11 * t_stop);
}

/// Two stacked blocks, both contacts able to stick at once and coupled through the mass
/// matrix: `lower` (mass `m1`) on the floor (normal `(m1 + m2) g`), `upper` (`m2`) on it at
/// `x + r` (normal `m2 g`), the lower one pushed by `p0 + c t`. The friction between the
/// blocks acts on `r` only (an internal pair does virtual work on the relative motion).
#[derive(Debug, Mechanism)]
#[coords(x, r)]
#[particle(lower, mass = m1, at = [x, 0.0])]
#[particle(upper, mass = m2, at = [x + r, 0.0])]
#[friction(along = x, mu_k = mu_k1, mu_s = mu_s1, normal = (m1 + m2) * g)]
#[friction(along = r, mu_k = mu_k2, mu_s = mu_s2, normal = m2 * g)]
#[generalized_force(push, along = x, value = p0 + c * t)]
pub struct Stack {
    pub m1: f64,
    pub m2: f64,
    pub g: f64,
    pub mu_k1: f64,
    pub mu_s1: f64,
    pub mu_k2: f64,
    pub mu_s2: f64,
    pub p0: f64,
    pub c: f64,
}

const STACK: Stack = Stack {
    m1: 2.0,
    m2: 1.0,
    g: 9.81,
    mu_k1: 0.2,
    mu_s1: 0.3,
    mu_k2: 0.15,
    mu_s2: 0.25,
    p0: 0.0,
    c: 0.0,
};

/// At rest under a constant push `P` (total mass `M = m1 + m2`):
/// - `P <= mu_s1 M g`: both stick, no acceleration;
/// - else the lower block slides; the upper rides along at `a = (P - mu_k1 M g) / M` if
///   that needs at most `mu_s2 m2 g` (`a <= mu_s2 g`);
/// - else both slide: the upper at `mu_k2 g`, the lower at `(P - mu_k1 M g - mu_k2 m2 g) / m1`.
#[test]
fn stacked_blocks_at_rest_take_the_consistent_modes() {
    let (m, g) = (3.0, 9.81);
    let zero = nalgebra::Vector2::zeros();
    for p0 in [0.0, 5.0, 8.8, 8.83, 10.0, 12.0, 16.0, 30.0] {
        let s = Stack { p0, ..STACK };
        let qdd = s.acceleration(0.0, &zero, &zero).unwrap();
        let (a1, a2) = if p0 <= 0.3 * m * g {
            (0.0, 0.0)
        } else if (p0 - 0.2 * m * g) / m <= 0.25 * g {
            let a = (p0 - 0.2 * m * g) / m;
            (a, a)
        } else {
            ((p0 - 0.2 * m * g - 0.15 * g) / 2.0, 0.15 * g)
        };
        // qdd = (x'', r''), r'' = a2 - a1.
        assert!(
            (qdd[0] - a1).abs() <= 1e-14 * (1.0 + a1.abs()),
            "P = {p0}: {qdd:?} vs {a1}, {a2}"
        );
        assert!(
            (qdd[1] - (a2 - a1)).abs() <= 1e-14 * (1.0 + a1.abs()),
            "P = {p0}: {qdd:?}"
        );
        if a1 == a2 {
            assert_eq!(qdd[1], 0.0, "P = {p0}: the upper block is held exactly");
        }
    }
}

/// A push growing at `c`: the lower block breaks away when `c t1 = mu_s1 M g`; the upper
/// rides with it (`x'' = (c t - mu_k1 M g) / M`) until that needs more than static friction,
/// `c t2 / M - mu_k1 g = mu_s2 g`; then both slide. Switch times and the velocities after
/// them against these closed forms.
#[test]
fn stacked_blocks_break_away_in_turn_at_the_closed_form_times() {
    let s = Stack { c: 10.0, ..STACK };
    let (m, g, c) = (3.0, 9.81, 10.0);
    let t1 = 0.3 * m * g / c;
    let t2 = m * (0.25 + 0.2) * g / c;
    // Phase 2 (both together) and phase 3 (both sliding) velocities.
    let v2 = |t: f64| c * (t * t - t1 * t1) / (2.0 * m) - 0.2 * g * (t - t1);
    let v_lower = |t: f64| {
        v2(t2) + c * (t * t - t2 * t2) / (2.0 * 2.0) - (0.2 * m * g + 0.15 * g) * (t - t2) / 2.0
    };
    let v_upper = |t: f64| v2(t2) + 0.15 * g * (t - t2);
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
                &s,
                0.0,
                s.initial_state(),
                2.0,
                &[],
            ),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(
                &Radau5::new(opts.clone()),
                &s,
                0.0,
                s.initial_state(),
                2.0,
                &[],
            ),
        ),
    ] {
        let run = run.unwrap();
        let sw: Vec<_> = run.switches.iter().map(|w| (w.t, w.from, w.to)).collect();
        assert_eq!(sw.len(), 2, "{name}: {sw:?}");
        assert_eq!(
            (sw[0].1, sw[0].2),
            ([Slip::Stick; 2], [Slip::Forward, Slip::Stick])
        );
        assert_eq!(
            (sw[1].1, sw[1].2),
            (
                [Slip::Forward, Slip::Stick],
                [Slip::Forward, Slip::Backward]
            )
        );
        assert!((sw[0].0 - t1).abs() <= 1e-12, "{name}: {} vs {t1}", sw[0].0);
        assert!((sw[1].0 - t2).abs() <= 1e-12, "{name}: {} vs {t2}", sw[1].0);
        let y = run.solution.at(1.2).unwrap();
        assert_relative_eq!(y[2], v2(1.2), max_relative = 1e-10);
        assert_eq!(y[3], 0.0, "{name}: the upper block rides exactly");
        let (t, y) = run.solution.last();
        assert_relative_eq!(y[2], v_lower(t), max_relative = 1e-10);
        assert_relative_eq!(y[2] + y[3], v_upper(t), max_relative = 1e-10);
    }
}

/// A block on a frictional table under a periodic push `p sin(w t)` stronger than static
/// friction (after the periodically forced block of Potra, Anitescu, Gavrea & Trinkle 2006;
/// parameters ours): it sticks, breaks away, slides, stops, and sticks or reverses.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[relaxed(n)]
#[particle(block, mass = m, at = [x, n])]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = reaction(n))]
#[generalized_force(push, along = x, value = p * sin(w * t))]
pub struct Shaken {
    pub m: f64,
    pub g: f64,
    pub mu_k: f64,
    pub mu_s: f64,
    pub p: f64,
    pub w: f64,
}

/// The reference, phase by phase in closed form. Stuck from `t0`: it breaks away at the first
/// `t` where `|p sin(w t)|` rises through `mu_s m g` (`w t = asin(r)` or `pi + asin(r)` mod
/// `2 pi`, `r = mu_s m g / p`), in the direction of the push. Sliding in direction `d` from
/// rest at `tb`: `v(t) = (p (cos(w tb) - cos(w t)) / w - d mu_k m g (t - tb)) / m`, which stops
/// at its first zero after `tb` (found by a scan and bisection); there it sticks if
/// `|p sin(w t)| <= mu_s m g`, else slides off in the push's direction.
fn shaken_reference(b: &Shaken, t_end: f64) -> Vec<(f64, Slip)> {
    let (mg, w, tau) = (b.m * b.g, b.w, 2.0 * std::f64::consts::PI);
    let r = b.mu_s * mg / b.p;
    let push = |t: f64| b.p * (w * t).sin();
    let mut out = Vec::new();
    let (mut t, mut stuck, mut d) = (0.0, true, 0.0);
    while t < t_end {
        if stuck {
            let base = (w * t / tau).floor() * tau;
            let tb = (0..3)
                .flat_map(|k| {
                    [r.asin(), std::f64::consts::PI + r.asin()]
                        .map(|a| (base + a + tau * k as f64) / w)
                })
                .filter(|&c| c > t)
                .fold(f64::INFINITY, f64::min);
            d = push(tb).signum();
            t = tb;
            stuck = false;
            out.push((
                t,
                if d > 0.0 {
                    Slip::Forward
                } else {
                    Slip::Backward
                },
            ));
        } else {
            let tb = t;
            let v = |s: f64| {
                (b.p * ((w * tb).cos() - (w * s).cos()) / w - d * b.mu_k * mg * (s - tb)) / b.m
            };
            let (mut lo, mut hi) = (tb + 1e-9, tb + 1e-9);
            while d * v(hi) > 0.0 {
                lo = hi;
                hi += 1e-3;
            }
            loop {
                let c = 0.5 * (lo + hi);
                if c <= lo || c >= hi {
                    break;
                }
                if d * v(c) > 0.0 { lo = c } else { hi = c }
            }
            t = hi;
            if push(t).abs() <= b.mu_s * mg {
                stuck = true;
                out.push((t, Slip::Stick));
            } else {
                d = push(t).signum();
                out.push((
                    t,
                    if d > 0.0 {
                        Slip::Forward
                    } else {
                        Slip::Backward
                    },
                ));
            }
        }
    }
    out.retain(|(t, _)| *t < t_end);
    out
}

#[test]
fn block_under_a_periodic_push_switches_at_the_closed_form_times() {
    let b = Shaken {
        m: 1.0,
        g: 9.81,
        mu_k: 0.2,
        mu_s: 0.3,
        p: 5.0,
        w: 3.0,
    };
    let t_end = 10.0;
    let reference = shaken_reference(&b, t_end);
    assert!(reference.len() >= 6, "{reference:?}");
    // With the step bounded below the push's period 2 pi / w = 2.1 s; the same without
    // `h_max` is `block_under_a_periodic_push_breaks_away_without_h_max`.
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        h_max: Some(0.1),
        ..Options::default()
    };
    for (name, run) in [
        (
            "DOPRI5",
            mbd::hybrid::solve(
                &Dopri5::new(opts.clone()),
                &b,
                0.0,
                b.initial_state(),
                t_end,
                &[],
            ),
        ),
        (
            "Radau5",
            mbd::hybrid::solve(
                &Radau5::new(opts.clone()),
                &b,
                0.0,
                b.initial_state(),
                t_end,
                &[],
            ),
        ),
    ] {
        let run = run.unwrap();
        let got: Vec<(f64, Slip)> = run.switches.iter().map(|s| (s.t, s.to[0])).collect();
        assert_eq!(
            got.len(),
            reference.len(),
            "{name}: {got:?} vs {reference:?}"
        );
        for (g, r) in got.iter().zip(&reference) {
            assert_eq!(g.1, r.1, "{name}: {got:?} vs {reference:?}");
            assert!(
                (g.0 - r.0).abs() <= 1e-9 * r.0,
                "{name}: {} vs {}",
                g.0,
                r.0
            );
        }
    }
}

/// Friction on a prismatic joint: case 05's crate as a sled on a joint along the slope
/// (`[cos a, -sin a]`, downhill), its joint force asked for with `reaction`; the normal
/// force is that force across the axis, `rx sin(a) + ry cos(a)` (its part along the axis,
/// which carries `s''`, drops out).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(sled, joint = prismatic(s, [cos(a), -sin(a)]), mass = m, inertia = 1.0, reaction)]
#[friction(along = s, mu = mu, normal = reaction(sled_rx) * sin(a) + reaction(sled_ry) * cos(a))]
#[init(der(s) = v0)]
pub struct Sled {
    pub m: f64,
    pub g: f64,
    pub a: f64,
    pub mu: f64,
    pub v0: f64,
}

#[test]
fn prismatic_joint_friction_stops_the_sled_like_the_crate() {
    let sled = Sled {
        m: 50.0,
        g: 9.81,
        a: 15f64.to_radians(),
        mu: 0.4,
        v0: 7.0,
    };
    let acc = 9.81 * (sled.a.sin() - 0.4 * sled.a.cos());
    let (t_stop, s_stop) = (-7.0 / acc, 49.0 / (-2.0 * acc));
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let run = mbd::hybrid::solve(
        &Dopri5::new(opts),
        &sled,
        0.0,
        sled.initial_state(),
        10.0,
        &[],
    )
    .unwrap();
    assert_eq!(run.switches.len(), 1);
    assert_eq!(run.switches[0].to, [Slip::Stick]);
    assert!(
        (run.switches[0].t - t_stop).abs() <= 1e-12,
        "{}",
        run.switches[0].t
    );
    let (_, y) = run.solution.last();
    assert_relative_eq!(y[0], s_stop, max_relative = 1e-12);
    assert_eq!(y[1], 0.0);
}

/// The periodic push of [`block_under_a_periodic_push_switches_at_the_closed_form_times`]
/// without `h_max`: stuck, the state is constant, so the methods' steps grow without bound
/// and the push can rise above `mu_s m g` and fall back within one step; the driver samples
/// the switching functions inside each step and must still find every breakaway, at loose
/// and tight tolerances. A breakaway from rest depends on `t` alone (the stuck state is
/// exact), so its time is held to the closed form to 1e-9 at any tolerance; the stops
/// (the end of a slide) carry the method's error, so the loose runs hold them to 1e-4 s.
#[test]
fn block_under_a_periodic_push_breaks_away_without_h_max() {
    let b = Shaken {
        m: 1.0,
        g: 9.81,
        mu_k: 0.3,
        mu_s: 0.5,
        p: 5.5,
        w: 3.0,
    };
    let t_end = 40.0;
    let reference = shaken_reference(&b, t_end);
    let breakaways = reference
        .windows(2)
        .filter(|p| p[0].1 == Slip::Stick)
        .count();
    assert!(breakaways >= 5, "{reference:?}");
    for (tol, stop_tol) in [(1e-6, 1e-4), (1e-12, 1e-9)] {
        let opts = Options {
            rtol: tol,
            atol: tol,
            ..Options::default()
        };
        let y0 = b.initial_state();
        for (name, run) in [
            (
                "DOPRI5",
                mbd::hybrid::solve(&Dopri5::new(opts.clone()), &b, 0.0, y0, t_end, &[]),
            ),
            (
                "Radau5",
                mbd::hybrid::solve(&Radau5::new(opts.clone()), &b, 0.0, y0, t_end, &[]),
            ),
        ] {
            let run = run.unwrap_or_else(|e| panic!("{name} {tol:e}: {e:?}"));
            let got: Vec<(f64, Slip)> = run.switches.iter().map(|s| (s.t, s.to[0])).collect();
            assert_eq!(
                got.len(),
                reference.len(),
                "{name} {tol:e}: {got:?} vs {reference:?}"
            );
            let mut from = Slip::Stick;
            for (g, r) in got.iter().zip(&reference) {
                assert_eq!(g.1, r.1, "{name} {tol:e}: {got:?} vs {reference:?}");
                let allowed = if from == Slip::Stick {
                    1e-9 * r.0
                } else {
                    stop_tol
                };
                assert!(
                    (g.0 - r.0).abs() <= allowed,
                    "{name} {tol:e}: {} vs {} (from {from:?})",
                    g.0,
                    r.0
                );
                from = r.1;
            }
        }
    }
}

/// A normal force that carries the acceleration the friction changes (a made-up load
/// `N = m g + m x''`): implicit, solved with the acceleration. Sliding forward,
/// `m x'' = -mu N` and `N = m g + m x''` give `N = m g / (1 + mu)`, `x'' = -mu g / (1 + mu)`;
/// backward, `N = m g / (1 - mu)`, `x'' = mu g / (1 - mu)`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g + m * der(der(x)))]
pub struct Pressed {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
}

#[test]
fn a_normal_force_that_carries_the_acceleration_is_solved_with_it() {
    let b = Pressed {
        m: 2.0,
        g: 9.81,
        mu: 0.3,
    };
    let a = |v: f64| {
        b.acceleration(
            0.0,
            &nalgebra::Vector1::new(0.0),
            &nalgebra::Vector1::new(v),
        )
        .unwrap()[0]
    };
    let (forward, backward) = (-0.3 * 9.81 / 1.3, 0.3 * 9.81 / 0.7);
    assert!(
        (a(1.0) - forward).abs() <= 1e-15 * forward.abs(),
        "{}",
        a(1.0)
    );
    assert!(
        (a(-1.0) - backward).abs() <= 1e-15 * backward,
        "{}",
        a(-1.0)
    );
    assert_eq!(a(0.0), 0.0);
    // Mode by mode: it stops at t = v0 / |x''| and stays.
    let run = mbd::hybrid::solve(
        &Dopri5::new(Options {
            rtol: 1e-12,
            atol: 1e-12,
            ..Options::default()
        }),
        &b,
        0.0,
        nalgebra::Vector2::new(0.0, 3.0),
        5.0,
        &[],
    )
    .unwrap();
    let t_stop = 3.0 / forward.abs();
    assert_eq!(run.switches.len(), 1);
    assert!((run.switches[0].t - t_stop).abs() <= 1e-12 * t_stop);
    assert_eq!(run.solution.last().1[1], 0.0);
}
