//! The README's slider-crank: a constrained, driven model, checked against the closed form.

use approx::assert_relative_eq;
use mbd::analysis::{NewtonOptions, kinematics};
use mbd::nalgebra;
use mbd::prelude::*;

/// Slider-crank driven at constant speed (Meriam & Kraige P5.212), as in the README.
#[derive(Debug, Mechanism)]
#[coords(beta, x)]
#[drive(theta = omega * t)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(rod, mass = m_rod, inertia = m_rod * l * l / 12.0,
        at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
        angle = -beta)]
#[particle(piston, mass = m_piston, at = [x, 0.0])]
#[output(v_piston = der(x))]
#[output(a_piston = der(der(x)))]
#[output(torque = reaction(theta))]
pub struct SliderCrank {
    pub r: f64,
    pub l: f64,
    pub omega: f64,
    pub m_rod: f64,
    pub m_piston: f64,
}

/// Closed form: `x = r cos th + sqrt(l^2 - r^2 sin^2 th)`, differentiated by hand with
/// `th' = omega` constant: `x' = -r w sin th - r^2 w sin th cos th / s`,
/// `s = sqrt(l^2 - r^2 sin^2 th)`.
fn piston(sc: &SliderCrank, th: f64) -> (f64, f64) {
    let (r, l, w) = (sc.r, sc.l, sc.omega);
    let s = (l * l - r * r * th.sin().powi(2)).sqrt();
    (
        r * th.cos() + s,
        -r * w * th.sin() - r * r * w * th.sin() * th.cos() / s,
    )
}

#[test]
fn slider_crank_kinematics_match_the_closed_form() {
    let sc = SliderCrank {
        r: 0.125,
        l: 0.35,
        omega: 157.08,
        m_rod: 0.6,
        m_piston: 0.82,
    };
    for k in 1..20 {
        let t = k as f64 * 1e-3;
        let guess = nalgebra::Vector2::new(0.3, 0.4);
        let ks = kinematics(&sc, t, &guess, &NewtonOptions::default()).unwrap();
        let (x, v) = piston(&sc, sc.omega * t);
        assert_relative_eq!(ks.q[1], x, max_relative = 1e-13);
        assert_relative_eq!(ks.qd[1], v, max_relative = 1e-11, epsilon = 1e-12);
        let y: mbd::Vector<4> = SliderCrankState {
            beta: ks.q[0],
            x: ks.q[1],
            beta_dot: ks.qd[0],
            x_dot: ks.qd[1],
        }
        .into();
        let o = sc.outputs(t, &y).unwrap();
        assert_relative_eq!(o.v_piston, v, max_relative = 1e-11, epsilon = 1e-12);
        // Power balance: the driving torque times omega is the rate of change of kinetic
        // energy (no gravity here): torque * w = dT/dt, with dT/dt by central difference.
        let h = 1e-6;
        let energy = |t: f64| {
            let ks = kinematics(&sc, t, &guess, &NewtonOptions::default()).unwrap();
            MechanismModel::energy(&sc, t, &ks.q, &ks.qd).unwrap()
        };
        let d_energy = (energy(t + h) - energy(t - h)) / (2.0 * h);
        assert_relative_eq!(o.torque * sc.omega, d_energy, max_relative = 1e-6);
    }
}
