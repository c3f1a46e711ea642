//! A closed loop's start is checked against its constraints on every path of the ordinary
//! solve: bridged, with `Options { passages: false, .. }`, and through `passage::Unbridged`
//! (the fixed-step methods' opt-out). A start off the constraints is refused with
//! `InvalidInput` instead of being projected, out of sight, after the first step.
//!
//! The model: a parallelogram four-bar (`a = c = 1`, `b = d = 2`) as a joint tree closed by a
//! pin, kept in the augmented form. On the parallelogram branch the rocker turns with the
//! crank and the coupler translates: `ps = th`, `ph = -th` (coupler's angle relative to the
//! crank), and the same for the rates, so `(th, ph, ps) = (1, -1, 1)` with rates `(w, -w, w)`
//! lies exactly on the position and velocity constraints.

use mbd::integrate::{Dopri5, Gauss, Integrator, Options, Radau5, Rk4};
use mbd::passage::Unbridged;
use mbd::prelude::*;

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[body(crank, joint = revolute(th), com = [a / 2.0, 0.0], mass = m, inertia = m * a * a / 12.0)]
#[body(coupler, parent = crank, joint = revolute(ph), at = [a, 0.0], com = [b / 2.0, 0.0],
       mass = m, inertia = m * b * b / 12.0)]
#[body(rocker, joint = revolute(ps), at = [d, 0.0], com = [c / 2.0, 0.0], mass = m,
       inertia = m * c * c / 12.0)]
#[close(pin, a = coupler, at_a = [b, 0.0], b = rocker, at_b = [c, 0.0])]
pub struct Parallelogram {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub m: f64,
    pub g: f64,
}

const P: Parallelogram = Parallelogram {
    a: 1.0,
    b: 2.0,
    c: 1.0,
    d: 2.0,
    m: 1.0,
    g: 9.81,
};

/// `[th, ph, ps, th', ph', ps']` on the parallelogram branch at `th = 1`, `th' = w`.
fn on_branch(w: f64) -> Vector<6> {
    Vector::<6>::from_column_slice(&[1.0, -1.0, 1.0, w, -w, w])
}

fn refused<T: std::fmt::Debug>(run: Result<T, Error>, what: &str, which: &str) {
    match run {
        Err(Error::InvalidInput { what: w, detail }) => {
            assert_eq!(w, "initial state", "{which}");
            assert!(detail.contains(what), "{which}: {detail}");
        }
        other => panic!("{which}: {other:?}"),
    }
}

fn unbridged(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        passages: false,
        ..Options::default()
    }
}

#[test]
fn unbridged_runs_refuse_a_start_off_the_constraints() {
    // The rocker 1e-3 rad off its place; then the rocker's rate 1e-3 rad/s off.
    let mut position = on_branch(0.5);
    position[2] += 1e-3;
    let mut velocity = on_branch(0.5);
    velocity[5] += 1e-3;
    for (y0, what) in [(position, "positions"), (velocity, "velocities")] {
        let dopri = Dopri5::new(unbridged(1e-8)).solve(&P, 0.0, y0, 0.2, &[]);
        refused(dopri, what, "DOPRI5, passages: false");
        let radau = Radau5::new(unbridged(1e-6)).solve(&P, 0.0, y0, 0.2, &[]);
        refused(radau, what, "Radau5, passages: false");
        let rk4 = Rk4::new(1e-2).solve(&Unbridged(&P), 0.0, y0, 0.2, &[]);
        refused(rk4, what, "RK4, Unbridged");
        let gauss = Gauss::new(1e-2).solve(&Unbridged(&P), 0.0, y0, 0.2, &[]);
        refused(gauss, what, "Gauss, Unbridged");
        // The bridged path refuses it too (it did before).
        let bridged = Dopri5::new(Options::default()).solve(&P, 0.0, y0, 0.2, &[]);
        refused(bridged, what, "DOPRI5, bridged");
    }
}

/// On the constraints the unbridged runs go on, and stay a parallelogram (`ps = th`), as
/// the bridged run does.
#[test]
fn unbridged_runs_start_on_the_constraints() {
    let y0 = on_branch(0.5);
    let runs = [
        Dopri5::new(unbridged(1e-9)).solve(&P, 0.0, y0, 0.2, &[]),
        Rk4::new(1e-3).solve(&Unbridged(&P), 0.0, y0, 0.2, &[]),
        Dopri5::new(Options {
            rtol: 1e-9,
            atol: 1e-9,
            ..Options::default()
        })
        .solve(&P, 0.0, y0, 0.2, &[]),
    ];
    let ends: Vec<Vector<6>> = runs
        .into_iter()
        .map(|r| r.expect("a start on the constraints runs").y_end)
        .collect();
    for y in &ends {
        assert!((y[2] - y[0]).abs() < 1e-7, "not a parallelogram: {y:?}");
        assert!((y[1] + y[0]).abs() < 1e-7, "coupler turned: {y:?}");
    }
    assert!((ends[0][0] - ends[2][0]).abs() < 1e-7, "{ends:?}");
}
