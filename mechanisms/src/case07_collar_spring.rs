//! Case 07: a collar pulled up a smooth rod by a spring, its speed at the stop B
//! (Meriam & Kraige 7th ed., P3/139, p. 182).
//!
//! **Problem.** A 0.9-kg collar is released from rest at A and slides up a smooth fixed rod
//! in the vertical plane to the stop at B, pulled by a spring (`k = 24 N/m`, unstretched
//! length 0.375 m) anchored at the fixed point O. Find its speed `v_B` at B.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost). The worked
//! stretches are `x_A = 0.4996 m` at A and `x_B = 0.125 m` at B, and B is `h_B = 0.25 m`
//! above A: `|OB| = 0.5 m`, `|OA| = 0.8746 m = sqrt(0.45^2 + 0.75^2)`. So with B directly
//! below O: O = (0, 0), B = (0, −0.5), A = (0.45, −0.75), 0.25 m below B (swapping 0.45 and
//! 0.75 would put A only 0.05 m below B). RecurDyn measures "v when the slider's X
//! displacement is zero": B at x = 0, below the anchor, consistent. The rod is the straight
//! line A→B (0.514782 m). The mass 0.9 kg is the textbook's datum (the manual's formula
//! needs it). g: with the printed `x_A = 0.4996` and `g = 9.807` the manual's formula gives
//! 1.15578 → 1.1558, with 9.81 it would give 1.15514: the manual used **g = 9.807**.
//!
//! **Model.** One free coordinate s, the distance from A along the rod: the collar, a
//! particle, at `A + s (B − A)/|B − A|`. The spring runs from the fixed point O to the
//! collar. Gravity `(0, −g)`; the rod is smooth. From rest at s = 0, B is the downward zero
//! crossing of the collar's x (terminal); `v_B` is the model's speed output there.
//!
//! **Reference (exact).** Energy: `v_B = sqrt((k/m)(x_A^2 − x_B^2) − 2 g h_B)` with
//! `x_A = sqrt(0.765) − 0.375 = 0.499642784226795 m`, `x_B = 0.125 m`:
//! **`v_B = 1.15627749645033 m/s`** at g = 9.807 (`mechanisms/reference/case07.py`: the
//! closed form and a numerical integration).
//!
//! **Discrepancies in the manual.** It rounds `x_A` to 0.4996 before squaring (and
//! multiplying by `k/m = 26.67`), which loses 0.0005 m/s: its 1.1558 is 1.15578; with the
//! exact `x_A` the value is **1.1562775** (the corrected reference, at the manual's g).
//! RecurDyn's 1.1556 matches g = 9.81 (1.1556287).

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Curve, Outcome, Row};
use mbd::prelude::*;

/// A collar on the straight rod from A to B (directly below the anchor O), pulled by a
/// spring from O; s is the distance travelled from A.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(s)]
#[point(anchor, at = [0.0, 0.0])]
#[particle(collar, mass = m,
           at = [a_x - a_x * s / hypot(a_x, b_y - a_y),
                 a_y + (b_y - a_y) * s / hypot(a_x, b_y - a_y)])]
#[spring(spring, from = anchor, to = collar, k = k, length = l0)]
#[init(s = 0.0, der(s) = 0.0)]
#[output(speed = norm(velocity(collar)))]
#[event(at_b = position(collar)[0], falling, terminal)]
pub struct CollarOnRod {
    pub m: f64,
    pub g: f64,
    pub k: f64,
    /// Unstretched length of the spring.
    pub l0: f64,
    /// The start A = (a_x, a_y) and the stop B = (0, b_y), O at the origin.
    pub a_x: f64,
    pub a_y: f64,
    pub b_y: f64,
}

/// The manual's data.
pub const MODEL: CollarOnRod = CollarOnRod {
    m: 0.9,
    g: 9.807,
    k: 24.0,
    l0: 0.375,
    a_x: 0.45,
    a_y: -0.75,
    b_y: -0.5,
};

/// The drawing beyond the model's shapes. The smooth rod the collar runs on.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("collar", 0)],
    ..Sketch::NONE
};

/// `v_B` from the work-energy balance `½ m v_B^2 = ½ k (x_A^2 − x_B^2) − m g h_B` (Meriam &
/// Kraige Sect. 3/7), given the stretch at A.
pub fn speed_at_b(x_a: f64, g: f64) -> f64 {
    let CollarOnRod {
        m, k, l0, a_y, b_y, ..
    } = MODEL;
    let x_b = -b_y - l0;
    ((k / m) * (x_a * x_a - x_b * x_b) - 2.0 * g * (b_y - a_y)).sqrt()
}

/// Exact reference `[v_B]` (see the module docs).
pub fn references() -> [f64; 1] {
    let CollarOnRod {
        g, l0, a_x, a_y, ..
    } = MODEL;
    [speed_at_b(a_x.hypot(a_y) - l0, g)]
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let sol = sim::integrate(&model, model.initial_state(), 5.0, &model.events())?;
    let at_b = sol
        .events
        .iter()
        .find(|e| e.event == 0)
        .ok_or(mbd::Error::InvalidInput {
            what: "case 07",
            detail: "the collar did not reach B".into(),
        })?;
    let v_b = model.outputs(at_b.t, &at_b.y)?.speed;
    let [reference] = references();
    Ok(Outcome {
        rows: vec![Row {
            quantity: "v_B",
            value: v_b,
            reference,
            method: sim::METHOD,
            curve: Curve::at_instant(
                "speed of the collar v [m/s]",
                sim::curve(&sol, 200, |t, y| Ok(model.outputs(t, y)?.speed))?,
                at_b.t,
            ),
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case07_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case07_reference_is_the_script_value() {
        // mechanisms/reference/case07.py: v_B = 1.15627749645033 (g = 9.807, exact x_A).
        assert_relative_eq!(references()[0], 1.156_277_496_450_33, max_relative = 1e-14);
    }

    #[test]
    fn case07_pins_the_corrected_speed() {
        // The manual's 1.1558 squares the rounded x_A = 0.4996 (1.15578440896216, case07.py).
        let manual = speed_at_b(0.4996, MODEL.g);
        assert_relative_eq!(manual, 1.155_784_408_962_16, max_relative = 1e-13);
        assert_eq!(format!("{manual:.4}"), "1.1558");
        assert_eq!(format!("{:.4}", references()[0]), "1.1563");
        // RecurDyn's 1.1556 matches g = 9.81 (1.15562868119367).
        let x_a = MODEL.a_x.hypot(MODEL.a_y) - MODEL.l0;
        assert_relative_eq!(
            speed_at_b(x_a, 9.81),
            1.155_628_681_193_67,
            max_relative = 1e-13
        );
    }

    #[test]
    fn case07_energy_is_conserved() {
        let model = MODEL;
        let sol = sim::integrate(&model, model.initial_state(), 5.0, &model.events()).unwrap();
        let energy = |y: &Vector<2>| {
            MechanismModel::energy(
                &model,
                0.0,
                &Vector::<1>::new(y[0]),
                &Vector::<1>::new(y[1]),
            )
            .unwrap()
        };
        let e0 = energy(&sol.y[0]);
        for y in &sol.y {
            assert_relative_eq!(
                energy(y),
                e0,
                epsilon = 1e-10 * model.k * model.l0 * model.l0
            );
        }
    }
}
