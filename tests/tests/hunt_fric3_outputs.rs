//! The friction force as an output: `mbd::friction::contact_forces` gives each contact's
//! force and mode at any state (it was only inside `forces`, summed with the other loads),
//! so a user can integrate the friction's power and check the energy balance. Closed form
//! beside the test.

use mbd::Slip;
use mbd::friction::contact_forces;
use mbd::integrate::{Dopri5, Integrator};
use mbd::prelude::*;

/// A block on a spring `k` over a rough floor (normal `n`).
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(tie, from = [0.0, 0.0], to = block, k = k)]
#[friction(along = x, mu_k = mu_k, mu_s = mu_s, normal = n)]
pub struct Coulomb {
    pub m: f64,
    pub k: f64,
    pub n: f64,
    pub mu_k: f64,
    pub mu_s: f64,
}

/// Released from `x0` at rest, each swing is a half cosine about `+-d`, `d = mu_k n / k`,
/// so the turning points are `|x_j| = x0 - 2 j d`; it sticks at the first with
/// `k |x_j| <= mu_s n` (here `j = 2`: 0.3, -0.1774, 0.0548). Sliding, the friction force is
/// `-+ mu_k n`; stuck at `x_2`, it holds the spring, `+k x_2`. Its work over the run,
/// `-mu_k n (|x0 - x1| + |x1 - x2|)`, is the energy lost, `k (x_2^2 - x0^2) / 2`; the
/// integral of `F x'` over the dense output (3-point Gauss-Legendre per step: `F` is
/// constant within each step and `x'` a polynomial) gives it to 1e-12.
#[test]
fn the_friction_force_output_integrates_to_the_energy_lost() {
    let p = Coulomb {
        m: 0.5,
        k: 8.0,
        n: 0.5 * 9.81,
        mu_k: 0.1,
        mu_s: 0.15,
    };
    let x0 = 0.3;
    let d = p.mu_k * p.n / p.k;
    let (x1, x2) = (-(x0 - 2.0 * d), x0 - 4.0 * d);
    assert!(p.k * x1.abs() > p.mu_s * p.n && p.k * x2.abs() <= p.mu_s * p.n);
    let lost = p.k * (x2 * x2 - x0 * x0) / 2.0;
    let work = -p.mu_k * p.n * ((x0 - x1).abs() + (x1 - x2).abs());
    assert!((lost - work).abs() < 1e-15);
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        dense: true,
        ..Options::default()
    };
    let sol = Dopri5::new(opts)
        .solve(&p, 0.0, Vector::<2>::new(x0, 0.0), 5.0, &[])
        .unwrap();
    let force = |t: f64, y: &Vector<2>| {
        contact_forces(&p, t, &Vector::<1>::new(y[0]), &Vector::<1>::new(y[1])).unwrap()
    };
    // Sliding back at first, held at the end.
    let early = sol.at(0.1).unwrap();
    assert_eq!(force(0.1, &early), ([Slip::Backward], [p.mu_k * p.n]));
    let (t, y) = sol.last();
    let (modes, [held]) = force(t, y);
    assert_eq!(modes, [Slip::Stick]);
    assert!((y[0] - x2).abs() < 1e-11, "rests at {} vs {x2}", y[0]);
    assert!((held - p.k * y[0]).abs() < 1e-15, "{held}");
    // The friction's work along the dense output.
    let (s3, w5, w8) = ((0.6f64).sqrt(), 5.0 / 9.0, 8.0 / 9.0);
    let mut integral = 0.0;
    for seg in &sol.segments {
        let mid = seg.t0 + seg.h / 2.0;
        for (u, w) in [(-s3, w5), (0.0, w8), (s3, w5)] {
            let t = mid + u * seg.h / 2.0;
            let y = seg.eval(t);
            integral += w * seg.h / 2.0 * force(t, &y).1[0] * y[1];
        }
    }
    assert!(
        (integral - work).abs() < 1e-12,
        "friction work {integral} vs {work}"
    );
}
