//! Charts of the rotation group that the integrators re-centre on the fly.
//!
//! A ball joint (`joint = ball(a, b, c)`, and a free joint's rotation,
//! `joint = free(x, y, z, a, b, c)`) has the modified Rodrigues parameters
//! `sigma = tan(phi / 4) n` of its rotation (by `phi` about the unit `n`) as coordinates:
//! regular everywhere but at the full turn `phi = 2π`, where `|sigma|` grows without bound.
//! The same rotation has the *shadow* parameters `-sigma / |sigma|^2` (the rotation by
//! `phi - 2π` about `n`), so switching to them whenever `|sigma| > 1` (`phi > π`) keeps every
//! ball joint within `|sigma| <= 1`. A generated model does it in
//! [`crate::OdeSystem::project`], after each accepted step (generalized-alpha, which does not
//! project, through [`shadow_motion`] on the joints of `Mechanism::rotation_charts`); the
//! dense output interpolates the step in the chart it was computed in. The orientation, the
//! angular velocity and so every output and the energy are the same on both sides of the
//! switch.

use crate::model::{Matrix, Vector};

/// `[a]x`, the cross-product matrix.
fn skew(a: &Vector<3>) -> Matrix<3, 3> {
    Matrix::<3, 3>::new(0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0)
}

/// The rotation (child to parent) of the parameters `sigma`:
/// `R = 1 + (8 [sigma]x^2 + 4 (1 - s2) [sigma]x) / (1 + s2)^2`, `s2 = |sigma|^2`.
pub fn rotation(sigma: &Vector<3>) -> Matrix<3, 3> {
    let s2 = sigma.norm_squared();
    let x = skew(sigma);
    Matrix::<3, 3>::identity() + (8.0 * x * x + 4.0 * (1.0 - s2) * x) / (1.0 + s2).powi(2)
}

/// The parameters of a rotation matrix, the set with `|sigma| <= 1`: `sigma = q_v / (1 + q_0)`
/// from the unit quaternion `(q_0 >= 0, q_v)`, which is found from the largest of its
/// components (Shepperd's method), so it is accurate at every angle. For a joint's initial
/// position from a rotation one knows.
pub fn parameters(r: &Matrix<3, 3>) -> Vector<3> {
    let tr = r.trace();
    let q = if tr > 0.0 {
        let s = 2.0 * (1.0 + tr).sqrt();
        let v = Vector::<3>::new(
            r[(2, 1)] - r[(1, 2)],
            r[(0, 2)] - r[(2, 0)],
            r[(1, 0)] - r[(0, 1)],
        );
        (0.25 * s, v / s)
    } else {
        let i = (0..3)
            .max_by(|&a, &b| r[(a, a)].total_cmp(&r[(b, b)]))
            .unwrap_or(0);
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let s = 2.0 * (1.0 + r[(i, i)] - r[(j, j)] - r[(k, k)]).sqrt();
        let mut v = Vector::<3>::zeros();
        v[i] = 0.25 * s;
        v[j] = (r[(j, i)] + r[(i, j)]) / s;
        v[k] = (r[(k, i)] + r[(i, k)]) / s;
        ((r[(k, j)] - r[(j, k)]) / s, v)
    };
    let (q0, v) = if q.0 < 0.0 { (-q.0, -q.1) } else { q };
    v / (1.0 + q0)
}

/// The parameters' rates for the joint's angular velocity `w` in the child's frame:
/// `sigma' = B w / 4`, `B = (1 - s2) 1 + 2 [sigma]x + 2 sigma sigma^T`. For a joint's
/// initial velocity (`w = R^T w_world` for an angular velocity in the parent's axes).
pub fn rates(sigma: &Vector<3>, w: &Vector<3>) -> Vector<3> {
    let b = (1.0 - sigma.norm_squared()) * Matrix::<3, 3>::identity()
        + 2.0 * skew(sigma)
        + 2.0 * sigma * sigma.transpose();
    b * w / 4.0
}

/// Switch every ball joint whose parameters left the unit ball to its shadow set.
/// `balls[k]` holds the state indices of joint `k`'s three coordinates; their rates are at
/// the same indices plus `n`. The rates follow the map's derivative:
/// `sigma_s' = -sigma' / s2 + 2 (sigma . sigma') sigma / s2^2`, `s2 = |sigma|^2`.
pub fn shadow<const D: usize>(y: &mut Vector<D>, n: usize, balls: &[[usize; 3]]) {
    for ball in balls {
        let sigma = ball.map(|i| y[i]);
        let s2: f64 = sigma.iter().map(|s| s * s).sum();
        if !(s2 > 1.0 && s2.is_finite()) {
            continue;
        }
        let rate = ball.map(|i| y[n + i]);
        let sd: f64 = sigma.iter().zip(&rate).map(|(s, r)| s * r).sum();
        for k in 0..3 {
            y[ball[k]] = -sigma[k] / s2;
            y[n + ball[k]] = -rate[k] / s2 + 2.0 * sd * sigma[k] / (s2 * s2);
        }
    }
}

/// [`shadow`] for a second-order integrator's state: positions `q`, rates `qd` and any
/// number of acceleration-like vectors `acc` (generalized-alpha's `qdd` and its algorithmic
/// acceleration), each joint `k` at the indices `balls[k]` of all of them. An acceleration
/// follows the map's second derivative: `sigma_s'' = J sigma'' + J'(sigma') sigma'`,
/// `J v = -v / s2 + 2 (sigma . v) sigma / s2^2`,
/// `J'(v) v = (4 (sigma . v) v + 2 |v|^2 sigma) / s2^2 - 8 (sigma . v)^2 sigma / s2^3`.
/// Returns whether any joint switched.
pub fn shadow_motion<const N: usize>(
    q: &mut Vector<N>,
    qd: &mut Vector<N>,
    acc: &mut [&mut Vector<N>],
    balls: &[[usize; 3]],
) -> bool {
    let mut switched = false;
    for ball in balls {
        let get = |v: &Vector<N>| Vector::<3>::new(v[ball[0]], v[ball[1]], v[ball[2]]);
        let (sigma, rate) = (get(q), get(qd));
        let s2 = sigma.norm_squared();
        if !(s2 > 1.0 && s2.is_finite()) {
            continue;
        }
        switched = true;
        let sd = sigma.dot(&rate);
        let j = |v: &Vector<3>| -v / s2 + 2.0 * sigma.dot(v) * sigma / (s2 * s2);
        let curve = (4.0 * sd * rate + 2.0 * rate.norm_squared() * sigma) / (s2 * s2)
            - 8.0 * sd * sd * sigma / (s2 * s2 * s2);
        let put = |v: &mut Vector<N>, x: Vector<3>| {
            for k in 0..3 {
                v[ball[k]] = x[k];
            }
        };
        for a in acc.iter_mut() {
            let x = j(&get(a)) + curve;
            put(a, x);
        }
        put(q, -sigma / s2);
        put(qd, j(&rate));
    }
    switched
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rotation matrix of modified Rodrigues parameters (written out independently of
    /// the derive: `R = 1 + (8 S^2 + 4 (1 - s2) S) / (1 + s2)^2`, `S = [sigma]x`).
    fn rotation(s: [f64; 3]) -> [[f64; 3]; 3] {
        let s2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
        let x = [[0.0, -s[2], s[1]], [s[2], 0.0, -s[0]], [-s[1], s[0], 0.0]];
        let mut r = [[0.0; 3]; 3];
        for i in 0..3 {
            for k in 0..3 {
                let x2: f64 = (0..3).map(|j| x[i][j] * x[j][k]).sum();
                let id = if i == k { 1.0 } else { 0.0 };
                r[i][k] = id + (8.0 * x2 + 4.0 * (1.0 - s2) * x[i][k]) / (1.0 + s2).powi(2);
            }
        }
        r
    }

    #[test]
    fn parameters_invert_rotation_at_every_angle() {
        for (axis, angle) in [
            ([0.3, -0.5, 0.8], 0.7),
            ([1.0, 0.0, 0.0], 3.1),
            ([0.0, 0.6, -0.8], -2.9),
            ([0.2, 0.2, 0.96], 0.0),
        ] {
            let n = Vector::<3>::from(axis).normalize();
            let sigma = n * (angle / 4.0_f64).tan();
            let r = super::rotation(&sigma);
            assert!((r * r.transpose() - Matrix::<3, 3>::identity()).norm() < 1e-14);
            let back = parameters(&r);
            assert!((back - sigma).norm() < 1e-14, "{back:?} {sigma:?}");
            // Independently: the rotation by `angle` about `n` (Rodrigues' formula).
            let x = skew(&n);
            let rodrigues =
                Matrix::<3, 3>::identity() + angle.sin() * x + (1.0 - angle.cos()) * x * x;
            assert!((rodrigues - r).norm() < 1e-14);
        }
        // Rates: R' = R [w]x, checked by a central difference along sigma'.
        let (sigma, w) = (
            Vector::<3>::new(0.3, -0.2, 0.6),
            Vector::<3>::new(1.0, -2.0, 0.5),
        );
        let sd = rates(&sigma, &w);
        let h = 1e-6;
        let dr =
            (super::rotation(&(sigma + h * sd)) - super::rotation(&(sigma - h * sd))) / (2.0 * h);
        assert!((dr - super::rotation(&sigma) * skew(&w)).norm() < 1e-9);
    }

    #[test]
    fn the_shadow_set_is_the_same_rotation_and_motion() {
        let (sigma, rate) = ([0.9, -0.6, 0.3], [0.4, 0.7, -1.1]);
        let mut y = Vector::<6>::from_column_slice(&[
            sigma[0], sigma[1], sigma[2], rate[0], rate[1], rate[2],
        ]);
        shadow(&mut y, 3, &[[0, 1, 2]]);
        let s2: f64 = sigma.iter().map(|s| s * s).sum();
        assert!(s2 > 1.0);
        let shadowed = [y[0], y[1], y[2]];
        assert!(shadowed.iter().map(|s| s * s).sum::<f64>() < 1.0);
        // Same rotation now, and a short time later along the two rates.
        let dt = 1e-6;
        let (r0, r1) = (rotation(sigma), rotation(shadowed));
        let later = |s: [f64; 3], r: [f64; 3]| std::array::from_fn(|k| s[k] + dt * r[k]);
        let (q0, q1) = (
            rotation(later(sigma, rate)),
            rotation(later(shadowed, [y[3], y[4], y[5]])),
        );
        for i in 0..3 {
            for k in 0..3 {
                assert!((r0[i][k] - r1[i][k]).abs() < 1e-14);
                // The two rotations' rates agree to the first-order step's O(dt^2).
                assert!(
                    ((q0[i][k] - r0[i][k]) - (q1[i][k] - r1[i][k])).abs()
                        < 1e-10 * dt.sqrt() + 1e-11
                );
            }
        }
        // Inside the unit ball nothing changes.
        let before = y;
        shadow(&mut y, 3, &[[0, 1, 2]]);
        assert_eq!(y, before);
    }
    #[test]
    fn the_shadow_motion_maps_accelerations_along_a_path() {
        // sigma(t) = s + v t + a t^2 / 2 crosses nothing; its shadow's second derivative
        // at t = 0 by a central difference of the map itself.
        let (s, v, a) = (
            Vector::<3>::new(0.9, -0.6, 0.3),
            Vector::<3>::new(0.4, 0.7, -1.1),
            Vector::<3>::new(-0.3, 0.2, 0.8),
        );
        let map = |t: f64| {
            let x = s + v * t + a * (t * t / 2.0);
            -x / x.norm_squared()
        };
        let dt = 1e-4;
        let dd = (map(dt) - 2.0 * map(0.0) + map(-dt)) / (dt * dt);
        let d = (map(dt) - map(-dt)) / (2.0 * dt);
        let (mut q, mut qd, mut qdd, mut other) = (s, v, a, a);
        assert!(shadow_motion(
            &mut q,
            &mut qd,
            &mut [&mut qdd, &mut other],
            &[[0, 1, 2]]
        ));
        assert!((q - map(0.0)).norm() < 1e-15);
        assert!((qd - d).norm() < 1e-7, "{qd} {d}");
        assert!((qdd - dd).norm() < 1e-6, "{qdd} {dd}");
        assert_eq!(qdd, other);
        // As `shadow` maps the first-order state.
        let mut y = Vector::<6>::new(s[0], s[1], s[2], v[0], v[1], v[2]);
        shadow(&mut y, 3, &[[0, 1, 2]]);
        assert_eq!(y.fixed_rows::<3>(0).into_owned(), q);
        assert!((y.fixed_rows::<3>(3).into_owned() - qd).norm() < 1e-15);
        // Inside the unit ball nothing moves.
        let before = (q, qd, qdd);
        assert!(!shadow_motion(
            &mut q,
            &mut qd,
            &mut [&mut qdd],
            &[[0, 1, 2]]
        ));
        assert_eq!((q, qd, qdd), before);
    }
}
