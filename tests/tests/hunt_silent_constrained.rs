//! Constrained models run wrongly by a user, each refused by a typed error (they returned a
//! wrong `Ok`): a Cartesian pendulum started at its pivot, where the constraint Jacobian
//! vanishes (its least-norm correction is zero, so the start check passed it), and the
//! unconstrained entry points (`GeneralizedAlpha::solve`, `static_equilibrium`) given a model
//! with constraint rows, which they silently dropped.

use mbd::analysis::{NewtonOptions, static_equilibrium, static_equilibrium_constrained};
use mbd::integrate::{
    Ali3, Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;

/// A pendulum in Cartesian coordinates, `x^2 + y^2 = l^2`, pulled down by a spring of rest
/// length zero from the ground point `(0, -2 l)`; no `#[init]`, so its initial state is the
/// pivot `(0, 0)`, which is not on the circle.
#[derive(Debug, Mechanism)]
#[mechanism(planar, augmented)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[point(anchor, at = [0.0, -2.0 * l])]
#[spring(pull, from = anchor, to = bob, k = k)]
#[constraint(x * x + y * y == l * l)]
pub struct Cartesian {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub k: f64,
}

const P: Cartesian = Cartesian {
    m: 1.0,
    l: 1.0,
    g: 9.81,
    k: 20.0,
};

/// The `what` and detail of an `InvalidInput`, or the other outcome for the message.
fn invalid<T>(r: Result<T, Error>) -> (String, String) {
    match r {
        Err(Error::InvalidInput { what, detail }) => (what.to_string(), detail),
        Err(e) => (format!("not InvalidInput: {e}"), String::new()),
        Ok(_) => ("Ok".into(), String::new()),
    }
}

#[test]
fn a_start_where_the_constraint_jacobian_vanishes_off_the_circle_is_refused_by_every_method() {
    let y0 = P.initial_state();
    // The start: the pivot, where Phi = -l^2 = -1 and Phi_q = [2x, 2y] = 0.
    assert_eq!(y0, Vector::<4>::zeros());
    let q0 = Vector::<2>::zeros();
    let opts = Options::default();
    let runs: [(&str, Result<Solution<4>, Error>); 10] = [
        (
            "DOPRI5",
            Dopri5::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[]),
        ),
        (
            "DOP853",
            Dop853::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[]),
        ),
        (
            "Vern9",
            Vern9::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[]),
        ),
        ("Auto", Auto::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[])),
        (
            "Radau5",
            Radau5::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[]),
        ),
        ("RK4", Rk4::new(0.01).solve(&P, 0.0, y0, 1.0, &[])),
        ("Gauss", Gauss::new(0.01).solve(&P, 0.0, y0, 1.0, &[])),
        ("Ali3", Ali3::new(0.01).solve(&P, 0.0, q0, q0, 1.0, &[])),
        (
            "generalized-alpha",
            GeneralizedAlpha::new(0.9, 0.01).solve_constrained::<_, 2, 1, 3, 4>(
                &P,
                0.0,
                q0,
                q0,
                1.0,
                &[],
            ),
        ),
        (
            "generalized-alpha (solve)",
            GeneralizedAlpha::new(0.9, 0.01).solve(&P, 0.0, q0, q0, 1.0, &[]),
        ),
    ];
    // Before: DOPRI5, DOP853, Vern9, Auto and RK4 returned `Ok` at rest at (0, -1) (projected
    // there after the first step), generalized-alpha `Ok` in free fall (y(1) = -g/2),
    // Radau5 and Gauss `TooManySteps` at t = 0, Ali3 `NonFinite`.
    for (method, run) in runs {
        let (what, detail) = invalid(run);
        assert!(
            what == "initial state" || what == "model",
            "{method}: {what}"
        );
        assert!(detail.contains("constraint"), "{method}: {detail}");
    }
}

#[test]
fn generalized_alpha_solve_of_a_constrained_model_is_refused() {
    // A start on the circle at the bottom, at rest: the constrained model stays there.
    let (q0, qd0) = (Vector::<2>::new(0.0, -P.l), Vector::<2>::zeros());
    let held: Solution<4> = GeneralizedAlpha::new(0.9, 0.01)
        .solve_constrained::<_, 2, 1, 3, 4>(&P, 0.0, q0, qd0, 1.0, &[])
        .unwrap();
    let end = held.y.last().unwrap();
    assert!(
        (end[0]).abs() < 1e-12 && (end[1] + P.l).abs() < 1e-12,
        "{end:?}"
    );
    // `solve` integrates `M qdd = f` without the constraint: the spring pulled the bob off
    // the circle towards (0, -2 l) and it returned `Ok`.
    let dropped: Result<Solution<4>, Error> =
        GeneralizedAlpha::new(0.9, 0.01).solve(&P, 0.0, q0, qd0, 1.0, &[]);
    let (what, detail) = invalid(dropped);
    assert_eq!(what, "model");
    assert!(detail.contains("solve_constrained"), "{detail}");
}

#[test]
fn static_equilibrium_of_a_constrained_model_is_refused() {
    let guess = Vector::<2>::new(0.1, -0.9);
    let opts = NewtonOptions::default();
    // The truth: on the circle, the bottom (0, -l) (gravity and the spring both pull down).
    let (q, _) = static_equilibrium_constrained::<_, 2, 1, 3>(&P, 0.0, &guess, &opts).unwrap();
    assert!(q[0].abs() < 1e-9 && (q[1] + P.l).abs() < 1e-9, "{q:?}");
    // Without the constraint the forces balance at y = -2 l - m g / k = -2.4905, off the
    // circle: `static_equilibrium` returned it as `Ok`.
    let (what, detail) = invalid(static_equilibrium(&P, 0.0, &guess, &opts));
    assert_eq!(what, "model");
    assert!(
        detail.contains("static_equilibrium_constrained"),
        "{detail}"
    );
}
