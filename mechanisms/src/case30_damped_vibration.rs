//! Case 30: free damped vibration, the position after the first half damped cycle
//! (Meriam & Kraige 7th ed., P8/36, p. 598).
//!
//! **Problem.** A block `m = 3 kg` on a spring `k = 108 N/m` and a viscous damper
//! `c = 18 N s/m` is released from rest at `x_0 = 0.3 m`. Find `x_1`, its position at the end
//! of the first half damped cycle (the first extreme on the other side).
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `m x'' + c x' + k x = 0` has no constant term: x is measured from the equilibrium, which is
//! the unstretched spring, so the motion is horizontal (gravity normal to it); RecurDyn's
//! quantity is the spring's deformation, −0.0489 m, confirming that there is no static
//! deflection. `ω_n = 6 rad/s`, `ζ = 0.5`, `ω_d = 3√3 = 5.196 rad/s`.
//!
//! **Model.** One particle, one free coordinate x (its displacement from the unstretched
//! position). A spring and a damper in parallel from a wall anchor to the block; the anchor
//! is `wall` = 1 m behind the block's equilibrium position, the spring's free length (any
//! positive distance gives the same motion: the spring's force depends on its extension x
//! only). Gravity `(0, −g)` acts normal to the motion and does no work. `x(0) = 0.3`,
//! `x'(0) = 0`. The first half damped cycle ends at the first extreme after release, the
//! upward crossing of `x'` (terminal).
//!
//! **Reference (exact).** `x(t) = x_0 (cos ω_d t + ζ/sqrt(1 − ζ^2) sin ω_d t) e^{−ζ ω_n t}`,
//! so `x' = 0` again at `t_1 = π/ω_d = π/(3√3) = 0.604599788078…` s, where
//! **`x_1 = −x_0 e^{−π ζ/sqrt(1 − ζ^2)} = −0.3 e^{−π/√3} = −0.048910060446474139458492106833 m`**
//! (30 digits: `mechanisms/reference/case30.py`, closed form and a 30-digit integration).
//!
//! **Discrepancies in the manual.** None in the result (−0.0489). Its text writes
//! "ω_d = 5.196/2π Hz = 0.827 Hz" and "T = 1/ω_d": it means the damped frequency
//! `f_d = ω_d/2π` and `T = 1/f_d = 1.209 s`; and it rounds `e^{−π/√3} = 0.163034` to 0.163.

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Curve, Outcome, Row};
use mbd::prelude::*;

/// A block on a spring and a damper in parallel, anchored to a wall `wall` behind the
/// block's equilibrium position; x is the spring's extension.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(x)]
#[point(anchor, at = [-wall, 0.0])]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(spring, from = anchor, to = block, k = k, length = wall)]
#[damper(damper, from = anchor, to = block, c = c)]
#[init(x = x_0, der(x) = 0.0)]
#[event(extreme = der(x), rising, terminal)]
pub struct DampedBlock {
    pub m: f64,
    pub g: f64,
    pub k: f64,
    pub c: f64,
    /// The anchor's distance behind the equilibrium position (the spring's free length).
    pub wall: f64,
    /// The release position.
    pub x_0: f64,
}

/// The manual's data.
pub const MODEL: DampedBlock = DampedBlock {
    m: 3.0,
    g: 9.81,
    k: 108.0,
    c: 18.0,
    wall: 1.0,
    x_0: 0.3,
};

/// The drawing beyond the model's shapes. The floor the block slides on.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("block", 0)],
    ..Sketch::NONE
};

/// `[ζ, ω_d]`: `ω_n = sqrt(k/m)`, `ζ = c / (2 sqrt(m k))`, `ω_d = ω_n sqrt(1 − ζ^2)`.
pub fn damping() -> [f64; 2] {
    let DampedBlock { m, k, c, .. } = MODEL;
    let zeta = c / (2.0 * (m * k).sqrt());
    [zeta, (k / m).sqrt() * (1.0 - zeta * zeta).sqrt()]
}

/// Exact reference `[x_1]`: `−x_0 e^{−π ζ / sqrt(1 − ζ^2)}` (see the module docs).
pub fn references() -> [f64; 1] {
    let [zeta, _] = damping();
    let decrement = std::f64::consts::PI * zeta / (1.0 - zeta * zeta).sqrt();
    [-MODEL.x_0 * (-decrement).exp()]
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let events = model.events();
    let sol = sim::integrate(&model, model.initial_state(), 5.0, &events)?;
    let extreme = sol.events.first().ok_or(mbd::Error::InvalidInput {
        what: "case 30",
        detail: "the block did not turn back".into(),
    })?;
    let [x_1] = references();
    Ok(Outcome {
        rows: vec![Row {
            quantity: "x_1",
            value: extreme.y[0],
            reference: x_1,
            method: sim::METHOD,
            curve: Curve::at_instant(
                "position x [m]",
                sim::sample(&sol, 200, |t, y| (t, y[0])),
                extreme.t,
            ),
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case30_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case30_reference_is_the_30_digit_value() {
        // mechanisms/reference/case30.py: x_1 = -0.048910060446474139458492106833 m.
        assert_relative_eq!(
            references()[0],
            -0.048_910_060_446_474_14,
            max_relative = 1e-15
        );
    }

    #[test]
    fn case30_turns_back_after_half_a_damped_period_losing_energy() {
        let model = MODEL;
        let events = model.events();
        let sol = sim::integrate(&model, model.initial_state(), 5.0, &events).unwrap();
        let [_, omega_d] = damping();
        assert_relative_eq!(
            sol.events[0].t,
            std::f64::consts::PI / omega_d,
            max_relative = 1e-9
        );
        // The damper only dissipates: the energy never rises along the solution.
        let energy = sim::sample(&sol, 200, |t, y| {
            let (q, qd) = (Vector::<1>::new(y[0]), Vector::<1>::new(y[1]));
            (t, MechanismModel::energy(&model, t, &q, &qd).unwrap())
        });
        let e0 = energy[0].1;
        for pair in energy.windows(2) {
            assert!(pair[1].1 <= pair[0].1 + 1e-12 * e0, "{pair:?}");
        }
    }

    #[test]
    fn case30_references_round_to_the_manual() {
        let [x_1] = references();
        let [zeta, omega_d] = damping();
        assert_eq!(format!("{x_1:.4}"), "-0.0489");
        assert_eq!(zeta, 0.5);
        assert_eq!(format!("{omega_d:.3}"), "5.196");
        // The manual's "0.827 Hz" is f_d = ω_d / 2π, its period 1.209 s = 1 / f_d.
        let f_d = omega_d / (2.0 * std::f64::consts::PI);
        assert_eq!(format!("{f_d:.3}"), "0.827");
        assert_eq!(format!("{:.3}", 1.0 / f_d), "1.209");
    }
}
