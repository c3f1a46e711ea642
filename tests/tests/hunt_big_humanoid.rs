//! Hunting big-model defects: a 30-dof spatial humanoid-like tree (a torso on a spherical
//! joint on a stand, a head, two arms and two legs of spherical, revolute and universal
//! joints, full inertia tensors and offset mass centres), its articulated-body recursion
//! against an independent reference written here: every joint split into elementary hinges,
//! the mass matrix from the bodies' Jacobians and the bias from the velocity-product
//! accelerations (Kane's form, `M qdd = sum J^T (F - m a0)`), and the energy of a long
//! tumbling run from that reference's own `T + V`.

use mbd::integrate::{Dop853, Integrator};
use mbd::nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use mbd::prelude::*;

#[path = "support/humanoid.rs"]
mod humanoid;
use humanoid::Humanoid;

/// One elementary hinge of the reference: a rotation about axis `axis` (0, 1, 2 = x, y, z)
/// of its parent hinge's frame at `at` (parent frame), carrying `mass` (zero for the
/// intermediate hinges of a multi-axis joint) with its centre at `com` (own frame).
struct Hinge {
    parent: Option<usize>,
    at: [f64; 3],
    axis: usize,
    mass: f64,
    com: [f64; 3],
    inertia: Matrix3<f64>,
    coord: &'static str,
}

/// A joint of the model as elementary hinges: spherical `rot_z(a) rot_y(b) rot_x(c)`,
/// universal `rot_x(a) rot_y(b)`, revolute about one axis; the body is on the last one.
#[allow(clippy::too_many_arguments)]
fn joint(
    hinges: &mut Vec<Hinge>,
    parent: Option<usize>,
    at: [f64; 3],
    axes: &[(usize, &'static str)],
    mass: f64,
    com: [f64; 3],
    inertia: Matrix3<f64>,
) -> usize {
    let mut p = parent;
    for (k, &(axis, coord)) in axes.iter().enumerate() {
        let last = k + 1 == axes.len();
        hinges.push(Hinge {
            parent: p,
            at: if k == 0 { at } else { [0.0; 3] },
            axis,
            mass: if last { mass } else { 0.0 },
            com: if last { com } else { [0.0; 3] },
            inertia: if last { inertia } else { Matrix3::zeros() },
            coord,
        });
        p = Some(hinges.len() - 1);
    }
    hinges.len() - 1
}

/// The humanoid above, hinge by hinge (the same numbers, typed again).
fn hinges() -> Vec<Hinge> {
    let d = |a: f64, b: f64, c: f64| Matrix3::from_diagonal(&Vector3::new(a, b, c));
    let (x, y, z) = (0, 1, 2);
    let mut h = Vec::new();
    let torso_i = Matrix3::new(0.6, 0.01, 0.02, 0.01, 0.5, 0.03, 0.02, 0.03, 0.2);
    let torso = joint(
        &mut h,
        None,
        [0.0, 0.0, 1.0],
        &[(z, "t1"), (y, "t2"), (x, "t3")],
        20.0,
        [0.0, 0.01, 0.25],
        torso_i,
    );
    let sph = |a: &'static str, b: &'static str, c: &'static str| [(z, a), (y, b), (x, c)];
    joint(
        &mut h,
        Some(torso),
        [0.0, 0.0, 0.5],
        &sph("h1", "h2", "h3"),
        5.0,
        [0.01, 0.0, 0.1],
        d(0.03, 0.03, 0.02),
    );
    type Names = [&'static str; 6];
    let arms: [(f64, Names); 2] = [
        (1.0, ["sl1", "sl2", "sl3", "el", "wl1", "wl2"]),
        (-1.0, ["sr1", "sr2", "sr3", "er", "wr1", "wr2"]),
    ];
    for (side, n) in arms {
        let arm = joint(
            &mut h,
            Some(torso),
            [0.0, 0.2 * side, 0.45],
            &sph(n[0], n[1], n[2]),
            2.0,
            [0.0, 0.02 * side, -0.15],
            d(0.02, 0.02, 0.004),
        );
        let fore = joint(
            &mut h,
            Some(arm),
            [0.0, 0.0, -0.3],
            &[(y, n[3])],
            1.2,
            [0.0, 0.0, -0.12],
            d(0.01, 0.01, 0.002),
        );
        joint(
            &mut h,
            Some(fore),
            [0.0, 0.0, -0.25],
            &[(x, n[4]), (y, n[5])],
            0.4,
            [0.01, 0.0, -0.05],
            d(0.001, 0.0012, 0.0005),
        );
    }
    let legs: [(f64, Names); 2] = [
        (1.0, ["hl1", "hl2", "hl3", "kl", "al1", "al2"]),
        (-1.0, ["hr1", "hr2", "hr3", "kr", "ar1", "ar2"]),
    ];
    for (side, n) in legs {
        let thigh = joint(
            &mut h,
            Some(torso),
            [0.0, 0.1 * side, -0.05],
            &sph(n[0], n[1], n[2]),
            8.0,
            [0.0, 0.0, -0.2],
            d(0.15, 0.15, 0.03),
        );
        let shank = joint(
            &mut h,
            Some(thigh),
            [0.0, 0.0, -0.45],
            &[(y, n[3])],
            3.5,
            [0.0, 0.0, -0.2],
            d(0.05, 0.05, 0.006),
        );
        joint(
            &mut h,
            Some(shank),
            [0.0, 0.0, -0.42],
            &[(x, n[4]), (y, n[5])],
            1.0,
            [0.05, 0.0, -0.04],
            d(0.002, 0.005, 0.005),
        );
    }
    h
}

fn rot(axis: usize, q: f64) -> Matrix3<f64> {
    let (s, c) = q.sin_cos();
    match axis {
        0 => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        1 => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// The reference: `M` and `f` of `M qdd = f` (gravity `-g z`) at hinge coordinates `q`,
/// `qd`, and `T + V`. Each hinge's world axis `u_j` at its origin `o_j`; a body's mass
/// centre Jacobian column for an ancestor hinge `j` is `u_j x (c - o_j)`, its angular one
/// `u_j`; with `qdd = 0` the forward pass gives the velocity-product accelerations `a0`,
/// `alpha0`, and `f_j = sum_b J_j . (m g - m a0) - Jw_j . (I alpha0 + w x I w)`.
fn reference(h: &[Hinge], g: f64, q: &[f64], qd: &[f64]) -> (DMatrix<f64>, DVector<f64>, f64) {
    let n = h.len();
    let mut rot_w = vec![Matrix3::identity(); n];
    let (mut o, mut w, mut v, mut al, mut a) = (
        vec![Vector3::zeros(); n],
        vec![Vector3::zeros(); n],
        vec![Vector3::zeros(); n],
        vec![Vector3::zeros(); n],
        vec![Vector3::zeros(); n],
    );
    let mut u = vec![Vector3::zeros(); n];
    for i in 0..n {
        let (rp, op, wp, vp, alp, ap) = match h[i].parent {
            Some(p) => (rot_w[p], o[p], w[p], v[p], al[p], a[p]),
            None => (
                Matrix3::identity(),
                Vector3::zeros(),
                Vector3::zeros(),
                Vector3::zeros(),
                Vector3::zeros(),
                Vector3::zeros(),
            ),
        };
        let r = rp * Vector3::from(h[i].at);
        o[i] = op + r;
        u[i] = rp.column(h[i].axis).into_owned();
        rot_w[i] = rp * rot(h[i].axis, q[i]);
        w[i] = wp + u[i] * qd[i];
        v[i] = vp + wp.cross(&r);
        al[i] = alp + wp.cross(&u[i]) * qd[i];
        a[i] = ap + alp.cross(&r) + wp.cross(&wp.cross(&r));
    }
    let ancestors = |mut i: usize| {
        let mut out = vec![i];
        while let Some(p) = h[i].parent {
            out.push(p);
            i = p;
        }
        out
    };
    let mut mass = DMatrix::zeros(n, n);
    let mut f = DVector::zeros(n);
    let mut energy = 0.0;
    let grav = Vector3::new(0.0, 0.0, -g);
    for b in (0..n).filter(|&b| h[b].mass > 0.0) {
        let d = rot_w[b] * Vector3::from(h[b].com);
        let c = o[b] + d;
        let iw = rot_w[b] * h[b].inertia * rot_w[b].transpose();
        let vc = v[b] + w[b].cross(&d);
        let a0 = a[b] + al[b].cross(&d) + w[b].cross(&w[b].cross(&d));
        let lin = h[b].mass * (grav - a0);
        let ang = -(iw * al[b] + w[b].cross(&(iw * w[b])));
        energy += 0.5 * h[b].mass * vc.norm_squared() + 0.5 * w[b].dot(&(iw * w[b]))
            - h[b].mass * grav.dot(&c);
        let anc = ancestors(b);
        let jv: Vec<Vector3<f64>> = anc.iter().map(|&j| u[j].cross(&(c - o[j]))).collect();
        for (k, &j) in anc.iter().enumerate() {
            f[j] += jv[k].dot(&lin) + u[j].dot(&ang);
            for (l, &i) in anc.iter().enumerate() {
                mass[(j, i)] += h[b].mass * jv[k].dot(&jv[l]) + u[j].dot(&(iw * u[i]));
            }
        }
    }
    (mass, f, energy)
}

/// The model's coordinate order mapped onto the reference's hinges.
fn order(h: &[Hinge]) -> Vec<usize> {
    Humanoid::COORDINATES
        .iter()
        .map(|c| {
            h.iter()
                .position(|x| x.coord == *c)
                .expect("a coordinate of the model")
        })
        .collect()
}

fn to_hinges(perm: &[usize], x: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; x.len()];
    for (k, &i) in perm.iter().enumerate() {
        out[i] = x[k];
    }
    out
}

/// A spread of states: every Euler pitch inside `(-1, 1)` rad, away from gimbal lock.
fn state(seed: f64) -> (Vector<30>, Vector<30>) {
    let q = Vector::<30>::from_fn(|i, _| 0.9 * (1.7 * i as f64 + seed).sin());
    let qd = Vector::<30>::from_fn(|i, _| 2.5 * (0.8 * i as f64 - 2.0 * seed).cos());
    (q, qd)
}

#[test]
fn a_thirty_dof_humanoid_tree_equals_its_hand_written_jacobian_form() {
    assert_eq!(Humanoid::COORDINATES.len(), 30);
    assert!(Humanoid::GENERATED.parts.contains(&"articulated_body"));
    let (p, h) = (Humanoid { g: 9.81 }, hinges());
    let perm = order(&h);
    for seed in [0.0, 0.7, 1.9, 3.1] {
        let (q, qd) = state(seed);
        let acc = p.acceleration(0.0, &q, &qd).unwrap();
        let (qh, qdh) = (
            to_hinges(&perm, q.as_slice()),
            to_hinges(&perm, qd.as_slice()),
        );
        let (m, f, _) = reference(&h, p.g, &qh, &qdh);
        let want = m
            .clone()
            .cholesky()
            .expect("a positive definite mass matrix")
            .solve(&f);
        let scale = want.amax();
        for (k, &i) in perm.iter().enumerate() {
            assert!(
                (acc[k] - want[i]).abs() < 1e-10 * scale,
                "seed {seed}: {} = {} against {} by hand",
                Humanoid::COORDINATES[k],
                acc[k],
                want[i]
            );
        }
        // The model's own mass matrix is the reference's, entry by entry.
        let mm = p.mass_matrix(0.0, &q);
        for (k, &i) in perm.iter().enumerate() {
            for (l, &j) in perm.iter().enumerate() {
                assert!(
                    (mm[(k, l)] - m[(i, j)]).abs() < 1e-12 * m.amax(),
                    "M[{k},{l}]"
                );
            }
        }
    }
}

#[test]
fn the_tumbling_humanoid_keeps_the_energy_of_the_hand_written_reference() {
    let (p, h) = (Humanoid { g: 9.81 }, hinges());
    let perm = order(&h);
    // Moderate angles and rates: the limbs swing through large motions without reaching
    // an Euler pitch of pi/2 in the second run.
    let q0 = Vector::<30>::from_fn(|i, _| 0.3 * (1.7 * i as f64).sin());
    let qd0 = Vector::<30>::from_fn(|i, _| 1.0 * (0.8 * i as f64).cos());
    let mut y0 = Vector::<60>::zeros();
    y0.fixed_rows_mut::<30>(0).copy_from(&q0);
    y0.fixed_rows_mut::<30>(30).copy_from(&qd0);
    let energy = |y: &Vector<60>| {
        let (q, qd) = (y.fixed_rows::<30>(0), y.fixed_rows::<30>(30));
        let qh = to_hinges(&perm, q.as_slice());
        let qdh = to_hinges(&perm, qd.as_slice());
        reference(&h, p.g, &qh, &qdh).2
    };
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let sol = Dop853::new(opts).solve(&p, 0.0, y0, 1.0, &[]).unwrap();
    let y1 = sol.last().1;
    let (e0, e1) = (energy(&y0), energy(y1));
    assert!((e1 - e0).abs() < 1e-8 * e0.abs(), "energy {e0} -> {e1}");
    assert!((y1 - y0).fixed_rows::<30>(0).amax() > 0.3, "it moved");
}
