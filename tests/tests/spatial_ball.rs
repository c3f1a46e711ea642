//! The ball joint (`joint = ball(s1, s2, s3)`): a spherical joint in modified Rodrigues
//! parameters, without the Euler angles' singularity. Checked against
//! - the same body written out with `rigid3` and the parameters' rotation matrix typed in
//!   by hand (Kane's projections of a rotation the derive differentiates itself);
//! - its own three generated algorithms (articulated body, composite rigid body + Newton-Euler,
//!   Kane);
//! - the Euler-angle `spherical` joint away from its singularity (to 1e-10 along a motion);
//! - physics: energy and angular momentum about the vertical through gimbal-lock
//!   orientations, where the Euler form stops, and a heavy top's steady precession in
//!   closed form.

use approx::assert_relative_eq;
use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// A heavy body on a ball joint, its mass centre `h` below the joint and off its axis by
/// `e`, with a general inertia tensor (the `HeavyBody` of `spatial_tree.rs` on a ball joint).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = ball(s1, s2, s3), com = [e, 0.0, -h], mass = m,
       inertia = [[ia, 0.01, 0.0], [0.01, ib, 0.02], [0.0, 0.02, ic]])]
#[output(omega_x = angular_velocity(top)[0])]
#[output(omega_y = angular_velocity(top)[1])]
#[output(omega_z = angular_velocity(top)[2])]
#[output(x = position(top)[0])]
#[output(y = position(top)[1])]
#[output(z = position(top)[2])]
#[output(vx = velocity(top)[0])]
#[output(vy = velocity(top)[1])]
pub struct BallBody {
    pub m: f64,
    pub e: f64,
    pub h: f64,
    pub ia: f64,
    pub ib: f64,
    pub ic: f64,
    pub g: f64,
}

/// [`BallBody`] through the articulated-body recursion (one body: by default the mass
/// matrix), `M` and `f` by composite rigid bodies and Newton-Euler.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, recursive)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = ball(s1, s2, s3), com = [e, 0.0, -h], mass = m,
       inertia = [[ia, 0.01, 0.0], [0.01, ib, 0.02], [0.0, 0.02, ic]])]
pub struct BallBodyRecursive {
    pub m: f64,
    pub e: f64,
    pub h: f64,
    pub ia: f64,
    pub ib: f64,
    pub ic: f64,
    pub g: f64,
}

/// [`BallBody`] with the rotation typed in: `R = 1 + (8 S^2 + 4 (1 - s2) S) / (1 + s2)^2`,
/// `S = [sigma]x`, written out entry by entry (`S^2 = sigma sigma^T - s2 1`).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[coords(s1, s2, s3)]
#[rigid3(top, mass = m, inertia = [[ia, 0.01, 0.0], [0.01, ib, 0.02], [0.0, 0.02, ic]],
    at = [[1.0 + (8.0 * (s1 * s1 - (s1 * s1 + s2 * s2 + s3 * s3))) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s1 * s2 - 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s3) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s1 * s3 + 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s2) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3))],
          [(8.0 * s2 * s1 + 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s3) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           1.0 + (8.0 * (s2 * s2 - (s1 * s1 + s2 * s2 + s3 * s3))) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s2 * s3 - 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s1) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3))],
          [(8.0 * s3 * s1 - 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s2) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s3 * s2 + 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s1) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           1.0 + (8.0 * (s3 * s3 - (s1 * s1 + s2 * s2 + s3 * s3))) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3))]]
        * [e, 0.0, -h],
    rotation = [[1.0 + (8.0 * (s1 * s1 - (s1 * s1 + s2 * s2 + s3 * s3))) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s1 * s2 - 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s3) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s1 * s3 + 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s2) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3))],
          [(8.0 * s2 * s1 + 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s3) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           1.0 + (8.0 * (s2 * s2 - (s1 * s1 + s2 * s2 + s3 * s3))) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s2 * s3 - 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s1) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3))],
          [(8.0 * s3 * s1 - 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s2) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           (8.0 * s3 * s2 + 4.0 * (1.0 - s1 * s1 - s2 * s2 - s3 * s3) * s1) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3)),
           1.0 + (8.0 * (s3 * s3 - (s1 * s1 + s2 * s2 + s3 * s3))) / ((1.0 + s1 * s1 + s2 * s2 + s3 * s3) * (1.0 + s1 * s1 + s2 * s2 + s3 * s3))]])]
pub struct BallBodyByHand {
    pub m: f64,
    pub e: f64,
    pub h: f64,
    pub ia: f64,
    pub ib: f64,
    pub ic: f64,
    pub g: f64,
}

/// The same body on the Euler-angle joint (`rot_z(psi) rot_y(theta) rot_x(phi)`).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = spherical(psi, theta, phi), com = [e, 0.0, -h], mass = m,
       inertia = [[ia, 0.01, 0.0], [0.01, ib, 0.02], [0.0, 0.02, ic]])]
#[output(omega_x = angular_velocity(top)[0])]
#[output(omega_y = angular_velocity(top)[1])]
#[output(omega_z = angular_velocity(top)[2])]
#[output(x = position(top)[0])]
#[output(y = position(top)[1])]
#[output(z = position(top)[2])]
pub struct EulerBody {
    pub m: f64,
    pub e: f64,
    pub h: f64,
    pub ia: f64,
    pub ib: f64,
    pub ic: f64,
    pub g: f64,
}

const BODY: BallBody = BallBody {
    m: 2.0,
    e: 0.05,
    h: 0.4,
    ia: 0.12,
    ib: 0.1,
    ic: 0.03,
    g: 9.81,
};

fn recursive() -> BallBodyRecursive {
    let p = &BODY;
    BallBodyRecursive {
        m: p.m,
        e: p.e,
        h: p.h,
        ia: p.ia,
        ib: p.ib,
        ic: p.ic,
        g: p.g,
    }
}

fn by_hand() -> BallBodyByHand {
    let p = &BODY;
    BallBodyByHand {
        m: p.m,
        e: p.e,
        h: p.h,
        ia: p.ia,
        ib: p.ib,
        ic: p.ic,
        g: p.g,
    }
}

fn euler() -> EulerBody {
    let p = &BODY;
    EulerBody {
        m: p.m,
        e: p.e,
        h: p.h,
        ia: p.ia,
        ib: p.ib,
        ic: p.ic,
        g: p.g,
    }
}

fn inertia() -> Matrix<3, 3> {
    let p = &BODY;
    Matrix::<3, 3>::new(p.ia, 0.01, 0.0, 0.01, p.ib, 0.02, 0.0, 0.02, p.ic)
}

fn skew(a: &Vector<3>) -> Matrix<3, 3> {
    Matrix::<3, 3>::new(0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0)
}

/// The rotation of modified Rodrigues parameters, written out here apart from the macro.
fn mrp_rotation(s: &Vector<3>) -> Matrix<3, 3> {
    let s2 = s.norm_squared();
    let x = skew(s);
    Matrix::<3, 3>::identity() + (8.0 * x * x + 4.0 * (1.0 - s2) * x) / (1.0 + s2).powi(2)
}

/// `B = (1 - s2) 1 + 2 [s]x + 2 s s^T`: `sigma' = B w / 4`, `w` the body-frame angular
/// velocity (Schaub and Junkins, "Analytical Mechanics of Space Systems", eq. 3.163).
fn mrp_b(s: &Vector<3>) -> Matrix<3, 3> {
    (1.0 - s.norm_squared()) * Matrix::<3, 3>::identity() + 2.0 * skew(s) + 2.0 * s * s.transpose()
}

/// The parameters of a rotation matrix, through its unit quaternion (Shepperd's choice of
/// the largest component), `sigma = q_v / (1 + q_0)` with `q_0 >= 0` (so `|sigma| <= 1`).
fn mrp_of(r: &Matrix<3, 3>) -> Vector<3> {
    let tr = r.trace();
    let q = if tr > 0.0 {
        let s = 2.0 * (1.0 + tr).sqrt();
        [
            0.25 * s,
            (r[(2, 1)] - r[(1, 2)]) / s,
            (r[(0, 2)] - r[(2, 0)]) / s,
            (r[(1, 0)] - r[(0, 1)]) / s,
        ]
    } else {
        let i = (0..3)
            .max_by(|&a, &b| r[(a, a)].total_cmp(&r[(b, b)]))
            .unwrap();
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let s = 2.0 * (1.0 + r[(i, i)] - r[(j, j)] - r[(k, k)]).sqrt();
        let mut q = [(r[(k, j)] - r[(j, k)]) / s, 0.0, 0.0, 0.0];
        q[1 + i] = 0.25 * s;
        q[1 + j] = (r[(j, i)] + r[(i, j)]) / s;
        q[1 + k] = (r[(k, i)] + r[(i, k)]) / s;
        q
    };
    let sign = if q[0] < 0.0 { -1.0 } else { 1.0 };
    Vector::<3>::new(q[1], q[2], q[3]) * sign / (1.0 + sign * q[0])
}

/// The ball joint's state for a rotation and a world-frame angular velocity.
fn ball_state(r: &Matrix<3, 3>, w_world: &Vector<3>) -> Vector<6> {
    let s = mrp_of(r);
    let sd = mrp_b(&s) * (r.transpose() * w_world) / 4.0;
    Vector::<6>::new(s[0], s[1], s[2], sd[0], sd[1], sd[2])
}

/// `rot_z(psi) rot_y(theta) rot_x(phi)`.
fn zyx(psi: f64, theta: f64, phi: f64) -> Matrix<3, 3> {
    let (sz, cz) = psi.sin_cos();
    let (sy, cy) = theta.sin_cos();
    let (sx, cx) = phi.sin_cos();
    let rz = Matrix::<3, 3>::new(cz, -sz, 0.0, sz, cz, 0.0, 0.0, 0.0, 1.0);
    let ry = Matrix::<3, 3>::new(cy, 0.0, sy, 0.0, 1.0, 0.0, -sy, 0.0, cy);
    let rx = Matrix::<3, 3>::new(1.0, 0.0, 0.0, 0.0, cx, -sx, 0.0, sx, cx);
    rz * ry * rx
}

fn split(y: &Vector<6>) -> (Vector<3>, Vector<3>) {
    (
        y.fixed_rows::<3>(0).into_owned(),
        y.fixed_rows::<3>(3).into_owned(),
    )
}

/// Energy and angular momentum about the vertical through the joint, from the state by
/// hand: `m g z_c + (m |v_c|^2 + w . I_c w) / 2` and `m (r x v)_z + (R I R^T w)_z`.
fn invariants(y: &Vector<6>) -> (f64, f64) {
    let p = &BODY;
    let o = p.outputs(0.0, y).unwrap();
    let (q, qd) = split(y);
    let rot = mrp_rotation(&q);
    let w = Vector::<3>::new(o.omega_x, o.omega_y, o.omega_z);
    let spin = rot * inertia() * rot.transpose() * w;
    let momentum = p.m * (o.x * o.vy - o.y * o.vx) + spin[2];
    (p.energy(0.0, &q, &qd).unwrap(), momentum)
}

const STATES: [([f64; 3], [f64; 3]); 4] = [
    ([0.3, -0.2, 0.5], [0.4, 1.1, -0.7]),
    ([-0.7, 0.6, 0.1], [-2.0, 0.3, 1.5]),
    ([0.9, 0.5, -0.4], [1.0, -1.0, 0.5]),
    ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
];

#[test]
fn ball_joint_equals_its_rotation_typed_in() {
    let (p, hand) = (&BODY, by_hand());
    for (q, qd) in STATES {
        let (q, qd) = (Vector::<3>::from(q), Vector::<3>::from(qd));
        let (m, m_hand): (Matrix<3, 3>, Matrix<3, 3>) = (
            p.mass_matrix(0.0, &q).unwrap(),
            hand.mass_matrix(0.0, &q).unwrap(),
        );
        assert_relative_eq!(m, m_hand, epsilon = 1e-14, max_relative = 1e-12);
        assert_relative_eq!(
            p.forces(0.0, &q, &qd).unwrap(),
            hand.forces(0.0, &q, &qd).unwrap(),
            epsilon = 1e-13,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            p.energy(0.0, &q, &qd).unwrap(),
            hand.energy(0.0, &q, &qd).unwrap(),
            max_relative = 1e-13
        );
    }
    // The generated angular velocity is the body-frame `w` of `sigma' = B w / 4`, in world axes.
    let (q, qd) = (
        Vector::<3>::new(0.6, -0.3, 0.5),
        Vector::<3>::new(0.2, 0.9, -1.3),
    );
    let y = Vector::<6>::new(q[0], q[1], q[2], qd[0], qd[1], qd[2]);
    let o = p.outputs(0.0, &y).unwrap();
    let w_body = mrp_b(&q).try_inverse().unwrap() * qd * 4.0;
    let w = mrp_rotation(&q) * w_body;
    assert_relative_eq!(
        Vector::<3>::new(o.omega_x, o.omega_y, o.omega_z),
        w,
        max_relative = 1e-13
    );
}

#[test]
fn ball_joint_recursions_equal_the_mass_matrix_form() {
    let (p, rec) = (&BODY, recursive());
    assert!(
        BallBodyRecursive::GENERATED
            .parts
            .contains(&"articulated_body")
    );
    assert!(!BallBody::GENERATED.parts.contains(&"articulated_body"));
    for (q, qd) in STATES {
        let (q, qd) = (Vector::<3>::from(q), Vector::<3>::from(qd));
        // Composite rigid bodies and Newton-Euler against Kane.
        let (m, m_rec): (Matrix<3, 3>, Matrix<3, 3>) = (
            p.mass_matrix(0.0, &q).unwrap(),
            rec.mass_matrix(0.0, &q).unwrap(),
        );
        assert_relative_eq!(m, m_rec, epsilon = 1e-14, max_relative = 1e-12);
        assert_relative_eq!(
            p.forces(0.0, &q, &qd).unwrap(),
            rec.forces(0.0, &q, &qd).unwrap(),
            epsilon = 1e-13,
            max_relative = 1e-12
        );
        // The articulated body (3x3 D in the angular velocity) against M^-1 f.
        let (a, a_rec) = (
            p.acceleration(0.0, &q, &qd).unwrap(),
            rec.acceleration(0.0, &q, &qd).unwrap(),
        );
        assert!(
            (a - a_rec).norm() <= 1e-12 * a.norm().max(1.0),
            "{a:?} {a_rec:?}"
        );
    }
}

fn tight() -> Options {
    Options {
        rtol: 1e-13,
        atol: 1e-13,
        dense: false,
        ..Default::default()
    }
}

/// Away from `theta = +-pi/2` both joints describe the same motion: from the same rotation
/// and angular velocity, the rotation, the mass centre and the angular velocity agree to
/// 1e-10 after 1.5 s (DOPRI5 at 1e-13, both).
#[test]
fn ball_joint_moves_as_the_euler_angle_joint_away_from_its_singularity() {
    let (p, e) = (&BODY, euler());
    let y_euler = Vector::<6>::from([0.1, 0.35, -0.2, 1.5, -0.4, 3.0]);
    let o = e.outputs(0.0, &y_euler).unwrap();
    let w = Vector::<3>::new(o.omega_x, o.omega_y, o.omega_z);
    let rot = zyx(y_euler[0], y_euler[1], y_euler[2]);
    let y_ball = ball_state(&rot, &w);
    let t1 = 1.5;
    let a = Dopri5::new(tight())
        .solve(&e, 0.0, y_euler, t1, &[])
        .unwrap();
    let b = Dopri5::new(tight()).solve(p, 0.0, y_ball, t1, &[]).unwrap();
    let ((ta, ya), (tb, yb)) = (a.last(), b.last());
    assert_eq!((ta, tb), (t1, t1));
    assert!(ya[1].abs() < 1.3, "pitch reached {}", ya[1]);
    let (oa, ob) = (e.outputs(t1, ya).unwrap(), p.outputs(t1, yb).unwrap());
    let (ra, rb) = (zyx(ya[0], ya[1], ya[2]), mrp_rotation(&split(yb).0));
    assert!((ra - rb).norm() < 1e-10, "rotation {}", (ra - rb).norm());
    let com = |x: f64, y: f64, z: f64| Vector::<3>::new(x, y, z);
    assert!((com(oa.x, oa.y, oa.z) - com(ob.x, ob.y, ob.z)).norm() < 1e-10);
    let (wa, wb) = (
        com(oa.omega_x, oa.omega_y, oa.omega_z),
        com(ob.omega_x, ob.omega_y, ob.omega_z),
    );
    assert!((wa - wb).norm() < 1e-10 * wa.norm(), "{wa:?} {wb:?}");
    // The motion is not trivial: the body turned by more than a radian.
    assert!((ra - rot).norm() > 1.0);
}

/// A symmetric top on a ball joint, its mass centre `l` above the pivot.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(top, joint = ball(s1, s2, s3), com = [0.0, 0.0, l], mass = m, inertia = diag(a, a, c))]
#[output(x = position(top)[0])]
#[output(y = position(top)[1])]
#[output(z = position(top)[2])]
pub struct BallTop {
    pub m: f64,
    pub l: f64,
    pub a: f64,
    pub c: f64,
    pub g: f64,
}

fn rot_y(b: f64) -> Matrix<3, 3> {
    zyx(0.0, b, 0.0)
}

fn rot_z(b: f64) -> Matrix<3, 3> {
    zyx(b, 0.0, 0.0)
}

/// Steady precession of a heavy symmetric top (Goldstein, Classical Mechanics, sec. 5.7):
/// with `A = a + m l^2` about the pivot, tilt `theta` from the upward vertical and spin
/// `w3 = w . e3`, the axis precesses uniformly at the slow root `Omega` of
/// `A cos(theta) Omega^2 - C w3 Omega + m g l = 0`: `e3(t) = rot_z(Omega t) e3(0)`. Spinning at
/// 100 rad/s, the rotation passes a half turn (`|sigma| = 1`) once per turn, so one
/// precession period (2.4 s) crosses the shadow switch about 38 times.
#[test]
fn heavy_top_precesses_steadily_as_in_closed_form() {
    let p = BallTop {
        m: 1.0,
        l: 0.1,
        a: 0.002,
        c: 0.004,
        g: 9.81,
    };
    let (theta, w3) = (0.6_f64, 100.0);
    let big_a = p.a + p.m * p.l * p.l;
    let (qa, qb, qc) = (big_a * theta.cos(), -p.c * w3, p.m * p.g * p.l);
    let omega = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
    let rot0 = rot_y(theta);
    let e3 = rot0 * Vector::<3>::z();
    let w = omega * Vector::<3>::z() + (w3 - omega * theta.cos()) * e3;
    let y0 = ball_state(&rot0, &w);
    let period = 2.0 * std::f64::consts::PI / omega;
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Default::default()
    };
    let sol = Dopri5::new(opts.clone())
        .solve(&p, 0.0, y0, period, &[])
        .unwrap();
    let mut worst: f64 = 0.0;
    for k in 0..=40 {
        let t = period * k as f64 / 40.0;
        let y = sol.at(t).unwrap();
        let o = p.outputs(t, &y).unwrap();
        let expected = rot_z(omega * t) * e3 * p.l;
        worst = worst.max((Vector::<3>::new(o.x, o.y, o.z) - expected).norm() / p.l);
    }
    // Every accepted state is inside the unit ball, and the parameters jumped to the
    // shadow set once per turn of the spin (it turns about 38 times).
    let sigma: Vec<Vector<3>> = sol.y.iter().map(|y| split(y).0).collect();
    assert!(sigma.iter().all(|s| s.norm() <= 1.0));
    let switches = sigma
        .windows(2)
        .filter(|w| (w[1] - w[0]).norm() > 1.0)
        .count();
    assert!((35..=45).contains(&switches), "{switches} switches");
    assert!(worst < 1e-9, "axis off the closed form by {worst:e}");
}

/// A heavy body started exactly at the Euler joint's gimbal lock (`rot_z(0.3) rot_y(pi/2)
/// rot_x(0.2)`), turning about every axis: the ball joint carries it through, the energy
/// and the angular momentum about the vertical conserved to 1e-10 over 4 s (1306 DOPRI5
/// steps at 1e-12). The Euler-angle form of the same body cannot start there (its mass
/// matrix is singular), and started beside it with the same angular velocity it needs ever
/// more steps: 16x as many at 1e-4 rad off (21 700), and at 1e-6 rad it stops at the
/// limit of 100 000 steps within 1e-9 s.
#[test]
fn ball_joint_passes_gimbal_lock_conserving_energy_and_vertical_momentum() {
    let p = &BODY;
    let (psi, phi, lock) = (0.3, 0.2, std::f64::consts::FRAC_PI_2);
    let w = Vector::<3>::new(1.5, -0.8, 2.5);
    let y0 = ball_state(&zyx(psi, lock, phi), &w);
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        dense: false,
        ..Default::default()
    };
    let sol = Dopri5::new(opts.clone())
        .solve(p, 0.0, y0, 4.0, &[])
        .unwrap();
    let (e0, l0) = invariants(&y0);
    assert!(
        l0.abs() > 0.5,
        "a zero momentum would make a weak test: {l0}"
    );
    for y in &sol.y {
        let (e, l) = invariants(y);
        assert!((e - e0).abs() < 1e-10 * e0.abs(), "energy {e} against {e0}");
        assert!(
            (l - l0).abs() < 1e-10 * l0.abs(),
            "momentum {l} against {l0}"
        );
    }
    // The motion is not trivial: the body turned by more than a radian.
    let (_, y1) = sol.last();
    assert!((mrp_rotation(&split(y1).0) - zyx(psi, lock, phi)).norm() > 1.0);
    let ball_steps = sol.stats.n_steps;

    // The Euler form: singular at the lock, ever slower beside it.
    let e = euler();
    let at_lock = e.acceleration(
        0.0,
        &Vector::<3>::new(psi, lock, phi),
        &Vector::<3>::new(1.0, 0.5, -1.0),
    );
    assert!(
        matches!(at_lock, Err(mbd::Error::SingularMassMatrix { .. })),
        "{at_lock:?}"
    );
    let beside = |d: f64| {
        let theta = lock - d;
        // The Euler rates of w (world axes): w = e_z psi' + R_z e_y theta' + R_z R_y e_x phi'.
        let (rz, ry) = (rot_z(psi), rot_y(theta));
        let axes = [
            Vector::<3>::z(),
            rz * Vector::<3>::y(),
            rz * ry * Vector::<3>::x(),
        ];
        let qd = Matrix::<3, 3>::from_columns(&axes).try_inverse().unwrap() * w;
        let y = Vector::<6>::new(psi, theta, phi, qd[0], qd[1], qd[2]);
        Dopri5::new(opts.clone()).solve(&e, 0.0, y, 4.0, &[])
    };
    let near = beside(1e-4).unwrap();
    assert!(
        near.stats.n_steps > 10 * ball_steps,
        "{} against {ball_steps}",
        near.stats.n_steps
    );
    assert!(beside(1e-6).is_err());
}

/// Two bodies on ball joints (a double spherical pendulum, the lower bar's joint at the
/// upper bar's end, off its axis) with a damped revolute wheel on the lower bar:
/// and generalised forces on a ball coordinate (`moment = B^T tau / 4` in the recursion):
/// the articulated-body recursion through two 3x3 joints, against the same tree's
/// composite-rigid-body and Newton-Euler form and against Kane's (`mass_matrix`).
#[derive(Debug, Mechanism)]
#[mechanism(spatial, inverse_dynamics)]
#[gravity(0.0, 0.0, -g)]
#[body(upper, joint = ball(a1, a2, a3), com = [0.0, 0.02, -l / 2.0], mass = m1,
       inertia = [[0.05, 0.003, 0.0], [0.003, 0.045, 0.002], [0.0, 0.002, 0.01]])]
#[body(lower, parent = upper, joint = ball(b1, b2, b3), at = [0.03, 0.0, -l],
       com = [0.01, 0.0, -l / 2.0], mass = m2, inertia = diag(0.03, 0.032, 0.005))]
#[body(wheel, parent = lower, joint = revolute(c, z), at = [0.0, 0.0, -l], mass = m3,
       inertia = diag(0.002, 0.002, 0.004))]
#[generalized_force(spin, along = c, value = -0.3 * der(c))]
#[generalized_force(twist, along = b2, value = -0.2 * der(b2) + 0.1 * a1)]
pub struct BallChain {
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub l: f64,
    pub g: f64,
}

/// [`BallChain`] by Kane's projections.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(upper, joint = ball(a1, a2, a3), com = [0.0, 0.02, -l / 2.0], mass = m1,
       inertia = [[0.05, 0.003, 0.0], [0.003, 0.045, 0.002], [0.0, 0.002, 0.01]])]
#[body(lower, parent = upper, joint = ball(b1, b2, b3), at = [0.03, 0.0, -l],
       com = [0.01, 0.0, -l / 2.0], mass = m2, inertia = diag(0.03, 0.032, 0.005))]
#[body(wheel, parent = lower, joint = revolute(c, z), at = [0.0, 0.0, -l], mass = m3,
       inertia = diag(0.002, 0.002, 0.004))]
#[generalized_force(spin, along = c, value = -0.3 * der(c))]
#[generalized_force(twist, along = b2, value = -0.2 * der(b2) + 0.1 * a1)]
pub struct BallChainKane {
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn ball_chain_recursions_equal_kanes_form() {
    let p = BallChain {
        m1: 1.2,
        m2: 0.8,
        m3: 0.3,
        l: 0.7,
        g: 9.81,
    };
    let k = BallChainKane {
        m1: 1.2,
        m2: 0.8,
        m3: 0.3,
        l: 0.7,
        g: 9.81,
    };
    assert!(BallChain::GENERATED.parts.contains(&"articulated_body"));
    let states: [([f64; 7], [f64; 7]); 3] = [
        (
            [0.3, -0.2, 0.5, -0.6, 0.4, 0.1, 1.0],
            [0.4, 1.1, -0.7, 0.9, -0.3, 1.2, 5.0],
        ),
        (
            [-0.9, 0.1, 0.35, 0.99, -0.05, 0.02, -2.0],
            [-2.0, 0.3, 1.5, 0.1, 2.2, -0.8, -3.0],
        ),
        ([0.0; 7], [0.0; 7]),
    ];
    for (q, qd) in states {
        let (q, qd) = (Vector::<7>::from(q), Vector::<7>::from(qd));
        let (m, m_kane): (Matrix<7, 7>, Matrix<7, 7>) = (
            p.mass_matrix(0.0, &q).unwrap(),
            k.mass_matrix(0.0, &q).unwrap(),
        );
        assert_relative_eq!(m, m_kane, epsilon = 1e-13, max_relative = 1e-12);
        let f = p.forces(0.0, &q, &qd).unwrap();
        assert_relative_eq!(
            f,
            k.forces(0.0, &q, &qd).unwrap(),
            epsilon = 1e-12,
            max_relative = 1e-12
        );
        let (a, a_kane) = (
            p.acceleration(0.0, &q, &qd).unwrap(),
            k.acceleration(0.0, &q, &qd).unwrap(),
        );
        assert!(
            (a - a_kane).norm() <= 1e-12 * a.norm().max(1.0),
            "{a:?}\n{a_kane:?}"
        );
        // Inverse dynamics by Newton-Euler: M qdd - f, zero at the motion's own qdd.
        let probe = Vector::<7>::from_fn(|i, _| 0.3 * i as f64 - 1.0);
        let id = p.inverse_dynamics(0.0, &q, &qd, &probe).unwrap();
        assert!((id - (m * probe - f)).norm() <= 1e-12 * (m.norm() * probe.norm() + f.norm()));
        assert!(p.inverse_dynamics(0.0, &q, &qd, &a).unwrap().norm() <= 1e-12 * f.norm().max(1.0));
    }
}
