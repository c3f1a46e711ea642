//! Case 25: a single-cylinder engine with the crank at 90°: the force in the wrist pin A
//! (Meriam & Kraige 7th ed., P6/105, p. 457).
//!
//! **Problem.** The engine runs at a constant `ω = 100π rad/s` (3000 rev/min). Crank OB
//! `r = 0.0425 m`; connecting rod AB 0.6 kg, `l = 0.1075 m`, its mass centre G 0.0325 m from
//! the crank pin B, radius of gyration about G 0.028 m; piston A 0.82 kg. Find the force on
//! the wrist pin A when the crank is perpendicular to the cylinder (θ = 90°). The manual
//! uses `g = 9.81 m/s^2`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost). `v_A = v_B`,
//! `ω_AB = 0`: the crank is perpendicular to the cylinder axis. `A_y − m_p g = m_p a_A`: the
//! cylinder is *vertical* with the piston *above* the crank (gravity opposes the piston's
//! upward acceleration); `a_A = (a_B)_n / tan θ` with `cos θ = r/l` (θ = 66.71°, the rod's
//! angle to the horizontal crank). `l_1 + l_2 = 0.1075` is the rod's length and
//! `ρ̄ = l_2 = 0.0325` multiplies `a_B` about B: G is 0.0325 m from the crank pin. Chosen
//! frame: O = (0, 0), the crank horizontal at t = 0, B = (r, 0), the piston on the y axis at
//! A = (0, sqrt(l^2 − r^2)); the crank turns counter-clockwise (the sense changes no
//! acceleration at this instant: `ω_AB = 0` and everything goes with `ω^2`).
//!
//! **Model.** The crank angle is driven, `θ(t) = ω t` (the crank is driven, so its mass does
//! not enter the pin force: it is left out). Two free coordinates, the rod's angle φ (B to
//! A, from +x) and the piston's height y, closed by the wrist pin: rod end
//! `B + l e(φ)` = piston `(0, y)` + `(u_x, u_y)`, with the pin's separation `(u_x, u_y)`
//! relaxed, so that `reaction(u_x)`, `reaction(u_y)` are the pin force (on the rod; the
//! piston gets the opposite). No degree of freedom: the state at t = 0 comes from
//! `kinematics` (assembled from `φ = atan2(sqrt(l^2 − r^2), −r)`, piston above O),
//! `R_A = |reaction(u)|` from the generated output. The rod: 0.6 kg, `I_G = 0.6 × 0.028^2`,
//! G = B + 0.0325 e(φ); the piston a 0.82-kg particle on the cylinder axis. Gravity acts on
//! every body (as in RecurDyn); no gas force, no friction.
//! The driven crank is also drawn as a uniform bar: prescribed, its mass enters no equation of
//! the rod, the piston or the wrist pin.
//!
//! **Reference (exact).** Piston: `A_y − m_p g = m_p a_A` with `a_A = r^2 ω^2 / sqrt(l^2 − r^2)
//! = 1805.40773018615 m/s^2`; rod, moments about B with `α_AB = −r ω^2/(l sin φ) =
//! −42480.181886733 rad/s^2`: `A_x = −355.570884956078 N`, `A_y = 1488.47853875264 N`,
//! **`R_A = 1530.35911293906963591643506021 N`** (`mechanisms/reference/case25.py`: closed
//! form and an independent redundant-coordinate multibody model, 30 digits). Without
//! gravity `R_A = 1521.55429570825`; with gravity on the piston only, 1530.18133746589.
//!
//! **Discrepancies in the manual.** It gives four answers (the `I_B` or the `I_G` form of the
//! rod's moment equation, with the rod's weight kept or not: 1530.1, 1530.3, 1530.5, 1530.7)
//! and tabulates 1530.5, the variant that keeps the piston's weight but drops the rod's. The
//! two forms are identical (`I_B α + ρ̄ × m a_B ≡ I_G α + ρ̄ × m a_G`); they differ in the
//! manual because `I_B = 0.00110415` is rounded to 0.0011 and `a_B = 4194.6` to 4195
//! (`α_AB` 42483.7 for 42480.18). The consistent model (gravity on every body) gives
//! **1530.3591**, the corrected value mbd is judged against (RecurDyn's 1531.3 is 0.06 %
//! above it). Its piston equation "`A_x = 0`" also ignores the cylinder wall: the pin force
//! has a horizontal part, −355.57 N, balanced by the wall.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, MILLISECONDS, Outcome, Read, Row};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// A vertical single-cylinder engine: crank OB driven at `omega`, rod BA (angle φ), piston
/// at height y; the wrist pin's separation `(ux, uy)` is relaxed.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(phi, y)]
#[drive(theta = omega * t)]
#[relaxed(ux, uy)]
#[point(crank_pin, at = [r * cos(theta), r * sin(theta)])]
#[rigid(crank, mass = m_rod, inertia = m_rod * r * r / 12.0,
        at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[rigid(rod, mass = m_rod, inertia = m_rod * k_g * k_g,
        at = [crank_pin[0] + rho * cos(phi), crank_pin[1] + rho * sin(phi)], angle = phi)]
#[particle(piston, mass = m_piston, at = [0.0, y])]
#[constraint(crank_pin[0] + l * cos(phi) == ux)]
#[constraint(crank_pin[1] + l * sin(phi) == y + uy)]
#[init(phi = atan2(sqrt(l * l - r * r), -r), y = sqrt(l * l - r * r))]
#[output(r_a = hypot(reaction(ux), reaction(uy)))]
#[output(pin_x_on_piston = -reaction(ux))]
#[output(pin_y_on_piston = -reaction(uy))]
#[output(alpha_ab = der(der(phi)))]
#[output(a_piston = der(der(y)))]
pub struct Engine {
    pub g: f64,
    /// Crank length and its constant rate.
    pub r: f64,
    pub omega: f64,
    /// Connecting rod: length, mass, G's distance from the crank pin, radius of gyration.
    pub l: f64,
    pub m_rod: f64,
    pub rho: f64,
    pub k_g: f64,
    pub m_piston: f64,
}

/// The manual's data.
pub const MODEL: Engine = Engine {
    g: 9.81,
    r: 0.0425,
    omega: 100.0 * std::f64::consts::PI,
    l: 0.1075,
    m_rod: 0.6,
    rho: 0.0325,
    k_g: 0.028,
    m_piston: 0.82,
};

/// The drawing beyond the model's shapes. The rod (not a uniform bar) through its pins, and the cylinder.
pub const SKETCH: Sketch = Sketch {
    bodies: &[("rod", &[At("crank_pin", 0), At("piston", 0)])],
    guides: &[At("piston", 0)],
    ..Sketch::NONE
};

/// The pin force at the instant by hand, `[α_AB, a_A, A_x, A_y, R_A]` (force of the rod on
/// the piston), with gravity `g_piston` on the piston and `g_rod` on the rod: the piston's
/// `A_y − m_p g = m_p a_A`, the rod's moments about B (see the module docs).
pub fn closed_form(g_piston: f64, g_rod: f64) -> [f64; 5] {
    let Engine {
        r,
        omega,
        l,
        m_rod,
        rho,
        k_g,
        m_piston,
        ..
    } = MODEL;
    let y_a = (l * l - r * r).sqrt();
    let a_a = r * r * omega * omega / y_a;
    let (ex, ey) = (-r / l, y_a / l); // the rod's direction, B to A
    // a_A = a_B + α k × l e with a_B = (−r ω^2, 0) and x_A fixed: −r ω^2 − α l e_y = 0.
    let alpha = -r * omega * omega / (l * ey);
    let a_gx = -r * omega * omega - alpha * rho * ey;
    let a_gy = alpha * rho * ex;
    let f_y = m_piston * (a_a + g_piston);
    // Rod about B: (A − B) × (−F) + (G − B) × (−m g j) = I_G α + (G − B) × m a_G.
    let (gx, gy, ax, ay) = (rho * ex, rho * ey, l * ex, l * ey);
    let rhs = m_rod * k_g * k_g * alpha + m_rod * (gx * a_gy - gy * a_gx) + gx * m_rod * g_rod;
    let f_x = (rhs + ax * f_y) / ay;
    [alpha, a_a, f_x, f_y, f_x.hypot(f_y)]
}

/// Exact reference `[R_A]`, gravity on every body.
pub fn references() -> [f64; 1] {
    [closed_form(MODEL.g, MODEL.g)[4]]
}

/// The kinematic state at `t`, assembled from the initial guess (piston above O).
pub fn state_at(model: &Engine, t: f64) -> mbd::Result<KinematicState<2>> {
    let y0 = model.initial_state();
    let guess = Vector::<2>::new(y0[0], y0[1]);
    kinematics(model, t, &guess, &NewtonOptions::default())
}

fn as_state(ks: &KinematicState<2>) -> Vector<4> {
    Vector::<4>::new(ks.q[0], ks.q[1], ks.qd[0], ks.qd[1])
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let [r_a] = references();
    let at_instant = model.outputs(0.0, &as_state(&state_at(&model, 0.0)?))?;
    // One crank revolution.
    let period = 2.0 * std::f64::consts::PI / model.omega;
    let times: Vec<f64> = (0..=200).map(|i| period * f64::from(i) / 200.0).collect();
    let y0 = model.initial_state();
    let guess = Vector::<2>::new(y0[0], y0[1]);
    let points = kinematic_sweep(&model, &times, &guess, &NewtonOptions::default())?
        .iter()
        .map(|ks| Ok((ks.t * 1e3, model.outputs(ks.t, &as_state(ks))?.r_a)))
        .collect::<mbd::Result<Vec<_>>>()?;
    Ok(Outcome {
        rows: vec![Row {
            quantity: "R_A",
            value: at_instant.r_a,
            reference: r_a,
            method: "kinematic analysis, generated outputs",
            curve: Curve {
                x_label: MILLISECONDS,
                y_label: "wrist pin force R_A [N]",
                points,
                read: Read::Ordinate { at: 0.0 },
            },
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case25_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-12);
        }
    }

    #[test]
    fn case25_references_are_the_30_digit_values() {
        // mechanisms/reference/case25.py.
        assert_relative_eq!(
            references()[0],
            1_530.359_112_939_069_6,
            max_relative = 1e-14
        );
        let [alpha, a_a, f_x, f_y, _] = closed_form(MODEL.g, MODEL.g);
        assert_relative_eq!(alpha, -42_480.181_886_733, max_relative = 1e-13);
        assert_relative_eq!(a_a, 1_805.407_730_186_15, max_relative = 1e-13);
        assert_relative_eq!(f_x, -355.570_884_956_078, max_relative = 1e-13);
        assert_relative_eq!(f_y, 1_488.478_538_752_64, max_relative = 1e-13);
        assert_relative_eq!(
            closed_form(0.0, 0.0)[4],
            1_521.554_295_708_25,
            max_relative = 1e-13
        );
        assert_relative_eq!(
            closed_form(MODEL.g, 0.0)[4],
            1_530.181_337_465_89,
            max_relative = 1e-13
        );
    }

    #[test]
    fn case25_pin_force_components_and_kinematics_match_the_hand_analysis() {
        for g in [MODEL.g, 0.0] {
            let model = Engine { g, ..MODEL };
            let ks = state_at(&model, 0.0).unwrap();
            // The rod does not turn at this instant: v_A = v_B.
            assert!(ks.qd[0].abs() < 1e-9, "{ks:?}");
            let o = model.outputs(0.0, &as_state(&ks)).unwrap();
            let [alpha, a_a, f_x, f_y, r_a] = closed_form(g, g);
            assert_relative_eq!(o.alpha_ab, alpha, max_relative = 1e-12);
            assert_relative_eq!(o.a_piston, a_a, max_relative = 1e-12);
            assert_relative_eq!(o.pin_x_on_piston, f_x, max_relative = 1e-12);
            assert_relative_eq!(o.pin_y_on_piston, f_y, max_relative = 1e-12);
            assert_relative_eq!(o.r_a, r_a, max_relative = 1e-12);
        }
    }

    #[test]
    fn case25_pins_the_corrected_pin_force() {
        let [r_a] = references();
        // The manual's 1530.5 drops the rod's weight and rounds I_B and a_B; the consistent
        // value (gravity on every body) is 1530.36, and the manual's own variant without the
        // rod's weight is, exactly, 1530.18.
        assert_eq!(format!("{r_a:.1}"), "1530.4");
        assert_eq!(format!("{:.1}", closed_form(MODEL.g, 0.0)[4]), "1530.2");
        // Its intermediates a_A = 1806 and A_y = 1488.8 carry the same rounding; exactly:
        let [_, a_a, _, f_y, _] = closed_form(MODEL.g, MODEL.g);
        assert_eq!(format!("{a_a:.0}"), "1805");
        assert_eq!(format!("{f_y:.1}"), "1488.5");
    }
}
