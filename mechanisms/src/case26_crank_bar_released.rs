//! Case 26: a crank and bar released from rest: the speed of B as OA passes the vertical
//! (Meriam & Kraige 7th ed., P6/139, p. 474).
//!
//! **Problem.** The 8-kg crank OA (`|OA| = 0.4 m`, its mass centre 0.18 m from O, radius of
//! gyration about O `k_O = 0.22 m`) is pinned at A to the uniform 12-kg slender bar AB, whose
//! end B slides on a smooth horizontal guide. Released from rest with OA horizontal, find the
//! speed `v_B` of B as OA swings through the vertical. The manual uses `g = 9.81 m/s^2`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `v_A = 0.4 ω`: `|OA| = 0.4 m`; `ΔT_OA = ½ m k_O^2 (v_A/0.4)^2` with 0.22: `k_O` is about O.
//! `ΔV_OA = −8 g 0.18`: the crank's G drops its full distance from O, so OA turns from
//! horizontal to vertical, A straight below O. `ΔV_AB = −12 g 0.2`: the bar's G drops half
//! of A's 0.4 m, so B keeps its height (a horizontal guide) and the bar is uniform. In the
//! final position `v_A = v_B` and `ω_AB = 0`: `v_A` is horizontal, so is `v_B`, and AB
//! translates for the instant, whatever the bar's length and the guide's height (AB not
//! vertical). The manual fixes neither: the result does not depend on them (the drops and
//! `ω_AB = 0` stay the same; a test runs three choices). Chosen: `|AB| = 0.8 m`, the guide on
//! the level of O: O = (0, 0), A_0 = (0.4, 0), B_0 = (1.2, 0), O, A and B in line at the
//! release (B at its outer dead point); OA swings clockwise, down. Final: A = (0, −0.4),
//! B = (sqrt(0.48), 0).
//!
//! **Model.** Two free coordinates, the crank's angle θ and the bar's angle φ (both from +x),
//! and one constraint: B = A + 0.8 e(φ) on the guide, `y_B = h`. Crank: 8 kg,
//! `I_G = 8 (0.22^2 − 0.18^2) = 0.128 kg m^2`, G = 0.18 e(θ); bar: 12 kg,
//! `I_G = 12 × 0.8^2/12`, G at mid-length; the slider B is light and smooth (`x_B` is an
//! output, not a coordinate). Released at rest from θ = 0; the vertical is the first
//! downward crossing of `θ + π/2` (terminal), where `v_B = |x_B'|` is read.
//!
//! **Reference (exact).** Work–energy from rest, with `ω_AB = 0` and `v_A = v_B` at the end:
//! `8 g 0.18 + 12 g 0.2 = ½ 8 k_O^2 (v/0.4)^2 + ½ 12 v^2`, so
//! **`v_B = sqrt(37.6704/7.21) = 2.28576976354309970719488989312 m/s`** and
//! `ω_OA = v_B/0.4 = 5.7144244088577…` rad/s (`mechanisms/reference/case26.py`: closed form
//! at 30 digits, and Lagrange's equation of the chain integrated in double precision for
//! three bar lengths and guide heights, all agreeing to 13 digits). Event time for the chosen
//! geometry: 0.379587080273 s.
//!
//! **Discrepancies in the manual.** None: its 2.29 is the exact value rounded.

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Curve, Outcome, Row};
use mbd::prelude::*;

/// A crank OA (angle θ) and a bar AB (angle φ) whose end B slides on the guide `y = h`.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(theta, phi)]
#[point(pivot_o, at = [0.0, 0.0])]
#[point(pin_a, at = [pivot_o[0] + r * cos(theta), pivot_o[1] + r * sin(theta)])]
#[point(slider_b, at = [pin_a[0] + l * cos(phi), pin_a[1] + l * sin(phi)])]
#[rigid(crank, mass = m_crank, inertia = m_crank * (k_o * k_o - r_g * r_g),
        at = [pivot_o[0] + r_g * cos(theta), pivot_o[1] + r_g * sin(theta)], angle = theta)]
#[rigid(bar, mass = m_bar, inertia = m_bar * l * l / 12.0,
        at = [pin_a[0] + l / 2.0 * cos(phi), pin_a[1] + l / 2.0 * sin(phi)], angle = phi)]
#[constraint(slider_b[1] == h)]
#[init(theta = 0.0, phi = asin(h / l), der(theta) = 0.0, der(phi) = 0.0)]
#[output(v_b = abs(der(slider_b[0])))]
#[output(omega_oa = der(theta))]
#[output(omega_ab = der(phi))]
#[event(oa_vertical = theta + PI / 2.0, falling, terminal)]
pub struct CrankAndBar {
    pub g: f64,
    /// Crank: mass, length OA, its G's distance from O, radius of gyration about O.
    pub m_crank: f64,
    pub r: f64,
    pub r_g: f64,
    pub k_o: f64,
    /// Bar: mass and length (the length is not in the manual; it does not matter).
    pub m_bar: f64,
    pub l: f64,
    /// Height of the guide above O (not in the manual; it does not matter).
    pub h: f64,
}

/// The manual's data, with the chosen bar length and guide height.
pub const MODEL: CrankAndBar = CrankAndBar {
    g: 9.81,
    m_crank: 8.0,
    r: 0.4,
    r_g: 0.18,
    k_o: 0.22,
    m_bar: 12.0,
    l: 0.8,
    h: 0.0,
};

/// The drawing beyond the model's shapes. The crank (not a uniform bar) from O to A, and B's guide.
pub const SKETCH: Sketch = Sketch {
    bodies: &[("crank", &[At("pivot_o", 0), At("pin_a", 0)])],
    guides: &[At("slider_b", 0)],
    ..Sketch::NONE
};

/// Exact reference `[v_B]` by work–energy (see the module docs).
pub fn references() -> [f64; 1] {
    let CrankAndBar {
        g,
        m_crank,
        r,
        r_g,
        k_o,
        m_bar,
        ..
    } = MODEL;
    let work = m_crank * g * r_g + m_bar * g * r / 2.0;
    let mass = m_crank * k_o * k_o / (2.0 * r * r) + m_bar / 2.0;
    [(work / mass).sqrt()]
}

/// Integrate `model` from the release to OA vertical; the event's `(t, y)`.
pub fn swing(model: &CrankAndBar) -> mbd::Result<(mbd::integrate::Solution<2>, f64, Vector<2>)> {
    let events = model.events();
    let sol = sim::integrate(model, model.initial_state(), 2.0, &events)?;
    let hit = sol.events.first().ok_or(mbd::Error::InvalidInput {
        what: "case 26",
        detail: "OA did not reach the vertical".into(),
    })?;
    let (t, y) = (hit.t, hit.y);
    Ok((sol, t, y))
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let (sol, t, y) = swing(&model)?;
    let [v_b] = references();
    let measured = model.outputs(t, &y)?.v_b;
    let speeds = sim::curve(&sol, 200, |t, y| Ok(model.outputs(t, y)?.v_b))?;
    Ok(Outcome {
        rows: vec![Row {
            quantity: "v_B",
            value: measured,
            reference: v_b,
            method: sim::METHOD,
            curve: Curve::at_instant("speed of B v_B [m/s]", speeds, t),
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case26_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case26_reference_is_the_30_digit_value() {
        // mechanisms/reference/case26.py: v_B = 2.28576976354309970719488989312 m/s.
        assert_relative_eq!(
            references()[0],
            2.285_769_763_543_099_7,
            max_relative = 1e-15
        );
    }

    #[test]
    fn case26_bar_translates_at_the_vertical_and_energy_is_conserved() {
        let (sol, t, y) = swing(&MODEL).unwrap();
        let o = MODEL.outputs(t, &y).unwrap();
        // mechanisms/reference/case26.py: t = 0.379587080273 s for the chosen geometry
        // (double-precision integration at rtol 1e-12, so 1e-9 here).
        assert_relative_eq!(t, 0.379_587_080_273, max_relative = 1e-9);
        assert_relative_eq!(-o.omega_oa, references()[0] / MODEL.r, max_relative = 1e-9);
        assert!(o.omega_ab.abs() < 1e-8, "{}", o.omega_ab);
        let (q, qd) = (Vector::<1>::new(y[0]), Vector::<1>::new(y[1]));
        let q0 = Vector::<1>::new(0.0);
        let e0 = MechanismModel::energy(&MODEL, 0.0, &q0, &Vector::zeros()).unwrap();
        let e1 = MechanismModel::energy(&MODEL, t, &q, &qd).unwrap();
        // The energy released, 8 g 0.18 + 12 g 0.2 = 37.6704 J, sets the scale.
        assert_relative_eq!(e1, e0, epsilon = 1e-9 * 37.6704);
        // Minimal coordinates: the state is θ alone and the guide's constraint holds by
        // construction. The bar's rate agrees with the closure solved by hand,
        // `r sin θ + l sin φ = h`: `φ' = −r cos θ θ' / (l cos φ)`.
        assert_eq!(<CrankAndBar as MechanismModel<1>>::COORDINATES, ["theta"]);
        assert!(
            CrankAndBar::GENERATED
                .parts
                .contains(&"minimal_closed_form")
        );
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            let (theta, rate) = (y[0], y[1]);
            let phi = ((MODEL.h - MODEL.r * theta.sin()) / MODEL.l).asin();
            let by_hand = -MODEL.r * theta.cos() * rate / (MODEL.l * phi.cos());
            let omega_ab = MODEL.outputs(t, y).unwrap().omega_ab;
            assert!(
                (omega_ab - by_hand).abs() < 1e-12 * (1.0 + by_hand.abs()),
                "{t}"
            );
        }
    }

    #[test]
    fn case26_speed_does_not_depend_on_the_unknown_bar_length_and_guide_height() {
        // The script's other two geometries (mechanisms/reference/case26.py).
        for (l, h) in [(0.8, -0.1), (1.0, -0.3)] {
            let model = CrankAndBar { l, h, ..MODEL };
            let (_, t, y) = swing(&model).unwrap();
            let v_b = model.outputs(t, &y).unwrap().v_b;
            assert_relative_eq!(v_b, references()[0], max_relative = 1e-9);
        }
    }

    #[test]
    fn case26_references_round_to_the_manual() {
        let [v_b] = references();
        assert_eq!(format!("{v_b:.2}"), "2.29");
    }
}
