//! Case 21: a parallelogram linkage driven by a couple: the force in the pin at D and the
//! links' angular acceleration (Meriam & Kraige 7th ed., P6/25, p. 428).
//!
//! **Problem.** The 25-kg bar BD is carried by two parallel links AB and CD, 0.6 m long,
//! with fixed pivots A and C; a couple `M = 200 N m` drives AB. At the instant the links are
//! horizontal and turn at `ω = 5 rad/s`. Find the force `R_D` in the pin at D and the
//! angular acceleration `α` of the links. The manual uses `g = 9.81 m/s^2`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `a_n = r ω^2 = 0.6 × 5^2`: both links are 0.6 m and BD translates (a parallelogram), so
//! every point of it has `a_n = 15 m/s^2` towards the pivots and `a_t = 0.6 α`.
//! `B_t − m g = m r α`: gravity is tangential, so the links are *horizontal* at the instant
//! and BD is vertical. `D_n × 0.8 = m a_n × 0.5` (moments about B): D is 0.8 m below B (so
//! C is 0.8 m below A) and G lies on BD, 0.5 m below B (m g and `m a_t` have no moment about
//! B only if G is on the vertical through B); BD's moment of inertia does not enter, as BD
//! translates. The manual treats AB as massless ("the mass of the link AB is ignored", so
//! `B_t = M / 0.6`) and CD as a massless two-force link (only a normal force at D).
//! Chosen frame: A = (0, 0), C = (0, −0.8), B = (0.6, 0), D = (0.6, −0.8), G = (0.6, −0.5);
//! M counter-clockwise on AB (it must lift BD: `B_t = 333 N > m g = 245 N`).
//!
//! **Model.** Two free coordinates: AB's angle θ and BD's angle φ (from the downward
//! vertical). B = `0.6 (cos θ, sin θ)`, D = B + `0.8 (sin φ, −cos φ)`, G = B +
//! `0.5 (sin φ, −cos φ)`. The massless AB is the couple's lever: M enters as the generalised
//! force along θ. The massless two-force link CD is the distance constraint
//! `|D − C| = 0.6 + s`, with its stretch s relaxed, so that `reaction(s)` is the force the link
//! exerts along CD on the bar, i.e. the pin force at D (`R_D = |reaction(s)|`; the link is in
//! tension when `reaction(s) < 0`, pulling D towards C). BD gets `I_G = 1 kg m^2` (any value:
//! BD translates; a test checks that another value changes nothing); it keeps the mass matrix
//! positive definite. Initial state: θ = φ = 0, `θ' = 5 rad/s`, `φ' = 0`. The quantities are
//! the generated outputs at t = 0; α is measured on CD itself, as the second derivative of
//! its angle `atan2(D − C)`.
//!
//! **Reference (exact).** `α = (M/0.6 − m g)/(m 0.6) = 52.85/9 = 5.872222… rad/s^2`;
//! `D_n = m 0.6 ω^2 × 0.5/0.8 = 234.375 N` exactly, `D_t = 0` (`mechanisms/reference/case21.py`:
//! closed form, and an independent redundant-coordinate multibody model at 30 digits, with
//! two values of `I_BD`). For the record, `R_B = 361.7823956 N` (`B_n = 140.625`,
//! `B_t = 333.333`).
//!
//! **Discrepancies in the manual.** `187.5/0.8 = 234.375`, so the manual's `R_D = 235.375` is
//! a typo (RecurDyn has the right 234.375); its table also labels R_D in m/s^2 (N). The
//! table's `α = 5.871` is a rounding slip: `(333.333 − 245.25)/15 = 5.87222`, as its own
//! text (5.872) says.

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Curve, Outcome, Row, series};
use mbd::prelude::*;

/// Bar BD carried by the links AB (driven by the couple) and CD (a two-force link, its
/// stretch `s` relaxed); θ is AB's angle, φ BD's angle from the downward vertical.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(theta, phi)]
#[relaxed(s)]
#[point(pivot_a, at = [0.0, 0.0])]
#[point(pin_b, at = [pivot_a[0] + r * cos(theta), pivot_a[1] + r * sin(theta)])]
#[point(pin_d, at = [pin_b[0] + h * sin(phi), pin_b[1] - h * cos(phi)])]
#[point(pivot_c, at = [0.0, -h])]
#[rigid(bar, mass = m, inertia = i_bar,
        at = [pin_b[0] + b_g * sin(phi), pin_b[1] - b_g * cos(phi)], angle = phi)]
#[constraint(hypot(pin_d[0] - pivot_c[0], pin_d[1] - pivot_c[1]) == r + s)]
#[generalized_force(on_ab, along = theta, value = couple)]
#[init(theta = 0.0, phi = 0.0, der(theta) = omega_0, der(phi) = 0.0)]
#[output(r_d = abs(reaction(s)))]
#[output(tension_cd = -reaction(s))]
#[output(alpha_cd = der(der(atan2(pin_d[1] - pivot_c[1], pin_d[0] - pivot_c[0]))))]
#[output(alpha_ab = der(der(theta)))]
pub struct Parallelogram {
    /// Mass of BD.
    pub m: f64,
    /// BD's moment of inertia about G (does not enter: BD translates).
    pub i_bar: f64,
    pub g: f64,
    /// Length of the links AB and CD.
    pub r: f64,
    /// BD's pin spacing, equal to the pivot spacing AC (a parallelogram).
    pub h: f64,
    /// Distance from B down to G.
    pub b_g: f64,
    /// The couple on AB.
    pub couple: f64,
    /// The links' angular velocity at the instant.
    pub omega_0: f64,
}

/// The manual's data.
pub const MODEL: Parallelogram = Parallelogram {
    m: 25.0,
    i_bar: 1.0,
    g: 9.81,
    r: 0.6,
    h: 0.8,
    b_g: 0.5,
    couple: 200.0,
    omega_0: 5.0,
};

/// The drawing beyond the model's shapes. The links AB and CD, and the bar BD through its pins.
pub const SKETCH: Sketch = Sketch {
    links: &[
        ("link_ab", At("pivot_a", 0), At("pin_b", 0)),
        ("link_cd", At("pivot_c", 0), At("pin_d", 0)),
    ],
    bodies: &[("bar", &[At("pin_b", 0), At("pin_d", 0)])],
    ..Sketch::NONE
};

/// Exact references `[R_D, α]`: `m r ω^2 b_g / h` and `(M/r − m g)/(m r)`.
pub fn references() -> [f64; 2] {
    let Parallelogram {
        m,
        g,
        r,
        h,
        b_g,
        couple,
        omega_0,
        ..
    } = MODEL;
    [
        m * r * omega_0 * omega_0 * b_g / h,
        (couple / r - m * g) / (m * r),
    ]
}

/// The plot's span: the links turn from horizontal to about 68°, clear of the parallelogram's
/// change point at 90° (links along AC).
const PLOT_SPAN: f64 = 0.2;

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let y0 = model.initial_state();
    let at_instant = model.outputs(0.0, &y0)?;
    let [r_d, alpha] = references();
    let sol = sim::integrate(&model, y0, PLOT_SPAN, &[])?;
    let samples = sim::curve(&sol, 200, |t, y| model.outputs(t, y))?;
    let method = "generated outputs at t = 0 (augmented system)";
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "R_D",
                value: at_instant.r_d,
                reference: r_d,
                method,
                curve: Curve::at_instant("pin force R_D [N]", series(&samples, |o| o.r_d), 0.0),
            },
            Row {
                quantity: "alpha",
                value: at_instant.alpha_cd,
                reference: alpha,
                method,
                curve: Curve::at_instant(
                    "angular acceleration of CD α [rad/s²]",
                    series(&samples, |o| o.alpha_cd),
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
    use mbd::analysis::constraint_drift;

    #[test]
    fn case21_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-12);
        }
    }

    #[test]
    fn case21_links_turn_together_and_cd_pulls() {
        let o = MODEL.outputs(0.0, &MODEL.initial_state()).unwrap();
        assert_relative_eq!(o.alpha_ab, o.alpha_cd, max_relative = 1e-12);
        // CD is in tension: it pulls BD towards C, supplying the centripetal force.
        assert_relative_eq!(o.tension_cd, 234.375, max_relative = 1e-12);
    }

    #[test]
    fn case21_inertia_of_the_translating_bar_does_not_enter() {
        let other = Parallelogram {
            i_bar: 3.0,
            ..MODEL
        };
        let (a, b) = (
            MODEL.outputs(0.0, &MODEL.initial_state()).unwrap(),
            other.outputs(0.0, &other.initial_state()).unwrap(),
        );
        assert_relative_eq!(a.r_d, b.r_d, max_relative = 1e-12);
        assert_relative_eq!(a.alpha_cd, b.alpha_cd, max_relative = 1e-12);
    }

    #[test]
    fn case21_loop_stays_closed_and_bar_translates() {
        let sol = sim::integrate(&MODEL, MODEL.initial_state(), PLOT_SPAN, &[]).unwrap();
        let (t, y) = sol.last();
        let (q, qd) = (Vector::<2>::new(y[0], y[1]), Vector::<2>::new(y[2], y[3]));
        let (position, velocity) = constraint_drift(&MODEL, t, &q, &qd);
        assert!(
            position < 1e-12 && velocity < 1e-10,
            "{position} {velocity}"
        );
        // A parallelogram: BD keeps its orientation.
        assert!(y[1].abs() < 1e-10 && y[3].abs() < 1e-9, "{y:?}");
    }

    #[test]
    fn case21_references_round_to_the_manual_where_it_is_right() {
        let [r_d, alpha] = references();
        // RecurDyn's 234.375 is exact; the manual's theory 235.375 is a typo.
        assert_eq!(r_d, 234.375);
        assert_relative_eq!(alpha, 52.85 / 9.0, max_relative = 1e-14);
        // Its text's 5.872 is right; the table's 5.871 is a rounding slip.
        assert_eq!(format!("{alpha:.3}"), "5.872");
    }
}
