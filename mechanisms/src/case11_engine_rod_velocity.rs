//! Case 11: a reciprocating engine, the velocity of the connecting rod's mass centre and its
//! angular velocity (Meriam & Kraige 7th ed., Sample Problem 5/9, p. 353).
//!
//! **Problem.** The crank OB (`r = 125 mm`) turns clockwise at 1500 rev/min = 50π rad/s; the
//! connecting rod AB (`l = 350 mm`) has its mass centre G 100 mm from B (250 mm from A); the
//! piston A runs on a line through O. At `θ = ∠AOB = 60°` find `v_A`, `v_G` and `ω_AB`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost). The law of
//! sines, `sin β = (r/l) sin θ`, gives `β = 18.0167°`, the angle of AB with the line OA. The
//! manual's `v_G/A = ω_AB × 0.25 (cos β, sin β)` from A: G is 0.25 m from A. Frame: O at the
//! origin, the piston's line along x with A on +x, `x_A = r cos θ + l cos β = 0.395358 m` at
//! the instant; `B = r (cos φ, sin φ)` with the crank angle `φ = θ`, and the clockwise crank
//! makes `φ(t) = π/3 − 50π t`. `G = A + 0.25 (cos ψ, sin ψ)`, `ψ = π − β` the angle of A→B;
//! `ω_AB = ψ' > 0` (counter-clockwise, as in the textbook).
//!
//! **Model.** Driven: the crank angle φ. Free: `x_A` and ψ, with the loop closure
//! (2 equations) `x_A + l (cos ψ, sin ψ) = r (cos φ, sin φ)`. Bodies: the crank OB and the
//! rod AB as uniform bars (mass centres at their midpoints, so that the report draws them
//! from joint to joint), and the piston; their masses (1 kg; not given) play no part in the
//! kinematics, and neither does gravity (the model has none). G is the rod's body-fixed point
//! 0.25 m from A (`a_g − l/2` from the midpoint towards B). `|v_G|` and `ω_AB` are the
//! model's outputs at t = 0, from a kinematic analysis.
//!
//! **Reference (exact).** From `l sin ψ = r sin φ`: `ψ' = r cos φ φ'/(l cos ψ)`,
//! `x_A' = −r sin φ φ' + l sin ψ ψ'`, `G' = (x_A' − 0.25 sin ψ ψ', 0.25 cos ψ ψ')`:
//! **`v_G = 19.2401164991188 m/s`**, **`ω_AB = 29.4962471631728 rad/s`**, and
//! `|v_A| = 20.1974314596473 m/s` (`mechanisms/reference/case11.py`: the closed forms and a
//! numerical differentiation of the loop closure).
//!
//! **Discrepancies in the manual.** Its `v_G = 19.23` comes from rounded intermediates
//! (`v_A = 20.19`, `ω_AB = 29.49`, `β = 18.02°` give 19.2327); exactly 19.2401, the textbook's
//! answer **19.24** (RecurDyn agrees): the corrected value. Its `ω_AB = 29.5` is right (the
//! worked 29.49 is 29.496 truncated); RecurDyn's 29.53 is 0.1 % off.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qd = -Phi_t";

/// A crank OB turning clockwise at `omega` from `phi_0`, the rod BA with its point G
/// `a_g` from A, and the piston A at `x_a` on the line through O; ψ is the angle of A→B.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(x_a, psi)]
#[drive(phi = phi_0 - omega * t)]
#[constraint(x_a + l * cos(psi) == r * cos(phi))]
#[constraint(l * sin(psi) == r * sin(phi))]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0,
        at = [r / 2.0 * cos(phi), r / 2.0 * sin(phi)], angle = phi)]
#[rigid(rod, mass = m, inertia = m * l * l / 12.0,
        at = [x_a + l / 2.0 * cos(psi), l / 2.0 * sin(psi)], angle = psi)]
#[particle(piston, mass = m, at = [x_a, 0.0])]
#[init(x_a = r * cos(phi_0) + sqrt(l * l - r * r * sin(phi_0) * sin(phi_0)),
       psi = PI - asin(r * sin(phi_0) / l))]
#[output(v_g = norm(velocity(rod, [a_g - l / 2.0, 0.0])))]
#[output(omega_ab = angular_velocity(rod))]
#[output(v_a = der(x_a))]
pub struct Engine {
    /// Mass of each body (immaterial to the kinematics).
    pub m: f64,
    pub r: f64,
    pub l: f64,
    /// Distance of the rod's mass centre G from A.
    pub a_g: f64,
    pub omega: f64,
    pub phi_0: f64,
}

/// The manual's data.
pub const MODEL: Engine = Engine {
    m: 1.0,
    r: 0.125,
    l: 0.35,
    a_g: 0.25,
    omega: 50.0 * std::f64::consts::PI,
    phi_0: std::f64::consts::FRAC_PI_3,
};

/// The drawing beyond the model's shapes. The piston's cylinder.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("piston", 0)],
    ..Sketch::NONE
};

/// `[|v_G|, ω_AB, |v_A|]` at t = 0 (see the module docs).
pub fn rates() -> [f64; 3] {
    let Engine {
        r,
        l,
        a_g,
        omega,
        phi_0: phi,
        ..
    } = MODEL;
    let phi_dot = -omega;
    let psi = std::f64::consts::PI - (r * phi.sin() / l).asin();
    let psi_dot = r * phi.cos() * phi_dot / (l * psi.cos());
    let x_dot = -r * phi.sin() * phi_dot + l * psi.sin() * psi_dot;
    let v_g = (x_dot - a_g * psi.sin() * psi_dot).hypot(a_g * psi.cos() * psi_dot);
    [v_g, psi_dot, x_dot.abs()]
}

/// Exact references `[v_G, ω_AB]`.
pub fn references() -> [f64; 2] {
    let [v_g, omega_ab, _] = rates();
    [v_g, omega_ab]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &KinematicState<2>) -> Vector<4> {
    EngineState {
        x_a: k.q[0],
        psi: k.q[1],
        x_a_dot: k.qd[0],
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
    let turn = 2.0 * std::f64::consts::PI / model.omega;
    let times: Vec<f64> = (0..=200).map(|i| turn * f64::from(i) / 200.0).collect();
    let samples = kinematic_sweep(&model, &times, &guess, &opts)?
        .iter()
        .map(|k| Ok((k.t, model.outputs(k.t, &state(k))?)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let [v_g, omega_ab] = references();
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "v_G",
                value: now.v_g,
                reference: v_g,
                method: METHOD,
                curve: Curve::at_instant(
                    "speed of the rod's mass centre v_G [m/s]",
                    series(&samples, |o| o.v_g),
                    0.0,
                ),
            },
            Row {
                quantity: "omega_AB",
                value: now.omega_ab,
                reference: omega_ab,
                method: METHOD,
                curve: Curve::at_instant(
                    "angular velocity of the rod ω_AB [rad/s]",
                    series(&samples, |o| o.omega_ab),
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
    fn case11_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case11_references_are_the_script_values() {
        // mechanisms/reference/case11.py.
        let [v_g, omega_ab, v_a] = rates();
        assert_relative_eq!(v_g, 19.240_116_499_118_8, max_relative = 1e-14);
        assert_relative_eq!(omega_ab, 29.496_247_163_172_8, max_relative = 1e-14);
        assert_relative_eq!(v_a, 20.197_431_459_647_3, max_relative = 1e-14);
    }

    #[test]
    fn case11_references_round_to_the_manual_where_it_is_right() {
        let [_, omega_ab, v_a] = rates();
        assert_eq!(format!("{omega_ab:.1}"), "29.5");
        assert_eq!(format!("{v_a:.2}"), "20.20");
        // The worked 29.49 and 20.19 truncate 29.496 and 20.197.
        assert_eq!(
            format!("{:.2}", (omega_ab * 100.0).trunc() / 100.0),
            "29.49"
        );
    }

    #[test]
    fn case11_pins_the_corrected_speed_of_g() {
        let [v_g, ..] = rates();
        // The manual's 19.23 from the rounded v_A = 20.19, ω_AB = 29.49, β = 18.02°:
        let beta = 18.02f64.to_radians();
        let manual = (20.19 - 0.25 * 29.49 * beta.sin()).hypot(0.25 * 29.49 * beta.cos());
        assert_eq!(format!("{manual:.2}"), "19.23");
        assert_eq!(format!("{v_g:.2}"), "19.24");
    }

    #[test]
    fn case11_piston_speed_and_loop_closure() {
        let model = MODEL;
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        let opts = NewtonOptions::default();
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        let k = kinematics(&model, 0.0, &guess, &opts).unwrap();
        let o = model.outputs(0.0, &state(&k)).unwrap();
        assert_relative_eq!(o.v_a.abs(), rates()[2], max_relative = 1e-12);
        let times: Vec<f64> = (0..=40).map(|i| 0.001 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &opts).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
        }
    }
}
