#![allow(mixed_script_confusables)] // rustc warns on a lone Greek letter (`θ`) as a name; it is meant.
//! The common mechanism classes written the way a newcomer writes them, from README.md and
//! the language reference (`mbd::language`) alone: a pendulum, a spring-mass-damper, the
//! README's driven slider-crank, a four-bar, a block sliding to rest on a rough floor and a
//! heavy top on a ball-and-socket joint. Each is checked against a closed form or a
//! conservation law derived beside it.

use mbd::analysis::linear::{linearize, modes};
use mbd::analysis::{NewtonOptions, assemble, consistent_velocities, kinematics};
use mbd::integrate::{Dopri5, Integrator};
use mbd::prelude::*;
use std::f64::consts::PI;

fn tight() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

/// A simple pendulum, Greek names and all: a bob of mass `m` on a massless rod `l`, `θ`
/// from the downward vertical, released at rest from `θ0`. It swings to `-θ0` in half a
/// period, and the exact period is `T = 2 π sqrt(l / g) / AGM(1, cos(θ0 / 2))`
/// (the complete elliptic integral by the arithmetic-geometric mean).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(θ)]
#[particle(bob, mass = m, at = [l * sin(θ), -l * cos(θ)])]
#[init(θ = θ0)]
#[event(turn = der(θ), rising, terminal)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub θ0: f64,
}

fn agm(mut a: f64, mut b: f64) -> f64 {
    while (a - b).abs() > 1e-16 * a {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    a
}

#[test]
fn pendulum_turns_at_the_exact_half_period() {
    let p = Pendulum {
        m: 0.3,
        l: 1.2,
        g: 9.81,
        θ0: 2.0,
    };
    let events = p.events();
    let sol = Dopri5::new(tight())
        .solve(&p, 0.0, p.initial_state(), 10.0, &events)
        .unwrap();
    let period = 2.0 * PI * (p.l / p.g).sqrt() / agm(1.0, (p.θ0 / 2.0).cos());
    let turn = &sol.events[0];
    assert!(
        (turn.t - period / 2.0).abs() < 1e-9,
        "{} vs {}",
        turn.t,
        period / 2.0
    );
    assert!((turn.y[0] + p.θ0).abs() < 1e-9);
}

/// A block on a spring and a damper to a wall point: `m x'' + c x' + k x = 0` about the
/// spring's rest length. Underdamped (`ζ = c / (2 sqrt(k m)) < 1`), from `x0` at rest:
/// `x(t) = e^(-ζ ω t) (x0 cos ω_d t + ζ ω x0 / ω_d sin ω_d t)`, `ω_d = ω sqrt(1 - ζ^2)`,
/// and its linearisation has one oscillatory mode (a complex pair): `ω_n = ω`, `ω_d`,
/// damping ratio `ζ`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[point(wall, at = [-1.0, 0.0])]
#[spring(s, from = wall, to = block, k = k, length = 1.0)]
#[damper(d, from = wall, to = block, c = c)]
#[init(x = 0.1)]
#[output(stretch = x, rate = der(x))]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
    pub c: f64,
}

#[test]
fn spring_mass_damper_follows_the_damped_closed_form_and_has_its_modes() {
    let p = Oscillator {
        m: 2.0,
        k: 50.0,
        c: 3.0,
    };
    let w = (p.k / p.m).sqrt();
    let zeta = p.c / (2.0 * (p.k * p.m).sqrt());
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let exact =
        |t: f64| (-zeta * w * t).exp() * 0.1 * ((wd * t).cos() + zeta * w / wd * (wd * t).sin());
    let sol = Dopri5::new(tight())
        .solve(&p, 0.0, p.initial_state(), 3.0, &[])
        .unwrap();
    for (t, y) in sol.t.iter().zip(&sol.y) {
        assert!((y[0] - exact(*t)).abs() < 1e-10, "t = {t}");
    }
    let a = linearize(&p, 0.0, &Vector::<2>::zeros()).unwrap();
    let found = modes(&a).unwrap();
    // One complex pair, listed once.
    assert_eq!(found.len(), 1);
    assert!((found[0].omega_n - w).abs() < 1e-12 * w);
    assert!((found[0].omega_d - wd).abs() < 1e-12 * w);
    assert!((found[0].damping_ratio.unwrap() - zeta).abs() < 1e-12);
}

/// README's first example, verbatim: the slider-crank driven at `θ = ω t`. Both of its
/// coordinates follow from the drive (no free coordinate: `kinematics` solves them at each
/// time; the state keeps both, augmented), and the piston's
/// speed is the derivative of `x = r cos θ + sqrt(l^2 - r^2 sin^2 θ)`:
/// `v = -r ω sin θ (1 + r cos θ / sqrt(l^2 - r^2 sin^2 θ))`.
#[derive(Debug, Mechanism)]
#[coords(beta, x)]
#[drive(theta = omega * t)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(rod, mass = m_rod, inertia = m_rod * l * l / 12.0,
        at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
        angle = -beta)]
#[particle(piston, mass = m_piston, at = [x, 0.0])]
#[output(v_piston = der(x))]
pub struct SliderCrank {
    pub r: f64,
    pub l: f64,
    pub omega: f64,
    pub m_rod: f64,
    pub m_piston: f64,
}

#[test]
fn readme_slider_crank_gives_the_piston_speed_of_the_closed_form() {
    let p = SliderCrank {
        r: 0.1,
        l: 0.35,
        omega: 30.0,
        m_rod: 1.0,
        m_piston: 0.5,
    };
    // Its two coordinates are both fixed by the drive: the kinematic analysis finds them.
    let newton = NewtonOptions::default();
    let mut guess = Vector::<2>::new(0.0, p.l + p.r);
    for t in [0.0, 0.013, 0.05, 0.1] {
        let th: f64 = p.omega * t;
        let root = (p.l * p.l - (p.r * th.sin()).powi(2)).sqrt();
        let v = -p.r * p.omega * th.sin() * (1.0 + p.r * th.cos() / root);
        let k = kinematics(&p, t, &guess, &newton).unwrap();
        guess = k.q;
        assert!((k.q[1] - (p.r * th.cos() + root)).abs() < 1e-12);
        let y = Vector::<4>::new(k.q[0], k.q[1], k.qd[0], k.qd[1]);
        let out = p.outputs(t, &y).unwrap();
        assert!(
            (out.v_piston - v).abs() < 1e-12,
            "t = {t}: {} vs {v}",
            out.v_piston
        );
    }
}

/// A four-bar as a joint tree closed by a pin: crank `a` from the ground origin, coupler
/// `b` on its tip, rocker `c` from the ground pivot `(d, 0)`, the coupler's tip pinned to
/// the rocker's. Light links, a flywheel-like crank (all inertia, so the loop's energy is
/// what the closure must conserve). The closure keeps the two tips together, and the
/// rocker's angle at each crank angle is the circle intersection written out below.
/// (Grashof: shortest + longest = 0.8 <= 1.05, the crank the shortest: a crank-rocker.)
#[derive(Debug, Mechanism)]
#[body(crank, joint = revolute(q1), com = [a / 2.0, 0.0], mass = 1.0, inertia = 0.5)]
#[body(coupler, parent = crank, joint = revolute(q2), at = [a, 0.0], com = [b / 2.0, 0.0],
       mass = 0.2, inertia = 0.2 * b * b / 12.0)]
#[body(rocker, joint = revolute(q3), at = [d, 0.0], com = [c / 2.0, 0.0],
       mass = 0.3, inertia = 0.3 * c * c / 12.0)]
#[close(pin, a = coupler, at_a = [b, 0.0], b = rocker, at_b = [c, 0.0])]
#[output(rocker_angle = angle(rocker), gap = norm(position(coupler, [b, 0.0]) - position(rocker, [c, 0.0])))]
pub struct FourBar {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
}

#[test]
fn four_bar_keeps_its_pin_and_the_rocker_angle_of_the_circle_intersection() {
    let p = FourBar {
        a: 0.2,
        b: 0.6,
        c: 0.5,
        d: 0.55,
    };
    assert_eq!(FourBar::COORDINATES.len(), 3);
    // A loop closed by `close` is kept augmented (the three angles; `minimal` is refused
    // with a reason): assemble it at a crank angle of 60 degrees turning at 2 rad/s.
    let newton = NewtonOptions::default();
    let held = [true, false, false];
    let q = assemble(
        &p,
        0.0,
        &Vector::<3>::new(PI / 3.0, -1.0, 1.0),
        &held,
        &newton,
    )
    .unwrap();
    let qd = consistent_velocities(&p, 0.0, &q, &Vector::<3>::new(2.0, 0.0, 0.0), &held).unwrap();
    let y0 = Vector::<6>::from_iterator(q.iter().chain(qd.iter()).copied());
    let sol = Dopri5::new(tight()).solve(&p, 0.0, y0, 1.0, &[]).unwrap();
    for (t, y) in sol.t.iter().zip(&sol.y) {
        let out = p.outputs(*t, y).unwrap();
        assert!(out.gap < 1e-9, "t = {t}: pin gap {}", out.gap);
        // Crank tip A = a (cos q1, sin q1); the rocker tip B is at b from A and c from
        // D = (d, 0): B = D + c (cos φ, sin φ) on the branch assembled from the default.
        let (ax, ay) = (p.a * y[0].cos(), p.a * y[0].sin());
        let (ex, ey) = (ax - p.d, ay);
        let e2 = ex * ex + ey * ey;
        // |B - A| = b with B - D = c u: c^2 - 2 c (u . e) + e^2 = b^2.
        let k = (p.c * p.c + e2 - p.b * p.b) / (2.0 * p.c);
        let base = ey.atan2(ex);
        let spread = (k / e2.sqrt()).acos();
        let phi = out.rocker_angle;
        let off = |cand: f64| (((phi - cand) + PI).rem_euclid(2.0 * PI) - PI).abs();
        assert!(
            off(base + spread).min(off(base - spread)) < 1e-9,
            "t = {t}: rocker at {phi}"
        );
    }
}

/// A block launched along a rough floor: `normal = m g` written out, so the friction is
/// `-mu m g sign(x')`; it stops at `t = v0 / (mu g)` after `v0^2 / (2 mu g)` and stays.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g)]
#[init(der(x) = v0)]
pub struct Sliding {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
    pub v0: f64,
}

#[test]
fn friction_block_stops_where_constant_deceleration_says_and_is_not_linearised_at_rest() {
    let p = Sliding {
        m: 3.0,
        g: 9.81,
        mu: 0.3,
        v0: 4.0,
    };
    let run =
        mbd::hybrid::solve(&Dopri5::new(tight()), &p, 0.0, p.initial_state(), 3.0, &[]).unwrap();
    let stop = p.v0 / (p.mu * p.g);
    assert_eq!(run.switches.len(), 1);
    assert!((run.switches[0].t - stop).abs() < 1e-12);
    let end = run.solution.last().1;
    assert!((end[0] - p.v0 * p.v0 / (2.0 * p.mu * p.g)).abs() < 1e-10);
    assert_eq!(end[1], 0.0);
    // Sliding, the linearisation exists (the friction force is constant in the state);
    // at rest, where the accelerations have no derivative, it is a typed error.
    let slide = linearize(&p, 0.0, &Vector::<2>::new(0.0, 1.0)).unwrap();
    assert_eq!(slide, Matrix::<2, 2>::new(0.0, 1.0, 0.0, 0.0));
    match linearize(&p, 0.0, &Vector::<2>::zeros()) {
        Err(Error::InvalidInput { what, .. }) => assert_eq!(what, "friction at rest"),
        other => panic!("expected friction at rest, got {other:?}"),
    }
}

/// A heavy symmetric top on a ball-and-socket joint at the ground origin: its symmetry
/// axis is the body `z`, its mass centre `h` up it. With `R = rot_z(a) rot_y(b) rot_x(c)`
/// (the `spherical` joint) and `ω` its angular velocity (ground frame, an output), the
/// conserved quantities are independent of the parametrisation: the energy, the angular
/// momentum about the vertical `L_z = (R J R^T ω)_z` with `J = diag(i1 + m h^2,
/// i1 + m h^2, i3)` about the pivot (gravity's moment about the pivot is horizontal), and
/// the spin `ω_3 = (R^T ω)_z` (Euler's third equation with `i1 = i2` and a moment normal
/// to the symmetry axis).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = spherical(a, b, c), com = [0.0, 0.0, h], mass = m,
       inertia = diag(i1, i1, i3))]
#[init(b = 0.4, der(c) = 40.0, der(a) = 1.0)]
#[output(w = angular_velocity(top))]
pub struct Top {
    pub m: f64,
    pub h: f64,
    pub i1: f64,
    pub i3: f64,
    pub g: f64,
}

#[test]
fn heavy_top_keeps_its_energy_vertical_momentum_and_spin() {
    let p = Top {
        m: 0.5,
        h: 0.04,
        i1: 4e-4,
        i3: 6e-4,
        g: 9.81,
    };
    let rot = |y: &Vector<6>| {
        let r = |axis: &nalgebra::Unit<nalgebra::Vector3<f64>>, q: f64| {
            nalgebra::Rotation3::from_axis_angle(axis, q).into_inner()
        };
        r(&nalgebra::Vector3::z_axis(), y[0])
            * r(&nalgebra::Vector3::y_axis(), y[1])
            * r(&nalgebra::Vector3::x_axis(), y[2])
    };
    let jp = nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::new(
        p.i1 + p.m * p.h * p.h,
        p.i1 + p.m * p.h * p.h,
        p.i3,
    ));
    let invariants = |y: &Vector<6>| {
        let o = p.outputs(0.0, y).unwrap();
        let w = nalgebra::Vector3::new(o.w_x, o.w_y, o.w_z);
        let r = rot(y);
        let lz = (r * jp * r.transpose() * w)[2];
        let spin = (r.transpose() * w)[2];
        let q = y.fixed_rows::<3>(0).into_owned();
        let qd = y.fixed_rows::<3>(3).into_owned();
        (
            p.energy(0.0, &q, &qd).unwrap(),
            lz,
            spin,
            w.dot(&(r * jp * r.transpose() * w)) / 2.0,
        )
    };
    let y0 = p.initial_state();
    let (e0, lz0, s0, kin0) = invariants(&y0);
    // The energy is the kinetic energy about the pivot plus m g h cos(tilt).
    let tilt0 = rot(&y0)[(2, 2)];
    assert!((e0 - (kin0 + p.m * p.g * p.h * tilt0)).abs() < 1e-12 * e0.abs());
    let sol = Dopri5::new(tight()).solve(&p, 0.0, y0, 1.0, &[]).unwrap();
    assert!(sol.y.len() > 10);
    for y in &sol.y {
        let (e, lz, s, _) = invariants(y);
        assert!((e - e0).abs() < 1e-9 * e0.abs(), "energy {e} vs {e0}");
        assert!((lz - lz0).abs() < 1e-9 * lz0.abs(), "L_z {lz} vs {lz0}");
        assert!((s - s0).abs() < 1e-9 * s0.abs(), "spin {s} vs {s0}");
    }
}
