//! Case 18: a rod sliding through a pivoted collar, the rod's angular acceleration
//! (Meriam & Kraige 7th ed., P5/204, p. 408).
//!
//! **Problem.** The crank OB (0.25 m) turns clockwise at a constant `ω_0 = 5 rad/s`; the rod
//! BD, pinned to the crank at B, slides through a collar pivoted at the fixed point C. Find
//! the angular acceleration `α_BD` of the rod at the instant shown.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `β = atan(250/600)` and `r_A/B = −0.65 i` with `0.65 = sqrt(0.25^2 + 0.6^2)`: the
//! triangle O-B-C is right-angled at O, OB = 0.25 m, OC = 0.6 m, BC = 0.65 m.
//! `r_OB = 0.25 (sin β i + cos β j)` and `r_A/B = −0.65 i`: the manual's axes are turned by β
//! so that x runs along the rod (in the sense D→B). In ground axes that is **OB vertical,
//! B = (0, 0.25), and C = (−0.6, 0)**, level with O: turning (0, 0.25) into the axes
//! `x' = (cos β, sin β)`, `y' = (−sin β, cos β)` gives `(0.25 sin β, 0.25 cos β)`, and
//! `C − B = (−0.6, −0.25) = −0.65 x'`. `ω_0 = −5 k` is constant (`a_B` has only its normal
//! term), so `v_B = (1.25, 0)`. "Point A" is the point of the rod momentarily at C. This
//! placement reproduces the manual's signs, `ω_BD = −0.74 k` and `α = −6.248 k`.
//!
//! **Model.** One driven coordinate, zero degrees of freedom, solved by kinematic analysis.
//! Driven: the crank angle from +y, clockwise, `ψ = ω_0 t`, so `B = 0.25 (sin ψ, cos ψ)`.
//! Free: the rod's angle φ (of C→B, from +x; `φ(0) = β = 22.62°`) and the distance s from C
//! to B along it (`s(0) = 0.65`). Constraint (2 equations): `C + s e(φ) = B(ψ)`. Bodies: the
//! crank and the rod as uniform rods, the collar at C turning with the rod; their masses
//! (1 kg), the rod's length (1 m) and gravity are not given in the problem and play no part
//! in the kinematics (the model has no gravity). At t = 0: `α_BD = φ''` (and `ω_BD = φ'`).
//!
//! **Reference (exact).** With `d = B − C = (0.6 + 0.25 sin ψ, 0.25 cos ψ)`, the rod's
//! direction turns at `ω_BD = (d × d')/|d|^2 = −0.3125/0.4225 = −125/169` and
//! `α_BD = (d × d'')/|d|^2 − 2 (d · d') ω_BD/|d|^2 = −1.115625/0.17850625`:
//! **`α_BD = −178500/28561 = −6.24978117012709639018241658205 rad/s^2`** (30 digits:
//! `mechanisms/reference/case18.py`, the vector formula and Newton on a redundant-coordinate
//! model of crank and rod, differentiated by mpmath).
//!
//! **Discrepancies in the manual.** Its method is right (the normal component of the collar
//! point's acceleration is the Coriolis term `2 ω_BD v_rel`), but it rounds `ω_BD` to 0.74
//! before forming `2 · 0.74 · 1.154 = 1.708`; with the exact `2 (125/169)(15/13) = 1.706873`,
//! `α = (−5.769231 + 1.706873)/0.65 = −6.249781`. Its text's −6.248 is that slip (−6.2485)
//! compounded by the rounded −5.769 and 1.154 (−6.24781); the table's **−6.25** is the exact value rounded, and RecurDyn's −6.24 agrees to 0.16 %.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qdd = gamma";

/// A crank OB turned clockwise at `omega_0` from the vertical; the rod BD, pinned at B,
/// slides through a collar pivoted at C, `oc` left of O. φ is the rod's angle, s the
/// distance CB.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(phi, s)]
#[drive(psi = omega_0 * t)]
#[constraint(s * cos(phi) - oc == ob * sin(psi))]
#[constraint(s * sin(phi) == ob * cos(psi))]
#[rigid(crank, mass = m, inertia = m * ob * ob / 12.0,
        at = [ob / 2.0 * sin(psi), ob / 2.0 * cos(psi)], angle = PI / 2.0 - psi)]
#[rigid(rod, mass = m, inertia = m * bd * bd / 12.0,
        at = [(s - bd / 2.0) * cos(phi) - oc, (s - bd / 2.0) * sin(phi)], angle = phi)]
#[rigid(collar, mass = m, inertia = m * ob * ob / 12.0, at = [-oc, 0.0], angle = phi)]
#[init(phi = atan2(ob, oc), s = hypot(ob, oc))]
#[output(omega_bd = angular_velocity(rod))]
#[output(alpha_bd = angular_acceleration(rod))]
pub struct RodThroughCollar {
    /// Mass of each body (immaterial to the kinematics).
    pub m: f64,
    pub ob: f64,
    /// Distance of the collar's pivot C left of O.
    pub oc: f64,
    /// Length of the rod (immaterial, at least BC).
    pub bd: f64,
    /// Clockwise angular velocity of the crank.
    pub omega_0: f64,
}

/// The manual's data.
pub const MODEL: RodThroughCollar = RodThroughCollar {
    m: 1.0,
    ob: 0.25,
    oc: 0.6,
    bd: 1.0,
    omega_0: 5.0,
};

/// The drawing beyond the model's shapes. The rod's far end and the collar's ends are free.
pub const SKETCH: Sketch = Sketch {
    free: &[At("rod", 2), At("collar", 1), At("collar", 2)],
    ..Sketch::NONE
};

/// `[ω_BD, α_BD]` at t = 0, the rotation rate of `d = B − C` (Meriam & Kraige Sect. 5/7):
/// `ω = (d × d')/|d|^2`, `α = (d × d'')/|d|^2 − 2 (d · d') ω/|d|^2`, with
/// `d = (oc + ob sin ψ, ob cos ψ)` and ψ turning uniformly.
pub fn rod_rates() -> [f64; 2] {
    let RodThroughCollar {
        ob, oc, omega_0: w, ..
    } = MODEL;
    let d = [oc, ob];
    let v = [ob * w, 0.0];
    let a = [0.0, -ob * w * w];
    let d2 = d[0] * d[0] + d[1] * d[1];
    let omega = (d[0] * v[1] - d[1] * v[0]) / d2;
    let alpha = (d[0] * a[1] - d[1] * a[0]) / d2 - 2.0 * (d[0] * v[0] + d[1] * v[1]) * omega / d2;
    [omega, alpha]
}

/// Exact reference `[α_BD]` (see the module docs).
pub fn references() -> [f64; 1] {
    [rod_rates()[1]]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &KinematicState<2>) -> Vector<4> {
    RodThroughCollarState {
        phi: k.q[0],
        s: k.q[1],
        phi_dot: k.qd[0],
        s_dot: k.qd[1],
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
    let [alpha_bd] = references();
    Ok(Outcome {
        rows: vec![Row {
            quantity: "alpha_BD",
            value: now.alpha_bd,
            reference: alpha_bd,
            method: METHOD,
            curve: Curve::at_instant(
                "angular acceleration of BD α_BD [rad/s²]",
                series(&samples, |o| o.alpha_bd),
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
    fn case18_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case18_references_are_the_exact_fractions() {
        // mechanisms/reference/case18.py: α_BD = −6.24978117012709639018241658205
        // = −178500/28561, ω_BD = −125/169.
        let [omega, alpha] = rod_rates();
        assert_relative_eq!(alpha, -178_500.0 / 28_561.0, max_relative = 1e-15);
        assert_relative_eq!(alpha, -6.249_781_170_127_096, max_relative = 1e-15);
        assert_relative_eq!(omega, -125.0 / 169.0, max_relative = 1e-15);
    }

    #[test]
    fn case18_references_round_to_the_manual() {
        let [omega, alpha] = rod_rates();
        assert_eq!(format!("{alpha:.2}"), "-6.25");
        assert_eq!(format!("{omega:.2}"), "-0.74");
    }

    #[test]
    fn case18_pins_the_text_slip() {
        // In the turned axes a_B,y' = −r ω_0^2 cos β, v_A = r ω_0 cos β, BC = 0.65, and
        // 0 = a_B,y' − BC α − 2 ω_BD v_A gives α.
        let (r, w, bc) = (0.25, 5.0, 0.65);
        let cos_beta = 0.6 / bc;
        let (a_b, v_a) = (-r * w * w * cos_beta, r * w * cos_beta);
        let alpha_with = |omega: f64| (a_b + 2.0 * omega * v_a) / bc;
        assert_relative_eq!(
            alpha_with(125.0 / 169.0),
            references()[0],
            max_relative = 1e-14
        );
        // The rounded ω_BD = 0.74 alone gives −6.2485; with the printed −5.769 and 1.154 too
        // it is the text's −6.248.
        assert_eq!(format!("{:.4}", alpha_with(0.74)), "-6.2485");
        assert_eq!(
            format!("{:.3}", (-5.769 + 2.0 * 0.74 * 1.154) / 0.65),
            "-6.248"
        );
    }

    #[test]
    fn case18_rod_rate_and_loop_closure() {
        let model = MODEL;
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        let opts = NewtonOptions::default();
        let k = kinematics(&model, 0.0, &guess, &opts).unwrap();
        // The init (B = C + BC e(β)) closes the loop exactly.
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        let o = model.outputs(0.0, &state(&k)).unwrap();
        assert_relative_eq!(o.omega_bd, rod_rates()[0], max_relative = 1e-12);
        // Over a turn of the crank the loop stays closed.
        let times: Vec<f64> = (0..=50).map(|i| 0.025 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &opts).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
        }
    }
}
