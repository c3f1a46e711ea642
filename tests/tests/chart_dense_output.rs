//! Dense output and events across a ball joint's chart switch (`mbd::chart`): past a half
//! turn the rotation parameters `sigma` jump to their shadow set `-sigma / |sigma|^2` after
//! the step, so a step that switched must be interpolated in the chart it was computed in.
//! References independent of the chart: the rotation matrix `R(sigma)` (the same for a set
//! and its shadow; written out below, not the library's), the mass centre's parabola under
//! gravity (closed form), the energy and the angular momentum (conserved), and DOPRI5 at
//! 1e-12 (whose continuous extension interpolates each step as computed).
//!
//! Generalized-alpha switches charts too (its rates and both accelerations mapped along):
//! over four turns its angular momentum error is second order in `h`.

use mbd::integrate::{
    Direction, Dop853, Dopri5, Event, Gauss, GeneralizedAlpha, Integrator, Options, Radau5,
    Solution, Vern9,
};
use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// A free body, its mass centre at `c` in its frame, principal moments along its axes.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [cx, cy, cz], mass = m,
       inertia = [[j1, 0.0, 0.0], [0.0, j2, 0.0], [0.0, 0.0, j3]])]
pub struct Flyer {
    pub m: f64,
    pub cx: f64,
    pub cy: f64,
    pub cz: f64,
    pub j1: f64,
    pub j2: f64,
    pub j3: f64,
    pub g: f64,
}

/// A body on a ball joint at the origin (a spatial pendulum), its mass centre below it.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = ball(s1, s2, s3), com = [cx, cy, cz], mass = m,
       inertia = [[j1, 0.0, 0.0], [0.0, j2, 0.0], [0.0, 0.0, j3]])]
pub struct Pendulum {
    pub m: f64,
    pub cx: f64,
    pub cy: f64,
    pub cz: f64,
    pub j1: f64,
    pub j2: f64,
    pub j3: f64,
    pub g: f64,
}

const MASS: f64 = 3.0;
const COM: [f64; 3] = [0.12, -0.05, 0.2];
const MOMENTS: [f64; 3] = [0.8, 1.3, 1.9];

fn flyer(g: f64) -> Flyer {
    Flyer {
        m: MASS,
        cx: COM[0],
        cy: COM[1],
        cz: COM[2],
        j1: MOMENTS[0],
        j2: MOMENTS[1],
        j3: MOMENTS[2],
        g,
    }
}

fn pendulum() -> Pendulum {
    Pendulum {
        m: MASS,
        cx: 0.1,
        cy: 0.05,
        cz: -0.4,
        j1: MOMENTS[0],
        j2: MOMENTS[1],
        j3: MOMENTS[2],
        g: 9.81,
    }
}

fn skew(a: &Vector<3>) -> Matrix<3, 3> {
    Matrix::<3, 3>::new(0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0)
}

/// `R = 1 + (8 S^2 + 4 (1 - s2) S) / (1 + s2)^2`, `S = [sigma]x`.
fn rotation(s: &Vector<3>) -> Matrix<3, 3> {
    let s2 = s.norm_squared();
    let x = skew(s);
    Matrix::<3, 3>::identity() + (8.0 * x * x + 4.0 * (1.0 - s2) * x) / (1.0 + s2).powi(2)
}

/// `B = (1 - s2) 1 + 2 [s]x + 2 s s^T`: `sigma' = B w / 4` (body axes `w`).
fn mrp_b(s: &Vector<3>) -> Matrix<3, 3> {
    (1.0 - s.norm_squared()) * Matrix::<3, 3>::identity() + 2.0 * skew(s) + 2.0 * s * s.transpose()
}

/// Body-axes angular velocity: `w = 4 B^T sigma' / (1 + s2)^2`.
fn body_rate(s: &Vector<3>, sd: &Vector<3>) -> Vector<3> {
    4.0 * mrp_b(s).transpose() * sd / (1.0 + s.norm_squared()).powi(2)
}

/// The free body's state `[p; sigma; p'; sigma']` for a body-axes `w` and the mass centre's
/// velocity `vc`: `p' = vc - R (w x c)`.
fn state(p: [f64; 3], sigma: [f64; 3], w: Vector<3>, vc: Vector<3>) -> Vector<12> {
    let s = Vector::<3>::from(sigma);
    let pd = vc - rotation(&s) * w.cross(&Vector::<3>::from(COM));
    let sd = mrp_b(&s) * w / 4.0;
    let mut y = Vector::<12>::zeros();
    for k in 0..3 {
        (y[k], y[3 + k], y[6 + k], y[9 + k]) = (p[k], s[k], pd[k], sd[k]);
    }
    y
}

fn sigma<const D: usize>(y: &Vector<D>, at: usize) -> Vector<3> {
    Vector::<3>::new(y[at], y[at + 1], y[at + 2])
}

/// The free body's mass centre, world axes.
fn com(y: &Vector<12>) -> Vector<3> {
    Vector::<3>::new(y[0], y[1], y[2]) + rotation(&sigma(y, 3)) * Vector::<3>::from(COM)
}

/// Angular momentum about the world origin (world axes) of the free body without gravity.
fn momentum(y: &Vector<12>) -> Vector<3> {
    let (s, sd) = (sigma(y, 3), sigma(y, 9));
    let (r, w, c) = (rotation(&s), body_rate(&s, &sd), Vector::<3>::from(COM));
    let pd = Vector::<3>::new(y[6], y[7], y[8]);
    let com_v = pd + r * w.cross(&c);
    let inertia = Matrix::<3, 3>::from_diagonal(&Vector::<3>::from(MOMENTS));
    MASS * com(y).cross(&com_v) + r * inertia * w
}

fn tight(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Default::default()
    }
}

/// The recorded steps `(t0, t1)` across which the parameters switched charts (they jump by
/// about `2 |sigma| ~ 2` there, by `h |sigma'|` elsewhere).
fn switching_steps<const D: usize>(sol: &Solution<D>, at: usize) -> Vec<(f64, f64)> {
    (1..sol.t.len())
        .filter(|&k| (sigma(&sol.y[k], at) - sigma(&sol.y[k - 1], at)).norm() > 1.0)
        .map(|k| (sol.t[k - 1], sol.t[k]))
        .collect()
}

/// Interior times of a step: 19 evenly spread.
fn inside((t0, t1): (f64, f64)) -> impl Iterator<Item = f64> {
    (1..20).map(move |i| t0 + (t1 - t0) * i as f64 / 20.0)
}

fn flyer_start() -> Vector<12> {
    let v0 = Vector::<3>::new(1.0, 0.5, 8.0);
    state(
        [0.0, 0.0, 1.0],
        [0.2, -0.1, 0.05],
        Vector::<3>::new(3.0, -6.0, 4.5),
        v0,
    )
}

const T_FLY: f64 = 1.6;

/// Every method's dense output inside the steps that switched charts: the mass centre on
/// its parabola, the rotation matrix on DOPRI5's at 1e-12.
#[test]
fn dense_output_inside_a_switching_step_is_the_step_as_computed() {
    let g = 9.81;
    let p = flyer(g);
    let y0 = flyer_start();
    let (c0, v0) = (com(&y0), Vector::<3>::new(1.0, 0.5, 8.0));
    let parabola = |t: f64| c0 + v0 * t + 0.5 * t * t * Vector::<3>::new(0.0, 0.0, -g);
    let reference = Dopri5::new(tight(1e-12))
        .solve(&p, 0.0, y0, T_FLY, &[])
        .unwrap();
    let (q0, qd0) = (
        y0.fixed_rows::<6>(0).into_owned(),
        y0.fixed_rows::<6>(6).into_owned(),
    );
    // (method, run, bound on the mass centre and on R inside switching steps)
    let runs: [(&str, Solution<12>, f64); 7] = [
        (
            "DOPRI5 1e-10",
            Dopri5::new(tight(1e-10))
                .solve(&p, 0.0, y0, T_FLY, &[])
                .unwrap(),
            1e-8,
        ),
        (
            "DOP853 1e-10",
            Dop853::new(tight(1e-10))
                .solve(&p, 0.0, y0, T_FLY, &[])
                .unwrap(),
            1e-8,
        ),
        (
            "Vern9 1e-10",
            Vern9::new(tight(1e-10))
                .solve(&p, 0.0, y0, T_FLY, &[])
                .unwrap(),
            1e-8,
        ),
        (
            "Radau5 1e-10",
            Radau5::new(tight(1e-10))
                .solve(&p, 0.0, y0, T_FLY, &[])
                .unwrap(),
            1e-8,
        ),
        (
            "Radau5 1e-6",
            Radau5::new(tight(1e-6))
                .solve(&p, 0.0, y0, T_FLY, &[])
                .unwrap(),
            1e-4,
        ),
        (
            "Gauss h = 1e-3",
            Gauss::new(1e-3).solve(&p, 0.0, y0, T_FLY, &[]).unwrap(),
            1e-9,
        ),
        (
            "generalized-alpha h = 1e-3",
            GeneralizedAlpha::new(0.9, 1e-3)
                .solve(&p, 0.0, q0, qd0, T_FLY, &[])
                .unwrap(),
            5e-4,
        ),
    ];
    for (name, sol, tol) in &runs {
        let steps = switching_steps(sol, 3);
        assert!(steps.len() >= 2, "{name}: {} switching steps", steps.len());
        let (mut off_com, mut off_r) = (0.0_f64, 0.0_f64);
        for &step in &steps {
            for t in inside(step) {
                let y = sol.at(t).unwrap();
                let r = rotation(&sigma(&reference.at(t).unwrap(), 3));
                off_com = off_com.max((com(&y) - parabola(t)).norm());
                off_r = off_r.max((rotation(&sigma(&y, 3)) - r).norm());
            }
        }
        println!(
            "{name}: {} switching steps, mass centre {off_com:.1e}, R {off_r:.1e}",
            steps.len()
        );
        assert!(
            off_com < *tol && off_r < *tol,
            "{name}: {off_com:e} m, R {off_r:e}"
        );
    }
}

/// A run of the free body with events.
type Run<'a> = dyn Fn(&[Event<'_, 12>]) -> Solution<12> + 'a;

/// An event whose closed-form time lies in the middle of a switching step: the mass centre's
/// `x` (uniform motion: `c0x + v0x t`) passing the value it has there. Located by each
/// method's dense output inside that step.
#[test]
fn events_inside_a_switching_step_are_located_where_they_are() {
    let p = flyer(9.81);
    let y0 = flyer_start();
    let c0x = com(&y0)[0];
    let methods: [(&str, &Run, f64); 3] = [
        (
            "DOPRI5",
            &|ev| {
                Dopri5::new(tight(1e-10))
                    .solve(&p, 0.0, y0, T_FLY, ev)
                    .unwrap()
            },
            1e-8,
        ),
        (
            "Radau5",
            &|ev| {
                Radau5::new(tight(1e-10))
                    .solve(&p, 0.0, y0, T_FLY, ev)
                    .unwrap()
            },
            1e-7,
        ),
        (
            "Gauss",
            &|ev| Gauss::new(1e-3).solve(&p, 0.0, y0, T_FLY, ev).unwrap(),
            1e-7,
        ),
    ];
    for (name, run, tol) in methods {
        let steps = switching_steps(&run(&[]), 3);
        for &(t0, t1) in &steps {
            let te = 0.5 * (t0 + t1);
            let level = c0x + 1.0 * te;
            let ev = [Event::new(
                "x",
                move |_, y: &Vector<12>| com(y)[0] - level,
                Direction::Rising,
            )];
            let sol = run(&ev);
            assert_eq!(sol.events.len(), 1, "{name}: {:?}", sol.events);
            let off = (sol.events[0].t - te).abs();
            assert!(
                off < tol,
                "{name}: event at {} for {te}: {off:e}",
                sol.events[0].t
            );
        }
        assert!(!steps.is_empty(), "{name}");
    }
}

/// The ball-jointed pendulum spinning about its own axis through many switches: at interior
/// times of the switching steps its energy is the start's and its rotation DOPRI5's.
#[test]
fn a_spinning_pendulum_interpolates_its_switching_steps() {
    let p = pendulum();
    let s0 = Vector::<3>::new(0.3, 0.1, 0.0);
    let sd0 = mrp_b(&s0) * Vector::<3>::new(0.5, -0.3, 9.0) / 4.0;
    let y0 = Vector::<6>::new(s0[0], s0[1], s0[2], sd0[0], sd0[1], sd0[2]);
    let t1 = 3.0;
    let energy = |y: &Vector<6>| {
        let (q, qd) = (
            y.fixed_rows::<3>(0).into_owned(),
            y.fixed_rows::<3>(3).into_owned(),
        );
        p.energy(0.0, &q, &qd).unwrap()
    };
    let e0 = energy(&y0);
    let reference = Dopri5::new(tight(1e-12))
        .solve(&p, 0.0, y0, t1, &[])
        .unwrap();
    let (q0, qd0) = (
        y0.fixed_rows::<3>(0).into_owned(),
        y0.fixed_rows::<3>(3).into_owned(),
    );
    let runs: [(&str, Solution<6>, f64); 6] = [
        (
            "DOPRI5",
            Dopri5::new(tight(1e-10))
                .solve(&p, 0.0, y0, t1, &[])
                .unwrap(),
            1e-7,
        ),
        (
            "DOP853",
            Dop853::new(tight(1e-10))
                .solve(&p, 0.0, y0, t1, &[])
                .unwrap(),
            1e-7,
        ),
        (
            "Vern9",
            Vern9::new(tight(1e-10))
                .solve(&p, 0.0, y0, t1, &[])
                .unwrap(),
            1e-7,
        ),
        (
            "Radau5",
            Radau5::new(tight(1e-10))
                .solve(&p, 0.0, y0, t1, &[])
                .unwrap(),
            5e-8,
        ),
        (
            "Gauss",
            Gauss::new(1e-3).solve(&p, 0.0, y0, t1, &[]).unwrap(),
            1e-9,
        ),
        (
            "generalized-alpha",
            GeneralizedAlpha::new(0.9, 1e-3)
                .solve(&p, 0.0, q0, qd0, t1, &[])
                .unwrap(),
            5e-4,
        ),
    ];
    for (name, sol, tol) in &runs {
        let steps = switching_steps(sol, 0);
        assert!(steps.len() >= 3, "{name}: {} switching steps", steps.len());
        let (mut off_e, mut off_r) = (0.0_f64, 0.0_f64);
        for &step in &steps {
            for t in inside(step) {
                let y = sol.at(t).unwrap();
                let r = rotation(&sigma(&reference.at(t).unwrap(), 0));
                off_e = off_e.max((energy(&y) - e0).abs() / e0.abs());
                off_r = off_r.max((rotation(&sigma(&y, 0)) - r).norm());
            }
        }
        println!(
            "pendulum {name}: {} switching steps, energy {off_e:.1e}, R {off_r:.1e}",
            steps.len()
        );
        assert!(
            off_e < *tol && off_r < *tol,
            "{name}: energy {off_e:e}, R {off_r:e}"
        );
    }
}

/// Generalized-alpha through four turns (5 rad/s for 5 s, no gravity): every state inside
/// the unit ball, the angular momentum about the origin conserved to second order (halving
/// `h` divides its error by about 4), the rotation on DOPRI5's at 1e-12 likewise.
#[test]
fn generalized_alpha_switches_charts_through_many_turns() {
    let p = flyer(0.0);
    let w = Vector::<3>::new(1.0, -4.0, 3.0) * (5.0 / 26.0_f64.sqrt());
    let y0 = state(
        [0.3, -1.0, 2.0],
        [0.3, -0.2, 0.5],
        w,
        Vector::<3>::new(0.5, 0.0, -0.3),
    );
    let t1 = 5.0;
    let reference = Dopri5::new(tight(1e-12))
        .solve(&p, 0.0, y0, t1, &[])
        .unwrap();
    let r_ref = rotation(&sigma(&reference.y_end, 3));
    let l0 = momentum(&y0);
    let (q0, qd0) = (
        y0.fixed_rows::<6>(0).into_owned(),
        y0.fixed_rows::<6>(6).into_owned(),
    );
    let errors: Vec<(f64, f64)> = [1e-3, 5e-4]
        .iter()
        .map(|&h| {
            let sol = GeneralizedAlpha::new(0.9, h)
                .solve(&p, 0.0, q0, qd0, t1, &[])
                .unwrap();
            assert!(sol.y.iter().all(|y| sigma(y, 3).norm() <= 1.0 + 1e-12));
            assert!(switching_steps(&sol, 3).len() >= 4, "h = {h}");
            let dl = sol
                .y
                .iter()
                .map(|y| (momentum(y) - l0).norm())
                .fold(0.0, f64::max);
            let dr = (rotation(&sigma(&sol.y_end, 3)) - r_ref).norm();
            println!("generalized-alpha h = {h:e}: angular momentum {dl:.2e}, R {dr:.2e}");
            (dl, dr)
        })
        .collect();
    let (l_ratio, r_ratio) = (errors[0].0 / errors[1].0, errors[0].1 / errors[1].1);
    println!("ratios: momentum {l_ratio:.2}, rotation {r_ratio:.2}");
    assert!(
        errors[0].0 < 1e-3 * l0.norm() && errors[0].1 < 1e-2,
        "{errors:?}"
    );
    assert!((3.0..5.5).contains(&l_ratio), "{l_ratio}");
    assert!((3.0..5.5).contains(&r_ratio), "{r_ratio}");
}

/// A cart sliding with Coulomb friction (run mode by mode, `mbd::hybrid`) carrying a
/// symmetric rotor on a ball joint at its mass centre, spinning about the vertical at 6
/// rad/s: the rotor turns as `Rz(6 t)` (no torque reaches it), through its chart switches
/// in every mode (a model with friction and no constraints switches charts too).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(cart, joint = prismatic(s, [1.0, 0.0, 0.0]), mass = m)]
#[body(rotor, parent = cart, joint = ball(s1, s2, s3), mass = m, inertia = diag(a, a, c))]
#[friction(along = s, mu = mu, normal = 2.0 * m * g)]
pub struct SlidingRotor {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub mu: f64,
    pub g: f64,
}

#[test]
fn a_rotor_on_a_sliding_cart_switches_charts_in_every_mode() {
    let p = SlidingRotor {
        m: 2.0,
        a: 0.3,
        c: 0.5,
        mu: 0.3,
        g: 9.81,
    };
    let spin = 6.0;
    // s = 0, sigma = 0; s' = 2 (stops at t = 2 / (0.3 g) = 0.68 s), sigma' = (0, 0, spin / 4).
    let y0 = Vector::<8>::from_column_slice(&[0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, spin / 4.0]);
    let t1 = 3.0;
    // (Radau5's global error over 18 rad at 1e-10: 1.1e-7, as on the free body.)
    for (name, sol, tol) in [
        (
            "DOPRI5",
            Dopri5::new(tight(1e-10))
                .solve(&p, 0.0, y0, t1, &[])
                .unwrap(),
            1e-8,
        ),
        (
            "Radau5",
            Radau5::new(tight(1e-10))
                .solve(&p, 0.0, y0, t1, &[])
                .unwrap(),
            1e-6,
        ),
    ] {
        assert!(!sol.switches.is_empty(), "{name}: the cart stops");
        assert!(
            sol.y.iter().all(|y| sigma(y, 1).norm() <= 1.0 + 1e-12),
            "{name}"
        );
        assert!(switching_steps(&sol, 1).len() >= 2, "{name}");
        let (c, s) = ((spin * t1).cos(), (spin * t1).sin());
        let rz = Matrix::<3, 3>::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        let off = (rotation(&sigma(&sol.y_end, 1)) - rz).norm();
        println!("rotor on a sliding cart, {name}: R off Rz(6 t) by {off:.1e}");
        assert!(off < tol, "{name}: {off:e}");
    }
}
