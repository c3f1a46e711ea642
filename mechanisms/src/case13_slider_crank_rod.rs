//! Case 13: a slider-crank, the connecting rod's angular velocity and acceleration
//! (Meriam & Kraige 7th ed., P5/57, p. 347).
//!
//! **Problem.** The crank OB (`r = 0.1 m`) turns at a constant `ω_0 = 3 rad/s`; the rod AB
//! (`l = 0.2 m`) drives the slider A on a line through O. At `θ = 60°` find `ω_AB` and `α_AB`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `l sin β = r sin θ`: β is the rod's angle with the slider's line, θ the crank's angle from
//! it. O = (0, 0), `B = r (cos θ, sin θ)`, `A = (x_A, 0)` with `x_A = r cos θ + l cos β` (A
//! beyond B's foot). The manual reports `ω_AB = β'` and `α_AB = β''`; with θ increasing
//! (`θ' = +3`, counter-clockwise) the rod's absolute angle `π − β` turns clockwise, so β' and
//! β'' are minus the rod's (counter-clockwise) angular velocity and acceleration.
//!
//! **Model.** Driven: `θ = π/3 + 3 t`. Free: `x_A` and β, with the loop closure (2 equations)
//! `x_A = r cos θ + l cos β`, `l sin β = r sin θ`. Bodies: the crank about O, the rod (its
//! mass centre midway, angle `π − β`), the slider; their masses (1 kg; not given) play no part
//! in the kinematics, and neither does gravity (the model has none). `ω_AB` and `α_AB` are the
//! model's outputs at t = 0 (the rod's angular velocity and acceleration, negated).
//!
//! **Reference (exact).** `β' = (r/l) ω_0 cos θ / sqrt(1 − ((r/l) sin θ)^2) = 3/sqrt(13) =
//! 0.832050294337844 rad/s`, `β'' = (r/l) ω_0^2 sin θ ((r/l)^2 − 1)/(1 − ((r/l) sin θ)^2)^{3/2}
//! = −3.99088629483448 rad/s^2` (`mechanisms/reference/case13.py`: the closed forms and a
//! numerical differentiation of the loop closure).
//!
//! **Discrepancies in the manual.** None: 0.832 and −3.99 are these, rounded; RecurDyn agrees.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str =
    "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qd = -Phi_t, Phi_q qdd = gamma";

/// A crank OB turning at `omega_0` from `theta_0`, the rod BA at angle β to the slider's
/// line, and the slider A at `x_a`.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(x_a, beta)]
#[drive(theta = theta_0 + omega_0 * t)]
#[constraint(x_a == r * cos(theta) + l * cos(beta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0,
        at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[rigid(rod, mass = m, inertia = m * l * l / 12.0,
        at = [x_a - l / 2.0 * cos(beta), l / 2.0 * sin(beta)], angle = PI - beta)]
#[particle(slider, mass = m, at = [x_a, 0.0])]
#[init(x_a = r * cos(theta_0) + sqrt(l * l - r * r * sin(theta_0) * sin(theta_0)),
       beta = asin(r * sin(theta_0) / l))]
#[output(omega_ab = -angular_velocity(rod))]
#[output(alpha_ab = -angular_acceleration(rod))]
pub struct SliderCrank {
    /// Mass of each body (immaterial to the kinematics).
    pub m: f64,
    pub r: f64,
    pub l: f64,
    pub omega_0: f64,
    pub theta_0: f64,
}

/// The manual's data.
pub const MODEL: SliderCrank = SliderCrank {
    m: 1.0,
    r: 0.1,
    l: 0.2,
    omega_0: 3.0,
    theta_0: std::f64::consts::FRAC_PI_3,
};

/// The drawing beyond the model's shapes. The slider's guide.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("slider", 0)],
    ..Sketch::NONE
};

/// Exact references `[β', β'']` at t = 0: from `sin β = (r/l) sin θ` with θ uniform,
/// `β' = (r/l) ω_0 cos θ / c`, `β'' = (r/l) ω_0^2 sin θ ((r/l)^2 − 1)/c^3`,
/// `c = sqrt(1 − ((r/l) sin θ)^2)`.
pub fn references() -> [f64; 2] {
    let SliderCrank {
        r,
        l,
        omega_0: w,
        theta_0: th,
        ..
    } = MODEL;
    let k = r / l;
    let c = (1.0 - (k * th.sin()).powi(2)).sqrt();
    [
        k * w * th.cos() / c,
        k * w * w * th.sin() * (k * k - 1.0) / c.powi(3),
    ]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &KinematicState<2>) -> Vector<4> {
    SliderCrankState {
        x_a: k.q[0],
        beta: k.q[1],
        x_a_dot: k.qd[0],
        beta_dot: k.qd[1],
    }
    .into()
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let opts = NewtonOptions::default();
    let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
    let now = model.outputs(0.0, &state(&kinematics(&model, 0.0, &guess, &opts)?))?;
    // Each compared quantity over the same span (the manual's plot and more).
    let turn = 2.0 * std::f64::consts::PI / model.omega_0;
    let times: Vec<f64> = (0..=200).map(|i| turn * f64::from(i) / 200.0).collect();
    let samples = kinematic_sweep(&model, &times, &guess, &opts)?
        .iter()
        .map(|k| Ok((k.t, model.outputs(k.t, &state(k))?)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let [omega_ab, alpha_ab] = references();
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "omega_AB",
                value: now.omega_ab,
                reference: omega_ab,
                method: METHOD,
                curve: Curve::at_instant(
                    "rod angular velocity β' [rad/s]",
                    series(&samples, |o| o.omega_ab),
                    0.0,
                ),
            },
            Row {
                quantity: "alpha_AB",
                value: now.alpha_ab,
                reference: alpha_ab,
                method: METHOD,
                curve: Curve::at_instant(
                    "rod angular acceleration β'' [rad/s²]",
                    series(&samples, |o| o.alpha_ab),
                    0.0,
                ),
            },
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case13_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case13_references_are_the_script_values_and_round_to_the_manual() {
        // mechanisms/reference/case13.py.
        let [omega_ab, alpha_ab] = references();
        assert_relative_eq!(omega_ab, 3.0 / 13f64.sqrt(), max_relative = 1e-14);
        assert_relative_eq!(omega_ab, 0.832_050_294_337_844, max_relative = 1e-14);
        assert_relative_eq!(alpha_ab, -3.990_886_294_834_48, max_relative = 1e-14);
        assert_eq!(format!("{omega_ab:.3}"), "0.832");
        assert_eq!(format!("{alpha_ab:.2}"), "-3.99");
    }

    #[test]
    fn case13_rod_rates_are_the_coordinate_rates_and_the_loop_stays_closed() {
        let model = MODEL;
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        let opts = NewtonOptions::default();
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        let times: Vec<f64> = (0..=40).map(|i| 0.05 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &opts).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
            let o = model.outputs(k.t, &state(&k)).unwrap();
            assert_relative_eq!(o.omega_ab, k.qd[1], max_relative = 1e-12, epsilon = 1e-14);
            assert_relative_eq!(o.alpha_ab, k.qdd[1], max_relative = 1e-9, epsilon = 1e-12);
        }
    }
}
