//! Run-time validation: parameters that no mechanism has are typed errors naming
//! them, never a wrong `Ok`; an event that cannot be evaluated stops the integration with
//! its error; body-fixed offsets are measured from the body frame's origin for every body.

use mbd::Vector;
use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;

/// One coordinate: `qdd = f / m` with the factors cancelled.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[particle(bob, mass = m, at = [l * sin(theta), -l * cos(theta)])]
#[init(theta = 0.5)]
pub struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

/// Two coordinates through the mass-matrix solve.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x, y)]
#[particle(a, mass = m1, at = [x, 0.0])]
#[particle(b, mass = m2, at = [x, y])]
#[spring(s, from = [0.0, 0.0], to = b, k = k, length = 0.5)]
#[init(y = -1.0)]
pub struct TwoMasses {
    m1: f64,
    m2: f64,
    k: f64,
}

/// A chain evaluated by the articulated-body recursion (no mass matrix, no pivots).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -9.81)]
#[chain(link, n = 3, joint = revolute, length = 1.0, mass = m, inertia = 0.1)]
#[init(link_q1 = 0.3)]
pub struct Chain {
    m: f64,
}

/// A block with Coulomb friction whose coefficient is a parameter.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = 9.81)]
#[init(der(x) = 1.0)]
pub struct Block {
    mu: f64,
}

fn run<S: OdeSystem<D>, const D: usize>(s: &S, y0: Vector<D>) -> Result<(), Error> {
    Dopri5::new(Options::default())
        .solve(s, 0.0, y0, 1.0, &[])
        .map(|_| ())
}

fn invalid(err: Error) -> (String, f64) {
    match err {
        Error::InvalidParameter { what, value, .. } => (what, value),
        other => panic!("expected InvalidParameter, got {other:?} ({other})"),
    }
}

#[test]
fn negative_masses_are_refused_by_every_evaluation() {
    let p = Pendulum {
        m: -2.0,
        l: 1.0,
        g: 9.81,
    };
    assert_eq!(
        invalid(run(&p, p.initial_state()).unwrap_err()),
        ("the mass of `bob`".into(), -2.0)
    );
    let two = TwoMasses {
        m1: 1.0,
        m2: -0.5,
        k: 10.0,
    };
    assert_eq!(
        invalid(run(&two, two.initial_state()).unwrap_err()),
        ("the mass of `b`".into(), -0.5)
    );
    let chain = Chain { m: -1.0 };
    let (what, value) = invalid(run(&chain, chain.initial_state()).unwrap_err());
    assert!(what.starts_with("the mass of `link_"), "{what}");
    assert_eq!(value, -1.0);
    // The same models with sensible parameters run.
    let p = Pendulum {
        m: 2.0,
        l: 1.0,
        g: 9.81,
    };
    run(&p, p.initial_state()).unwrap();
    let chain = Chain { m: 1.0 };
    run(&chain, chain.initial_state()).unwrap();
}

#[test]
fn a_nan_parameter_is_named_not_called_a_singular_mass_matrix() {
    let p = Pendulum {
        m: 1.0,
        l: f64::NAN,
        g: 9.81,
    };
    let err = run(&p, p.initial_state()).unwrap_err();
    assert_eq!(invalid(err.clone()).0, "parameter `l`");
    assert_eq!(err.to_string(), "parameter `l` is NaN: it must be finite");
    let two = TwoMasses {
        m1: f64::INFINITY,
        m2: 1.0,
        k: 10.0,
    };
    assert_eq!(
        invalid(run(&two, two.initial_state()).unwrap_err()).0,
        "parameter `m1`"
    );
}

#[test]
fn element_constants_are_checked_where_no_solve_would_notice() {
    let two = TwoMasses {
        m1: 1.0,
        m2: 1.0,
        k: -10.0,
    };
    let (what, value) = invalid(run(&two, two.initial_state()).unwrap_err());
    assert_eq!(
        (what.as_str(), value),
        ("the stiffness of spring `s`", -10.0)
    );
    let block = Block { mu: -0.3 };
    let (what, _) = invalid(run(&block, block.initial_state()).unwrap_err());
    assert_eq!(what, "the friction coefficient along `x`");
    assert!(Block { mu: 0.3 }.check_parameters().is_ok());
}

/// A pendulum whose event function `sqrt(theta)` turns NaN once the bob swings past the
/// bottom: the run must stop there with an error, not go on never firing the event.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(theta)]
#[particle(bob, mass = 1.0, at = [sin(theta), -cos(theta)])]
#[event(odd = sqrt(theta), falling)]
#[init(theta = 0.5)]
pub struct OddEvent {}

#[test]
fn an_event_that_turns_nan_stops_the_run_with_an_error() {
    // sqrt(theta) is NaN once theta < 0: the pendulum swings from 0.5 to -0.5 within 1 s.
    let m = OddEvent {};
    let events = m.events();
    let err = Dopri5::new(Options::default())
        .solve(&m, 0.0, m.initial_state(), 2.0, &events)
        .unwrap_err();
    match &err {
        Error::EventFailed {
            event,
            t,
            cause: None,
        } => {
            assert_eq!(event, "odd");
            // theta = 0.5 cos(w t) crosses zero near t = pi / (2 w) with w ~ sqrt(9.81).
            assert!(*t > 0.3 && *t < 0.7, "{t}");
        }
        other => panic!("expected EventFailed, got {other:?}"),
    }
    assert!(
        err.to_string()
            .starts_with("event `odd` is NaN or infinite at t = 0."),
        "{err}"
    );
}

/// One rule for body-fixed offsets: from the body frame's origin (a tree body's joint, a
/// free body's `at`), in the body's axes.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -9.81)]
#[body(bar, parent = ground, joint = revolute(q), com = [0.0, -l / 2.0], mass = 1.0, inertia = 0.1)]
#[body(tip, parent = bar, joint = fixed, at = [0.0, -l], mass = 0.5)]
#[rigid(free, mass = 1.0, inertia = 0.1, at = [2.0, 0.0], angle = q)]
#[output(bar_tip_x = position(bar, [0.0, -l])[0])]
#[output(bar_tip_y = position(bar, [0.0, -l])[1])]
#[output(mass_tip_x = position(tip, [0.1, 0.0])[0])]
#[output(mass_tip_y = position(tip, [0.1, 0.0])[1])]
#[output(free_x = position(free, [1.0, 0.0])[0])]
#[output(free_y = position(free, [1.0, 0.0])[1])]
pub struct Offsets {
    #[default(1.5)]
    l: f64,
}

#[test]
fn offsets_are_measured_from_the_body_frame_origin() {
    let m = Offsets { l: 1.5 };
    let q = 0.4f64;
    let y = Vector::<2>::new(q, 0.0);
    let o = m.outputs(0.0, &y).unwrap();
    // Bar turned by q about the pivot: its point [0, -l] is at l (sin q, -cos q).
    assert!(
        (o.bar_tip_x - 1.5 * q.sin()).abs() < 1e-14 && (o.bar_tip_y + 1.5 * q.cos()).abs() < 1e-14
    );
    // A point mass welded at the tip (no inertia, still a frame): [0.1, 0] turned by q.
    let (tx, ty) = (
        1.5 * q.sin() + 0.1 * q.cos(),
        -1.5 * q.cos() + 0.1 * q.sin(),
    );
    assert!((o.mass_tip_x - tx).abs() < 1e-14 && (o.mass_tip_y - ty).abs() < 1e-14);
    // A free body's frame is at its `at`.
    assert!((o.free_x - (2.0 + q.cos())).abs() < 1e-14 && (o.free_y - q.sin()).abs() < 1e-14);
}
