//! Case 15: a four-bar linkage, the angular velocities of the coupler and the rocker
//! (Meriam & Kraige 7th ed., P5/89, p. 361).
//!
//! **Problem.** In the four-bar O-B-A-C the crank OB turns clockwise at `ω_OB = 0.5 rad/s`.
//! Find the angular velocities of the coupler AB and of the rocker AC at the instant shown
//! (where `tan θ = 4/3` for the rocker).
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `v_B = −0.5 k × 0.12 j = 0.06 i`: O = (0, 0), B = (0, 0.12), the crank vertical, 120 mm.
//! `v_A = −ω_AC k × (−0.12 i + 0.16 j)`: `r_CA = (−0.12, 0.16)`, `|CA| = 0.2 m`, the 4/3 slope.
//! `v_A/B = −ω_AB k × (−0.24 i + 0.04 j)`: `r_BA = (−0.24, 0.04)`, so A = (−0.24, 0.16) and
//! C = A − r_CA = (−0.12, 0). Links: ground OC = 0.12, crank OB = 0.12, coupler
//! `BA = sqrt(0.0592) = 0.2433105`, rocker CA = 0.2. The manual takes the angular velocities
//! clockwise-positive (−k). Its heading "Calculate the Accelerations" is a mislabel: only
//! velocities are computed.
//!
//! **Model.** Driven: the crank angle `φ = π/2 − 0.5 t`. Free: the coupler's angle ψ (of B→A)
//! and the rocker's angle χ (of C→A), with the loop closure (2 equations)
//! `OB (cos φ, sin φ) + BA (cos ψ, sin ψ) = C + CA (cos χ, sin χ)`, the link lengths taken from
//! the instant's points. Bodies: the three moving links as uniform rods; their masses (1 kg;
//! not given) play no part in the kinematics, and neither does gravity (the model has none).
//! The clockwise angular velocities `ω_AB`, `ω_AC` are the model's outputs at t = 0.
//!
//! **Reference (exact).** The velocity loop `v_B + ω_AB k × r_BA = ω_AC k × r_CA`: its i row
//! `0.16 ω_AC = 0.06 + 0.04 ω_AB` and j row `0.12 ω_AC = 0.24 ω_AB` (clockwise-positive) give
//! **`ω_AB = 3/14 = 0.2142857… rad/s`, `ω_AC = 3/7 = 0.4285714… rad/s`**
//! (`mechanisms/reference/case15.py`: the closed form and a numerical differentiation of the
//! loop closure).
//!
//! **Discrepancies in the manual.** None: 0.214 and 0.429 are these, rounded (both
//! clockwise); RecurDyn agrees.

use crate::drawing::Sketch;
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qd = -Phi_t";

/// A four-bar: crank OB (`ob`, from O = (0, 0), clockwise at `omega_ob` from the vertical),
/// coupler BA and rocker CA about C = (c_x, 0), with A at `(a_x, a_y)` at t = 0; ψ and χ are
/// the angles of B→A and C→A.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(psi, chi)]
#[drive(phi = PI / 2.0 - omega_ob * t)]
#[constraint(ob * cos(phi) + hypot(a_x, a_y - ob) * cos(psi)
             == c_x + hypot(a_x - c_x, a_y) * cos(chi))]
#[constraint(ob * sin(phi) + hypot(a_x, a_y - ob) * sin(psi)
             == hypot(a_x - c_x, a_y) * sin(chi))]
#[rigid(crank, mass = m, inertia = m * ob * ob / 12.0,
        at = [ob / 2.0 * cos(phi), ob / 2.0 * sin(phi)], angle = phi)]
#[rigid(coupler, mass = m, inertia = m * (a_x * a_x + (a_y - ob) * (a_y - ob)) / 12.0,
        at = [ob * cos(phi) + hypot(a_x, a_y - ob) / 2.0 * cos(psi),
              ob * sin(phi) + hypot(a_x, a_y - ob) / 2.0 * sin(psi)], angle = psi)]
#[rigid(rocker, mass = m, inertia = m * ((a_x - c_x) * (a_x - c_x) + a_y * a_y) / 12.0,
        at = [c_x + hypot(a_x - c_x, a_y) / 2.0 * cos(chi),
              hypot(a_x - c_x, a_y) / 2.0 * sin(chi)], angle = chi)]
#[init(psi = atan2(a_y - ob, a_x), chi = atan2(a_y, a_x - c_x))]
#[output(omega_ab = -angular_velocity(coupler))]
#[output(omega_ac = -angular_velocity(rocker))]
pub struct FourBar {
    /// Mass of each link (immaterial to the kinematics).
    pub m: f64,
    pub ob: f64,
    /// Clockwise angular velocity of the crank.
    pub omega_ob: f64,
    /// A at the instant, and the rocker's pivot C = (c_x, 0).
    pub a_x: f64,
    pub a_y: f64,
    pub c_x: f64,
}

/// The manual's data.
pub const MODEL: FourBar = FourBar {
    m: 1.0,
    ob: 0.12,
    omega_ob: 0.5,
    a_x: -0.24,
    a_y: 0.16,
    c_x: -0.12,
};

/// The drawing: the model's own shapes.
pub const SKETCH: Sketch = Sketch::NONE;

/// Exact references `[ω_AB, ω_AC]`, clockwise-positive: the velocity loop
/// `v_B + w_1 k × r_BA = w_2 k × r_CA` (counter-clockwise w; Meriam & Kraige Sect. 5/4)
/// solved by Cramer's rule.
pub fn references() -> [f64; 2] {
    let FourBar {
        ob,
        omega_ob,
        a_x,
        a_y,
        c_x,
        ..
    } = MODEL;
    let (v_bx, v_by) = (omega_ob * ob, 0.0);
    let (ba_x, ba_y) = (a_x, a_y - ob);
    let (ca_x, ca_y) = (a_x - c_x, a_y);
    let det = ba_y * ca_x - ca_y * ba_x;
    let w1 = (v_bx * ca_x + ca_y * v_by) / det;
    let w2 = (ba_y * v_by + v_bx * ba_x) / det;
    [-w1, -w2]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &KinematicState<2>) -> Vector<4> {
    FourBarState {
        psi: k.q[0],
        chi: k.q[1],
        psi_dot: k.qd[0],
        chi_dot: k.qd[1],
    }
    .into()
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let opts = NewtonOptions::default();
    let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
    let now = model.outputs(0.0, &state(&kinematics(&model, 0.0, &guess, &opts)?))?;
    // Each compared quantity over the same span (the manual's plot and more).
    let times: Vec<f64> = (0..=100).map(|i| f64::from(i) / 100.0).collect();
    let samples = kinematic_sweep(&model, &times, &guess, &opts)?
        .iter()
        .map(|k| Ok((k.t, model.outputs(k.t, &state(k))?)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let [omega_ab, omega_ac] = references();
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "omega_AB",
                value: now.omega_ab,
                reference: omega_ab,
                method: METHOD,
                curve: Curve::at_instant(
                    "clockwise angular velocity of AB ω_AB [rad/s]",
                    series(&samples, |o| o.omega_ab),
                    0.0,
                ),
            },
            Row {
                quantity: "omega_AC",
                value: now.omega_ac,
                reference: omega_ac,
                method: METHOD,
                curve: Curve::at_instant(
                    "angular velocity of AC ω_AC [rad/s]",
                    series(&samples, |o| o.omega_ac),
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
    fn case15_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case15_references_are_the_fractions_and_round_to_the_manual() {
        // mechanisms/reference/case15.py: 3/14 and 3/7.
        let [omega_ab, omega_ac] = references();
        assert_relative_eq!(omega_ab, 3.0 / 14.0, max_relative = 1e-14);
        assert_relative_eq!(omega_ac, 3.0 / 7.0, max_relative = 1e-14);
        assert_eq!(format!("{omega_ab:.3}"), "0.214");
        assert_eq!(format!("{omega_ac:.3}"), "0.429");
    }

    #[test]
    fn case15_link_lengths_and_loop_closure() {
        let model = MODEL;
        let FourBar {
            ob, a_x, a_y, c_x, ..
        } = model;
        // Coupler sqrt(0.0592), rocker 0.2, ground 0.12.
        assert_relative_eq!(a_x.hypot(a_y - ob), 0.0592f64.sqrt(), max_relative = 1e-15);
        assert_relative_eq!((a_x - c_x).hypot(a_y), 0.2, max_relative = 1e-15);
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        let times: Vec<f64> = (0..=20).map(|i| 0.05 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &NewtonOptions::default()).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
        }
    }
}
