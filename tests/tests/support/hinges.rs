#![allow(dead_code)] // each test file uses its own part
//! An independent reference for spatial joint trees (hunt_big tests): every joint split into
//! elementary hinges about one axis of the parent hinge's frame, the mass matrix from the
//! bodies' Jacobians and the generalised forces from the velocity-product accelerations
//! (Kane's form), written without the derive's recursions.

use mbd::nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// One elementary hinge of the reference: a rotation about axis `axis` (0, 1, 2 = x, y, z)
/// of its parent hinge's frame at `at` (parent frame), carrying `mass` (zero for the
/// intermediate hinges of a multi-axis joint) with its centre at `com` (own frame).
pub struct Hinge {
    pub parent: Option<usize>,
    pub at: [f64; 3],
    pub axis: usize,
    pub mass: f64,
    pub com: [f64; 3],
    pub inertia: Matrix3<f64>,
    pub coord: String,
}

/// A joint of the model as elementary hinges: spherical `rot_z(a) rot_y(b) rot_x(c)`,
/// universal `rot_x(a) rot_y(b)`, revolute about one axis; the body is on the last one.
pub fn joint(
    hinges: &mut Vec<Hinge>,
    parent: Option<usize>,
    at: [f64; 3],
    axes: &[(usize, String)],
    mass: f64,
    com: [f64; 3],
    inertia: Matrix3<f64>,
) -> usize {
    let mut p = parent;
    for (k, (axis, coord)) in axes.iter().enumerate() {
        let last = k + 1 == axes.len();
        hinges.push(Hinge {
            parent: p,
            at: if k == 0 { at } else { [0.0; 3] },
            axis: *axis,
            mass: if last { mass } else { 0.0 },
            com: if last { com } else { [0.0; 3] },
            inertia: if last { inertia } else { Matrix3::zeros() },
            coord: coord.clone(),
        });
        p = Some(hinges.len() - 1);
    }
    hinges.len() - 1
}

pub fn rot(axis: usize, q: f64) -> Matrix3<f64> {
    let (s, c) = q.sin_cos();
    match axis {
        0 => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        1 => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// Every hinge frame's world rotation `r`, origin `o`, angular velocity `w`, origin
/// velocity `v`, and with `qdd = 0` the accelerations `al` (angular), `a` (origin); `u` the
/// hinge's world axis.
pub struct Frames {
    pub r: Vec<Matrix3<f64>>,
    pub o: Vec<Vector3<f64>>,
    pub w: Vec<Vector3<f64>>,
    pub v: Vec<Vector3<f64>>,
    pub al: Vec<Vector3<f64>>,
    pub a: Vec<Vector3<f64>>,
    pub u: Vec<Vector3<f64>>,
}

/// The forward pass from the ground, hinge by hinge.
pub fn frames(h: &[Hinge], q: &[f64], qd: &[f64]) -> Frames {
    let n = h.len();
    let z = vec![Vector3::zeros(); n];
    let mut f = Frames {
        r: vec![Matrix3::identity(); n],
        o: z.clone(),
        w: z.clone(),
        v: z.clone(),
        al: z.clone(),
        a: z.clone(),
        u: z,
    };
    for i in 0..n {
        let zero = Vector3::zeros();
        let (rp, op, wp, vp, alp, ap) = match h[i].parent {
            Some(p) => (f.r[p], f.o[p], f.w[p], f.v[p], f.al[p], f.a[p]),
            None => (Matrix3::identity(), zero, zero, zero, zero, zero),
        };
        let r = rp * Vector3::from(h[i].at);
        f.o[i] = op + r;
        f.u[i] = rp.column(h[i].axis).into_owned();
        f.r[i] = rp * rot(h[i].axis, q[i]);
        f.w[i] = wp + f.u[i] * qd[i];
        f.v[i] = vp + wp.cross(&r);
        f.al[i] = alp + wp.cross(&f.u[i]) * qd[i];
        f.a[i] = ap + alp.cross(&r) + wp.cross(&wp.cross(&r));
    }
    f
}

/// The reference: `M` and `f` of `M qdd = f` (gravity `-g z`) at hinge coordinates `q`,
/// `qd`, and `T + V`. Each hinge's world axis `u_j` at its origin `o_j`; a body's mass
/// centre Jacobian column for an ancestor hinge `j` is `u_j x (c - o_j)`, its angular one
/// `u_j`; with `qdd = 0` the forward pass gives the velocity-product accelerations `a0`,
/// `alpha0`, and `f_j = sum_b J_j . (m g - m a0) - Jw_j . (I alpha0 + w x I w)`.
pub fn reference(h: &[Hinge], g: f64, q: &[f64], qd: &[f64]) -> (DMatrix<f64>, DVector<f64>, f64) {
    let n = h.len();
    let Frames {
        r: rot_w,
        o,
        w,
        v,
        al,
        a,
        u,
    } = frames(h, q, qd);
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

/// `coordinates` (a model's order) mapped onto the hinges: the hinge index of each.
pub fn order(h: &[Hinge], coordinates: &[&str]) -> Vec<usize> {
    coordinates
        .iter()
        .map(|c| {
            h.iter()
                .position(|x| x.coord == *c)
                .expect("a coordinate of the model")
        })
        .collect()
}

/// A model-ordered vector in hinge order.
pub fn to_hinges(perm: &[usize], x: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; x.len()];
    for (k, &i) in perm.iter().enumerate() {
        out[i] = x[k];
    }
    out
}

/// The reference's accelerations at a model-ordered state, in the model's order.
pub fn accelerations(h: &[Hinge], perm: &[usize], g: f64, q: &[f64], qd: &[f64]) -> Vec<f64> {
    let (m, f, _) = reference(h, g, &to_hinges(perm, q), &to_hinges(perm, qd));
    let qdd = m
        .cholesky()
        .expect("a positive definite mass matrix")
        .solve(&f);
    perm.iter().map(|&i| qdd[i]).collect()
}
