//! Charts of the rotation group that the integrators re-centre on the fly.
//!
//! A ball joint (`joint = ball(a, b, c)`) has the modified Rodrigues parameters
//! `sigma = tan(phi / 4) n` of its rotation (by `phi` about the unit `n`) as coordinates:
//! regular everywhere but at the full turn `phi = 2π`, where `|sigma|` grows without bound.
//! The same rotation has the *shadow* parameters `-sigma / |sigma|^2` (the rotation by
//! `phi - 2π` about `n`), so switching to them whenever `|sigma| > 1` (`phi > π`) keeps every
//! ball joint within `|sigma| <= 1`. A generated model does it in
//! [`crate::OdeSystem::project`], after each accepted step; the orientation, the angular
//! velocity and so every output and the energy are the same on both sides of the switch.

use crate::model::Vector;

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
    fn the_shadow_set_is_the_same_rotation_and_motion() {
        let (sigma, rate) = ([0.9, -0.6, 0.3], [0.4, 0.7, -1.1]);
        let mut y = Vector::<6>::from_column_slice(&[sigma[0], sigma[1], sigma[2], rate[0], rate[1], rate[2]]);
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
                assert!(((q0[i][k] - r0[i][k]) - (q1[i][k] - r1[i][k])).abs() < 1e-10 * dt.sqrt() + 1e-11);
            }
        }
        // Inside the unit ball nothing changes.
        let before = y;
        shadow(&mut y, 3, &[[0, 1, 2]]);
        assert_eq!(y, before);
    }
}
