//! Run-time mistakes a newcomer makes with the README's own models, each answered by a
//! typed error naming what is wrong (never a panic, a NaN or a wrong `Ok`): a tolerance or
//! step out of its domain for every method, a run backwards or from a NaN state through the
//! friction driver, a linearisation of a model derived without `jacobian`, and the README's
//! slider-crank with a rod too short to reach (no configuration exists).

use mbd::analysis::linear::linearize;
use mbd::analysis::{NewtonOptions, kinematics};
use mbd::integrate::{Auto, Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Radau5, Rk4};
use mbd::prelude::*;

/// A pendulum written without `#[mechanism(jacobian)]`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(th)]
#[particle(bob, mass = m, at = [l * sin(th), -l * cos(th)])]
#[init(th = 0.3)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

const P: Pendulum = Pendulum {
    m: 1.0,
    l: 1.0,
    g: 9.81,
};

/// The `what` of an `InvalidInput`, or the run's other outcome for the message.
fn what<T: std::fmt::Debug>(r: Result<T, Error>) -> String {
    match r {
        Err(Error::InvalidInput { what, .. }) => what.to_string(),
        other => format!("not InvalidInput: {other:?}"),
    }
}

#[test]
fn a_tolerance_or_step_out_of_its_domain_is_named_by_every_method() {
    let y0 = P.initial_state();
    let (q0, qd0) = (Vector::<1>::new(y0[0]), Vector::<1>::new(y0[1]));
    for (field, opts) in [
        (
            "rtol",
            Options {
                rtol: -1e-8,
                ..Options::default()
            },
        ),
        (
            "rtol",
            Options {
                rtol: f64::NAN,
                ..Options::default()
            },
        ),
        (
            "atol",
            Options {
                atol: 0.0,
                ..Options::default()
            },
        ),
        (
            "h_max",
            Options {
                h_max: Some(-0.1),
                ..Options::default()
            },
        ),
        (
            "h0",
            Options {
                h0: Some(0.0),
                ..Options::default()
            },
        ),
    ] {
        let runs = [
            (
                "DOPRI5",
                what(Dopri5::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[])),
            ),
            (
                "DOP853",
                what(Dop853::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[])),
            ),
            (
                "Auto",
                what(Auto::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[])),
            ),
            (
                "Radau5",
                what(Radau5::new(opts.clone()).solve(&P, 0.0, y0, 1.0, &[])),
            ),
        ];
        for (method, got) in runs {
            assert_eq!(got, field, "{method} with a bad {field}");
        }
    }
    // Fixed-step methods: the step itself.
    for h in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        let rk4 = what(Rk4::new(h).solve(&P, 0.0, y0, 1.0, &[]));
        let gauss = what(Gauss::new(h).solve(&P, 0.0, y0, 1.0, &[]));
        let alpha: Result<Solution<2>, Error> =
            GeneralizedAlpha::new(0.9, h).solve(&P, 0.0, q0, qd0, 1.0, &[]);
        assert_eq!(
            (rk4, gauss, what(alpha)),
            ("h".into(), "h".into(), "h".into()),
            "h = {h}"
        );
    }
}

/// The friction block of the language docs' incline, run through `mbd::hybrid` wrongly.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g)]
#[init(der(x) = 2.0)]
pub struct Block {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
}

#[test]
fn the_friction_driver_refuses_a_backward_run_a_nan_state_and_a_bad_tolerance() {
    let b = Block {
        m: 1.0,
        g: 9.81,
        mu: 0.2,
    };
    let y0 = b.initial_state();
    let dopri = Dopri5::new(Options::default());
    assert_eq!(
        what(mbd::hybrid::solve(&dopri, &b, 1.0, y0, 0.0, &[])),
        "t1"
    );
    let nan = Vector::<2>::new(f64::NAN, 2.0);
    assert_eq!(
        what(mbd::hybrid::solve(&dopri, &b, 0.0, nan, 1.0, &[])),
        "y0"
    );
    let loose = Dopri5::new(Options {
        rtol: 0.0,
        ..Options::default()
    });
    assert_eq!(
        what(mbd::hybrid::solve(&loose, &b, 0.0, y0, 1.0, &[])),
        "rtol"
    );
}

#[test]
fn linearising_a_model_without_its_jacobian_says_how_to_derive_it() {
    match linearize(&P, 0.0, &Vector::<2>::zeros()) {
        Err(Error::InvalidInput { what, detail }) => {
            assert_eq!(what, "linearize");
            assert!(detail.contains("#[mechanism(jacobian)]"), "{detail}");
        }
        other => panic!("{other:?}"),
    }
}

/// README's slider-crank (see `hunt_newcomer_classes`), given a rod shorter than the
/// crank: at `θ = π / 2` the rod cannot reach the line of the piston (`l sin β = r` has no
/// solution for `l < r`), so the kinematic analysis has no configuration to find.
#[derive(Debug, Mechanism)]
#[coords(beta, x)]
#[drive(theta = omega * t)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(rod, mass = m_rod, inertia = m_rod * l * l / 12.0,
        at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
        angle = -beta)]
#[particle(piston, mass = m_piston, at = [x, 0.0])]
pub struct SliderCrank {
    pub r: f64,
    pub l: f64,
    pub omega: f64,
    pub m_rod: f64,
    pub m_piston: f64,
}

#[test]
fn a_slider_crank_whose_rod_cannot_reach_has_no_configuration() {
    let p = SliderCrank {
        r: 0.5,
        l: 0.2,
        omega: 1.0,
        m_rod: 1.0,
        m_piston: 1.0,
    };
    let t = std::f64::consts::FRAC_PI_2;
    let got = kinematics(
        &p,
        t,
        &Vector::<2>::new(1.0, 0.0),
        &NewtonOptions::default(),
    );
    assert!(
        matches!(
            got,
            Err(Error::AssemblyFailed { .. } | Error::SingularConstraintJacobian { .. })
        ),
        "{got:?}"
    );
}
