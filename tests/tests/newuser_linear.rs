//! A model written big by repetition, linearised: twenty beads on a line joined by
//! springs, held between two walls, against the closed form of the discrete string.
//!
//! `n = 20` beads of mass `m` at `x_i`, springs `k` of zero rest length from the wall at 0 to
//! bead 1, bead `i` to `i + 1`, bead 20 to the wall at `L = 21`. The beads move along the
//! line only, so each spring's energy is `k (x_{i+1} - x_i)^2 / 2` while they keep their
//! order: at the equilibrium `x_i = i` the stiffness is `k` times the tridiagonal `(-1, 2, -1)`
//! matrix and `w_j^2 = (4 k / m) sin^2(j pi / (2 (n + 1)))`, `j = 1 ..= n`.

use mbd::prelude::*;
use std::f64::consts::PI;

#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[repeat(i in 1..=20, coords(x[i]), particle(p[i], mass = m, at = [x[i], 0.0]))]
#[repeat(i in 1..20, spring(s[i], from = p[i], to = p[i + 1], k = k))]
#[point(left, at = [0.0, 0.0])]
#[point(right, at = [el, 0.0])]
#[spring(sl, from = left, to = p1, k = k)]
#[spring(sr, from = p20, to = right, k = k)]
pub struct Beads {
    pub m: f64,
    pub k: f64,
    pub el: f64,
}

#[test]
fn twenty_beads_have_the_modes_of_the_discrete_string() {
    let p = Beads {
        m: 0.5,
        k: 3.0,
        el: 21.0,
    };
    let rest = Vector::<20>::from_fn(|i, _| (i + 1) as f64);
    // The equilibrium is one: no acceleration there.
    let y = Vector::<40>::from_fn(|i, _| if i < 20 { rest[i] } else { 0.0 });
    assert!(p.rhs(0.0, &y).unwrap().amax() < 1e-13);
    let modes = mbd::analysis::linear::undamped_modes(&p, 0.0, &rest).unwrap();
    assert_eq!(modes.len(), 20);
    for (j, mode) in modes.iter().enumerate() {
        let s = ((j + 1) as f64 * PI / 42.0).sin();
        let want = 4.0 * p.k / p.m * s * s;
        assert!((mode.omega_squared - want).abs() < 1e-12 * want, "mode {j}");
    }
}
