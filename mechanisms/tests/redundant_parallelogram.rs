//! A parallelogram with a third parallel crank: over-constrained but mobile.
//!
//! Three cranks of length `l` and mass `m` pinned to the ground at `x = 0, l, 2 l`, and one
//! coupler (length `2 l`, mass `mc`) pinned to crank 0's tip and, by two closing pins, to the
//! tips of cranks 1 and 2: 4 angles and 4 closure equations, yet one degree of freedom, since
//! the third crank's pin repeats what the parallelogram already imposes (one row of `Phi_q`
//! is redundant, at every position).
//!
//! **Reference (one coordinate, by hand).** Every crank turns by the same angle `th` and the
//! coupler translates with the crank tips, so `T = 3 (m l^2 / 6) th'^2 + mc l^2 th'^2 / 2`
//! and `V = 3 m g (l / 2) sin th + mc g l sin th`; Lagrange's equation:
//! `(m + mc) l^2 th'' = -(3 m / 2 + mc) g l cos th`.

use mbd::analysis::rank_and_redundant;
use mbd::integrate::Integrator;
use mbd::prelude::*;
use mbd::{Dopri5, OdeSystem, Options};
use std::f64::consts::FRAC_PI_2;

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[body(crank0, joint = revolute(c0), at = [0.0, 0.0], com = [0.5 * l, 0.0], mass = m,
       inertia = m * l * l / 12.0)]
#[body(coupler, parent = crank0, joint = revolute(k), at = [l, 0.0], com = [l, 0.0],
       mass = mc, inertia = mc * 4.0 * l * l / 12.0)]
#[body(crank1, joint = revolute(c1), at = [l, 0.0], com = [0.5 * l, 0.0], mass = m,
       inertia = m * l * l / 12.0)]
#[body(crank2, joint = revolute(c2), at = [2.0 * l, 0.0], com = [0.5 * l, 0.0], mass = m,
       inertia = m * l * l / 12.0)]
#[close(pin1, a = coupler, at_a = [l, 0.0], b = crank1, at_b = [l, 0.0])]
#[close(pin2, a = coupler, at_a = [2.0 * l, 0.0], b = crank2, at_b = [l, 0.0])]
pub struct ThreeCranks {
    pub m: f64,
    pub mc: f64,
    pub l: f64,
    pub g: f64,
}

/// The reduced equation of the module docs, `y = [th, th']`.
struct Reduced(f64, f64);

impl OdeSystem<2> for Reduced {
    fn rhs(&self, _t: f64, y: &mbd::Vector<2>) -> mbd::Result<mbd::Vector<2>> {
        Ok(mbd::Vector::<2>::new(y[1], -self.1 * y[0].cos() / self.0))
    }
}

#[test]
fn third_crank_is_redundant_and_the_motion_follows_the_parallelogram() {
    let s = ThreeCranks {
        m: 1.0,
        mc: 2.0,
        l: 1.0,
        g: 9.81,
    };
    // Coordinates in declaration order: c0, k, c1, c2; cranks vertical, coupler
    // horizontal (k = -pi/2 relative to crank 0), crank tips moving at 1 m/s along +x.
    let w = -1.0 / s.l;
    let y0 = mbd::Vector::<8>::from_row_slice(&[
        FRAC_PI_2, -FRAC_PI_2, FRAC_PI_2, FRAC_PI_2, w, -w, w, w,
    ]);
    let q0 = y0.fixed_rows::<4>(0).into_owned();
    assert!(s.phi(0.0, &q0).amax() < 1e-14);
    let (rank, redundant) = rank_and_redundant(&s.phi_q(0.0, &q0));
    assert_eq!((rank, redundant.len()), (3, 1), "one pin is redundant");
    let t1 = 3.0;
    let o = |tol: f64| Options {
        rtol: tol,
        atol: tol,
        ..Default::default()
    };
    let reference = Dopri5::new(o(1e-13))
        .solve(
            &Reduced((s.m + s.mc) * s.l * s.l, (1.5 * s.m + s.mc) * s.g * s.l),
            0.0,
            mbd::Vector::<2>::new(FRAC_PI_2, w),
            t1,
            &[],
        )
        .unwrap();
    let error_and_spread = |sol: &mbd::Solution<8>| {
        (0..=60).fold((0.0f64, 0.0f64), |(e, sp), k| {
            let t = t1 * k as f64 / 60.0;
            let (y, r) = (sol.at(t).unwrap(), reference.at(t).unwrap());
            let spread = (y[2] - y[0]).abs().max((y[3] - y[0]).abs());
            (e.max((y[0] - r[0]).abs()), sp.max(spread))
        })
    };
    // DOPRI5 passes the flat (singular) positions at t = 0.73, 1.9 s on the parallelogram,
    // its error converging with the tolerance. (At 1e-9 and tighter it is 5e-4 and worse:
    // the acceleration-level limit of docs/STABILITY.md; measured, not asserted.)
    let mut errors = vec![];
    for tol in [1e-6, 1e-7, 1e-8] {
        let sol = Dopri5::new(o(tol)).solve(&s, 0.0, y0, t1, &[]).unwrap();
        let (err, spread) = error_and_spread(&sol);
        eprintln!("three cranks, DOPRI5 {tol:e}: crank 0 error {err:e}, spread {spread:e}");
        assert!(spread < 1e-8, "{spread:e}");
        errors.push(err);
    }
    assert!(
        errors[2] < 1e-6 && errors[2] < 0.1 * errors[0],
        "{errors:?}"
    );
    // The index-3 augmented Lagrangian integrator, second order.
    let mut errors = vec![];
    for h in [2e-3, 1e-3] {
        let sol = mbd::integrate::Ali3::new(h)
            .solve::<_, 4, 4, 8>(&s, 0.0, q0, y0.fixed_rows::<4>(4).into_owned(), t1, &[])
            .unwrap();
        let (err, spread) = error_and_spread(&sol);
        eprintln!("three cranks, ALI3-P h = {h:e}: crank 0 error {err:e}, spread {spread:e}");
        assert!(spread < 1e-5, "{spread:e}");
        errors.push(err);
    }
    assert!(
        errors[1] < 1e-4 && errors[0] / errors[1] > 3.5,
        "{errors:?}"
    );
    // The multipliers of the redundant pins are not unique: the solve returns finite,
    // minimum-norm ones, and the accelerations are the reduced equation's.
    let qd0 = y0.fixed_rows::<4>(4).into_owned();
    let (qdd, lambda) = s.acceleration_and_multipliers(0.0, &q0, &qd0).unwrap();
    let th_dd = -(1.5 * s.m + s.mc) * s.g * FRAC_PI_2.cos() / ((s.m + s.mc) * s.l);
    assert!((qdd[0] - th_dd).abs() < 1e-10, "{} vs {th_dd}", qdd[0]);
    assert!(lambda.iter().all(|v| v.is_finite()));
}
