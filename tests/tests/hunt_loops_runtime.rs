//! Hunt: run-time bad input on closed loops in both forms. A four-bar whose lengths, given at
//! run time, cannot close (ground 10, the other bars 1 + 3 + 2.5 = 6.5 < 10: no configuration
//! exists, by the triangle inequality) must give typed errors from every entry point and every
//! method, never `Ok` with NaN.

use mbd::integrate::{
    Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;

macro_rules! four_bar {
    ($name:ident, $($opt:ident),*) => {
        /// A crank-rocker under gravity: crank `th`, coupler `be`, rocker `ga` about `(d, 0)`.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[gravity(0.0, -g)]
        #[coords(th, be, ga)]
        #[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
        #[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
        #[rigid(crank, mass = m, inertia = m * a * a / 12.0,
                at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
        #[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
                at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
        #[rigid(rocker, mass = m, inertia = m * c * c / 12.0,
                at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
        #[init(th = 0.5, be = 0.7260165921021776, ga = 1.7229599395818342, der(th) = 1.0)]
        #[output(rocker_angle = ga, rocker_rate = der(ga), tip = position(rocker, [c / 2.0, 0.0]))]
        #[event(rocker_up = ga - 2.0)]
        pub struct $name {
            #[default(1.0)] pub a: f64,
            #[default(3.0)] pub b: f64,
            #[default(2.5)] pub c: f64,
            #[default(3.5)] pub d: f64,
            #[default(1.0)] pub m: f64,
            #[default(9.81)] pub g: f64,
        }
    };
}
four_bar!(FourBar, jacobian);
four_bar!(FourBarAugmented, jacobian, augmented);

const APART: FourBar = FourBar {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 10.0,
    m: 1.0,
    g: 9.81,
};
const APART_AUG: FourBarAugmented = FourBarAugmented {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 10.0,
    m: 1.0,
    g: 9.81,
};

/// An error, of the kind `want` (by its variant name) where one is given.
fn typed<T: std::fmt::Debug>(what: &str, r: mbd::Result<T>) {
    let want = if what.starts_with("minimal ") {
        Some("SingularPosition")
    } else if what.starts_with("augmented ") {
        Some("InvalidInput")
    } else {
        None
    };
    match r {
        Err(e) => {
            let kind = format!("{e:?}");
            assert!(want.is_none_or(|w| kind.starts_with(w)), "{what}: {kind}");
        }
        Ok(v) => panic!("{what}: Ok({v:?}) for a loop that cannot close"),
    }
}

/// Every `Integrator` from `y` over `[0, 1]`: each must refuse, as `typed` asks of `"{form} {method}"`.
fn typed_by_every_integrator<S: OdeSystem<D>, const D: usize>(
    form: &str,
    p: &S,
    y: Vector<D>,
    events: &[mbd::Event<'_, D>],
) {
    let opts = Options::default;
    let runs = [
        ("dopri5", Dopri5::new(opts()).solve(p, 0.0, y, 1.0, events)),
        ("dop853", Dop853::new(opts()).solve(p, 0.0, y, 1.0, events)),
        ("vern9", Vern9::new(opts()).solve(p, 0.0, y, 1.0, events)),
        ("radau5", Radau5::new(opts()).solve(p, 0.0, y, 1.0, events)),
        ("rk4", Rk4::new(1e-2).solve(p, 0.0, y, 1.0, events)),
        ("gauss", Gauss::new(1e-2).solve(p, 0.0, y, 1.0, events)),
        (
            "generalized-alpha",
            Integrator::solve(&GeneralizedAlpha::new(0.8, 1e-2), p, 0.0, y, 1.0, events),
        ),
    ];
    for (method, r) in runs {
        typed(&format!("{form} {method}"), r);
    }
}

#[test]
fn minimal_form_refuses_a_loop_that_cannot_close_everywhere() {
    let p = APART;
    let y = p.initial_state();
    assert!(y.iter().all(|v| v.is_finite()), "{y}");
    typed("minimal rhs", p.rhs(0.0, &y));
    typed("minimal outputs", p.outputs(0.0, &y));
    let q = y.fixed_rows::<1>(0).into_owned();
    let qd = y.fixed_rows::<1>(1).into_owned();
    typed("minimal acceleration", p.acceleration(0.0, &q, &qd));
    typed("minimal jacobian", p.jacobian(0.0, &y));
    typed_by_every_integrator("minimal", &p, y, &p.events());
    typed(
        "static_equilibrium",
        mbd::analysis::statics::static_equilibrium(&p, 0.0, &q, &Default::default()),
    );
    typed(
        "minimal undamped_modes",
        mbd::analysis::linear::undamped_modes(&p, 0.0, &q),
    );
    typed(
        "minimal linearize",
        mbd::analysis::linear::linearize(&p, 0.0, &y),
    );
    typed("minimal energy", p.energy(0.0, &q, &qd));
    typed("minimal mass_matrix", p.mass_matrix(0.0, &q));
    typed("minimal forces", p.forces(0.0, &q, &qd));
    typed(
        "minimal inverse_dynamics",
        p.inverse_dynamics(0.0, &q, &qd, &Vector::<1>::zeros()),
    );
}

#[test]
fn augmented_form_refuses_a_loop_that_cannot_close_everywhere() {
    let p = APART_AUG;
    let y = p.initial_state();
    let q = y.fixed_rows::<3>(0).into_owned();
    let qd = y.fixed_rows::<3>(3).into_owned();
    let held = [true, false, false];
    typed(
        "assemble",
        mbd::analysis::assembly::assemble(&p, 0.0, &q, &held, &Default::default()),
    );
    typed_by_every_integrator("augmented", &p, y, &p.events());
    typed(
        "augmented generalized-alpha constrained",
        GeneralizedAlpha::new(0.8, 1e-2).solve_constrained::<_, 3, 2, 5, 6>(
            &p,
            0.0,
            q,
            qd,
            1.0,
            &[],
        ),
    );
    typed(
        "augmented ali3",
        mbd::integrate::Ali3::new(1e-2).solve::<_, 3, 2, 6>(&p, 0.0, q, qd, 1.0, &[]),
    );
    typed(
        "static_equilibrium_constrained",
        mbd::analysis::statics::static_equilibrium_constrained::<_, 3, 2, 5>(
            &p,
            0.0,
            &q,
            &Default::default(),
        ),
    );
}

/// The index-3 methods on a start off the constraints: like the ordinary solve, they must
/// refuse it (or at least not move it onto the constraints unseen and return `Ok`).
#[test]
fn index_three_methods_refuse_a_start_off_the_constraints() {
    let p = FourBarAugmented {
        d: 3.5,
        ..APART_AUG
    };
    let y = p.initial_state();
    let q = y.fixed_rows::<3>(0).into_owned();
    let qd = y.fixed_rows::<3>(3).into_owned();
    assert!(
        Dopri5::new(Options::default())
            .solve(&p, 0.0, y, 0.5, &[])
            .is_ok()
    );
    let mut off = q;
    off[2] += 1e-3;
    let mut fast = qd;
    fast[2] += 0.5;
    for (what, q0, qd0) in [("positions", off, qd), ("velocities", q, fast)] {
        let ali3 = mbd::integrate::Ali3::new(1e-2).solve::<_, 3, 2, 6>(&p, 0.0, q0, qd0, 0.5, &[]);
        let alpha = GeneralizedAlpha::new(0.8, 1e-2).solve_constrained::<_, 3, 2, 5, 6>(
            &p,
            0.0,
            q0,
            qd0,
            0.5,
            &[],
        );
        println!("{what}: ali3 {:?}", ali3.as_ref().map(|s| s.y[0]));
        println!("{what}: alpha {:?}", alpha.as_ref().map(|s| s.y[0]));
        assert!(
            matches!(ali3, Err(mbd::Error::InvalidInput { .. })),
            "ali3 {what}"
        );
        assert!(
            matches!(alpha, Err(mbd::Error::InvalidInput { .. })),
            "alpha {what}"
        );
    }
}
