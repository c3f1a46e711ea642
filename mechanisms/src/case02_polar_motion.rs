//! Case 02: velocity and acceleration in polar coordinates (Meriam & Kraige 7th ed., P2/136,
//! p. 72).
//!
//! **Problem.** A point B moves with `r = 500 mm`, `r' = −150 mm/s` and `θ' = 60 deg/s` at
//! the instant considered. Find the magnitudes of its velocity `v` and acceleration `a`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost). B moves in
//! polar coordinates about a fixed pole O: `B = r (cos θ, sin θ)`. The manual's
//! `a_r = r'' − r θ'^2 = −548.31 mm/s^2` is exactly `−r θ'^2 = −500 (π/3)^2 = −548.311`, so
//! `r'' = 0`; its `a_θ = −314.16 mm/s^2` is exactly `2 r' θ' = 2 (−150)(π/3) = −314.159`, so
//! `θ'' = 0`. Both rates are therefore constant: `r(t) = 0.5 − 0.15 t m`,
//! `θ(t) = (π/3) t rad` (θ(0) = 0 is chosen; the magnitudes do not depend on it).
//!
//! **Model.** No free coordinate: r and θ are both driven, and B is a particle (1 kg, not
//! given and immaterial) at `r (cos θ, sin θ)`; no gravity (the motion is prescribed).
//! SI units (the manual works in mm; its table is in m). `v = |velocity(B)|` and
//! `a = |acceleration(B)|` are the model's outputs at t = 0.
//!
//! **Reference (exact).** `v = sqrt(r'^2 + (r θ')^2) = 0.544661066910457… m/s` and
//! `a = sqrt((r θ'^2)^2 + (2 r' θ')^2) = 0.631934638003356… m/s^2`
//! (`mechanisms/reference/case02.py`: the closed forms, and a numerical differentiation of the
//! position).
//!
//! **Discrepancies in the manual.** None: its 0.5447 and 0.63193 are these, rounded, and
//! RecurDyn agrees.

use crate::drawing::Sketch;
use crate::validation::{Curve, Outcome, Row, series};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "generated outputs of the driven motion";

/// A point B driven in polar coordinates: `r = r_0 + r_dot t`, `θ = theta_dot t`.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[drive(r = r_0 + r_dot * t)]
#[drive(theta = theta_dot * t)]
#[particle(b, mass = m, at = [r * cos(theta), r * sin(theta)])]
#[output(v = norm(velocity(b)))]
#[output(a = norm(acceleration(b)))]
pub struct PolarMotion {
    /// Mass of B (immaterial).
    pub m: f64,
    pub r_0: f64,
    pub r_dot: f64,
    pub theta_dot: f64,
}

/// The manual's data.
pub const MODEL: PolarMotion = PolarMotion {
    m: 1.0,
    r_0: 0.5,
    r_dot: -0.15,
    theta_dot: std::f64::consts::FRAC_PI_3,
};

/// The drawing: the model's own shapes (B alone; its polar radius is no member).
pub const SKETCH: Sketch = Sketch::NONE;

/// Exact references `[v, a]`: `v = sqrt(r'^2 + (r θ')^2)`,
/// `a = sqrt((r'' − r θ'^2)^2 + (r θ'' + 2 r' θ')^2)` with `r'' = θ'' = 0`
/// (Meriam & Kraige Eqs. 2/13 and 2/14).
pub fn references() -> [f64; 2] {
    let PolarMotion {
        r_0: r,
        r_dot,
        theta_dot,
        ..
    } = MODEL;
    [
        r_dot.hypot(r * theta_dot),
        (r * theta_dot * theta_dot).hypot(2.0 * r_dot * theta_dot),
    ]
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let no_state = Vector::<0>::zeros();
    let now = model.outputs(0.0, &no_state)?;
    // B's speed and acceleration over time, while r > 0 (until t = 3.33 s).
    let samples = (0..=150)
        .map(|i| {
            let t = 3.0 * f64::from(i) / 150.0;
            Ok((t, model.outputs(t, &no_state)?))
        })
        .collect::<mbd::Result<Vec<_>>>()?;
    let [v, a] = references();
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "v",
                value: now.v,
                reference: v,
                method: METHOD,
                curve: Curve::at_instant("speed of B v [m/s]", series(&samples, |o| o.v), 0.0),
            },
            Row {
                quantity: "a",
                value: now.a,
                reference: a,
                method: METHOD,
                curve: Curve::at_instant(
                    "acceleration of B a [m/s²]",
                    series(&samples, |o| o.a),
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
    fn case02_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-12);
        }
    }

    #[test]
    fn case02_references_round_to_the_manual() {
        // mechanisms/reference/case02.py: v = 0.544661066910457, a = 0.631934638003356.
        let [v, a] = references();
        assert_relative_eq!(v, 0.544_661_066_910_457, max_relative = 1e-14);
        assert_relative_eq!(a, 0.631_934_638_003_356, max_relative = 1e-14);
        assert_eq!(format!("{v:.4}"), "0.5447");
        assert_eq!(format!("{a:.5}"), "0.63193");
        // The manual's components, in mm/s^2: a_r = −548.31, a_θ = −314.16.
        let PolarMotion {
            r_0,
            r_dot,
            theta_dot,
            ..
        } = MODEL;
        assert_eq!(
            format!("{:.2}", -1e3 * r_0 * theta_dot * theta_dot),
            "-548.31"
        );
        assert_eq!(format!("{:.2}", 2e3 * r_dot * theta_dot), "-314.16");
    }

    #[test]
    fn case02_kinetic_energy_of_the_driven_point() {
        // With no gravity the energy is m v^2 / 2 at every instant.
        let model = MODEL;
        let none = Vector::<0>::zeros();
        for t in [0.0, 0.7, 2.1] {
            let v = model.outputs(t, &none).unwrap().v;
            let r = model.r_0 + model.r_dot * t;
            assert_relative_eq!(
                v,
                model.r_dot.hypot(r * model.theta_dot),
                max_relative = 1e-14
            );
            assert_relative_eq!(
                MechanismModel::energy(&model, t, &none, &none).unwrap(),
                0.5 * model.m * v * v,
                max_relative = 1e-14
            );
        }
    }
}
