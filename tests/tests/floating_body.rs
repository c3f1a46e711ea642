//! The free joint (`joint = free(x, y, z, s1, s2, s3)`) on a single rigid body: a body
//! flying freely, its joint origin off its mass centre, with a general (rotated, asymmetric)
//! inertia tensor. Checked against
//! - Newton-Euler about the mass centre, by hand: `m r_c'' = m g`, `I w' + w x I w = 0`
//!   (body axes), turned into the joint's coordinates (below, [`reference`]);
//! - Euler's torque-free motion in closed form (Jacobi's elliptic functions: Landau and
//!   Lifshitz, Mechanics, sec. 37): the intermediate-axis (Dzhanibekov) flip, its period
//!   `2 K(k) / rate`;
//! - conservation: angular momentum in world axes, kinetic energy, uniform motion of the
//!   mass centre without gravity; the parabola of the mass centre under gravity;
//!   every integrator family (DOPRI5, Vern9, Radau5, generalized-alpha).

use mbd::integrate::{Dopri5, GeneralizedAlpha, Integrator, Options, Radau5, Vern9};
use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// A free body, its mass centre at `c` in its frame, its central inertia
/// `Q diag(i1, i2, i3) Q^T` (entries below, from [`inertia`]); a free joint takes the
/// articulated-body recursion by default, even alone.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [cx, cy, cz], mass = m,
       inertia = [[j11, j12, j13], [j12, j22, j23], [j13, j23, j33]])]
pub struct Flyer {
    pub m: f64,
    pub cx: f64,
    pub cy: f64,
    pub cz: f64,
    pub j11: f64,
    pub j12: f64,
    pub j13: f64,
    pub j22: f64,
    pub j23: f64,
    pub j33: f64,
    pub g: f64,
}

/// The same body through the mass-matrix form (Kane's projections), not the recursion.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [cx, cy, cz], mass = m,
       inertia = [[j11, j12, j13], [j12, j22, j23], [j13, j23, j33]])]
pub struct FlyerKane {
    pub m: f64,
    pub cx: f64,
    pub cy: f64,
    pub cz: f64,
    pub j11: f64,
    pub j12: f64,
    pub j13: f64,
    pub j22: f64,
    pub j23: f64,
    pub j33: f64,
    pub g: f64,
}

/// Principal moments, `I1 < I2 < I3`.
const PRINCIPAL: [f64; 3] = [0.8, 1.3, 1.9];
const MASS: f64 = 3.0;
const COM: [f64; 3] = [0.12, -0.05, 0.2];

fn skew(a: &Vector<3>) -> Matrix<3, 3> {
    Matrix::<3, 3>::new(0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0)
}

/// The principal axes in the body frame: a fixed rotation (Rodrigues' formula about
/// `(1, 2, 2) / 3` by 0.7 rad).
fn principal_axes() -> Matrix<3, 3> {
    let n = Vector::<3>::new(1.0, 2.0, 2.0) / 3.0;
    let x = skew(&n);
    Matrix::<3, 3>::identity() + 0.7_f64.sin() * x + (1.0 - 0.7_f64.cos()) * x * x
}

/// The central inertia in the body frame.
fn inertia() -> Matrix<3, 3> {
    let q = principal_axes();
    q * Matrix::<3, 3>::from_diagonal(&Vector::<3>::from(PRINCIPAL)) * q.transpose()
}

fn flyer(g: f64) -> Flyer {
    let i = inertia();
    Flyer {
        m: MASS,
        cx: COM[0],
        cy: COM[1],
        cz: COM[2],
        j11: i[(0, 0)],
        j12: i[(0, 1)],
        j13: i[(0, 2)],
        j22: i[(1, 1)],
        j23: i[(1, 2)],
        j33: i[(2, 2)],
        g,
    }
}

fn kane(g: f64) -> FlyerKane {
    let f = flyer(g);
    FlyerKane {
        m: f.m,
        cx: f.cx,
        cy: f.cy,
        cz: f.cz,
        j11: f.j11,
        j12: f.j12,
        j13: f.j13,
        j22: f.j22,
        j23: f.j23,
        j33: f.j33,
        g,
    }
}

/// The rotation of modified Rodrigues parameters `sigma = tan(phi / 4) n`:
/// `R = 1 + (8 S^2 + 4 (1 - s2) S) / (1 + s2)^2`, `S = [sigma]x`.
fn mrp_rotation(s: &Vector<3>) -> Matrix<3, 3> {
    let s2 = s.norm_squared();
    let x = skew(s);
    Matrix::<3, 3>::identity() + (8.0 * x * x + 4.0 * (1.0 - s2) * x) / (1.0 + s2).powi(2)
}

/// `B = (1 - s2) 1 + 2 [s]x + 2 s s^T`: `sigma' = B w / 4` for the body-axes angular
/// velocity `w`; `B B^T = (1 + s2)^2 1`.
fn mrp_b(s: &Vector<3>) -> Matrix<3, 3> {
    (1.0 - s.norm_squared()) * Matrix::<3, 3>::identity() + 2.0 * skew(s) + 2.0 * s * s.transpose()
}

/// `B'` along `sigma'`: the derivative of each term of `B`.
fn mrp_b_dot(s: &Vector<3>, sd: &Vector<3>) -> Matrix<3, 3> {
    -2.0 * s.dot(sd) * Matrix::<3, 3>::identity()
        + 2.0 * skew(sd)
        + 2.0 * (sd * s.transpose() + s * sd.transpose())
}

/// The body-axes angular velocity of `(sigma, sigma')`: `w = 4 B^T sigma' / (1 + s2)^2`.
fn body_rate(s: &Vector<3>, sd: &Vector<3>) -> Vector<3> {
    4.0 * mrp_b(s).transpose() * sd / (1.0 + s.norm_squared()).powi(2)
}

/// A state `[p; sigma; p'; sigma']` for a rotation `sigma`, a body-axes angular velocity
/// `w` and the mass centre's velocity `vc` (world axes): `p' = vc - R (w x c)`.
fn state(p: [f64; 3], sigma: [f64; 3], w: Vector<3>, vc: Vector<3>) -> Vector<12> {
    let s = Vector::<3>::from(sigma);
    let sd = mrp_b(&s) * w / 4.0;
    let pd = vc - mrp_rotation(&s) * w.cross(&Vector::<3>::from(COM));
    let mut y = Vector::<12>::zeros();
    for k in 0..3 {
        y[k] = p[k];
        y[3 + k] = s[k];
        y[6 + k] = pd[k];
        y[9 + k] = sd[k];
    }
    y
}

struct Motion {
    rot: Matrix<3, 3>,
    /// Body axes.
    w: Vector<3>,
    com: Vector<3>,
    com_v: Vector<3>,
}

/// The body's motion from the state, by hand.
fn motion(y: &Vector<12>) -> Motion {
    let (p, s) = (y.fixed_rows::<3>(0), y.fixed_rows::<3>(3).into_owned());
    let (pd, sd) = (y.fixed_rows::<3>(6), y.fixed_rows::<3>(9).into_owned());
    let rot = mrp_rotation(&s);
    let w = body_rate(&s, &sd);
    let c = Vector::<3>::from(COM);
    Motion {
        rot,
        w,
        com: p + rot * c,
        com_v: pd + rot * w.cross(&c),
    }
}

/// Newton-Euler about the mass centre: `w' = -I^-1 (w x I w)` (body axes), `r_c'' = g`;
/// then `p'' = r_c'' - R (w' x c + w x (w x c))` and `sigma'' = (B w' + B' w) / 4`.
fn reference(y: &Vector<12>, g: f64) -> Vector<6> {
    let s = y.fixed_rows::<3>(3).into_owned();
    let sd = y.fixed_rows::<3>(9).into_owned();
    let Motion { rot, w, .. } = motion(y);
    let i = inertia();
    let wd = -i.try_inverse().unwrap() * w.cross(&(i * w));
    let c = Vector::<3>::from(COM);
    let pdd = Vector::<3>::new(0.0, 0.0, -g) - rot * (wd.cross(&c) + w.cross(&w.cross(&c)));
    let sdd = (mrp_b(&s) * wd + mrp_b_dot(&s, &sd) * w) / 4.0;
    Vector::<6>::new(pdd[0], pdd[1], pdd[2], sdd[0], sdd[1], sdd[2])
}

/// Kinetic energy and angular momentum about the world origin, world axes.
fn invariants(y: &Vector<12>) -> (f64, Vector<3>) {
    let Motion { rot, w, com, com_v } = motion(y);
    let i = inertia();
    let t = 0.5 * MASS * com_v.norm_squared() + 0.5 * w.dot(&(i * w));
    (t, MASS * com.cross(&com_v) + rot * i * w)
}

fn split(y: &Vector<12>) -> (Vector<6>, Vector<6>) {
    (
        y.fixed_rows::<6>(0).into_owned(),
        y.fixed_rows::<6>(6).into_owned(),
    )
}

/// Joint origin, parameters, body-axes angular velocity, mass-centre velocity.
type Start = ([f64; 3], [f64; 3], [f64; 3], [f64; 3]);

const STATES: [Start; 4] = [
    (
        [0.3, -1.0, 2.0],
        [0.3, -0.2, 0.5],
        [0.4, 1.1, -0.7],
        [0.5, 0.0, -0.3],
    ),
    (
        [0.0, 0.0, 0.0],
        [-0.7, 0.6, 0.1],
        [-2.0, 0.3, 1.5],
        [0.0, 2.0, 0.0],
    ),
    (
        [5.0, 2.0, -1.0],
        [0.9, 0.4, -0.1],
        [1.0, -1.0, 0.5],
        [-1.0, 0.4, 2.0],
    ),
    (
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
    ),
];

/// The generated recursion (articulated body, three prismatic steps and a ball) and the
/// generated mass-matrix form both equal Newton-Euler by hand.
#[test]
fn free_body_accelerations_equal_newton_euler_by_hand() {
    assert!(Flyer::GENERATED.parts.contains(&"articulated_body"));
    assert!(!FlyerKane::GENERATED.parts.contains(&"articulated_body"));
    assert_eq!(
        Flyer::COORDINATES,
        ["x", "y", "z", "s1", "s2", "s3"],
        "translation first, then the rotation"
    );
    for g in [0.0, 9.81] {
        let (p, k) = (flyer(g), kane(g));
        for (at, sigma, w, vc) in STATES {
            let y = state(at, sigma, Vector::<3>::from(w), Vector::<3>::from(vc));
            let (q, qd) = split(&y);
            let want = reference(&y, g);
            let scale = want.amax().max(1.0);
            for (name, got) in [
                ("recursion", p.acceleration(0.0, &q, &qd).unwrap()),
                ("mass matrix", k.acceleration(0.0, &q, &qd).unwrap()),
            ] {
                assert!(
                    (got - want).amax() < 1e-12 * scale,
                    "{name}, g = {g}: {got:?} against {want:?}"
                );
            }
            // The energy the model reports is `T + V` by hand.
            let (t, _) = invariants(&y);
            let v = MASS * g * motion(&y).com[2];
            let e = p.energy(0.0, &q, &qd).unwrap();
            assert!((e - (t + v)).abs() < 1e-12 * (t + v).abs().max(1.0));
        }
    }
}

fn tight(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Default::default()
    }
}

/// Zero gravity, tumbling about all three axes for 40 s (about 25 turns): angular momentum
/// in world axes and kinetic energy conserved to 1e-10, the mass centre moving uniformly
/// along a line, by DOPRI5 and Vern9; every accepted state inside the chart's unit ball,
/// and the switch to the shadow set passed many times.
#[test]
fn free_body_conserves_momentum_and_energy_over_many_turns() {
    let p = flyer(0.0);
    let vc0 = Vector::<3>::new(0.3, -0.2, 0.1);
    let y0 = state(
        [1.0, 0.0, -0.5],
        [0.2, 0.1, -0.3],
        Vector::<3>::new(2.5, -3.0, 4.0),
        vc0,
    );
    let (t0, l0) = invariants(&y0);
    let c0 = motion(&y0).com;
    let t1 = 40.0;
    let runs = [
        (
            "DOPRI5",
            Dopri5::new(tight(1e-13)).solve(&p, 0.0, y0, t1, &[]),
        ),
        (
            "Vern9",
            Vern9::new(tight(1e-13)).solve(&p, 0.0, y0, t1, &[]),
        ),
    ];
    for (name, sol) in runs {
        let sol = sol.unwrap();
        let mut switches = 0;
        for (k, (t, y)) in sol.t.iter().zip(&sol.y).enumerate() {
            let (e, l) = invariants(y);
            assert!(
                (e - t0).abs() < 1e-10 * t0,
                "{name} t = {t}: T {e} against {t0}"
            );
            assert!(
                (l - l0).norm() < 1e-10 * l0.norm(),
                "{name} t = {t}: L {l:?} against {l0:?}"
            );
            let c = motion(y).com;
            assert!(
                (c - (c0 + vc0 * *t)).norm() < 1e-10 * (1.0 + t),
                "{name} t = {t}"
            );
            let sigma = y.fixed_rows::<3>(3);
            assert!(sigma.norm() <= 1.0, "{name}: |sigma| = {}", sigma.norm());
            if k > 0 && (sigma - sol.y[k - 1].fixed_rows::<3>(3)).norm() > 1.0 {
                switches += 1;
            }
        }
        assert_eq!(*sol.t.last().unwrap(), t1);
        // |w| about 5.4 rad/s for 40 s: about 34 turns, one switch per turn.
        assert!(switches > 20, "{name}: {switches} switches");
    }
}

/// The complete elliptic integral of the first kind by the arithmetic-geometric mean:
/// `K(k) = pi / (2 agm(1, sqrt(1 - k^2)))`.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Jacobi's `sn`, `cn`, `dn` of `u` with modulus `k`, by the descending Landen
/// transformation (Abramowitz and Stegun, 16.4): the AGM sequence `a_n, c_n`, then
/// `phi_N = 2^N a_N u` and `sin(2 phi_{n-1} - phi_n) = (c_n / a_n) sin(phi_n)`.
fn jacobi(u: f64, k: f64) -> (f64, f64, f64) {
    let (mut a, mut c, mut b) = (vec![1.0_f64], vec![k], (1.0 - k * k).sqrt());
    while c.last().unwrap().abs() > 1e-16 {
        let an = *a.last().unwrap();
        a.push(0.5 * (an + b));
        c.push(0.5 * (an - b));
        b = (an * b).sqrt();
    }
    let n = a.len() - 1;
    let mut phi = 2f64.powi(n as i32) * a[n] * u;
    for m in (1..=n).rev() {
        phi = 0.5 * (phi + (c[m] / a[m] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    (sn, cn, (1.0 - k * k * sn * sn).sqrt())
}

/// The Dzhanibekov flip: spinning at 6 rad/s about the intermediate principal axis with a
/// 1 % push about the major one, the body turns its intermediate axis over, again and
/// again. Landau and Lifshitz (sec. 37), principal axes `I1 < I2 < I3`, `L^2 > 2 E I2`:
/// `W1 = a1 cn(tau)`, `W2 = a2 sn(tau)`, `W3 = a3 dn(tau)` with
/// `a1^2 = (L^2 - 2 E I3) / (I1 (I1 - I3))`, `a2^2 = (L^2 - 2 E I3) / (I2 (I2 - I3))`,
/// `a3^2 = (L^2 - 2 E I1) / (I3 (I3 - I1))`, `tau = rate t`,
/// `rate^2 = (I3 - I2) (L^2 - 2 E I1) / (I1 I2 I3)`,
/// `k^2 = (I2 - I1) (2 E I3 - L^2) / ((I3 - I2) (L^2 - 2 E I1))`. Started at `tau = K`
/// (`W = (0, a2, a3 k')`), `W2` changes sign every `2 K / rate`. The generated body (its
/// principal axes rotated in its frame, its mass centre off the joint origin) follows the
/// closed form at every accepted step over 4 flips, with Radau5 and DOPRI5 at 1e-12; near
/// the separatrix the flip's timing amplifies the local errors (measured: DOPRI5 1.1e-8,
/// Radau5 2.4e-7 of |w|), while a wrong model would be off by the whole |w| (a flip early
/// or late).
#[test]
fn free_body_flips_about_its_intermediate_axis_as_in_closed_form() {
    let p = flyer(0.0);
    let [i1, i2, i3] = PRINCIPAL;
    let w0 = Vector::<3>::new(0.0, 6.0, 0.06); // principal axes
    let e2 = i1 * w0[0].powi(2) + i2 * w0[1].powi(2) + i3 * w0[2].powi(2);
    let l2 = (i1 * w0[0]).powi(2) + (i2 * w0[1]).powi(2) + (i3 * w0[2]).powi(2);
    let a1 = ((l2 - e2 * i3) / (i1 * (i1 - i3))).sqrt();
    let a2 = ((l2 - e2 * i3) / (i2 * (i2 - i3))).sqrt();
    let a3 = ((l2 - e2 * i1) / (i3 * (i3 - i1))).sqrt();
    let rate = ((i3 - i2) * (l2 - e2 * i1) / (i1 * i2 * i3)).sqrt();
    let k = ((i2 - i1) * (e2 * i3 - l2) / ((i3 - i2) * (l2 - e2 * i1))).sqrt();
    let big_k = elliptic_k(k);
    // The closed form starts where the state does.
    assert!((a2 - w0[1]).abs() < 1e-12 && (a3 * (1.0 - k * k).sqrt() - w0[2]).abs() < 1e-12);
    let q = principal_axes();
    let y0 = state(
        [0.0, 0.0, 0.0],
        [0.1, -0.2, 0.3],
        q * w0,
        Vector::<3>::zeros(),
    );
    let half = 2.0 * big_k / rate;
    let t1 = 4.0 * half + 0.5;
    let closed = |t: f64| {
        let (sn, cn, dn) = jacobi(big_k + rate * t, k);
        Vector::<3>::new(a1 * cn, a2 * sn, a3 * dn)
    };
    for (name, sol, tol) in [
        (
            "Radau5",
            Radau5::new(tight(1e-12)).solve(&p, 0.0, y0, t1, &[]),
            1e-6,
        ),
        (
            "DOPRI5",
            Dopri5::new(tight(1e-12)).solve(&p, 0.0, y0, t1, &[]),
            3e-8,
        ),
    ] {
        let sol = sol.unwrap();
        let mut worst: f64 = 0.0;
        let mut flips = 0;
        let mut last_sign = 1.0;
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            let w = q.transpose() * motion(y).w;
            worst = worst.max((w - closed(t)).norm() / w0.norm());
            if w[1].signum() != last_sign {
                flips += 1;
                last_sign = w[1].signum();
            }
        }
        assert_eq!(flips, 4, "{name}");
        assert!(worst < tol, "{name}: off the closed form by {worst:e}");
    }
    // The flip takes long: 4.06 s between flips at 6 rad/s.
    assert!(half > 4.0 && half < 4.1, "{half}");
}

/// Under gravity the mass centre follows the parabola `r0 + v0 t + g t^2 / 2` while the
/// body tumbles (at every accepted step), by Radau5 (tolerance 1e-11: within 1e-9) and
/// generalized-alpha (h = 1e-3, second order: within 1e-4), below a full turn (|w| t = 4.3
/// rad; `chart_dense_output.rs` takes generalized-alpha through switches).
#[test]
fn free_body_under_gravity_follows_the_parabola() {
    let g = 9.81;
    let p = flyer(g);
    let v0 = Vector::<3>::new(1.0, 0.5, 8.0);
    let w = Vector::<3>::new(1.0, -2.0, 1.5);
    let y0 = state([0.0, 0.0, 1.0], [0.2, -0.1, 0.05], w, v0);
    let c0 = motion(&y0).com;
    let parabola = |t: f64| c0 + v0 * t + 0.5 * t * t * Vector::<3>::new(0.0, 0.0, -g);
    let t1 = 1.6;
    let radau = Radau5::new(tight(1e-11))
        .solve(&p, 0.0, y0, t1, &[])
        .unwrap();
    let (q0, qd0) = split(&y0);
    let alpha: Solution<12> = GeneralizedAlpha::new(0.9, 1e-3)
        .solve(&p, 0.0, q0, qd0, t1, &[])
        .unwrap();
    for (name, sol, tol) in [("Radau5", radau, 1e-9), ("generalized-alpha", alpha, 1e-4)] {
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            let off = (motion(y).com - parabola(t)).norm();
            assert!(off < tol, "{name} t = {t}: {off:e} off the parabola");
        }
        let (_, y1) = sol.last();
        let e = |y: &Vector<12>| {
            let (q, qd) = split(y);
            p.energy(0.0, &q, &qd).unwrap()
        };
        assert!((e(y1) - e(&y0)).abs() < tol * e(&y0), "{name} energy");
    }
}

/// Two point masses welded on a line, flying free: nothing resists a turn about the line,
/// so the motion is undetermined at every state (the derive folds the articulated inertia's
/// zero determinant): a typed error from every evaluation, never a NaN handed back.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[body(dumbbell, joint = free(x, y, z, s1, s2, s3), mass = 1.0)]
#[body(other_end, parent = dumbbell, joint = fixed, at = [0.5, 0.0, 0.0], mass = 1.0)]
pub struct Dumbbell {}

#[test]
fn an_undetermined_rotation_is_a_typed_error() {
    let p = Dumbbell {};
    let q = Vector::<6>::new(0.0, 0.0, 0.0, 0.1, 0.2, 0.3);
    let qd = Vector::<6>::new(1.0, 0.0, 0.0, 0.1, -0.2, 0.3);
    let a = p.acceleration(0.0, &q, &qd);
    assert!(matches!(a, Err(Error::NonFinite { .. })), "{a:?}");
    let mut y = Vector::<12>::zeros();
    y.fixed_rows_mut::<6>(0).copy_from(&q);
    y.fixed_rows_mut::<6>(6).copy_from(&qd);
    let run = Dopri5::default().solve(&p, 0.0, y, 1.0, &[]);
    assert!(run.is_err(), "{run:?}");
}
