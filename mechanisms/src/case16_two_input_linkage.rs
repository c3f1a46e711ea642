//! Case 16: a two-input linkage, the angular velocity of BC (Meriam & Kraige 7th ed.,
//! P5/195, p. 405).
//!
//! **Problem.** Link OC (pivot O, `OC = 0.3 m`) turns clockwise at `ω_OC = 2 rad/s` while
//! the slider A moves horizontally at `v_A = 1.2 m/s`; A and C are joined by the links AB
//! (0.5 m) and BC (0.4 m), pinned at B. Find the angular velocity `ω_BC` of BC (the manual
//! also finds `ω_AB`). Both inputs are prescribed, so the linkage has no free motion.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `v_C = −ω_OC k × 0.3 j = 0.6 i`: C is 0.3 m directly above O and OC turns clockwise.
//! `v_B/C = (v_A − v_C)/tan θ = 0.6/(3/4)`, `v_B/A = (v_A − v_C)/sin θ = 0.6/(3/5)`,
//! `ω_BC = 0.8/0.4`, `ω_AB = 1.0/0.5`: BC = 0.4 m, AB = 0.5 m, and the angle θ between the
//! links is the 3-4-5 angle. `v_B = 0.6 i + 0.8 j` with `v_A = 1.2 i` (the same sense as
//! `v_C`, since the manual subtracts `v_A − v_C = 0.6`): `v_B/C = 0.8 j` is normal to BC, so
//! **BC is horizontal**; `v_B/A = −0.6 i + 0.8 j` is normal to AB, so **AB rises at
//! atan(3/4) = 36.87°**. With O at the origin, putting B left or right of C and A above or
//! below B gives four placements: B = (0.4, 0.3), A = (0, 0) puts A on the pivot O
//! (rejected); B = (−0.4, 0.3) with A = (−0.8, 0) or (0, 0.6) gives `ω_BC = −2`;
//! **B = (0.4, 0.3), A = (0.8, 0.6)** gives `ω_BC = +2`, `ω_AB = −2`, the only
//! non-degenerate placement that reproduces RecurDyn's positive "angular velocity on Z axis
//! of BC" = 2. That one is chosen: at t = 0, O = (0, 0), C = (0, 0.3), B = (0.4, 0.3),
//! A = (0.8, 0.6), and A runs on the line y = 0.6.
//!
//! **Model.** Zero degrees of freedom, solved by kinematic analysis. Driven: the angle of
//! O→C, `θ_OC = π/2 − ω_OC t`, and the slider, `x_A = 0.8 + v_A t`. Free: the link angles
//! `θ_CB` (of C→B) and `θ_BA` (of B→A), both from +x. Loop closure (2 equations):
//! `OC e(θ_OC) + CB e(θ_CB) + AB e(θ_BA) = (x_A, y_A)`, `e(θ) = (cos θ, sin θ)`. The links
//! are uniform rods and the slider a particle; their masses (1 kg, not given in the problem)
//! play no part in the kinematics. Gravity plays none either and the model has none.
//! `ω_BC` is the angular velocity of link CB at t = 0.
//!
//! **Reference (exact).** The velocity loop `v_C + ω_BC k × (B − C) + ω_AB k × (A − B) = v_A`
//! with `v_C = −ω_OC k × (C − O) = (0.6, 0)`, `B − C = (0.4, 0)`, `A − B = (0.4, 0.3)`:
//! the x row `−0.3 ω_AB = 0.6` and the y row `0.4 ω_BC + 0.4 ω_AB = 0` give
//! **`ω_BC = 2 rad/s`** and `ω_AB = −2 rad/s`, exactly (`mechanisms/reference/case16.py`:
//! the closed form, and Newton plus the velocity solve on the loop-closure model, at 30
//! digits).
//!
//! **Discrepancies in the manual.** None: its arithmetic is exact (a 3-4-5 triangle) and
//! RecurDyn's 2 agrees.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qd = -Phi_t";

/// Link OC turned clockwise at `omega_oc` from the vertical, slider A driven along
/// `y = y_a` at `v_a` from `x_a0`, and the links CB and BA between them.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(theta_cb, theta_ba)]
#[drive(theta_oc = PI / 2.0 - omega_oc * t)]
#[drive(x_a = x_a0 + v_a * t)]
#[constraint(oc * cos(theta_oc) + cb * cos(theta_cb) + ab * cos(theta_ba) == x_a)]
#[constraint(oc * sin(theta_oc) + cb * sin(theta_cb) + ab * sin(theta_ba) == y_a)]
#[rigid(link_oc, mass = m, inertia = m * oc * oc / 12.0,
        at = [oc / 2.0 * cos(theta_oc), oc / 2.0 * sin(theta_oc)], angle = theta_oc)]
#[rigid(link_cb, mass = m, inertia = m * cb * cb / 12.0,
        at = [oc * cos(theta_oc) + cb / 2.0 * cos(theta_cb),
              oc * sin(theta_oc) + cb / 2.0 * sin(theta_cb)], angle = theta_cb)]
#[rigid(link_ba, mass = m, inertia = m * ab * ab / 12.0,
        at = [x_a - ab / 2.0 * cos(theta_ba), y_a - ab / 2.0 * sin(theta_ba)], angle = theta_ba)]
#[particle(slider_a, mass = m, at = [x_a, y_a])]
#[init(theta_cb = 0.0, theta_ba = atan2(y_a - oc, x_a0 - cb))]
#[output(omega_bc = angular_velocity(link_cb))]
#[output(omega_ab = angular_velocity(link_ba))]
pub struct TwoInputLinkage {
    /// Mass of each link and of the slider (immaterial to the kinematics).
    pub m: f64,
    pub oc: f64,
    pub cb: f64,
    pub ab: f64,
    /// Clockwise angular velocity of OC.
    pub omega_oc: f64,
    /// Speed of the slider A (to the right).
    pub v_a: f64,
    /// Position of A at t = 0, and the height of its line.
    pub x_a0: f64,
    pub y_a: f64,
}

/// The manual's data.
pub const MODEL: TwoInputLinkage = TwoInputLinkage {
    m: 1.0,
    oc: 0.3,
    cb: 0.4,
    ab: 0.5,
    omega_oc: 2.0,
    v_a: 1.2,
    x_a0: 0.8,
    y_a: 0.6,
};

/// The drawing beyond the model's shapes. The slider's guide.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("slider_a", 0)],
    ..Sketch::NONE
};

/// `[ω_BC, ω_AB]` at t = 0 from the velocity loop
/// `v_C + ω_BC k × (B − C) + ω_AB k × (A − B) = v_A` (Meriam & Kraige Sect. 5/4), solved by
/// Cramer's rule, with the positions of the module docs.
pub fn link_rates() -> [f64; 2] {
    let TwoInputLinkage {
        oc,
        cb,
        omega_oc,
        v_a,
        x_a0,
        y_a,
        ..
    } = MODEL;
    // C = (0, oc), B = (cb, oc), A = (x_a0, y_a); v_C = −ω_OC k × (C − O).
    let (bc_x, bc_y) = (cb, 0.0);
    let (ab_x, ab_y) = (x_a0 - cb, y_a - oc);
    let (v_c_x, v_c_y) = (omega_oc * oc, 0.0);
    // Rows: −bc_y ω_BC − ab_y ω_AB = v_A − v_Cx;  bc_x ω_BC + ab_x ω_AB = −v_Cy.
    let (r_x, r_y) = (v_a - v_c_x, -v_c_y);
    let det = -bc_y * ab_x + ab_y * bc_x;
    [
        (r_x * ab_x + ab_y * r_y) / det,
        (-bc_y * r_y - r_x * bc_x) / det,
    ]
}

/// Exact reference `[ω_BC]` (see the module docs).
pub fn references() -> [f64; 1] {
    [link_rates()[0]]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &mbd::analysis::KinematicState<2>) -> Vector<4> {
    TwoInputLinkageState {
        theta_cb: k.q[0],
        theta_ba: k.q[1],
        theta_cb_dot: k.qd[0],
        theta_ba_dot: k.qd[1],
    }
    .into()
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let opts = NewtonOptions::default();
    let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
    let now = kinematics(&model, 0.0, &guess, &opts)?;
    let omega_bc = model.outputs(0.0, &state(&now))?.omega_bc;
    // ω_BC against time, from the instant until just before the links
    // BC and AB line up (|A − C| = 0.9 m, at about t = 0.075 s).
    let times: Vec<f64> = (0..=100).map(|i| 0.06 * f64::from(i) / 100.0).collect();
    let samples = kinematic_sweep(&model, &times, &guess, &opts)?
        .iter()
        .map(|k| Ok((k.t, model.outputs(k.t, &state(k))?)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let [reference] = references();
    Ok(Outcome {
        rows: vec![Row {
            quantity: "omega_BC",
            value: omega_bc,
            reference,
            method: METHOD,
            curve: Curve::at_instant(
                "angular velocity of BC ω_BC [rad/s]",
                series(&samples, |o| o.omega_bc),
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
    fn case16_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case16_references_are_exact_and_round_to_the_manual() {
        // mechanisms/reference/case16.py: ω_BC = 2, ω_AB = −2 exactly.
        let [omega_bc, omega_ab] = link_rates();
        assert_relative_eq!(omega_bc, 2.0, max_relative = 1e-15);
        assert_relative_eq!(omega_ab, -2.0, max_relative = 1e-15);
        assert_eq!(format!("{omega_bc:.0}"), "2");
        assert_eq!(format!("{:.0}", omega_ab.abs()), "2");
    }

    #[test]
    fn case16_closes_the_loop_at_the_reconstructed_instant() {
        let model = MODEL;
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        let k = kinematics(&model, 0.0, &guess, &NewtonOptions::default()).unwrap();
        // The reconstructed instant (BC horizontal, B = (0.4, 0.3)) closes the loop exactly:
        // θ_CB = 0, θ_BA = atan(3/4).
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        assert_relative_eq!(k.q[0], 0.0, epsilon = 1e-15);
        assert_relative_eq!(k.q[1], 0.75f64.atan(), max_relative = 1e-15);
        let o = model.outputs(0.0, &state(&k)).unwrap();
        assert_relative_eq!(o.omega_ab, link_rates()[1], max_relative = 1e-12);
        // Along the sweep the loop stays closed.
        let times: Vec<f64> = (0..=30).map(|i| 0.002 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &NewtonOptions::default()).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
        }
    }
}
