//! Case 23: a block turned 90° by a small reversing torque (Meriam & Kraige 7th ed.,
//! P6/57, p. 439).
//!
//! **Problem.** A 6000-kg block, 1.5 m × 2.5 m, turns about a fixed axis O at `d = 2.05 m`
//! from its mass centre G, driven by a torque `T = 30 N m`. It starts from rest and must
//! arrive at 90° at rest: the torque acts for the first 45°, then is reversed. Find the time
//! `t_90deg` of the 90° turn.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `I_G = (1/12) 6000 (1.5^2 + 2.5^2)`: a rectangular block turning about an axis normal to
//! its 1.5 × 2.5 face; `I_O = I_G + m 2.05^2`: the axis is 2.05 m from G. `ΣM_O = I_O α`
//! holds T alone, so gravity has no moment about the axis (a vertical axis): g plays no
//! part, and the model has none. `π/4 = ½ α t_1^2`, `t = 2 t_1`: uniform acceleration
//! through 45°, then the same deceleration through the next 45°, so the block stops at 90°.
//!
//! **Model.** One body, one free coordinate θ (the turn from the start): G at
//! `d (cos θ, sin θ)` (the direction at θ = 0 is immaterial), angle θ,
//! `I_G = 4250 kg m^2`, and the torque on the block. The reversal is a state event: phase 1
//! (torque `+T`) runs from rest to the first upward crossing of `θ − π/4` (terminal);
//! phase 2 (torque `−T`) starts from that state and runs to the stop, the downward crossing
//! of `θ'` (terminal). The model is autonomous, so phase 2 runs on its own clock and
//! `t_90deg = t_1 + t_2`. The stop is not sought as `θ − π/2 = 0`: there `θ' = 0`, a grazing
//! zero.
//!
//! **Reference (exact).** `α = T / I_O = 30 / 29465 = 1.018157135584…e-3 rad/s^2`;
//! `t_1 = sqrt(π I_O / (2 T)) = 39.2782865244957908…` s and
//! **`t_90deg = 2 t_1 = 78.5565730489915816190620404844 s`** (30 digits:
//! `mechanisms/reference/case23.py`, closed form and a two-phase integration).
//!
//! **Discrepancies in the manual.** None beyond rounding: its 78.56 is right to 4 digits (with
//! its rounded α = 1.018e-3 the time would be 78.5626). RecurDyn's 78.6 agrees.

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Animation, Curve, Frame, Outcome, Row};
use mbd::Drawable;
use mbd::integrate::Solution;
use mbd::prelude::*;

/// A rectangular block `a × b` turning about a fixed axis at `d` from its mass centre under a
/// torque `torque`; θ is the turn from the start.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(theta)]
#[point(axis, at = [0.0, 0.0])]
#[rigid(block, mass = m, inertia = m * (a * a + b * b) / 12.0,
        at = [axis[0] + d * cos(theta), axis[1] + d * sin(theta)], angle = theta)]
#[torque(turning, on = block, value = torque)]
#[init(theta = 0.0, der(theta) = 0.0)]
#[event(halfway = theta - theta_switch, rising, terminal)]
#[event(stops = der(theta), falling, terminal)]
pub struct Block {
    pub m: f64,
    /// The sides of the face normal to the axis.
    pub a: f64,
    pub b: f64,
    /// Distance from the axis O to G.
    pub d: f64,
    /// The applied torque (reversed at `theta_switch`).
    pub torque: f64,
    /// The angle at which the torque is reversed.
    pub theta_switch: f64,
}

/// The manual's data, for the first phase (torque `+T`).
pub const MODEL: Block = Block {
    m: 6000.0,
    a: 1.5,
    b: 2.5,
    d: 2.05,
    torque: 30.0,
    theta_switch: std::f64::consts::FRAC_PI_4,
};

/// The drawing beyond the model's shapes. The block from its axis O to its mass centre.
pub const SKETCH: Sketch = Sketch {
    bodies: &[("block", &[At("axis", 0)])],
    ..Sketch::NONE
};

/// The second phase: the torque reversed.
pub const REVERSED: Block = Block {
    torque: -MODEL.torque,
    ..MODEL
};

/// Moment of inertia about the axis: `I_O = m (a^2 + b^2)/12 + m d^2`.
pub fn inertia_about_o() -> f64 {
    let Block { m, a, b, d, .. } = MODEL;
    m * (a * a + b * b) / 12.0 + m * d * d
}

/// Exact reference `[t_90deg]`: `2 sqrt(π I_O / (2 T))` (see the module docs).
pub fn references() -> [f64; 1] {
    [2.0 * (std::f64::consts::PI * inertia_about_o() / (2.0 * MODEL.torque)).sqrt()]
}

/// The two phases: to the reversal, and from there (on its own clock) to the stop.
pub fn phases() -> mbd::Result<(Solution<2>, Solution<2>)> {
    let missing = |detail: &str| mbd::Error::InvalidInput {
        what: "case 23",
        detail: detail.into(),
    };
    let events = MODEL.events();
    let first = sim::integrate(&MODEL, MODEL.initial_state(), 200.0, &events[..1])?;
    let switch = first.events.first().ok_or(missing("45° was not reached"))?;
    // Phase 2 watches only the stop: it starts on the switch surface itself.
    let events = REVERSED.events();
    let second = sim::integrate(&REVERSED, switch.y, 200.0, &events[1..])?;
    second
        .events
        .first()
        .ok_or(missing("the block did not stop"))?;
    Ok((first, second))
}

/// The block over both phases (the torque reversed at the switch), for the report: `span`
/// and the stills as [`crate::validation::Draw`] asks, on the run's clock.
pub fn draw(span: f64, at: &[f64]) -> mbd::Result<Animation> {
    let (first, second) = phases()?;
    let t_switch = first.events[0].t;
    let end = t_switch + second.last().0;
    let frame = |t: f64| -> mbd::Result<Option<Frame>> {
        let (model, sol, t_phase) = if t <= t_switch {
            (&MODEL, &first, t)
        } else {
            (&REVERSED, &second, t - t_switch)
        };
        let Some(y) = sol.at(t_phase) else {
            return Ok(None);
        };
        let shapes = model.geometry(t_phase, &y)?;
        Ok(Some(Frame {
            t,
            shapes,
            outputs: Vec::new(),
            added: Vec::new(),
        }))
    };
    let span = span.min(end);
    let mut frames = Vec::new();
    for i in 0..=sim::FRAMES {
        frames.extend(frame(span * i as f64 / sim::FRAMES as f64)?);
    }
    let mut stills = Vec::new();
    for &t in at.iter().filter(|t| (0.0..=span).contains(*t)) {
        stills.extend(frame(t)?);
    }
    let drawn = Animation {
        frames,
        stills,
        ..Animation::default()
    };
    crate::drawing::apply(drawn, &SKETCH)
}

pub fn run() -> mbd::Result<Outcome> {
    let (first, second) = phases()?;
    let (t_switch, stop) = (first.events[0].t, &second.events[0]);
    let t_90 = t_switch + stop.t;
    let [reference] = references();
    let mut points = sim::sample(&first, 100, |t, y| (t, y[0].to_degrees()));
    points.extend(sim::sample(&second, 100, |t, y| {
        (t_switch + t, y[0].to_degrees())
    }));
    Ok(Outcome {
        rows: vec![Row {
            quantity: "t_90deg",
            value: t_90,
            reference,
            method: sim::METHOD,
            curve: Curve::instant_of("turn θ [deg]", points, stop.y[0].to_degrees()),
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case23_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case23_reference_is_the_30_digit_value() {
        // mechanisms/reference/case23.py: t_90deg = 78.5565730489915816190620404844 s.
        assert_relative_eq!(references()[0], 78.556_573_048_991_58, max_relative = 1e-15);
        assert_relative_eq!(inertia_about_o(), 29465.0, max_relative = 1e-15);
    }

    #[test]
    fn case23_stops_at_90_degrees_with_the_work_of_the_torque() {
        let (first, second) = phases().unwrap();
        let (switch, stop) = (&first.events[0], &second.events[0]);
        // Work-energy: the kinetic energy at the reversal is the torque's work T π/4.
        let e = MechanismModel::energy(
            &MODEL,
            switch.t,
            &Vector::<1>::new(switch.y[0]),
            &Vector::<1>::new(switch.y[1]),
        )
        .unwrap();
        assert_relative_eq!(e, MODEL.torque * MODEL.theta_switch, max_relative = 1e-9);
        assert_relative_eq!(switch.t, references()[0] / 2.0, max_relative = 1e-9);
        // The reversed torque takes the same work back over the same angle.
        assert_relative_eq!(stop.y[0], std::f64::consts::FRAC_PI_2, max_relative = 1e-9);
    }

    #[test]
    fn case23_references_round_to_the_manual() {
        let [t_90] = references();
        assert_eq!(format!("{t_90:.2}"), "78.56");
        assert_eq!(
            format!("{:.3e}", MODEL.torque / inertia_about_o()),
            "1.018e-3"
        );
    }
}
