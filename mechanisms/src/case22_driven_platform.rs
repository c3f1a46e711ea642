//! Case 22: a platform carried by a driven parallelogram: the force in the link pin D at
//! `t = 0` and `t = 1 s` (Meriam & Kraige 7th ed., P6/29, p. 429).
//!
//! **Problem.** A platform is carried in curvilinear translation by two parallel 1.2-m links;
//! one of them is driven through `θ(t) = (π/6)(1 − cos(πt/2))`. Find the force `F_D` in the
//! pin at D at `t = 0` and at `t = 1 s`. The manual uses `g = 9.81 m/s^2`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `a_t = r θ'' = 1.2 π^3/24`, `a_n = 1.2 θ'^2`: links of 1.2 m (CD = 1200 mm); the platform
//! translates (no `I_G` term anywhere). At `t = 0` (θ = 0),
//! `(m g − F_D) 0.6 = m a_t 0.48` (moments about F): m g and `F_D` are parallel, so the links
//! are *vertical* there with `F_D` along the link, both with a 0.6 m arm about F; the
//! horizontal `m a_t` has a 0.48 m arm, so G is 0.6 m from F along FD (right above D) and
//! 0.48 m from the line FD. At `t = 1 s` (θ = 30°),
//! `m g 0.6 − F_D 0.6 cos θ = m a_n (0.6 cos θ − 0.48 sin θ)`: `F_D` keeps the link's
//! direction, so CD is a massless two-force link pinned at C and D, and the other link, EF,
//! is the driven one; `a_n` points along the links to the pivots. The signs hold only with
//! G 0.48 m *above* FD and the links pointing up from their pivots, turning so that D moves
//! to +x as θ grows. "CE = 600 mm": the fixed pivots are 0.6 m apart (= FD). The mass is not
//! printed: the t = 0 result gives `m = 1714/(9.81 − 0.8 a_t) = 200.006`, the t = 1 s one
//! 199.997, so `m = 200 kg` (with `g = 9.807` the first would give 200.08, so `g = 9.81`).
//! Chosen frame: C = (0, 0), E = (−0.6, 0), F = E + 1.2 (sin θ, cos θ), D = F + (0.6, 0),
//! G = F + (0.6, 0.48).
//!
//! **Model.** The driven link EF's angle θ(t) from the upward vertical (clockwise); one free
//! coordinate, the platform's angle φ, and one constraint, so no degree of freedom: the
//! motion follows from kinematic analysis. F = E + 1.2 (sin θ, cos θ), D = F + `R(φ)`
//! (0.6, 0), G = F + `R(φ)` (0.6, 0.48). The massless two-force link CD is the distance
//! constraint `|D − C| = 1.2 + s` with its stretch s relaxed, so that `reaction(s)` is the
//! force along CD on the platform, i.e. the pin force (`F_D = |reaction(s)|`; the link is in
//! compression when `reaction(s) > 0`). The platform gets `I_G = 10 kg m^2` (any value: it
//! translates; a test checks it). The states at `t = 0` and `t = 1 s` come from
//! `kinematics`, the forces from the generated outputs there.
//! The driven link EF is also a uniform bar, there to be drawn: prescribed, its mass enters no
//! equation of φ or the pin forces.
//!
//! **Reference (exact).** `F_D(0) = m (g − 0.8 × 1.2 π^3/24) = m (g − 0.04 π^3) =
//! 1713.94978655760143859618947946 N`;
//! `F_D(1) = [m g 0.6 − m a_n (0.6 cos 30° − 0.48 sin 30°)]/(0.6 cos 30°)` with
//! `a_n = 1.2 (π^2/12)^2`, `= 2178.15952448341819606327049318 N`
//! (`mechanisms/reference/case22.py`: closed form and an independent redundant-coordinate
//! multibody model with massless links, at 30 digits).
//!
//! **Discrepancies in the manual.** The table's 1714 and 2178 are right (rounded); its text's
//! 2178.13 comes from rounded intermediates (`a_n = 0.812`); exact 2178.1595.

use crate::drawing::{At, Sketch};
use crate::validation::{Curve, Outcome, Row};
use mbd::analysis::{KinematicState, NewtonOptions, kinematic_sweep, kinematics};
use mbd::prelude::*;

/// A platform on the driven link EF (angle θ(t)) and the two-force link CD (its stretch `s`
/// relaxed); φ is the platform's angle.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(phi)]
#[drive(theta = amplitude * (1.0 - cos(rate * t)))]
#[relaxed(s)]
#[point(pin_f, at = [-spacing + l * sin(theta), l * cos(theta)])]
#[rigid(link_f, mass = m, inertia = m * l * l / 12.0,
        at = [-spacing + l / 2.0 * sin(theta), l / 2.0 * cos(theta)], angle = PI / 2.0 - theta)]
#[point(pin_d, at = [pin_f[0] + spacing * cos(phi), pin_f[1] + spacing * sin(phi)])]
#[rigid(platform, mass = m, inertia = i_platform,
        at = [pin_f[0] + fg_along * cos(phi) - fg_normal * sin(phi),
              pin_f[1] + fg_along * sin(phi) + fg_normal * cos(phi)],
        angle = phi)]
#[point(pivot_c, at = [0.0, 0.0])]
#[constraint(hypot(pin_d[0] - pivot_c[0], pin_d[1] - pivot_c[1]) == l + s)]
#[init(phi = 0.0)]
#[output(f_d = abs(reaction(s)))]
#[output(compression_cd = reaction(s))]
pub struct DrivenPlatform {
    /// Mass of the platform (inferred, see the module docs).
    pub m: f64,
    /// The platform's moment of inertia about G (does not enter: it translates).
    pub i_platform: f64,
    pub g: f64,
    /// Length of the links EF and CD.
    pub l: f64,
    /// Spacing of the fixed pivots CE, equal to FD (a parallelogram).
    pub spacing: f64,
    /// G from F, along FD and normal to it.
    pub fg_along: f64,
    pub fg_normal: f64,
    /// The drive `θ = amplitude (1 − cos(rate t))`.
    pub amplitude: f64,
    pub rate: f64,
}

/// The manual's data.
pub const MODEL: DrivenPlatform = DrivenPlatform {
    m: 200.0,
    i_platform: 10.0,
    g: 9.81,
    l: 1.2,
    spacing: 0.6,
    fg_along: 0.6,
    fg_normal: 0.48,
    amplitude: std::f64::consts::FRAC_PI_6,
    rate: std::f64::consts::FRAC_PI_2,
};

/// The drawing beyond the model's shapes. The link CD, and the platform through its pins F and D.
pub const SKETCH: Sketch = Sketch {
    links: &[("link_cd", At("pivot_c", 0), At("pin_d", 0))],
    bodies: &[("platform", &[At("pin_f", 0), At("pin_d", 0)])],
    ..Sketch::NONE
};

/// The pin force `F_D` at time `t`, by moments about F on the translating platform (see
/// the module docs).
pub fn force_at(t: f64) -> f64 {
    let DrivenPlatform {
        m,
        g,
        l,
        spacing,
        fg_along,
        fg_normal,
        amplitude,
        rate,
        ..
    } = MODEL;
    let theta = amplitude * (1.0 - (rate * t).cos());
    let theta_d = amplitude * rate * (rate * t).sin();
    let theta_dd = amplitude * rate * rate * (rate * t).cos();
    let (a_t, a_n) = (l * theta_dd, l * theta_d * theta_d);
    // The platform translates with F: a_G = a_t (cos θ, −sin θ) − a_n (sin θ, cos θ).
    // Moments about F of the link force F_D (along CD, at D: arm `spacing cos θ`), gravity
    // (arm `fg_along`) and the inertia force: F_D spacing cos θ = m g fg_along + m r_FG × a_G.
    let (s, c) = theta.sin_cos();
    let a_g = [a_t * c - a_n * s, -a_t * s - a_n * c];
    let inertia_moment = m * (fg_along * a_g[1] - fg_normal * a_g[0]);
    (m * g * fg_along + inertia_moment) / (spacing * c)
}

/// Exact references `[F_D(0), F_D(1 s)]`.
pub fn references() -> [f64; 2] {
    [force_at(0.0), force_at(1.0)]
}

/// The kinematic state at `t` (the platform starts level).
pub fn state_at(model: &DrivenPlatform, t: f64) -> mbd::Result<KinematicState<1>> {
    kinematics(model, t, &Vector::<1>::zeros(), &NewtonOptions::default())
}

/// The state vector `[q; qd]` of a kinematic state, for the generated outputs.
fn as_state(ks: &KinematicState<1>) -> Vector<2> {
    Vector::<2>::new(ks.q[0], ks.qd[0])
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let method = "kinematic analysis, generated outputs";
    let [reference_0, reference_1] = references();
    let times: Vec<f64> = (0..=200).map(|i| 2.0 * f64::from(i) / 200.0).collect();
    let forces = kinematic_sweep(&model, &times, &Vector::zeros(), &NewtonOptions::default())?
        .iter()
        .map(|ks| Ok((ks.t, model.outputs(ks.t, &as_state(ks))?.f_d)))
        .collect::<mbd::Result<Vec<_>>>()?;
    let mut rows = Vec::new();
    for (quantity, t, reference) in [("F_D_t0", 0.0, reference_0), ("F_D_t1", 1.0, reference_1)] {
        let ks = state_at(&model, t)?;
        rows.push(Row {
            quantity,
            value: model.outputs(t, &as_state(&ks))?.f_d,
            reference,
            method,
            curve: Curve::at_instant("pin force F_D [N]", forces.clone(), t),
        });
    }
    Ok(Outcome { rows })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case22_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-12);
        }
    }

    #[test]
    fn case22_references_are_the_30_digit_values() {
        // mechanisms/reference/case22.py, at 30 digits.
        let [f0, f1] = references();
        assert_relative_eq!(f0, 1_713.949_786_557_601_4, max_relative = 1e-14);
        assert_relative_eq!(f1, 2_178.159_524_483_418_2, max_relative = 1e-14);
        // The closed forms as the manual writes them.
        let DrivenPlatform { m, g, .. } = MODEL;
        let pi = std::f64::consts::PI;
        assert_relative_eq!(f0, m * (g - 0.04 * pi.powi(3)), max_relative = 1e-14);
        let (c30, s30) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let a_n = 1.2 * (pi * pi / 12.0).powi(2);
        let manual = (m * g * 0.6 - m * a_n * (0.6 * c30 - 0.48 * s30)) / (0.6 * c30);
        assert_relative_eq!(f1, manual, max_relative = 1e-14);
    }

    #[test]
    fn case22_platform_translates_and_cd_is_in_compression() {
        let model = MODEL;
        let times: Vec<f64> = (0..=20).map(|i| 0.1 * f64::from(i)).collect();
        let sweep =
            kinematic_sweep(&model, &times, &Vector::zeros(), &NewtonOptions::default()).unwrap();
        for ks in &sweep {
            assert!(ks.q[0].abs() < 1e-12 && ks.qd[0].abs() < 1e-12, "{ks:?}");
            let o = model.outputs(ks.t, &as_state(ks)).unwrap();
            // The link props the platform up.
            assert!(o.compression_cd > 0.0);
            assert_relative_eq!(o.f_d, force_at(ks.t), max_relative = 1e-11);
        }
    }

    #[test]
    fn case22_inertia_of_the_translating_platform_does_not_enter() {
        let other = DrivenPlatform {
            i_platform: 3.0,
            ..MODEL
        };
        for t in [0.0, 1.0] {
            let a = MODEL
                .outputs(t, &as_state(&state_at(&MODEL, t).unwrap()))
                .unwrap();
            let b = other
                .outputs(t, &as_state(&state_at(&other, t).unwrap()))
                .unwrap();
            assert_relative_eq!(a.f_d, b.f_d, max_relative = 1e-12);
        }
    }

    #[test]
    fn case22_references_round_to_the_manual() {
        let [f0, f1] = references();
        assert_eq!(format!("{f0:.0}"), "1714");
        assert_eq!(format!("{f1:.0}"), "2178");
        // The text's 2178.13 is off in the second decimal: the exact value is 2178.16.
        assert_eq!(format!("{f1:.2}"), "2178.16");
    }
}
