//! A closed loop in minimal coordinates inside and outside its closure's domain: every
//! public function on the model either equals the hand formula (inside) or returns the
//! typed error naming the singular position (outside), never a NaN.
//!
//! The model: a slider-crank reduced to its crank angle `th`. Crank `r = 1` with a point
//! mass `m_a` at its tip `A = r (cos th, sin th)`, a massless rod `l = 0.5` from `A` to the
//! piston `B = (x, 0)` (mass `m_p`), the rod at angle `-be`, a spring `k` on the piston
//! about `x0`, gravity `g` along `-y`.
//!
//! Hand derivation (independent of the derive). Closure: `l sin be = r sin th`, so with
//! `u = r sin th / l` the rod angle is `be = asin u` and exists only for `|u| < 1`: the
//! domain is `|sin th| < l / r = 1/2`, i.e. `|th| < pi/6` (or `|th - pi| < pi/6`); at
//! `|u| = 1` the rod is perpendicular to the slide (a limit position), beyond it the loop
//! cannot close. With `s, c = sin th, cos th` and `kk = cos be = sqrt(1 - u^2)`:
//!
//! - `x = r c + l kk`, `x_th = -r s - r^2 s c / (l kk)`,
//!   `x_thth = -r c - (r^2 / l) ((c^2 - s^2) / kk + r^2 s^2 c^2 / (l^2 kk^3))`;
//! - `T = (m_a r^2 + m_p x_th^2) th'^2 / 2`, so `M = m_a r^2 + m_p x_th^2`;
//! - `V = m_a g r s + k (x - x0)^2 / 2`;
//! - Lagrange: `M th'' = f` with `f = -dV/dth - (dM/dth) th'^2 / 2`
//!   `= -m_a g r c - k (x - x0) x_th - m_p x_th x_thth th'^2`;
//! - `E = T + V`; inverse dynamics `M th'' - f`.
//!
//! With `g = 0` and `x0 = x(th*)` the static equilibrium is `th*` (the spring at rest), and
//! there `K = d^2 V / dth^2 = k x_th^2`, so the linearisation is
//! `A = [[0, 1], [-k x_th^2 / M, 0]]` and the undamped mode `omega^2 = k x_th^2 / M`.

use approx::assert_relative_eq;
use mbd::analysis::{linear, statics};
use mbd::prelude::*;

#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(th, be, x)]
#[constraint(x == r * cos(th) + l * cos(be))]
#[constraint(l * sin(be) == r * sin(th))]
#[particle(tip, mass = m_a, at = [r * cos(th), r * sin(th)])]
#[particle(piston, mass = m_p, at = [x, 0.0])]
#[potential(0.5 * k * (x - x0) * (x - x0))]
#[output(piston = x, rod = be)]
#[event(piston_at_rest_length = x - x0)]
#[init(th = 0.3, der(th) = 2.0)]
pub struct Crank {
    pub r: f64,
    pub l: f64,
    pub m_a: f64,
    pub m_p: f64,
    pub k: f64,
    pub x0: f64,
    pub g: f64,
}

const CRANK: Crank = Crank {
    r: 1.0,
    l: 0.5,
    m_a: 1.3,
    m_p: 0.7,
    k: 40.0,
    x0: 1.2,
    g: 9.81,
};

/// `(x, x_th, x_thth)` by the hand derivation above.
fn piston(p: &Crank, th: f64) -> (f64, f64, f64) {
    let (r, l) = (p.r, p.l);
    let (s, c) = th.sin_cos();
    let u = r * s / l;
    let kk = (1.0 - u * u).sqrt();
    let x = r * c + l * kk;
    let x_th = -r * s - r * r * s * c / (l * kk);
    let x_thth = -r * c
        - (r * r / l) * ((c * c - s * s) / kk + r * r * s * s * c * c / (l * l * kk.powi(3)));
    (x, x_th, x_thth)
}

/// `(M, f, E)` by hand.
fn hand(p: &Crank, th: f64, thd: f64) -> (f64, f64, f64) {
    let (x, x_th, x_thth) = piston(p, th);
    let r = p.r;
    let mass = p.m_a * r * r + p.m_p * x_th * x_th;
    let f =
        -p.m_a * p.g * r * th.cos() - p.k * (x - p.x0) * x_th - p.m_p * x_th * x_thth * thd * thd;
    let e = 0.5 * mass * thd * thd + p.m_a * p.g * r * th.sin() + 0.5 * p.k * (x - p.x0).powi(2);
    (mass, f, e)
}

/// The singular-position error at `t`, naming the rod's closed form and the crank angle.
fn singular<T: std::fmt::Debug>(what: &str, t: f64, th: f64, r: mbd::Result<T>) {
    match r {
        Err(Error::SingularPosition { t: at, detail }) => {
            assert_eq!(at, t, "{what}: {detail}");
            assert!(detail.contains("`be`"), "{what}: {detail}");
            assert!(detail.contains(&format!("th = {th}")), "{what}: {detail}");
        }
        other => panic!("{what}: {other:?}, not the singular position at th = {th}"),
    }
}

/// The hand derivation's derivatives of `x` agree with central differences of its `x`.
#[test]
fn hand_derivatives_agree_with_differences() {
    let p = CRANK;
    for th in [-0.4, 0.1, 0.45, std::f64::consts::PI - 0.3] {
        let h = 1e-5;
        let ((xp, xp_th, _), (xm, xm_th, _)) = (piston(&p, th + h), piston(&p, th - h));
        let (_, x_th, x_thth) = piston(&p, th);
        assert_relative_eq!((xp - xm) / (2.0 * h), x_th, max_relative = 1e-8);
        assert_relative_eq!((xp_th - xm_th) / (2.0 * h), x_thth, max_relative = 1e-7);
    }
}

#[test]
fn inside_the_domain_every_function_is_the_hand_formula() {
    let p = CRANK;
    assert_eq!(Crank::DOF, 1);
    for (t, th, thd) in [(0.0, 0.3, 2.0), (0.7, -0.45, -1.5), (1.5, 3.0, 0.4)] {
        let (q, qd) = (Vector::<1>::new(th), Vector::<1>::new(thd));
        let (mass, f, e) = hand(&p, th, thd);
        assert_relative_eq!(p.mass_matrix(t, &q).unwrap()[0], mass, max_relative = 1e-13);
        assert_relative_eq!(p.forces(t, &q, &qd).unwrap()[0], f, max_relative = 1e-12);
        assert_relative_eq!(p.energy(t, &q, &qd).unwrap(), e, max_relative = 1e-13);
        let qdd = p.acceleration(t, &q, &qd).unwrap()[0];
        assert_relative_eq!(qdd, f / mass, max_relative = 1e-12);
        let y = Vector::<2>::new(th, thd);
        assert_relative_eq!(p.rhs(t, &y).unwrap()[1], f / mass, max_relative = 1e-12);
        let probe = Vector::<1>::new(0.8);
        assert_relative_eq!(
            p.inverse_dynamics(t, &q, &qd, &probe).unwrap()[0],
            mass * 0.8 - f,
            max_relative = 1e-12
        );
        let (x, ..) = piston(&p, th);
        let out = p.outputs(t, &y).unwrap();
        assert_relative_eq!(out.piston, x, max_relative = 1e-14);
        assert_relative_eq!(out.rod, (p.r * th.sin() / p.l).asin(), max_relative = 1e-14);
        assert_relative_eq!(
            p.event_piston_at_rest_length(t, &y).unwrap(),
            x - p.x0,
            epsilon = 1e-14
        );
        let margin = 1.0 - (p.r * th.sin() / p.l).abs();
        assert_relative_eq!(
            Mechanism::chart_margin(&p, t, &q).unwrap(),
            margin,
            max_relative = 1e-14
        );
        // The exact Jacobian's velocity column: d qdd / d th' = -2 m_p x_th x_thth th' / M.
        let (_, x_th, x_thth) = piston(&p, th);
        let jac = p.jacobian(t, &y).unwrap();
        assert_relative_eq!(jac[(0, 1)], 1.0);
        assert_relative_eq!(
            jac[(1, 1)],
            -2.0 * p.m_p * x_th * x_thth * thd / mass,
            max_relative = 1e-11
        );
    }
}

#[test]
fn outside_the_domain_every_function_names_the_singular_position() {
    let p = CRANK;
    // sin 1 = 0.84 > 1/2 and sin(pi/6 + 1e-9) just above it: the rod cannot reach the slide.
    for (t, th) in [
        (0.0, 1.0),
        (2.5, std::f64::consts::FRAC_PI_6 + 1e-9),
        (1.0, -2.0),
    ] {
        let (q, qd) = (Vector::<1>::new(th), Vector::<1>::new(1.0));
        let y = Vector::<2>::new(th, 1.0);
        singular("mass_matrix", t, th, p.mass_matrix(t, &q));
        singular("forces", t, th, p.forces(t, &q, &qd));
        singular("energy", t, th, p.energy(t, &q, &qd));
        singular(
            "inverse_dynamics",
            t,
            th,
            p.inverse_dynamics(t, &q, &qd, &qd),
        );
        singular("acceleration", t, th, p.acceleration(t, &q, &qd));
        singular("rhs", t, th, p.rhs(t, &y));
        singular("jacobian", t, th, p.jacobian(t, &y));
        singular("outputs", t, th, p.outputs(t, &y));
        singular("event", t, th, p.event_piston_at_rest_length(t, &y));
        singular("linearize", t, th, linear::linearize(&p, t, &y));
        singular("undamped_modes", t, th, linear::undamped_modes(&p, t, &q));
        singular(
            "static_equilibrium",
            t,
            th,
            statics::static_equilibrium(&p, t, &q, &Default::default()),
        );
        assert!(Mechanism::chart_margin(&p, t, &q).unwrap() < 0.0);
    }
}

/// With `g = 0` and the spring at rest at `th* = 0.2`: statics finds `th*`, the
/// linearisation and the undamped mode there are the hand formulas.
#[test]
fn statics_and_linearisation_inside_the_domain() {
    let star = 0.2;
    let p = Crank {
        g: 0.0,
        x0: piston(&CRANK, star).0,
        ..CRANK
    };
    let q =
        statics::static_equilibrium(&p, 0.0, &Vector::<1>::new(0.35), &Default::default()).unwrap();
    assert_relative_eq!(q[0], star, epsilon = 1e-10);
    let q = Vector::<1>::new(star);
    let (mass, _, _) = hand(&p, star, 0.0);
    let (_, x_th, _) = piston(&p, star);
    let stiffness = p.k * x_th * x_th;
    let a = linear::linearize(&p, 0.0, &Vector::<2>::new(star, 0.0)).unwrap();
    assert_relative_eq!(a[(0, 1)], 1.0);
    assert_relative_eq!(a[(1, 0)], -stiffness / mass, max_relative = 1e-10);
    assert!(a[(1, 1)].abs() < 1e-14 && a[(0, 0)] == 0.0);
    let modes = linear::undamped_modes(&p, 0.0, &q).unwrap();
    assert_eq!(modes.len(), 1);
    assert_relative_eq!(
        modes[0].omega_squared,
        stiffness / mass,
        max_relative = 1e-10
    );
}

/// A Newton step out of the domain is halved back into it. From `th = 0.12` (near the
/// maximum of `f`, where `f'` nearly vanishes) the full step of the hand `f` lands at
/// `th = 1.53`, where the loop cannot close; statics still ends at one of the hand
/// equilibria `th = 0, +-0.2` (`x = x0` or `x_th = 0`) or `pi`.
#[test]
fn statics_halves_a_step_that_leaves_the_domain() {
    let p = Crank {
        g: 0.0,
        x0: piston(&CRANK, 0.2).0,
        ..CRANK
    };
    let f = |th: f64| hand(&p, th, 0.0).1;
    let (guess, h) = (0.12, 1e-6);
    let newton = guess - f(guess) * 2.0 * h / (f(guess + h) - f(guess - h));
    assert!(
        newton.sin().abs() > 0.5,
        "the full step stays inside: {newton}"
    );
    let q = statics::static_equilibrium(&p, 0.0, &Vector::<1>::new(guess), &Default::default())
        .unwrap();
    let equilibria = [-0.2, 0.0, 0.2, std::f64::consts::PI];
    assert!(
        equilibria.iter().any(|e| (q[0] - e).abs() < 1e-10),
        "{q} is none of {equilibria:?}"
    );
}

/// The same loop driven through its limit position in the augmented form (`th = w t`, the
/// rod and the piston solved from the constraints): the kinematic sweep follows the hand
/// closure up to the limit `th = pi/6` and stops there with a typed error naming the
/// configuration (the first sample past it, `t = 0.55`, has `sin 0.55 > 1/2`: the loop cannot
/// close), never an `Ok` with NaN; assembly at `th = 1` refuses too.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(augmented)]
#[coords(be, x)]
#[drive(th = w * t)]
#[constraint(x == r * cos(th) + l * cos(be))]
#[constraint(l * sin(be) == r * sin(th))]
#[particle(tip, mass = 1.0, at = [r * cos(th), r * sin(th)])]
#[particle(piston, mass = 1.0, at = [x, 0.0])]
pub struct DrivenCrank {
    pub r: f64,
    pub l: f64,
    pub w: f64,
}

#[test]
fn a_sweep_through_the_limit_position_stops_with_a_typed_error() {
    use mbd::analysis::{assembly, kinematics};
    let p = DrivenCrank {
        r: 1.0,
        l: 0.5,
        w: 1.0,
    };
    let guess = Vector::<2>::new(0.0, 1.5);
    let inside: Vec<f64> = (0..=10).map(|i| 0.05 * i as f64).collect();
    let states = kinematics::kinematic_sweep(&p, &inside, &guess, &Default::default()).unwrap();
    for s in &states {
        let th = s.t;
        assert_relative_eq!(s.q[0], (th.sin() / 0.5).asin(), max_relative = 1e-10);
        assert_relative_eq!(s.q[1], piston(&CRANK, th).0, max_relative = 1e-10);
    }
    let past: Vec<f64> = (0..=20).map(|i| 0.05 * i as f64).collect();
    // The sweep marches halved sub-steps from the last sample inside (0.5) towards the first
    // past it (0.55), so it stops at the limit `sin(w t) = l / r`, `t = pi / 6`, to within its
    // halvings, and names the configuration there.
    match kinematics::kinematic_sweep(&p, &past, &guess, &Default::default()) {
        Err(
            Error::AssemblyFailed { t, detail, .. }
            | Error::SingularConstraintJacobian { t, detail },
        ) => {
            assert!((t - std::f64::consts::FRAC_PI_6).abs() < 1e-6, "{t}");
            assert!(detail.starts_with("at q = ["), "{detail}");
        }
        other => panic!("{other:?}"),
    }
    match assembly::assemble(&p, 1.0, &guess, &[false; 2], &Default::default()) {
        Err(Error::AssemblyFailed { t, .. } | Error::SingularConstraintJacobian { t, .. }) => {
            assert_eq!(t, 1.0)
        }
        other => panic!("{other:?}"),
    }
}
