//! The kinematic analysis and the assembly failing at a singular position, or where no
//! assembly exists, name the configuration `q` where they stopped (and the constraint rows
//! that lost rank there), not only `t`. The model: a slider-crank (crank `r`, rod `l`)
//! driven by its piston, `x = x0 + v t`. The closed form: the loop closes iff the crank
//! pin, at distance `r` from the origin, is at distance `l` from the piston, i.e. iff
//! `|x| <= r + l`; at `x = r + l` crank and rod lie stretched along `x` (`theta = beta =
//! 0`), where the first row's derivatives `(r sin theta, l sin beta)` vanish (the second's
//! are `(-r, l)`): a toggle position, named as row 0.

use mbd::analysis::{NewtonOptions, assemble, kinematic_sweep, kinematics};
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[coords(theta, beta)]
#[drive(x = x0 + v * t)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0,
        at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
pub struct PistonDriven {
    pub r: f64,
    pub l: f64,
    pub x0: f64,
    pub v: f64,
    pub m: f64,
}

const SC: PistonDriven = PistonDriven {
    r: 0.1,
    l: 0.3,
    x0: 0.3,
    v: 1.0,
    m: 1.0,
};

/// `t` and the message of an assembly or singular-Jacobian error, which must name `q`.
fn stopped<T: std::fmt::Debug>(r: mbd::Result<T>) -> (f64, String) {
    let e = r.expect_err("past the rod's reach there is no configuration");
    let message = e.to_string();
    let t = match e {
        Error::AssemblyFailed { t, ref detail, .. }
        | Error::SingularConstraintJacobian { t, ref detail } => {
            assert!(detail.starts_with("at q = [theta = "), "{detail}");
            assert!(detail.contains(", beta = "), "{detail}");
            t
        }
        other => panic!("expected an assembly error, got {other:?}"),
    };
    assert!(message.contains("at q = [theta = "), "{message}");
    (t, message)
}

#[test]
fn a_sweep_past_the_rods_reach_names_where_it_stopped() {
    // The reach r + l = 0.4 is met at t = 0.1: the sweep assembles up to there, and fails
    // after it (at the toggle or a sub-step just past it) naming where.
    let opts = NewtonOptions::default();
    let times = [0.0, 0.04, 0.08, 0.12];
    let guess = Vector::<2>::new(1.0, 0.3);
    let (t, message) = stopped(kinematic_sweep(&SC, &times, &guess, &opts));
    eprintln!("{message}");
    assert!((0.1 - 1e-6..=0.12).contains(&t), "{t}");
    if message.starts_with("constraint Jacobian lost rank") {
        assert!(
            message.contains("constraint rows 0 (counting from 0)"),
            "{message}"
        );
    }
    // Directly beyond the reach: no configuration closes the loop.
    let (t, message) = stopped(kinematics(&SC, 0.15, &guess, &opts));
    eprintln!("{message}");
    assert_eq!(t, 0.15);
    let (t, message) = stopped(assemble(&SC, 0.15, &guess, &[false; 2], &opts));
    eprintln!("{message}");
    assert_eq!(t, 0.15);
}
