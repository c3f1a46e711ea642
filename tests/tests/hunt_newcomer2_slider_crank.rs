//! The README's slider-crank, no longer driven at constant speed but turned by a motor
//! torque on a crank of its own mass: the crank angle becomes a free coordinate and the
//! derive closes the loop in it (minimal coordinates, state `[th, th']`).
//!
//! Hand derivation (no gravity: the mechanism lies flat). With `l sin b = r sin th`,
//! `b' = kb th'`, `kb = r cos th / (l cos b)`; the piston `x = r cos th + l cos b`,
//! `x' = kx th'`, `kx = -r sin th - l sin b kb`; the rod's centre
//! `(r cos th + l/2 cos b, r sin th - l/2 sin b)` moves at `(gx, gy) th'` with
//! `gx = -r sin th - l/2 sin b kb`, `gy = r cos th - l/2 cos b kb = r cos th / 2`; the rod
//! turns at `-b'`. The kinetic energy is `M(th) th'^2 / 2` with
//! `M = ic + mc r^2/4 + mr (gx^2 + gy^2) + ir kb^2 + mp kx^2`, and the torque `tau` is the
//! only load, so from rest `th'' = tau / M(th)` and, at any later time,
//! `M(th) th'^2 / 2 = tau (th - th0)` (work-energy).

use mbd::prelude::*;

/// A crank (uniform bar), a rod and a piston; the motor torque `tau` turns the crank.
#[derive(Debug, Mechanism)]
#[coords(th, beta, x)]
#[constraint(x == l * cos(beta) + r * cos(th))]
#[constraint(l * sin(beta) == r * sin(th))]
#[rigid(crank, mass = mc, inertia = mc * r * r / 12.0,
        at = [r / 2.0 * cos(th), r / 2.0 * sin(th)], angle = th)]
#[rigid(rod, mass = mr, inertia = mr * l * l / 12.0,
        at = [r * cos(th) + l / 2.0 * cos(beta), r * sin(th) - l / 2.0 * sin(beta)],
        angle = -beta)]
#[particle(piston, mass = mp, at = [x, 0.0])]
#[torque(motor, on = crank, value = tau)]
#[init(th = 0.2)]
#[output(v_piston = der(x))]
pub struct Driven {
    pub r: f64,
    pub l: f64,
    pub mc: f64,
    pub mr: f64,
    pub mp: f64,
    pub tau: f64,
}

const P: Driven = Driven {
    r: 0.1,
    l: 0.35,
    mc: 2.0,
    mr: 1.0,
    mp: 0.5,
    tau: 3.0,
};

/// `M(th)`, `kx(th)` of the hand derivation.
fn by_hand(p: &Driven, th: f64) -> (f64, f64) {
    let b = (p.r * th.sin() / p.l).asin();
    let kb = p.r * th.cos() / (p.l * b.cos());
    let kx = -p.r * th.sin() - p.l * b.sin() * kb;
    let gx = -p.r * th.sin() - p.l / 2.0 * b.sin() * kb;
    let gy = p.r * th.cos() / 2.0;
    let ic = p.mc * p.r * p.r / 12.0 + p.mc * p.r * p.r / 4.0;
    let ir = p.mr * p.l * p.l / 12.0;
    let m = ic + p.mr * (gx * gx + gy * gy) + ir * kb * kb + p.mp * kx * kx;
    (m, kx)
}

#[test]
fn the_crank_angle_is_the_state() {
    assert_eq!(Driven::COORDINATES, ["th"]);
    assert_eq!(P.initial_state(), Vector::<2>::new(0.2, 0.0));
}

#[test]
fn from_rest_the_crank_accelerates_at_torque_over_reduced_inertia() {
    for th in [0.0, 0.4, 1.3, 2.0, 3.5, 5.0] {
        let got = P
            .acceleration(0.0, &Vector::<1>::new(th), &Vector::<1>::zeros())
            .unwrap()[0];
        let want = P.tau / by_hand(&P, th).0;
        assert!(
            (got - want).abs() < 1e-12 * want,
            "th = {th}: {got} vs {want}"
        );
    }
}

#[test]
fn the_motor_work_becomes_kinetic_energy_and_the_piston_speed_follows() {
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let y0 = P.initial_state();
    let sol = Dopri5::new(opts).solve(&P, 0.0, y0, 1.0, &[]).unwrap();
    let mut turned = 0.0;
    for k in 1..=20 {
        let t = 0.05 * k as f64;
        let y = sol.at(t).unwrap();
        let (th, thd) = (y[0], y[1]);
        let (m, kx) = by_hand(&P, th);
        let kinetic = 0.5 * m * thd * thd;
        let work = P.tau * (th - y0[0]);
        assert!((kinetic - work).abs() < 1e-9 * work.max(1e-3), "t = {t}");
        let v = P.outputs(t, &y).unwrap().v_piston;
        assert!((v - kx * thd).abs() < 1e-12 * (1.0 + v.abs()), "t = {t}");
        turned = th - y0[0];
    }
    assert!(
        turned > 2.0 * std::f64::consts::PI,
        "only {turned} rad in 1 s"
    );
}
