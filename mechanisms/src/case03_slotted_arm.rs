//! Case 03: a pin in a slotted arm, driven by a crank, in polar coordinates
//! (Meriam & Kraige 7th ed., P2/161, p. 77).
//!
//! **Problem.** A crank of 90 mm turns at a constant `β' = 60 rad/s`; its pin A slides in the
//! slot of an arm pivoted at O. At `β = 30°` find `r'`, `r''`, `θ'`, `θ''` of the pin in the
//! polar coordinates `(r, θ)` about O.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost). The manual's
//! loop closure `r cos θ + 90 cos β = 300`, `r sin θ = 90 sin β` (mm) puts the crank's centre
//! C 300 mm from O on the line θ = 0, and the pin at `A = C + 90 (−cos β, sin β)`: O = (0, 0),
//! C = (0.3, 0), `A = (0.3 − 0.09 cos β, 0.09 sin β)` m. At β = 30°: r = 0.226571 m,
//! θ = 11.4559°, `γ = β + θ = 41.456°`. Its `v_r = +v sin γ` and `v_θ = +v cos γ` (both
//! positive) follow from `A' = 0.09 β' (sin β, cos β)` with `β' = +60 rad/s`: β increases,
//! and `β'' = 0`, so the pin's acceleration is centripetal, `0.09 · 60^2 = 324 m/s^2` toward C.
//!
//! **Model.** Driven: `β = π/6 + 60 t`. Free: the pin's polar coordinates r (along the arm)
//! and θ (the arm's angle). Loop closure (2 equations):
//! `r (cos θ, sin θ) = C + 0.09 (−cos β, sin β)`. Bodies: the crank turning about C, the arm
//! turning about O, and the pin as a particle; their masses (1 kg; not given) play no part in
//! the kinematics, and neither does gravity (the model has none). `r'`, `r''`, `θ'`, `θ''`
//! are the model's outputs at t = 0, from a kinematic analysis.
//!
//! **Reference (exact).** With `A = C + a (−cos β, sin β)`, `A' = a β' (sin β, cos β)`,
//! `A'' = a β'^2 (cos β, −sin β)` and the polar unit vectors `e_r`, `e_θ` at A:
//! `r' = A' · e_r`, `r θ' = A' · e_θ`, `r'' = A'' · e_r + r θ'^2`,
//! `θ'' = (A'' · e_θ − 2 r' θ')/r` (Meriam & Kraige Eq. 2/14). So **`r' = 3.57503097043263
//! m/s`, `r'' = 315.118336703883 m/s^2`, `θ' = 17.8624290534681 rad/s`,
//! `θ'' = −1510.4255702626 rad/s^2`** (`mechanisms/reference/case03.py`: the closed form and a
//! numerical differentiation of the loop closure's solution).
//!
//! **Discrepancies in the manual.** Its table's labels are shifted by one ("r 3.58,
//! ṙ 315, …"): the values are r' and r'' (the comparison table names them `r_dot`,
//! `r_ddot`). Its **θ' = 17.88 is a typo**: the worked solution and RecurDyn give 17.86, and
//! the exact 17.8624 is the corrected value. The worked `r'' = 315 082.68 mm/s^2` squares the
//! rounded `θ' = 17.86` (with `r = 226.57`, `γ = 41.46°`): the exact value is 315 118.34
//! (RecurDyn 315.12); its table's 315 is right. The worked `θ'' = −1510.48` uses the rounded
//! `r'`, `θ'` and γ: exactly −1510.4256 (RecurDyn −1510.43); the table's −1510 is right.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row, series};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str =
    "kinematic analysis: Newton on Phi = 0 (tol 1e-12), Phi_q qd = -Phi_t, Phi_q qdd = gamma";

/// A crank of radius `a` about C (at `oc` from O on the line θ = 0) turning at `beta_dot`
/// from `beta_0`; its pin at polar coordinates `(r, θ)` about O slides in the arm's slot.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(r, theta)]
#[drive(beta = beta_0 + beta_dot * t)]
#[constraint(r * cos(theta) == oc - a * cos(beta))]
#[constraint(r * sin(theta) == a * sin(beta))]
#[rigid(crank, mass = m, inertia = m * a * a / 12.0,
        at = [oc - a / 2.0 * cos(beta), a / 2.0 * sin(beta)], angle = PI - beta)]
#[rigid(arm, mass = m, inertia = m * (oc + a) * (oc + a) / 12.0,
        at = [(oc + a) / 2.0 * cos(theta), (oc + a) / 2.0 * sin(theta)], angle = theta)]
#[particle(pin, mass = m, at = [r * cos(theta), r * sin(theta)])]
#[init(r = hypot(oc - a * cos(beta_0), a * sin(beta_0)),
       theta = atan2(a * sin(beta_0), oc - a * cos(beta_0)))]
#[output(r_dot = der(r))]
#[output(r_ddot = der(der(r)))]
#[output(theta_dot = der(theta))]
#[output(theta_ddot = der(der(theta)))]
pub struct SlottedArm {
    /// Mass of each body (immaterial to the kinematics).
    pub m: f64,
    /// Crank radius.
    pub a: f64,
    /// Distance from the arm's pivot O to the crank's centre C.
    pub oc: f64,
    pub beta_0: f64,
    pub beta_dot: f64,
}

/// The manual's data.
pub const MODEL: SlottedArm = SlottedArm {
    m: 1.0,
    a: 0.09,
    oc: 0.3,
    beta_0: std::f64::consts::FRAC_PI_6,
    beta_dot: 60.0,
};

/// The drawing beyond the model's shapes. The slotted arm's tip is free.
pub const SKETCH: Sketch = Sketch {
    free: &[At("arm", 1)],
    ..Sketch::NONE
};

/// Exact references `[r', r'', θ', θ'']` at t = 0 (see the module docs).
pub fn references() -> [f64; 4] {
    let SlottedArm {
        a,
        oc,
        beta_0: b,
        beta_dot: w,
        ..
    } = MODEL;
    let p = [oc - a * b.cos(), a * b.sin()];
    let v = [a * w * b.sin(), a * w * b.cos()];
    let acc = [a * w * w * b.cos(), -a * w * w * b.sin()];
    let r = p[0].hypot(p[1]);
    let (e_r, e_theta) = ([p[0] / r, p[1] / r], [-p[1] / r, p[0] / r]);
    let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
    let r_dot = dot(v, e_r);
    let theta_dot = dot(v, e_theta) / r;
    let r_ddot = dot(acc, e_r) + r * theta_dot * theta_dot;
    let theta_ddot = (dot(acc, e_theta) - 2.0 * r_dot * theta_dot) / r;
    [r_dot, r_ddot, theta_dot, theta_ddot]
}

/// The state `[q; qd]` of a kinematic solution, for the model's outputs.
fn state(k: &KinematicState<2>) -> Vector<4> {
    SlottedArmState {
        r: k.q[0],
        theta: k.q[1],
        r_dot: k.qd[0],
        theta_dot: k.qd[1],
    }
    .into()
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let opts = NewtonOptions::default();
    let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
    let now = model.outputs(0.0, &state(&kinematics(&model, 0.0, &guess, &opts)?))?;
    // Each rate over one turn of the crank.
    let turn = 2.0 * std::f64::consts::PI / model.beta_dot;
    let times: Vec<f64> = (0..=200).map(|i| turn * f64::from(i) / 200.0).collect();
    let samples = kinematic_sweep(&model, &times, &guess, &opts)?
        .iter()
        .map(|k| Ok((k.t, model.outputs(k.t, &state(k))?)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let [r_dot, r_ddot, theta_dot, theta_ddot] = references();
    let row = |quantity, value, reference, label, f: fn(&SlottedArmOutputs) -> f64| Row {
        quantity,
        value,
        reference,
        method: METHOD,
        curve: Curve::at_instant(label, series(&samples, f), 0.0),
    };
    Ok(Outcome {
        rows: vec![
            row(
                "r_dot",
                now.r_dot,
                r_dot,
                "pin velocity along the slot r' [m/s]",
                |o| o.r_dot,
            ),
            row("r_ddot", now.r_ddot, r_ddot, "r'' [m/s²]", |o| o.r_ddot),
            row(
                "theta_dot",
                now.theta_dot,
                theta_dot,
                "arm's angular velocity θ' [rad/s]",
                |o| o.theta_dot,
            ),
            row(
                "theta_ddot",
                now.theta_ddot,
                theta_ddot,
                "θ'' [rad/s²]",
                |o| o.theta_ddot,
            ),
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case03_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case03_references_are_the_script_values() {
        // mechanisms/reference/case03.py.
        let [r_dot, r_ddot, theta_dot, theta_ddot] = references();
        assert_relative_eq!(r_dot, 3.575_030_970_432_63, max_relative = 1e-14);
        assert_relative_eq!(r_ddot, 315.118_336_703_883, max_relative = 1e-14);
        assert_relative_eq!(theta_dot, 17.862_429_053_468_1, max_relative = 1e-14);
        assert_relative_eq!(theta_ddot, -1_510.425_570_262_6, max_relative = 1e-14);
    }

    #[test]
    fn case03_references_round_to_the_manual_where_it_is_right() {
        let [r_dot, r_ddot, _, theta_ddot] = references();
        assert_eq!(format!("{r_dot:.2}"), "3.58");
        assert_eq!(format!("{r_ddot:.0}"), "315");
        assert_eq!(format!("{theta_ddot:.0}"), "-1510");
    }

    #[test]
    fn case03_pins_the_corrections() {
        let [_, r_ddot, theta_dot, theta_ddot] = references();
        // The table's θ' = 17.88 is a typo for the worked solution's 17.86.
        assert_eq!(format!("{theta_dot:.2}"), "17.86");
        // The worked r'' and θ'' (mm) come from the rounded θ' = 17.86, r = 226.57,
        // γ = 41.46° and r' = 3575.32:
        let g = 41.46f64.to_radians();
        let r_ddot_manual = 226.57 * 17.86 * 17.86 + 324e3 * g.cos();
        assert_eq!(format!("{r_ddot_manual:.2}"), "315082.68");
        let theta_ddot_manual = (-324e3 * g.sin() - 2.0 * 3575.32 * 17.86) / 226.57;
        assert_eq!(format!("{theta_ddot_manual:.2}"), "-1510.48");
        // Exactly: 315 118.34 mm/s^2 and −1510.4256 rad/s^2 (RecurDyn 315.12, −1510.43).
        assert_eq!(format!("{:.2}", 1e3 * r_ddot), "315118.34");
        assert_eq!(format!("{theta_ddot:.2}"), "-1510.43");
    }

    #[test]
    fn case03_pin_acceleration_is_centripetal_and_the_loop_stays_closed() {
        let model = MODEL;
        let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
        let opts = NewtonOptions::default();
        assert!(model.phi(0.0, &guess).norm() < 1e-15);
        let times: Vec<f64> = (0..=40).map(|i| 0.0025 * f64::from(i)).collect();
        for k in kinematic_sweep(&model, &times, &guess, &opts).unwrap() {
            assert!(model.phi(k.t, &k.q).norm() < 1e-12);
            // |a_pin| = a β'^2 at every instant: (r'' − r θ'^2)^2 + (r θ'' + 2 r' θ')^2.
            let o = model.outputs(k.t, &state(&k)).unwrap();
            let r = k.q[0];
            let a_r = o.r_ddot - r * o.theta_dot * o.theta_dot;
            let a_theta = r * o.theta_ddot + 2.0 * o.r_dot * o.theta_dot;
            assert_relative_eq!(
                a_r.hypot(a_theta),
                model.a * model.beta_dot * model.beta_dot,
                max_relative = 1e-10
            );
        }
    }
}
