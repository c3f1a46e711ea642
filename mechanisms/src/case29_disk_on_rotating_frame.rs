//! Case 29: a disk spinning on a rotating frame: its angular acceleration and the
//! acceleration of the rim point A (Meriam & Kraige 7th ed., P7/46, p. 536).
//!
//! **Problem.** A frame turns about the fixed vertical z axis at a constant `Ω = 4π rad/s`;
//! a disk of radius 0.1 m mounted on it spins relative to the frame at a constant
//! `p = 10π rad/s`. Find the disk's angular acceleration α and the acceleration `a_A` of the
//! point A at the top of the disk's rim, at the instant shown.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `p = 10π j` fixed in the frame (`p' = Ω × p`): the disk spins about the frame's y axis.
//! `Ω = 4π k`: the frame turns about the fixed z axis through the origin.
//! `R_O = 0.3 i + 0.1 k`: the disk's centre is 0.3 m from the z axis, along the frame's x
//! axis, and 0.1 m above the origin. `r_A/O = 0.1 k`: A is the disk's top point at the
//! instant, on the rim (the disk in the frame's x–z plane). `v_rel = p × r_A/O = π i`: A moves
//! towards +x relative to the frame, as a positive rotation about +y takes +z to +x. Chosen:
//! at t = 0 the frame's axes are the ground's.
//!
//! **Model.** Spatial, everything driven (no free coordinate, state of dimension 0): the
//! frame's angle `ψ = Ω t` about z and the disk's spin `φ = p t` about the frame's y axis.
//! The frame: its shaft (0 to 0.1 m up the z axis) and its arm (from the shaft's top to the
//! disk's centre), uniform bars turning with ψ, there to be drawn.
//! The disk: centre `R_z(ψ) (0.3, 0, 0.1)`, rotation `R_z(ψ) R_y(φ)`; A is the body-fixed
//! point `(0, 0, 0.1)` of the disk. Its mass and inertia play no part (kinematics): a
//! uniform thin disk of 1 kg is given. The generated outputs at t = 0 are the disk's
//! angular acceleration (world x component) and A's acceleration (world components).
//!
//! **Reference (exact).** `ω = Ω k + p R_z(ψ) j`, so `α = Ω k × p j = −p Ω i`:
//! **`α_x = −40π^2 = −394.784176043574344753379639995 rad/s^2`** (`α_y = α_z = 0`);
//! `a_A = 2π^2 (−2.4, 4, −5)`: **`a_Ax = −4.8π^2 = −47.3741011252289213704055567994`,
//! `a_Ay = 8π^2 = 78.956835208714868950675927999`, `a_Az = −10π^2 =
//! −98.6960440108935861883449099987 m/s^2`**, `|a_A| = 134.979244282222205145312662845`
//! (`mechanisms/reference/case29.py`: closed form, and A(t) and ω(t) from the rotation
//! matrices differentiated at 30 digits).
//!
//! **Discrepancies in the manual.** None: −394.78, −47.37, 78.96, −98.70 and 134.98 are the
//! exact values rounded.

use crate::drawing::Sketch;
use crate::validation::{Curve, Outcome, Row, series};
use mbd::prelude::*;

/// A disk of radius `radius` on a frame turning at `big_omega` about z, spinning at `p`
/// about the frame's y axis, its centre at `(d, 0, h)` in the frame.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[mechanism(spatial)]
#[drive(psi = big_omega * t)]
#[drive(phi = p * t)]
#[rigid3(shaft, mass = m, inertia = diag(m * h * h / 12.0, m * h * h / 12.0, 0.0),
         at = [0.0, 0.0, h / 2.0], rotation = rot_z(psi))]
#[rigid3(arm, mass = m, inertia = diag(0.0, m * d * d / 12.0, m * d * d / 12.0),
         at = rot_z(psi) * [d / 2.0, 0.0, h], rotation = rot_z(psi))]
#[rigid3(disk, mass = m,
         inertia = diag(m * radius * radius / 4.0, m * radius * radius / 2.0,
                        m * radius * radius / 4.0),
         at = rot_z(psi) * [d, 0.0, h], rotation = rot_z(psi) * rot_y(phi))]
#[output(alpha_x = angular_acceleration(disk)[0])]
#[output(alpha_y = angular_acceleration(disk)[1])]
#[output(alpha_z = angular_acceleration(disk)[2])]
#[output(a_a_x = acceleration(disk, [0.0, 0.0, radius])[0])]
#[output(a_a_y = acceleration(disk, [0.0, 0.0, radius])[1])]
#[output(a_a_z = acceleration(disk, [0.0, 0.0, radius])[2])]
#[output(omega_x = angular_velocity(disk)[0])]
#[output(omega_y = angular_velocity(disk)[1])]
#[output(omega_z = angular_velocity(disk)[2])]
pub struct SpinningDisk {
    /// The frame's rate about z.
    pub big_omega: f64,
    /// The disk's spin relative to the frame.
    pub p: f64,
    pub radius: f64,
    /// The disk's centre in the frame: distance from the z axis, and height.
    pub d: f64,
    pub h: f64,
    /// The disk's mass (plays no part: kinematics).
    pub m: f64,
}

/// The manual's data.
pub const MODEL: SpinningDisk = SpinningDisk {
    big_omega: 4.0 * std::f64::consts::PI,
    p: 10.0 * std::f64::consts::PI,
    radius: 0.1,
    d: 0.3,
    h: 0.1,
    m: 1.0,
};

/// The drawing: the model's own shapes.
pub const SKETCH: Sketch = Sketch::NONE;

/// Exact references `[α_x, a_Ax, a_Ay, a_Az]` (see the module docs).
pub fn references() -> [f64; 4] {
    let pi2 = std::f64::consts::PI * std::f64::consts::PI;
    [-40.0 * pi2, -4.8 * pi2, 8.0 * pi2, -10.0 * pi2]
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let state = Vector::<0>::zeros();
    let o = model.outputs(0.0, &state)?;
    let [alpha_x, a_x, a_y, a_z] = references();
    let method = "generated outputs (fully driven, t = 0)";
    // Each quantity over one turn of the frame.
    let turn = 2.0 * std::f64::consts::PI / model.big_omega;
    let samples = (0..=200)
        .map(|i| {
            let t = turn * f64::from(i) / 200.0;
            Ok((t, model.outputs(t, &state)?))
        })
        .collect::<mbd::Result<Vec<_>>>()?;
    let row = |quantity, value, reference, label, f: fn(&SpinningDiskOutputs) -> f64| Row {
        quantity,
        value,
        reference,
        method,
        curve: Curve::at_instant(label, series(&samples, f), 0.0),
    };
    Ok(Outcome {
        rows: vec![
            row(
                "alpha_x",
                o.alpha_x,
                alpha_x,
                "disk angular acceleration α_x [rad/s²]",
                |o| o.alpha_x,
            ),
            row("a_Ax", o.a_a_x, a_x, "acceleration of A, x [m/s²]", |o| {
                o.a_a_x
            }),
            row("a_Ay", o.a_a_y, a_y, "acceleration of A, y [m/s²]", |o| {
                o.a_a_y
            }),
            row("a_Az", o.a_a_z, a_z, "acceleration of A, z [m/s²]", |o| {
                o.a_a_z
            }),
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case29_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-12);
        }
    }

    #[test]
    fn case29_references_are_the_30_digit_values() {
        // mechanisms/reference/case29.py.
        let [alpha_x, a_x, a_y, a_z] = references();
        assert_relative_eq!(alpha_x, -394.784_176_043_574_34, max_relative = 1e-15);
        assert_relative_eq!(a_x, -47.374_101_125_228_92, max_relative = 1e-15);
        assert_relative_eq!(a_y, 78.956_835_208_714_87, max_relative = 1e-15);
        assert_relative_eq!(a_z, -98.696_044_010_893_59, max_relative = 1e-15);
    }

    #[test]
    fn case29_angular_velocity_and_acceleration_stay_as_derived() {
        // ω = Ω k + p R_z(Ω t) j and α = Ω k × ω = −p Ω (cos Ω t, sin Ω t, 0): |α| = p Ω
        // at every instant, and α_z = 0.
        let SpinningDisk { big_omega, p, .. } = MODEL;
        for i in 0..=20 {
            let t = 0.025 * f64::from(i);
            let o = MODEL.outputs(t, &Vector::<0>::zeros()).unwrap();
            let (c, s) = ((big_omega * t).cos(), (big_omega * t).sin());
            let scale = p * big_omega;
            assert_relative_eq!(o.omega_x, -p * s, epsilon = 1e-13 * p);
            assert_relative_eq!(o.omega_y, p * c, epsilon = 1e-13 * p);
            assert_relative_eq!(o.omega_z, big_omega, max_relative = 1e-13);
            assert_relative_eq!(o.alpha_x, -scale * c, epsilon = 1e-13 * scale);
            assert_relative_eq!(o.alpha_y, -scale * s, epsilon = 1e-13 * scale);
            assert!(o.alpha_z.abs() < 1e-13 * scale, "{}", o.alpha_z);
        }
    }

    #[test]
    fn case29_references_round_to_the_manual() {
        let [alpha_x, a_x, a_y, a_z] = references();
        assert_eq!(format!("{alpha_x:.2}"), "-394.78");
        assert_eq!(format!("{a_x:.2}"), "-47.37");
        assert_eq!(format!("{a_y:.2}"), "78.96");
        assert_eq!(format!("{a_z:.2}"), "-98.70");
        let magnitude = (a_x * a_x + a_y * a_y + a_z * a_z).sqrt();
        assert_eq!(format!("{magnitude:.2}"), "134.98");
    }
}
