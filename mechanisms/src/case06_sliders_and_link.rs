//! Case 06: two sliders joined by a light rigid bar, their accelerations and the bar's force
//! (Meriam & Kraige 7th ed., chapter 3, constrained rectilinear motion; the manual misprints
//! the reference as "pp.129, P.3.2", copied from case 05).
//!
//! **Problem.** Slider A (2 kg) and slider B (3 kg) are joined by a light rigid bar of length
//! 0.5 m; A is pushed by `P = 40 N`. At `x_A = 0.4 m` with `v_A = 0.9 m/s` find the
//! accelerations of A and B and the force T in the bar. Weight plays no part.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost). The manual's
//! constraint `x_A^2 + x_B^2 = 0.5^2`: A and B slide on perpendicular guides through O,
//! `A = (x_A, 0)`, `B = (0, y_B)` (the manual's "x_B" is B's coordinate on its own guide),
//! `y_B = 0.3`. `2 x_A x_A' + 2 y_B y_B' = 0` gives `y_B' = −1.2 m/s` (the manual's
//! `v_B = 1.2` is the magnitude; B moves toward O). Its free-body diagrams, `P − T cos θ =
//! m_A a_A` with `cos θ = x_A/0.5 = 4/5` and `−T sin θ = m_B a_B` with no weight term: the bar
//! is in tension and pulls A toward B, and B's guide is horizontal too (the mechanism lies in
//! a horizontal plane). The manual's units in "Basic conditions" (mm, mm/s, deg/s) are wrong;
//! the numbers are m and m/s.
//!
//! **Model.** One free coordinate `x_A`; the bar's length is relaxed into `0.5 + e` with e
//! pinned at zero, so that `reaction(e)` is the generalised force the bar exerts along its
//! length, `−T` (a tension pulls the ends together). `y_B = sqrt((0.5 + e)^2 − x_A^2)`; A and B
//! are particles; the push `(P, 0)` acts on A; no gravity in the plane of motion.
//! `x_A(0) = 0.4`, `x_A'(0) = 0.9`. `a_A`, `a_B` (B's acceleration along its guide) and T are
//! the model's outputs at t = 0.
//!
//! **Reference (exact).** The constraint differentiated twice, `x a_A + y a_B + v_A^2 + v_B^2
//! = 0`, gives `a_B = −7.5 − (4/3) a_A`; the free-body diagrams give `a_B = −10 + a_A/2`; so
//! **`a_A = 15/11 = 1.363636… m/s^2`, `a_B = −205/22 = −9.318181… m/s^2`,
//! `T = −5 a_B = 1025/22 = 46.590909… N`** (`mechanisms/reference/case06.py`: the closed form
//! and a numerical solution of the constrained equations).
//!
//! **Discrepancies in the manual.** None in the results (1.36, −9.318, 46.59 are these,
//! rounded; the worked solution's 1.364 too). Its reference and its units are misprinted (above).

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Curve, Outcome, Row, series};
use mbd::prelude::*;

/// How the case is measured.
const METHOD: &str = "generated outputs at t = 0 (accelerations and the bar's reaction)";

/// Slider A on the x guide pushed by `p`, slider B on the y guide, joined by a bar of
/// length `l`, relaxed into `l + e` so that `reaction(e)` is its axial force.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(x_a)]
#[relaxed(e)]
#[particle(a, mass = m_a, at = [x_a, 0.0])]
#[particle(b, mass = m_b, at = [0.0, sqrt((l + e) * (l + e) - x_a * x_a)])]
#[force(push, at = [x_a, 0.0], value = [p, 0.0])]
#[init(x_a = x_a0, der(x_a) = v_a0)]
#[output(a_a = der(der(x_a)))]
#[output(a_b = acceleration(b)[1])]
#[output(tension = -reaction(e))]
#[event(b_near_o = position(b)[1] - l / 10.0, falling, terminal)]
pub struct SlidersAndLink {
    pub m_a: f64,
    pub m_b: f64,
    pub l: f64,
    pub p: f64,
    pub x_a0: f64,
    pub v_a0: f64,
}

/// The manual's data.
pub const MODEL: SlidersAndLink = SlidersAndLink {
    m_a: 2.0,
    m_b: 3.0,
    l: 0.5,
    p: 40.0,
    x_a0: 0.4,
    v_a0: 0.9,
};

/// The drawing beyond the model's shapes. The light bar AB and the sliders' guides.
pub const SKETCH: Sketch = Sketch {
    links: &[("bar_ab", At("a", 0), At("b", 0))],
    guides: &[At("a", 0), At("b", 0)],
    ..Sketch::NONE
};

/// Exact references `[a_A, a_B, T]`: from `m_B a_B = −T y/l`, `m_A a_A = P − T x/l` and
/// `x a_A + y a_B + v_A^2 + v_B^2 = 0`, `v_B = −x v_A / y` (Meriam & Kraige Sect. 3/4):
/// `a_A (m_A + m_B x^2/y^2) = P − m_B x (v_A^2 + v_B^2)/y^2`.
pub fn references() -> [f64; 3] {
    let SlidersAndLink {
        m_a,
        m_b,
        l,
        p,
        x_a0: x,
        v_a0: v_a,
    } = MODEL;
    let y = (l * l - x * x).sqrt();
    let v_b = -x * v_a / y;
    let v_sq = v_a * v_a + v_b * v_b;
    let a_a = (p - m_b * x * v_sq / (y * y)) / (m_a + m_b * x * x / (y * y));
    let a_b = -(x * a_a + v_sq) / y;
    [a_a, a_b, -m_b * a_b * l / y]
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let y0 = model.initial_state();
    let now = model.outputs(0.0, &y0)?;
    // Each quantity over time, until B nears O (the bar would reach the toggle y_B = 0).
    let sol = sim::integrate(&model, y0, 1.0, &model.events())?;
    let samples = (0..=200)
        .filter_map(|i| {
            let t = sol.last().0 * f64::from(i) / 200.0;
            sol.at(t).map(|y| (t, y))
        })
        .map(|(t, y)| Ok((t, model.outputs(t, &y)?)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let [a_a, a_b, tension] = references();
    let row = |quantity, value, reference, label, f: fn(&SlidersAndLinkOutputs) -> f64| Row {
        quantity,
        value,
        reference,
        method: METHOD,
        curve: Curve::at_instant(label, series(&samples, f), 0.0),
    };
    Ok(Outcome {
        rows: vec![
            row("a_A", now.a_a, a_a, "acceleration of A a_A [m/s²]", |o| {
                o.a_a
            }),
            row("a_B", now.a_b, a_b, "acceleration of B a_B [m/s²]", |o| {
                o.a_b
            }),
            row("T", now.tension, tension, "force in the bar T [N]", |o| {
                o.tension
            }),
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case06_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-12);
        }
    }

    #[test]
    fn case06_references_are_the_fractions_and_round_to_the_manual() {
        let [a_a, a_b, tension] = references();
        assert_relative_eq!(a_a, 15.0 / 11.0, max_relative = 1e-14);
        assert_relative_eq!(a_b, -205.0 / 22.0, max_relative = 1e-14);
        assert_relative_eq!(tension, 1025.0 / 22.0, max_relative = 1e-14);
        assert_eq!(format!("{a_a:.2}"), "1.36");
        assert_eq!(format!("{a_a:.3}"), "1.364");
        assert_eq!(format!("{a_b:.3}"), "-9.318");
        assert_eq!(format!("{tension:.2}"), "46.59");
    }

    #[test]
    fn case06_work_of_the_push_is_the_energy_gained() {
        // The bar does no work (its length is held): E(t) − E(0) = P (x_A(t) − x_A(0)).
        let model = MODEL;
        let sol = sim::integrate(&model, model.initial_state(), 1.0, &model.events()).unwrap();
        assert_eq!(sol.stopped_by, Some(0));
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
            let work = model.p * (y[0] - model.x_a0);
            assert_relative_eq!(energy(y) - e0, work, epsilon = 1e-9 * (e0 + work.abs()));
        }
    }
}
