//! Every method at a limit position of a loop reduced to minimal coordinates by closed
//! forms (issue 14: no silent branch switch; a typed error naming the position).
//!
//! Four-bar `(a, b, c, d)`: crank `th` about the origin, coupler `be`, rocker `ga` about
//! `(d, 0)`, all absolute angles; the rocker tip is the two-circle intersection (`+` the
//! elbow above `AD`). The rate equations solved by Cramer's rule give `be' = kb th'`,
//! `ga' = kg th'`; with one coordinate, Lagrange's equation is
//! `J th'' + J'(th) th'^2 / 2 + V'(th) = 0`, `J = sum m |dp/dth|^2 + I (dphi/dth)^2` over the
//! bodies, `V` gravity's potential; `J'` by a central difference of the analytic `J`.

use mbd::integrate::{Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4};
use mbd::prelude::*;
use std::f64::consts::PI;

mod support;

use support::Bar4;

/// A four-bar that is not Grashof (`a = 2`, `b = 2.6`, `c = 1.5`, `d = 1`: `s + l = 3.6 >
/// p + q = 3.5`): the input link `th` cannot turn round. Its limits are where coupler and
/// rocker fold, `|A - D| = b - c`: `cos(th_lim) = (a^2 + d^2 - (b - c)^2) / (2 a d)`. Free of
/// gravity, started at `th = pi` with `th' = -2`, it reaches `th_lim` with `th' = 0` at the
/// time `int_{th_lim}^{pi} sqrt(J / (2 E)) dth` (energy conserved), computed with
/// `th = th_lim + u^2` by the composite midpoint rule. There the two assembly branches meet:
/// the physical motion continues on the other branch; the minimal form cannot follow.
#[derive(Debug, Clone, Mechanism)]
#[coords(th, be, ga)]
#[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
#[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
#[rigid(crank, mass = m, inertia = m * a * a / 12.0,
        at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
#[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
        at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
#[rigid(rocker, mass = m, inertia = m * c * c / 12.0,
        at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
#[init(th = 3.141592653589793, be = 0.5235983011156989, ga = 2.0931125762773357,
       der(th) = -2.0)]
pub struct TripleRocker {
    #[default(2.0)]
    pub a: f64,
    #[default(2.6)]
    pub b: f64,
    #[default(1.5)]
    pub c: f64,
    #[default(1.0)]
    pub d: f64,
    #[default(1.0)]
    pub m: f64,
}

/// The same linkage under gravity, released from rest at `th = 4.2`: the crank swings down
/// and gravity turns it back at `th_1` (`V(th_1) = V(4.2)`, about 5.52), far from both limit
/// positions (`th_lim = 0.32` and `2 pi - th_lim = 5.96`): an ordinary turning point.
#[derive(Debug, Clone, Mechanism)]
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
#[init(th = 4.2, be = 1.302384799781749, ga = 2.6073754263662714)]
pub struct SwingingRocker {
    #[default(2.0)]
    pub a: f64,
    #[default(2.6)]
    pub b: f64,
    #[default(1.5)]
    pub c: f64,
    #[default(1.0)]
    pub d: f64,
    #[default(1.0)]
    pub m: f64,
    #[default(9.81)]
    pub g: f64,
}

const ROCKER: Bar4 = Bar4 {
    a: 2.0,
    b: 2.6,
    c: 1.5,
    d: 1.0,
    m: 1.0,
    g: 0.0,
};
const TRIPLE: TripleRocker = TripleRocker {
    a: 2.0,
    b: 2.6,
    c: 1.5,
    d: 1.0,
    m: 1.0,
};

fn limit_angle() -> f64 {
    let (a, b, c, d) = (ROCKER.a, ROCKER.b, ROCKER.c, ROCKER.d);
    ((a * a + d * d - (b - c) * (b - c)) / (2.0 * a * d)).acos()
}

/// The time to reach the limit from `th = pi`, `th' = -2`.
fn time_to_limit() -> f64 {
    let lim = limit_angle();
    let energy = 0.5 * ROCKER.inertia_and_gravity(PI, 1.0).0 * 4.0;
    let (u1, n) = ((PI - lim).sqrt(), 200_000);
    let du = u1 / n as f64;
    (0..n)
        .map(|i| {
            let u = (i as f64 + 0.5) * du;
            let j = ROCKER.inertia_and_gravity(lim + u * u, 1.0).0;
            (j / (2.0 * energy)).sqrt() * 2.0 * u * du
        })
        .sum()
}

/// A `SingularPosition` within `t_tol` of the limit's time, naming `th` at or just past it.
fn assert_stops_at_the_limit<T>(run: Result<T, Error>, method: &str, t_tol: f64) {
    let th_tol = t_tol / 3.0;
    let (lim, t_lim) = (limit_angle(), time_to_limit());
    match run {
        Err(Error::SingularPosition { t, detail }) => {
            assert!((t - t_lim).abs() < t_tol, "{method}: t = {t}, want {t_lim}");
            let th: f64 = detail
                .split("th = ")
                .nth(1)
                .and_then(|s| s.split(':').next())
                .and_then(|s| s.trim().parse().ok())
                .unwrap_or_else(|| panic!("{method}: {detail}"));
            assert!(
                th <= lim + 1e-9 && th > lim - th_tol,
                "{method}: th = {th}, want {lim}"
            );
        }
        Err(other) => panic!("{method}: {other}"),
        Ok(_) => panic!("{method}: Ok past the limit position at t = {t_lim}"),
    }
}

/// The time a step of `h` stops within: the instant extrapolated from a window of two steps
/// lies within two steps of the limit's (and 1e-2, the adaptive methods' bound at 1e-6).
fn within(h: f64) -> f64 {
    (2.0 * h).min(1e-2)
}

#[test]
fn rk4_stops_at_the_limit_position_at_every_step_size() {
    assert_eq!(TripleRocker::COORDINATES, ["th"]);
    let y0 = TRIPLE.initial_state();
    // 2e-2, 2e-3, 1e-3: stages that never land outside the domain (the run used to reflect
    // on the same branch and return Ok); 5e-3, 1e-4: a stage lands outside.
    for h in [2e-2, 2e-3, 1e-3, 5e-3, 1e-4] {
        let rk4 = Rk4::new(h).solve(&TRIPLE, 0.0, y0, 5.0, &[]);
        assert_stops_at_the_limit(rk4, &format!("RK4 h = {h}"), within(h));
    }
}

#[test]
fn generalized_alpha_stops_at_the_limit_position_naming_it() {
    let y0 = TRIPLE.initial_state();
    let (q0, qd0) = (Vector::<1>::new(y0[0]), Vector::<1>::new(y0[1]));
    for h in [1e-2, 2e-3, 1e-3] {
        let alpha: Result<Solution<2>, Error> =
            GeneralizedAlpha::new(0.9, h).solve(&TRIPLE, 0.0, q0, qd0, 5.0, &[]);
        assert_stops_at_the_limit(alpha, &format!("generalized-alpha h = {h}"), within(h));
        // The same method driven through the first-order system.
        let first_order =
            Integrator::solve(&GeneralizedAlpha::new(0.9, h), &TRIPLE, 0.0, y0, 5.0, &[]);
        assert_stops_at_the_limit(
            first_order,
            &format!("generalized-alpha (OdeSystem) h = {h}"),
            within(h),
        );
    }
}

/// The implicit Gauss method (order 4): its Newton iteration fails on the steps next to the
/// limit (it ended with `NewtonFailed`); the chart watch names the position instead, as for
/// RK4 and generalized-alpha, whether a step passes the limit or Newton fails before it.
#[test]
fn gauss_stops_at_the_limit_position_naming_it() {
    let y0 = TRIPLE.initial_state();
    for h in [2e-2, 1e-2, 2e-3, 1e-3] {
        let gauss = Gauss::new(h).solve(&TRIPLE, 0.0, y0, 5.0, &[]);
        assert_stops_at_the_limit(gauss, &format!("Gauss h = {h}"), within(h));
    }
}

/// The reference: Lagrange's equation in the crank angle from [`Bar4`], by a hand-written
/// RK4 at `h = 1e-4` (its error ~1e-13, below the central difference's ~1e-10).
fn swing_reference(t1: f64) -> (f64, f64) {
    let bar = Bar4 { g: 9.81, ..ROCKER };
    let f = |y: [f64; 2]| [y[1], bar.crank_acceleration(y[0], y[1], 1.0)];
    let n = (t1 / 1e-4).round() as usize;
    let h = t1 / n as f64;
    let mut y = [4.2, 0.0];
    for _ in 0..n {
        let k1 = f(y);
        let k2 = f([y[0] + h / 2.0 * k1[0], y[1] + h / 2.0 * k1[1]]);
        let k3 = f([y[0] + h / 2.0 * k2[0], y[1] + h / 2.0 * k2[1]]);
        let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
        for i in 0..2 {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    (y[0], y[1])
}

/// The far turning point `th_1 > 3 pi / 2` with `V(th_1) = V(4.2)`, by bisection.
fn swing_turning_point() -> f64 {
    let bar = Bar4 { g: 9.81, ..ROCKER };
    let v0 = bar.potential(4.2, 1.0);
    let (mut lo, mut hi) = (1.5 * PI, 2.0 * PI - limit_angle() - 1e-9);
    assert!(
        bar.potential(hi, 1.0) > v0,
        "the swing would reach the limit"
    );
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if bar.potential(mid, 1.0) > v0 {
            hi = mid
        } else {
            lo = mid
        }
    }
    lo
}

#[test]
fn a_physical_turning_point_is_no_limit_position() {
    let sys = SwingingRocker {
        a: 2.0,
        b: 2.6,
        c: 1.5,
        d: 1.0,
        m: 1.0,
        g: 9.81,
    };
    let y0 = sys.initial_state();
    let (th1, t1) = (swing_turning_point(), 4.0);
    // Far from the limits: the watch must not mistake gravity's turn for a reflection.
    assert!(th1 < 2.0 * PI - limit_angle() - 0.4, "{th1}");
    let (th_ref, thd_ref) = swing_reference(t1);
    // (h, tolerance): RK4's global error ~ C h^4.
    for (h, tol) in [(2e-2, 1e-4), (2e-3, 1e-7), (1e-3, 1e-8)] {
        let sol = Rk4::new(h)
            .solve(&sys, 0.0, y0, t1, &[])
            .unwrap_or_else(|e| panic!("RK4 h = {h}: {e}"));
        let y = *sol.y.last().unwrap();
        assert!(
            (y[0] - th_ref).abs() < tol && (y[1] - thd_ref).abs() < 10.0 * tol,
            "RK4 h = {h}: {y:?} vs ({th_ref}, {thd_ref})"
        );
        let th_max = sol.y.iter().map(|y| y[0]).fold(f64::MIN, f64::max);
        assert!(
            (th_max - th1).abs() < 1e-2,
            "RK4 h = {h}: turned at {th_max}, want {th1}"
        );
    }
    let (q0, qd0) = (Vector::<1>::new(y0[0]), Vector::<1>::new(y0[1]));
    let sol: Solution<2> = GeneralizedAlpha::new(0.9, 1e-3)
        .solve(&sys, 0.0, q0, qd0, t1, &[])
        .unwrap();
    let th_max = sol.y.iter().map(|y| y[0]).fold(f64::MIN, f64::max);
    assert!(
        (th_max - th1).abs() < 1e-2,
        "generalized-alpha: turned at {th_max}, want {th1}"
    );
}

/// The adaptive methods stop at the limit because a stage lands past it.
#[test]
fn non_grashof_four_bar_stops_at_its_limit_position_with_a_typed_error() {
    assert_eq!(TripleRocker::COORDINATES, ["th"]);
    let (be, ga) = ROCKER.close(PI, 1.0);
    assert!((be - 0.5235983011156989).abs() < 1e-12 && (ga - 2.0931125762773357).abs() < 1e-12);
    let y0 = TRIPLE.initial_state();
    for tol in [1e-6, 1e-10] {
        let opts = Options {
            rtol: tol,
            atol: tol,
            ..Options::default()
        };
        let t_tol = if tol > 1e-8 { 1e-2 } else { 1e-4 };
        let dopri = Dopri5::new(opts.clone()).solve(&TRIPLE, 0.0, y0, 5.0, &[]);
        assert_stops_at_the_limit(dopri, "DOPRI5", t_tol);
        let dop853 = Dop853::new(opts.clone()).solve(&TRIPLE, 0.0, y0, 5.0, &[]);
        assert_stops_at_the_limit(dop853, "DOP853", t_tol);
        let radau = Radau5::new(opts).solve(&TRIPLE, 0.0, y0, 5.0, &[]);
        assert_stops_at_the_limit(radau, "Radau5", t_tol);
    }
    for h in [1e-4, 5e-3] {
        let rk4 = Rk4::new(h).solve(&TRIPLE, 0.0, y0, 5.0, &[]);
        assert_stops_at_the_limit(rk4, "RK4", 1e-2);
    }
}
