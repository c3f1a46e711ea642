//! Closed-form references shared by the integration tests of `mbd-core` and of the `tests`
//! crate (which includes this file by path): the rigid pendulum's motion by Jacobi's
//! elliptic functions. Checked against tabulated values in `explicit.rs`.
#![allow(dead_code, reason = "each test file uses a subset")]

use std::f64::consts::PI;

/// The arithmetic-geometric mean: `a_{n+1} = (a_n + b_n)/2`, `b_{n+1} = sqrt(a_n b_n)`.
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    while (a - b).abs() > 4.0 * f64::EPSILON * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// Complete elliptic integral of the first kind, `K(k) = pi / (2 AGM(1, sqrt(1 - k^2)))`
/// (Abramowitz & Stegun 17.6.1-17.6.4; DLMF 19.8.5).
pub fn elliptic_k(k: f64) -> f64 {
    PI / (2.0 * agm(1.0, (1.0 - k * k).sqrt()))
}

/// Jacobi `sn(u, k)` by the AGM / descending Landen scheme (Abramowitz & Stegun 16.4):
/// `a0 = 1`, `b0 = sqrt(1 - k^2)`, `c0 = k`; `a_{n+1} = (a_n + b_n)/2`,
/// `b_{n+1} = sqrt(a_n b_n)`, `c_{n+1} = (a_n - b_n)/2` until `c_N` is negligible;
/// `phi_N = 2^N a_N u`, then `phi_{n-1} = (phi_n + asin(c_n sin(phi_n) / a_n)) / 2` and
/// `sn = sin(phi_0)`.
pub fn jacobi_sn(u: f64, k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    let (mut av, mut cv) = (vec![a], vec![k]);
    while cv.last().is_some_and(|c| c.abs() > 4.0 * f64::EPSILON) && cv.len() < 40 {
        let c = 0.5 * (a - b);
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
        av.push(a);
        cv.push(c);
    }
    let n = av.len() - 1;
    let mut phi = 2f64.powi(n as i32) * av[n] * u;
    for i in (1..=n).rev() {
        phi = 0.5 * (phi + (cv[i] * phi.sin() / av[i]).asin());
    }
    phi.sin()
}

/// The rigid pendulum `theta'' = -w^2 sin(theta)` released from rest at `theta0`:
/// `sin(theta/2) = s sn(K(s) - w t, s)`, `s = sin(theta0/2)`.
pub fn pendulum_angle(w: f64, theta0: f64, t: f64) -> f64 {
    let s = (theta0 / 2.0).sin();
    2.0 * (s * jacobi_sn(elliptic_k(s) - w * t, s)).asin()
}
