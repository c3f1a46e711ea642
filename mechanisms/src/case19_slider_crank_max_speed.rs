//! Case 19: a slider-crank, the maximum piston speed and the crank angle where it occurs
//! (Meriam & Kraige 7th ed., P5/212, p. 408).
//!
//! **Problem.** The crank OB (`r = 0.125 m`) turns at a constant 1500 rev/min; the connecting
//! rod BA (`l = 0.35 m`) drives the piston A along a line through O. Find the maximum piston
//! speed `v_A,max` and the crank angle θ at which it occurs.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `x = l cos β + r cos θ`, `l sin β = r sin θ`: x = OA along the cylinder's axis through O,
//! θ the crank angle from the axis on the piston's side (θ = 0: top dead centre, B between O
//! and A), β the rod's angle to the axis. `v_A = −x'` (positive toward O) with
//! `θ' = ω = 1500 · 2π/60 = 50π rad/s` constant, so
//! `v_A = r ω sin θ [1 + cos θ / sqrt((l/r)^2 − sin^2 θ)]`. Chosen frame: O = (0, 0), the
//! axis along +x, `B = r (cos θ, sin θ)`, `A = (x, 0)`, the crank turning counter-clockwise.
//!
//! **Model.** Driven: `θ = ω t`. Free: β (the rod's angle below the axis when B is above
//! it) and x. Loop closure (2 equations): `r cos θ + l cos β = x`, `r sin θ = l sin β`.
//! Bodies: the crank and the rod as uniform rods, the piston a particle; their masses (1 kg,
//! not given in the problem) play no part in the motion, which the drive fixes, and neither
//! does gravity (the model has none). The state at t = 0 (θ = β = 0, x = r + l) is
//! completed by a kinematic analysis and integrated over one turn of the crank. The maximum
//! of `v_A` is an event: the downward zero crossing of `a_A = −x''`, the only one in a turn;
//! θ and `v_A` are the model's outputs there.
//!
//! **Reference (exact).** `dv_A/dθ = r ω [cos θ + cos 2θ / S + sin^2 2θ / (4 S^3)]`,
//! `S = sqrt((l/r)^2 − sin^2 θ)` (the manual's `a_A / ω`), vanishes in (0, π/2) at
//! **`θ* = 1.26120378899873158511696063826 rad`** (72.2616542155°), where
//! **`v_A,max = 20.865434027180891742303204609 m/s`**, at `t = θ*/ω =
//! 8.02907269061503592658465551877e-3 s` (30 digits: `mechanisms/reference/case19.py`, the
//! root of `dv_A/dθ`, and the event located on the loop-closure model).
//!
//! **Discrepancies in the manual.** Its table's `θ = 1.2566 rad` is the 72° grid point of its
//! plot, not the maximum; the manual's own root of `a_A = 0`, 1.26125 rad = 72.26°, is the
//! right place, and **1.261204 rad** is the corrected value (`v_A` at 72° is 20.86514, so
//! `v_A,max = 20.865` is unaffected). RecurDyn's 1.2566 is also a sampled value. Not in the
//! table: its `a_A,max = 4172.97 m/s^2` at θ = 0 uses rounded coefficients (0.357, 0.128,
//! ω = 157.08); exactly `r ω^2 (1 + r/l) = 4185.769724`, and `a_A(180°) = r ω^2 (r/l − 1) =
//! −1982.733027` (manual −1983.19).

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Curve, Outcome, Read, Row};
use mbd::analysis::{KinematicState, NewtonOptions, kinematics};
use mbd::prelude::*;

/// A slider-crank: crank OB (`r`) turning at `omega` from top dead centre, rod BA (`l`),
/// piston A at `x` on the axis through O; β is the rod's angle to the axis.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[coords(beta, x)]
#[drive(theta = omega * t)]
#[constraint(r * cos(theta) + l * cos(beta) == x)]
#[constraint(r * sin(theta) == l * sin(beta))]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0,
        at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[rigid(rod, mass = m, inertia = m * l * l / 12.0,
        at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
        angle = -beta)]
#[particle(piston, mass = m, at = [x, 0.0])]
#[init(beta = 0.0, x = r + l)]
#[output(crank_angle = theta)]
#[output(v_a = -der(x))]
#[output(a_a = -der(der(x)))]
#[event(v_a_max = -der(der(x)), falling)]
pub struct SliderCrank {
    /// Mass of each body (immaterial to the kinematics).
    pub m: f64,
    pub r: f64,
    pub l: f64,
    pub omega: f64,
}

/// The manual's data.
pub const MODEL: SliderCrank = SliderCrank {
    m: 1.0,
    r: 0.125,
    l: 0.35,
    omega: 1500.0 * 2.0 * std::f64::consts::PI / 60.0,
};

/// The drawing beyond the model's shapes. The piston's cylinder.
pub const SKETCH: Sketch = Sketch {
    guides: &[At("piston", 0)],
    ..Sketch::NONE
};

/// The piston's speed toward O and its derivative in θ:
/// `v_A = r ω [sin θ + sin 2θ / (2 S)]`,
/// `dv_A/dθ = r ω [cos θ + cos 2θ / S + sin^2 2θ / (4 S^3)]`, `S = sqrt((l/r)^2 − sin^2 θ)`
/// (Meriam & Kraige P5/212; `a_A = ω dv_A/dθ`).
pub fn piston_speed(theta: f64) -> [f64; 2] {
    let SliderCrank { r, l, omega, .. } = MODEL;
    let s = ((l / r).powi(2) - theta.sin().powi(2)).sqrt();
    let (s2, c2) = ((2.0 * theta).sin(), (2.0 * theta).cos());
    [
        r * omega * (theta.sin() + s2 / (2.0 * s)),
        r * omega * (theta.cos() + c2 / s + s2 * s2 / (4.0 * s.powi(3))),
    ]
}

/// The crank angle of the maximum speed: the root of `dv_A/dθ` in (1, 1.5) rad, where it
/// falls through zero, by bisection to the last bit.
pub fn angle_of_max_speed() -> f64 {
    let (mut lo, mut hi) = (1.0_f64, 1.5_f64);
    while hi - lo > f64::EPSILON * hi {
        let mid = 0.5 * (lo + hi);
        if piston_speed(mid)[1] > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Exact references `[v_A,max, θ at v_A,max]` (see the module docs).
pub fn references() -> [f64; 2] {
    let theta = angle_of_max_speed();
    [piston_speed(theta)[0], theta]
}

/// The state `[q; qd]` of a kinematic solution.
fn state(k: &KinematicState<2>) -> Vector<4> {
    SliderCrankState {
        beta: k.q[0],
        x: k.q[1],
        beta_dot: k.qd[0],
        x_dot: k.qd[1],
    }
    .into()
}

/// The consistent state at `t`: the positions assembled from the `init` guess, the
/// velocities from the drive.
fn state_at(model: &SliderCrank, t: f64) -> mbd::Result<Vector<4>> {
    let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
    Ok(state(&kinematics(
        model,
        t,
        &guess,
        &NewtonOptions::default(),
    )?))
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let y0 = state_at(&model, 0.0)?;
    let turn = 2.0 * std::f64::consts::PI / model.omega;
    let events = model.events();
    let sol = sim::integrate(&model, y0, turn, &events)?;
    let at_max = sol
        .events
        .iter()
        .find(|e| e.event == 0)
        .ok_or(mbd::Error::InvalidInput {
            what: "case 19",
            detail: "the piston speed had no maximum in a turn".into(),
        })?;
    let found = model.outputs(at_max.t, &at_max.y)?;
    // Over the crank angle the run sweeps in its turn (the run's own abscissa: the
    // maximum is compared where it lies, not at an instant of the table).
    let samples = sim::curve(&sol, 200, |t, y| model.outputs(t, y))?;
    let speed: Vec<(f64, f64)> = samples
        .iter()
        .map(|(_, o)| (o.crank_angle, o.v_a))
        .collect();
    const ANGLE: &str = "crank angle θ over the run [rad]";
    const SPEED: &str = "piston speed v_A [m/s]";
    let [v_max, theta_max] = references();
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "v_A_max",
                value: found.v_a,
                reference: v_max,
                method: sim::METHOD,
                curve: Curve {
                    x_label: ANGLE,
                    y_label: SPEED,
                    points: speed.clone(),
                    read: Read::Ordinate {
                        at: found.crank_angle,
                    },
                },
            },
            Row {
                quantity: "theta_at_v_A_max",
                value: found.crank_angle,
                reference: theta_max,
                method: sim::METHOD,
                curve: Curve {
                    x_label: ANGLE,
                    y_label: SPEED,
                    points: speed,
                    read: Read::Abscissa { y: found.v_a },
                },
            },
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case19_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case19_references_are_the_30_digit_values() {
        // mechanisms/reference/case19.py: θ* = 1.26120378899873158511696063826 rad,
        // v_A,max = 20.865434027180891742303204609 m/s.
        let [v_max, theta] = references();
        assert_relative_eq!(theta, 1.261_203_788_998_731_6, max_relative = 1e-15);
        assert_relative_eq!(v_max, 20.865_434_027_180_89, max_relative = 1e-15);
    }

    #[test]
    fn case19_references_round_to_the_manual_where_it_is_right() {
        let [v_max, theta] = references();
        assert_eq!(format!("{v_max:.3}"), "20.865");
        // The manual's own root of a_A = 0: 1.26125 rad = 72.26°.
        assert_eq!(format!("{:.2}", theta.to_degrees()), "72.26");
    }

    #[test]
    fn case19_pins_the_corrected_angle() {
        let [_, theta] = references();
        // The table's 1.2566 rad is the 72° grid point, not the maximum.
        let grid = 0.4 * std::f64::consts::PI;
        assert_eq!(format!("{grid:.4}"), "1.2566");
        assert_eq!(format!("{theta:.4}"), "1.2612");
        // There the speed is 20.86514 (case19.py: 20.8651406281778343529105721224), so the
        // maximum to 5 digits is unaffected.
        assert_relative_eq!(
            piston_speed(grid)[0],
            20.865_140_628_177_834,
            max_relative = 1e-14
        );
    }

    #[test]
    fn case19_event_time_and_accelerations_of_the_model() {
        let out = run().unwrap();
        let model = MODEL;
        // case19.py: the event at t = 8.02907269061503592658465551877e-3 s.
        assert_relative_eq!(
            out.rows[1].value / model.omega,
            8.029_072_690_615_036e-3,
            max_relative = 1e-9
        );
        // At top and bottom dead centre a_A = r ω^2 (±1 + r/l): 4185.7697236762904856664135937
        // and −1982.73302700455865110514328122 (case19.py); the manual's 4172.97 and −1983.19
        // use rounded coefficients.
        let SliderCrank { r, l, omega, .. } = model;
        for (t, exact) in [
            (0.0, r * omega * omega * (1.0 + r / l)),
            (
                std::f64::consts::PI / omega,
                r * omega * omega * (r / l - 1.0),
            ),
        ] {
            let a_a = model.outputs(t, &state_at(&model, t).unwrap()).unwrap().a_a;
            assert_relative_eq!(a_a, exact, max_relative = 1e-12);
        }
        assert_relative_eq!(
            r * omega * omega * (1.0 + r / l),
            4_185.769_723_676_29,
            max_relative = 1e-14
        );
        assert_relative_eq!(
            r * omega * omega * (r / l - 1.0),
            -1_982.733_027_004_558_6,
            max_relative = 1e-14
        );
    }

    #[test]
    fn case19_loop_stays_closed_over_the_turn() {
        let model = MODEL;
        let turn = 2.0 * std::f64::consts::PI / model.omega;
        let sol = sim::integrate(&model, state_at(&model, 0.0).unwrap(), turn, &[]).unwrap();
        for (t, y) in sol.t.iter().zip(&sol.y) {
            let q = Vector::<2>::new(y[0], y[1]);
            assert!(model.phi(*t, &q).norm() < 1e-12);
            // The drive fixes the motion: x = r cos θ + sqrt(l^2 − r^2 sin^2 θ).
            let th = model.omega * t;
            let x = model.r * th.cos() + (model.l.powi(2) - (model.r * th.sin()).powi(2)).sqrt();
            assert_relative_eq!(y[1], x, max_relative = 1e-10);
        }
    }
}
