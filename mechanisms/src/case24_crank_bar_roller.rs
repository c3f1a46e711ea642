//! Case 24: a crank-driven bar with a roller on the floor: the normal force at B
//! (Meriam & Kraige 7th ed., P6/92, p. 454).
//!
//! **Problem.** The crank OA (0.4 m) turns at a constant `ω_0 = 4.5 rad/s`; the uniform
//! 10-kg bar AB (1.0 m) is pinned to it at A, and its end B carries a light roller on a
//! horizontal floor. At the instant shown `ω_AB = 3 rad/s`. Find the normal force `N_B` under
//! the roller. The manual uses `g = 9.81 m/s^2`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `a_A = 0.4 × 4.5^2 = 8.1` (normal term only): OA = 0.4 m, `ω_0` constant.
//! `ΣM_A: m g 0.3 − N_B 0.6 = … − m a_A 0.4`: G is 0.3 m and B 0.6 m from A horizontally
//! (`N_B` vertical: a horizontal floor); with AB = 1.0 m, B is 0.8 m below A (`tan θ = 3/4`
//! from the vertical) and G, at mid-length, 0.4 m below A. The moment of `m a_A` has the arm
//! 0.4 m, G's vertical offset: `a_A` is horizontal, so *OA is horizontal*. Velocity check:
//! `v_A = 1.8 m/s` vertical and B moves horizontally, so `ω_AB 0.6 = 1.8`, `ω_AB = 3 rad/s`
//! as given (OA vertical would give `ω_AB = 0`). `a_B` horizontal gives
//! `α_AB = 9/(3/4) = 12 rad/s^2`. The moment balance gives 36.38 only with `a_A` pointing
//! from A to B's side: *O is on the same side of A as B* (the other side would give
//! −71.6 N, the roller lifting off). Chosen frame: O = (0.4, 0.8), A = (0, 0.8),
//! B = (0.6, 0), G = (0.3, 0.4); `ω_0` counter-clockwise, so A moves down, `ω_AB = +3`
//! (ccw), `α_AB = −12` (cw), `a_G = (0.6, 0)`.
//!
//! **Model.** The crank's angle is driven, `θ(t) = π + ω_0 t`; A = O + 0.4 (cos θ, sin θ) (the
//! crank itself is driven, so its mass does not enter `N_B`: it is left out). One free
//! coordinate, the bar's angle φ (A to B from +x), and one constraint, B on the floor:
//! `y_B = h` with the roller's lift h relaxed, so `reaction(h)` is the floor's upward force on
//! the bar. No degree of freedom: the state at t = 0 comes from `kinematics` (assembled from
//! `φ = −asin(0.8)`, B right of A), `N_B` from the generated output. The bar: m = 10 kg,
//! `I_G = m L^2/12`, G at mid-length. The roller is light and free (no friction).
//! The driven crank OA is also a uniform bar, there to be drawn: prescribed, its mass enters no
//! equation of φ or N_B.
//!
//! **Reference (exact).** Moments about A:
//! `0.6 N_B − 0.3 m g = I_G α_AB + r_G/A × m a_G`, so
//! **`N_B = (29.43 − 7.6)/0.6 = 2183/60 = 36.3833… N`** (`mechanisms/reference/case24.py`:
//! closed form and an independent redundant-coordinate multibody model, 30 digits).
//!
//! **Discrepancies in the manual.** None in the result (36.38); its "6 rad/s^2" for
//! `(a_G/A)_t` is a unit slip (m/s^2).

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// A bar pinned at A to a crank turning at `omega_0` about O, its end B on the floor (the
/// roller's lift `h` relaxed); φ is the bar's angle from +x.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(phi)]
#[drive(theta = PI + omega_0 * t)]
#[relaxed(h)]
#[point(pin_a, at = [o_x + r * cos(theta), o_y + r * sin(theta)])]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0,
        at = [o_x + r / 2.0 * cos(theta), o_y + r / 2.0 * sin(theta)], angle = theta)]
#[rigid(bar, mass = m, inertia = m * l * l / 12.0,
        at = [pin_a[0] + l / 2.0 * cos(phi), pin_a[1] + l / 2.0 * sin(phi)], angle = phi)]
#[constraint(pin_a[1] + l * sin(phi) == h)]
#[init(phi = -asin(o_y / l))]
#[output(n_b = reaction(h))]
#[output(omega_ab = der(phi))]
#[output(alpha_ab = der(der(phi)))]
#[output(v_b_x = velocity(bar, [l / 2.0, 0.0])[0])]
#[output(v_b_y = velocity(bar, [l / 2.0, 0.0])[1])]
pub struct CrankBar {
    /// Mass and length of the bar AB.
    pub m: f64,
    pub l: f64,
    pub g: f64,
    /// The crank: length, pivot O and its constant rate.
    pub r: f64,
    pub o_x: f64,
    pub o_y: f64,
    pub omega_0: f64,
}

/// The manual's data.
pub const MODEL: CrankBar = CrankBar {
    m: 10.0,
    l: 1.0,
    g: 9.81,
    r: 0.4,
    o_x: 0.4,
    o_y: 0.8,
    omega_0: 4.5,
};

/// The drawing beyond the model's shapes. The floor under the roller B.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("bar", 1)],
    ..Sketch::NONE
};

/// `[ω_AB, α_AB, N_B]` at the instant, by hand (see the module docs): B = A + L e(φ) moves
/// horizontally, A moves down at `r ω_0` with the centripetal `a_A = (r ω_0^2, 0)`.
pub fn closed_form() -> [f64; 3] {
    let CrankBar {
        m,
        l,
        g,
        r,
        o_y,
        omega_0,
        ..
    } = MODEL;
    let (dx, dy) = ((l * l - o_y * o_y).sqrt(), -o_y); // B − A
    let omega = r * omega_0 / dx; // v_A,y + ω dx = 0
    let alpha = omega * omega * dy / dx; // a_B,y = 0
    let a_gx = r * omega_0 * omega_0 - alpha * dy / 2.0 - omega * omega * dx / 2.0;
    let a_gy = alpha * dx / 2.0 - omega * omega * dy / 2.0;
    let i_g = m * l * l / 12.0;
    let moment = i_g * alpha + m * (dx / 2.0 * a_gy - dy / 2.0 * a_gx);
    [omega, alpha, (moment + m * g * dx / 2.0) / dx]
}

/// Exact reference `[N_B]`.
pub fn references() -> [f64; 1] {
    [closed_form()[2]]
}

/// The kinematic state at `t`, assembled from the initial guess (B right of A).
pub fn state_at(t: f64) -> mbd::Result<KinematicState<1>> {
    let guess = Vector::<1>::new(MODEL.initial_state()[0]);
    kinematics(&MODEL, t, &guess, &NewtonOptions::default())
}

fn as_state(ks: &KinematicState<1>) -> Vector<2> {
    Vector::<2>::new(ks.q[0], ks.qd[0])
}

/// The plot's span: the crank turns from 180° to about 309°, clear of the bar standing
/// vertical (A 1.0 m above the floor, at 390°).
const PLOT_SPAN: f64 = 0.5;

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let [n_b] = references();
    let at_instant = model.outputs(0.0, &as_state(&state_at(0.0)?))?;
    let times: Vec<f64> = (0..=200)
        .map(|i| PLOT_SPAN * f64::from(i) / 200.0)
        .collect();
    let guess = Vector::<1>::new(model.initial_state()[0]);
    let points = kinematic_sweep(&model, &times, &guess, &NewtonOptions::default())?
        .iter()
        .map(|ks| Ok((ks.t, model.outputs(ks.t, &as_state(ks))?.n_b)))
        .collect::<mbd::Result<Vec<_>>>()?;
    Ok(Outcome {
        rows: vec![Row {
            quantity: "N_B",
            value: at_instant.n_b,
            reference: n_b,
            method: "kinematic analysis, generated outputs",
            curve: Curve::at_instant("normal force N_B [N]", points, 0.0),
        }],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case24_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-12);
        }
    }

    #[test]
    fn case24_reference_is_exact() {
        // mechanisms/reference/case24.py: N_B = 2183/60 = 36.3833333333333333333333333333 N.
        let [omega, alpha, n_b] = closed_form();
        assert_relative_eq!(n_b, 2183.0 / 60.0, max_relative = 1e-14);
        assert_relative_eq!(omega, 3.0, max_relative = 1e-14);
        assert_relative_eq!(alpha, -12.0, max_relative = 1e-14);
    }

    #[test]
    fn case24_bar_kinematics_match_the_hand_analysis() {
        let ks = state_at(0.0).unwrap();
        let o = MODEL.outputs(0.0, &as_state(&ks)).unwrap();
        assert_relative_eq!(ks.q[0], (-0.8f64).atan2(0.6), max_relative = 1e-14);
        assert_relative_eq!(o.omega_ab, 3.0, max_relative = 1e-12);
        assert_relative_eq!(o.alpha_ab, -12.0, max_relative = 1e-12);
        // The roller rolls along the floor: v_B = v_A + ω k × (0.6, −0.8) = (2.4, 0).
        assert_relative_eq!(o.v_b_x, 2.4, max_relative = 1e-12);
        assert!(o.v_b_y.abs() < 1e-12);
    }

    #[test]
    fn case24_references_round_to_the_manual() {
        let [n_b] = references();
        assert_eq!(format!("{n_b:.2}"), "36.38");
    }
}
