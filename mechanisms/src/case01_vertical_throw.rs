//! Case 01: a ball thrown vertically (Meriam & Kraige 7th ed., P2.13, p. 31).
//!
//! **Problem.** A ball is thrown up from A at `v0 = 25 m/s`. Find the height `h` it rises
//! above B, 15 m above A, the time `t_AB` from A until it passes B on the way down, and its
//! speed `v_B` there. The manual uses `g = 9.807 m/s^2`.
//!
//! **Model.** One particle, one coordinate: its height `y` above A; gravity `-g`.
//! The apex is the zero crossing of `der(y)` (falling, recorded); B is the zero crossing of
//! `y - 15` on the way down (falling, terminal).
//!
//! **Reference (exact).** Constant deceleration: apex `S = v0^2 / (2g)`, so
//! `h = v0^2/(2g) - 15 = 16.864994392...`; `v_B = sqrt(v0^2 - 2 g 15) = 18.187633161...`;
//! `t_AB = (v0 + v_B)/g = 4.403755...`. The manual's 16.865, 4.404 and 18.188 are these,
//! rounded.

use crate::drawing::Sketch;
use crate::sim;
use crate::validation::{Curve, Outcome, Row};
use mbd::prelude::*;

/// A ball thrown up at `v0` from `y = 0`.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(y)]
#[particle(ball, mass = m, at = [0.0, y])]
#[init(y = 0.0, der(y) = v0)]
#[output(speed = norm(velocity(ball)))]
#[event(apex = der(y), falling)]
#[event(passes_b = y - b, falling, terminal)]
pub struct VerticalThrow {
    pub m: f64,
    pub g: f64,
    pub v0: f64,
    /// Height of B above A.
    pub b: f64,
}

/// The manual's data.
pub const MODEL: VerticalThrow = VerticalThrow {
    m: 1.0,
    g: 9.807,
    v0: 25.0,
    b: 15.0,
};

/// The drawing: the model's own shapes.
pub const SKETCH: Sketch = Sketch::NONE;

/// Exact references, from constant-acceleration kinematics (see the module docs).
pub fn references() -> [f64; 3] {
    let VerticalThrow { g, v0, b, .. } = MODEL;
    let v_b = (v0 * v0 - 2.0 * g * b).sqrt();
    [v0 * v0 / (2.0 * g) - b, (v0 + v_b) / g, v_b]
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let events = model.events();
    let sol = sim::integrate(&model, model.initial_state(), 10.0, &events)?;
    let apex = sol
        .events
        .iter()
        .find(|e| e.event == 0)
        .ok_or(mbd::Error::InvalidInput {
            what: "case 01",
            detail: "the apex was not reached".into(),
        })?;
    let at_b = sol
        .events
        .iter()
        .find(|e| e.event == 1)
        .ok_or(mbd::Error::InvalidInput {
            what: "case 01",
            detail: "B was not reached".into(),
        })?;
    let [h, t_ab, v_b] = references();
    let speed = model.outputs(at_b.t, &at_b.y)?.speed;
    let height = sim::sample(&sol, 200, |t, y| (t, y[0]));
    let above_b = sim::sample(&sol, 200, |t, y| (t, y[0] - model.b));
    let speeds = sim::curve(&sol, 200, |t, y| Ok(model.outputs(t, y)?.speed))?;
    let row = |quantity, value, reference, curve| Row {
        quantity,
        value,
        reference,
        method: sim::METHOD,
        curve,
    };
    Ok(Outcome {
        rows: vec![
            row(
                "h",
                apex.y[0] - model.b,
                h,
                Curve::at_instant("height above B y − 15 m [m]", above_b, apex.t),
            ),
            row(
                "t_AB",
                at_b.t,
                t_ab,
                Curve::instant_of("height above A y [m]", height, model.b),
            ),
            row(
                "v_B",
                speed,
                v_b,
                Curve::at_instant("speed [m/s]", speeds, at_b.t),
            ),
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case01_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case01_references_round_to_the_manual() {
        let [h, t_ab, v_b] = references();
        assert_eq!(format!("{h:.3}"), "16.865");
        assert_eq!(format!("{t_ab:.3}"), "4.404");
        assert_eq!(format!("{v_b:.3}"), "18.188");
    }
}
