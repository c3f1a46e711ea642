//! The reference of the floating-base tests (`floating_tree`, `floating_humanoid`), written
//! without the derive: Kane's equations in the generalised speeds `u = (p', w, q_h')` (`w`
//! the base's angular velocity in world axes, `q_h` the hinges), each body's mass-centre and
//! angular Jacobians written from the joint axes, the velocity-product accelerations from a
//! forward pass at `u' = 0`: `M_u = sum m Jv^T Jv + Jw^T I Jw`,
//! `f_u = sum Jv^T m (g - a0) - Jw^T (I al0 + w x I w)`. The base's `u'` gives the free
//! joint's accelerations by `sigma'' = (B R^T w' + B' W) / 4` (`W = R^T w`, body axes;
//! `(R^T)' w = -W x W = 0`), `B = (1 - s2) 1 + 2 [s]x + 2 s s^T` (`sigma' = B W / 4`).
#![allow(dead_code, reason = "each test file uses the part it needs")]

use mbd::nalgebra::{DMatrix, DVector, Matrix3, Vector3};

type M3 = Matrix3<f64>;
type V3 = Vector3<f64>;

/// One body of the reference: its parent (`None`: the base, on the free joint), hinge axis
/// (0, 1, 2 = x, y, z of the parent's frame) and coordinate index in the model.
pub struct Part {
    pub parent: Option<usize>,
    pub axis: usize,
    pub coord: usize,
    pub at: [f64; 3],
    pub com: [f64; 3],
    pub mass: f64,
    pub inertia: M3,
}

pub fn skew(a: &V3) -> M3 {
    M3::new(0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0)
}

pub fn rot(axis: usize, q: f64) -> M3 {
    let (s, c) = q.sin_cos();
    match axis {
        0 => M3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        1 => M3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => M3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// Modified Rodrigues parameters: `R = 1 + (8 S^2 + 4 (1 - s2) S) / (1 + s2)^2`.
pub fn mrp_rotation(s: &V3) -> M3 {
    let s2 = s.norm_squared();
    let x = skew(s);
    M3::identity() + (8.0 * x * x + 4.0 * (1.0 - s2) * x) / (1.0 + s2).powi(2)
}

/// `sigma' = B W / 4`, `B = (1 - s2) 1 + 2 [s]x + 2 s s^T`, `B B^T = (1 + s2)^2 1`.
pub fn mrp_b(s: &V3) -> M3 {
    (1.0 - s.norm_squared()) * M3::identity() + 2.0 * skew(s) + 2.0 * s * s.transpose()
}

pub fn mrp_b_dot(s: &V3, sd: &V3) -> M3 {
    -2.0 * s.dot(sd) * M3::identity()
        + 2.0 * skew(sd)
        + 2.0 * (sd * s.transpose() + s * sd.transpose())
}

/// Each body's world rotation, joint origin, hinge axis (world), angular velocity and
/// origin velocity, and at `u' = 0` its angular and origin accelerations.
pub struct Pass {
    pub r: Vec<M3>,
    pub o: Vec<V3>,
    pub axis: Vec<V3>,
    pub w: Vec<V3>,
    pub v: Vec<V3>,
    pub al: Vec<V3>,
    pub a: Vec<V3>,
}

pub fn pass(parts: &[Part], q: &[f64], qd: &[f64]) -> Pass {
    let n = parts.len();
    let z = vec![V3::zeros(); n];
    let mut f = Pass {
        r: vec![M3::identity(); n],
        o: z.clone(),
        axis: z.clone(),
        w: z.clone(),
        v: z.clone(),
        al: z.clone(),
        a: z,
    };
    let s = V3::new(q[3], q[4], q[5]);
    let sd = V3::new(qd[3], qd[4], qd[5]);
    f.r[0] = mrp_rotation(&s);
    f.o[0] = V3::from(parts[0].at) + V3::new(q[0], q[1], q[2]);
    f.v[0] = V3::new(qd[0], qd[1], qd[2]);
    // W = 4 B^T sigma' / (1 + s2)^2 (body axes); w = R W.
    f.w[0] = f.r[0] * (4.0 * mrp_b(&s).transpose() * sd / (1.0 + s.norm_squared()).powi(2));
    for i in 1..n {
        let p = parts[i].parent.expect("only the base is on the free joint");
        let arm = f.r[p] * V3::from(parts[i].at);
        f.o[i] = f.o[p] + arm;
        f.axis[i] = f.r[p].column(parts[i].axis).into_owned();
        f.r[i] = f.r[p] * rot(parts[i].axis, q[parts[i].coord]);
        let rate = qd[parts[i].coord];
        f.w[i] = f.w[p] + f.axis[i] * rate;
        f.v[i] = f.v[p] + f.w[p].cross(&arm);
        f.al[i] = f.al[p] + f.w[p].cross(&f.axis[i]) * rate;
        f.a[i] = f.a[p] + f.al[p].cross(&arm) + f.w[p].cross(&f.w[p].cross(&arm));
    }
    f
}

pub fn ancestors(parts: &[Part], mut i: usize) -> Vec<usize> {
    let mut out = vec![i];
    while let Some(p) = parts[i].parent {
        out.push(p);
        i = p;
    }
    out
}

/// Kane's equations in `u`, solved; then `q''` in the model's coordinates (the base's six
/// first).
pub fn reference(parts: &[Part], g: f64, q: &[f64], qd: &[f64]) -> Vec<f64> {
    let f = pass(parts, q, qd);
    let n = q.len();
    let mut mass = DMatrix::<f64>::zeros(n, n);
    let mut force = DVector::<f64>::zeros(n);
    let grav = V3::new(0.0, 0.0, -g);
    for (b, part) in parts.iter().enumerate().filter(|(_, p)| p.mass > 0.0) {
        let d = f.r[b] * V3::from(part.com);
        let c = f.o[b] + d;
        let iw = f.r[b] * part.inertia * f.r[b].transpose();
        let a0 = f.a[b] + f.al[b].cross(&d) + f.w[b].cross(&f.w[b].cross(&d));
        let lin = part.mass * (grav - a0);
        let ang = -(iw * f.al[b] + f.w[b].cross(&(iw * f.w[b])));
        // Columns (linear, angular) of this body's Jacobians.
        let mut cols: Vec<(usize, V3, V3)> = Vec::new();
        for k in 0..3 {
            let e = V3::ith(k, 1.0);
            cols.push((k, e, V3::zeros()));
            cols.push((3 + k, e.cross(&(c - f.o[0])), e));
        }
        for &j in ancestors(parts, b).iter().filter(|&&j| j > 0) {
            let u = f.axis[j];
            cols.push((parts[j].coord, u.cross(&(c - f.o[j])), u));
        }
        for &(j, jv, jw) in &cols {
            force[j] += jv.dot(&lin) + jw.dot(&ang);
            for &(k, kv, kw) in &cols {
                mass[(j, k)] += part.mass * jv.dot(&kv) + jw.dot(&(iw * kw));
            }
        }
    }
    let ud = mass.cholesky().expect("positive definite").solve(&force);
    let s = V3::new(q[3], q[4], q[5]);
    let sd = V3::new(qd[3], qd[4], qd[5]);
    let rt = f.r[0].transpose();
    let w_body = rt * f.w[0];
    let wd = V3::new(ud[3], ud[4], ud[5]);
    let sdd = (mrp_b(&s) * rt * wd + mrp_b_dot(&s, &sd) * w_body) / 4.0;
    let mut out: Vec<f64> = ud.iter().copied().collect();
    out[3..6].copy_from_slice(sdd.as_slice());
    out
}

/// Total linear and angular momentum (about the world origin) and kinetic energy, by hand.
pub fn momenta(parts: &[Part], q: &[f64], qd: &[f64]) -> (V3, V3, f64) {
    let f = pass(parts, q, qd);
    let (mut lin, mut ang, mut t) = (V3::zeros(), V3::zeros(), 0.0);
    for (b, part) in parts.iter().enumerate() {
        let d = f.r[b] * V3::from(part.com);
        let c = f.o[b] + d;
        let vc = f.v[b] + f.w[b].cross(&d);
        let iw = f.r[b] * part.inertia * f.r[b].transpose();
        lin += part.mass * vc;
        ang += part.mass * c.cross(&vc) + iw * f.w[b];
        t += 0.5 * part.mass * vc.norm_squared() + 0.5 * f.w[b].dot(&(iw * f.w[b]));
    }
    (lin, ang, t)
}

/// A joint of elementary hinges (`axes`: axis and model coordinate index), massless frames
/// between them, the body on the last: a spherical joint `rot_z rot_y rot_x`, a universal
/// `rot_x rot_y`. Returns the body's index.
pub fn hinges(
    parts: &mut Vec<Part>,
    parent: usize,
    at: [f64; 3],
    axes: &[(usize, usize)],
    (mass, com, inertia): (f64, [f64; 3], M3),
) -> usize {
    let mut p = parent;
    for (k, &(axis, coord)) in axes.iter().enumerate() {
        let last = k + 1 == axes.len();
        parts.push(Part {
            parent: Some(p),
            axis,
            coord,
            at: if k == 0 { at } else { [0.0; 3] },
            mass: if last { mass } else { 0.0 },
            com: if last { com } else { [0.0; 3] },
            inertia: if last { inertia } else { M3::zeros() },
        });
        p = parts.len() - 1;
    }
    p
}
