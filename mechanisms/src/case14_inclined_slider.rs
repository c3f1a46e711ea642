//! Case 14: a crank, a link and a slider on an inclined guide, the speeds of the slider and
//! of the link's midpoint (Meriam & Kraige 7th ed., P5/80, p. 359).
//!
//! **Problem.** The crank OB (`r = 0.25 m`) turns clockwise at `ω_OB = 0.8 rad/s`; the link AB
//! (`l = 0.5 m`) drives the end A along a straight guide inclined at 20°. At the instant OB is
//! horizontal find the speed `v_A` of A and `v_C` of the link's midpoint C.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `v_B = −0.8 k × 0.25 i = −0.2 j`: O = (0, 0), B = (0.25, 0). `OA = sqrt(l^2 − r^2) = 0.433`
//! and "θ = acos(r/l) = 60°": the triangle OAB is right-angled at O, A = (0, −0.4330127)
//! directly below O. The instant centre I: `IA = 0.461 = OA/cos 20°` and
//! `r_IA = (0.158, −0.433)`, `0.158 = OA tan 20°`; I is on the line OB (normal to `v_B`) at
//! x = −0.1576, so the normal to A's path makes 20° with the vertical: **A's guide is the line
//! through A along (cos 20°, sin 20°)**. The table's "OA–OB angle β = 20°" is this inclination,
//! mislabelled. `r_BC = −0.25 (cos 60°, sin 60°)`: C is the midpoint of AB. (The RecurDyn text
//! "measure the time when the slider is 1 m" is copied from case 09.)
//!
//! **Model.** Driven: the crank angle `φ = −0.8 t`. Free: the slider's travel s along the
//! guide from its position at t = 0 and the link's angle ψ (of B→A), with the loop closure
//! (2 equations) `r (cos φ, sin φ) + l (cos ψ, sin ψ) = (0, −h) + s (cos 20°, sin 20°)`,
//! `h = sqrt(l^2 − r^2)`. Bodies: the crank about O, the link (mass centre C), the slider at A;
//! their masses (1 kg; not given) play no part in the kinematics, and neither does gravity (the
//! model has none). `v_A` and `v_C` are the model's speeds at t = 0.
//!
//! **Reference (exact).** With `x_I = −h tan 20°`: `ω_AB = r ω_OB/(r − x_I)`,
//! `v_A = ω_AB h / cos 20°`, `v_C = ω_AB sqrt((r/2 − x_I)^2 + (h/2)^2)`:
//! **`v_A = 0.226103174969427 m/s`, `v_C = 0.174682126915598 m/s`**,
//! `ω_AB = 0.490672638762271 rad/s` (`mechanisms/reference/case14.py`: the closed forms and a
//! numerical differentiation of the loop closure).
//!
//! **Discrepancies in the manual.** It rounds `ω_AB` to 0.49 and `r_IA` to (0.158, −0.433), so
//! its **`v_A = 0.2259`** is 0.1 % low: the corrected value is **0.22610317** (RecurDyn's
//! 0.2261 agrees). Its `v_C = 0.1747` happens to round correctly.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qd = -Phi_t";

/// A crank OB of radius r turning clockwise at `omega_ob` from the horizontal, the link BA of
/// length l, and the slider A on the guide at `incline` through `(0, −sqrt(l^2 − r^2))`; s is
/// the slider's travel, ψ the link's angle.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(s, psi)]
#[drive(phi = -omega_ob * t)]
#[constraint(r * cos(phi) + l * cos(psi) == s * cos(incline))]
#[constraint(r * sin(phi) + l * sin(psi) == s * sin(incline) - sqrt(l * l - r * r))]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0,
        at = [r / 2.0 * cos(phi), r / 2.0 * sin(phi)], angle = phi)]
#[rigid(link, mass = m, inertia = m * l * l / 12.0,
        at = [r * cos(phi) + l / 2.0 * cos(psi), r * sin(phi) + l / 2.0 * sin(psi)],
        angle = psi)]
#[particle(slider, mass = m,
           at = [s * cos(incline), s * sin(incline) - sqrt(l * l - r * r)])]
#[init(s = 0.0, psi = atan2(-sqrt(l * l - r * r), -r))]
#[output(v_a = norm(velocity(slider)))]
#[output(v_c = norm(velocity(link)))]
#[output(omega_ab = -angular_velocity(link))]
pub struct InclinedSlider {
    /// Mass of each body (immaterial to the kinematics).
    pub m: f64,
    pub r: f64,
    pub l: f64,
    /// Clockwise angular velocity of the crank.
    pub omega_ob: f64,
    /// The guide's inclination.
    pub incline: f64,
}

/// The manual's data.
pub const MODEL: InclinedSlider = InclinedSlider {
    m: 1.0,
    r: 0.25,
    l: 0.5,
    omega_ob: 0.8,
    incline: 20.0 * std::f64::consts::PI / 180.0,
};

/// The drawing beyond the model's shapes. The inclined guide.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("slider", 0)],
    ..Sketch::NONE
};

/// `[v_A, v_C, ω_AB]` at t = 0 from the instant centre I on the line OB at
/// `x_I = −h tan(incline)` (Meriam & Kraige Sect. 5/5).
pub fn speeds() -> [f64; 3] {
    let InclinedSlider {
        r,
        l,
        omega_ob,
        incline,
        ..
    } = MODEL;
    let h = (l * l - r * r).sqrt();
    let x_i = -h * incline.tan();
    let omega_ab = r * omega_ob / (r - x_i);
    [
        omega_ab * h / incline.cos(),
        omega_ab * (r / 2.0 - x_i).hypot(h / 2.0),
        omega_ab,
    ]
}

/// Exact references `[v_A, v_C]`.
pub fn references() -> [f64; 2] {
    let [v_a, v_c, _] = speeds();
    [v_a, v_c]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &KinematicState<2>) -> Vector<4> {
    InclinedSliderState {
        s: k.q[0],
        psi: k.q[1],
        s_dot: k.qd[0],
        psi_dot: k.qd[1],
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
    let [v_a, v_c] = references();
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "v_A",
                value: now.v_a,
                reference: v_a,
                method: METHOD,
                curve: Curve::at_instant(
                    "speed of the slider v_A [m/s]",
                    series(&samples, |o| o.v_a),
                    0.0,
                ),
            },
            Row {
                quantity: "v_C",
                value: now.v_c,
                reference: v_c,
                method: METHOD,
                curve: Curve::at_instant(
                    "speed of the link's midpoint v_C [m/s]",
                    series(&samples, |o| o.v_c),
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
    fn case14_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case14_references_are_the_script_values() {
        // mechanisms/reference/case14.py.
        let [v_a, v_c, omega_ab] = speeds();
        assert_relative_eq!(v_a, 0.226_103_174_969_427, max_relative = 1e-14);
        assert_relative_eq!(v_c, 0.174_682_126_915_598, max_relative = 1e-14);
        assert_relative_eq!(omega_ab, 0.490_672_638_762_271, max_relative = 1e-14);
    }

    #[test]
    fn case14_references_round_to_the_manual_where_it_is_right() {
        let [_, v_c, omega_ab] = speeds();
        assert_eq!(format!("{v_c:.4}"), "0.1747");
        assert_eq!(format!("{omega_ab:.2}"), "0.49");
    }

    #[test]
    fn case14_pins_the_corrected_slider_speed() {
        let [v_a, ..] = speeds();
        // The manual's 0.2259 from the rounded ω_AB = 0.49 and r_IA = (0.158, −0.433).
        assert_eq!(format!("{:.4}", 0.49 * 0.158f64.hypot(0.433)), "0.2259");
        assert_eq!(format!("{v_a:.4}"), "0.2261");
    }

    #[test]
    fn case14_link_rate_and_loop_closure() {
        let model = MODEL;
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        let opts = NewtonOptions::default();
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        let k = kinematics(&model, 0.0, &guess, &opts).unwrap();
        let o = model.outputs(0.0, &state(&k)).unwrap();
        assert_relative_eq!(o.omega_ab, speeds()[2], max_relative = 1e-12);
        let times: Vec<f64> = (0..=20).map(|i| 0.05 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &opts).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
        }
    }
}
