//! Case 12: a crank pin sliding in a slotted link, the link's angular velocity
//! (Meriam & Kraige 7th ed., P5/54, p. 346).
//!
//! **Problem.** A crank of radius r turns at a constant rate `θ'`; its pin slides in a slotted
//! link pivoted at a fixed point a distance l from the crank's pivot. At `θ = 45°` find the
//! angular velocity ω of the slotted link.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost). The manual's
//! law of sines `r sin(θ + β) = l sin β`, i.e. `tan β = r sin θ/(l − r cos θ)`: in the triangle
//! of the crank's pivot P1, the link's pivot P2 and the pin X, `P1P2 = l`, `P1X = r`, θ is the
//! crank's angle at P1 from P1→P2 and β the angle at P2 between P2→P1 and P2→X. P1 = (0, 0),
//! P2 = (l, 0), `X = r (cos θ, sin θ)`. The worked numbers use **`θ' = 3 rad/s`, `l = 0.2 m`,
//! `r = 0.1 m`** (β = 28.68° and ω = 0.572 both follow from them exactly). β grows with θ, so
//! with the crank counter-clockwise the link turns clockwise at `ω = β'`.
//!
//! **Model.** Driven: `θ = π/4 + 3 t`. Free: the pin's distance s from P2 along the slot and
//! the link's angle φ (of P2→X, `φ = π − β`), with the constraint (2 equations)
//! `P2 + s (cos φ, sin φ) = r (cos θ, sin θ)`. Bodies: the crank about P1, the link about P2,
//! the pin's slider block at X turning with the link; their masses (1 kg; not given) play no
//! part in the kinematics, and neither does gravity (the model has none). The link's
//! clockwise angular velocity `ω = −φ'` is the model's output at t = 0.
//!
//! **Reference (exact).** `β' = θ' (r l cos θ − r^2)/(l^2 + r^2 − 2 l r cos θ)`:
//! **`ω = 0.572230709491639 rad/s`**, `β = 28.6750500631048°` (`mechanisms/reference/case12.py`:
//! the closed form and a numerical differentiation of the constraint's solution).
//!
//! **Discrepancies in the manual.** None in the result (0.572; RecurDyn agrees). Its "Basic
//! conditions" table (`ω_OA = 0.5 rad/s`, `r = 0.2`, `l = 0.1`) is wrong and contradicts its
//! own answer: `θ' = 0.5 rad/s` with the worked geometry gives `ω = 0.0954 rad/s`, and
//! `r = 0.2 > l = 0.1` would make the crank longer than the pivot distance (a different,
//! fully rotating link).

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qd = -Phi_t";

/// A crank of radius r about P1 = (0, 0) turning at `theta_dot` from `theta_0`, its pin
/// sliding in the slot of a link pivoted at P2 = (l, 0); s is the pin's distance from P2,
/// φ the link's angle.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(s, phi)]
#[drive(theta = theta_0 + theta_dot * t)]
#[constraint(l + s * cos(phi) == r * cos(theta))]
#[constraint(s * sin(phi) == r * sin(theta))]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0,
        at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[rigid(link, mass = m, inertia = m * (l + r) * (l + r) / 12.0,
        at = [l + (l + r) / 2.0 * cos(phi), (l + r) / 2.0 * sin(phi)], angle = phi)]
#[rigid(slider, mass = m, inertia = m * r * r / 12.0,
        at = [l + s * cos(phi), s * sin(phi)], angle = phi)]
#[init(s = hypot(r * cos(theta_0) - l, r * sin(theta_0)),
       phi = atan2(r * sin(theta_0), r * cos(theta_0) - l))]
#[output(omega_link = -angular_velocity(link))]
pub struct SlottedLink {
    /// Mass of each body (immaterial to the kinematics).
    pub m: f64,
    pub r: f64,
    /// Distance between the pivots.
    pub l: f64,
    pub theta_0: f64,
    pub theta_dot: f64,
}

/// The worked solution's data.
pub const MODEL: SlottedLink = SlottedLink {
    m: 1.0,
    r: 0.1,
    l: 0.2,
    theta_0: std::f64::consts::FRAC_PI_4,
    theta_dot: 3.0,
};

/// The drawing beyond the model's shapes. The link's far end and the slider's ends are free.
pub const SKETCH: Sketch = Sketch {
    free: &[At("link", 1), At("slider", 1), At("slider", 2)],
    ..Sketch::NONE
};

/// The link's clockwise angular velocity at crank angle θ and rate `theta_dot`:
/// `β' = θ' (r l cos θ − r^2)/(l^2 + r^2 − 2 l r cos θ)`, from `tan β = r sin θ/(l − r cos θ)`.
pub fn link_rate(theta_dot: f64) -> f64 {
    let SlottedLink {
        r, l, theta_0: th, ..
    } = MODEL;
    theta_dot * (r * l * th.cos() - r * r) / (l * l + r * r - 2.0 * l * r * th.cos())
}

/// Exact reference `[ω_link]`.
pub fn references() -> [f64; 1] {
    [link_rate(MODEL.theta_dot)]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &KinematicState<2>) -> Vector<4> {
    SlottedLinkState {
        s: k.q[0],
        phi: k.q[1],
        s_dot: k.qd[0],
        phi_dot: k.qd[1],
    }
    .into()
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let opts = NewtonOptions::default();
    let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
    let now = model.outputs(0.0, &state(&kinematics(&model, 0.0, &guess, &opts)?))?;
    // Each compared quantity over the same span (the manual's plot and more).
    let turn = 2.0 * std::f64::consts::PI / model.theta_dot;
    let times: Vec<f64> = (0..=200).map(|i| turn * f64::from(i) / 200.0).collect();
    let samples = kinematic_sweep(&model, &times, &guess, &opts)?
        .iter()
        .map(|k| Ok((k.t, model.outputs(k.t, &state(k))?)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let [omega] = references();
    Ok(Outcome {
        rows: vec![Row {
            quantity: "omega_link",
            value: now.omega_link,
            reference: omega,
            method: METHOD,
            curve: Curve::at_instant(
                "clockwise angular velocity of the link ω [rad/s]",
                series(&samples, |o| o.omega_link),
                0.0,
            ),
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case12_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case12_reference_is_the_script_value_and_rounds_to_the_manual() {
        // mechanisms/reference/case12.py: ω = 0.572230709491639, β = 28.6750500631048°.
        let [omega] = references();
        assert_relative_eq!(omega, 0.572_230_709_491_639, max_relative = 1e-14);
        assert_eq!(format!("{omega:.3}"), "0.572");
        let SlottedLink {
            r, l, theta_0: th, ..
        } = MODEL;
        let beta = (r * th.sin()).atan2(l - r * th.cos());
        assert_relative_eq!(
            beta.to_degrees(),
            28.675_050_063_104_8,
            max_relative = 1e-14
        );
    }

    #[test]
    fn case12_pins_the_wrong_data_table() {
        // The table's ω_OA = 0.5 rad/s would give 0.0954 rad/s, not the answer 0.572.
        assert_eq!(format!("{:.4}", link_rate(0.5)), "0.0954");
    }

    #[test]
    fn case12_loop_stays_closed() {
        let model = MODEL;
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        let times: Vec<f64> = (0..=40).map(|i| 0.05 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &NewtonOptions::default()).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
        }
    }
}
