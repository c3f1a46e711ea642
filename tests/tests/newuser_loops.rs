//! Closed loops as a new user writes them, each against a reference derived here.
//!
//! Four-bar `(a, b, c, d)`: crank `th` about the origin, coupler `be`, rocker `ga` about
//! `(d, 0)`, all absolute angles. Position: the crank tip `A = a (cos th, sin th)` and the
//! rocker tip `C` at distances `b` from `A` and `c` from `D = (d, 0)` (the two-circle
//! intersection; `+` the elbow above `AD`). Velocities: the loop's rate equations
//! `-b sin(be) be' + c sin(ga) ga' = a sin(th) th'`, `b cos(be) be' - c cos(ga) ga' = -a cos(th) th'`
//! solved by Cramer's rule give `be' = kb th'`, `ga' = kg th'`. With one coordinate,
//! Lagrange's equation is `J th'' + J'(th) th'^2 / 2 + V'(th) = Q`, `J = sum m |dp/dth|^2 + I (dphi/dth)^2`
//! over the bodies (mass centres `p`, angles `phi`), `V` gravity's potential; `J'` by a
//! central difference of the analytic `J` (step 1e-5: error ~1e-10 relative).

use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;
use std::f64::consts::PI;

/// A crank-rocker written with coordinates and loop equations (reduced by the derive to the
/// crank angle, on the branch of the `init`).
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
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
#[init(th = 0.5, be = 0.7260165921021776, ga = 1.7229599395818342)]
#[output(rocker_rate = der(ga), rocker_angle = ga)]
#[event(rocker_at = ga - 1.8, rising, terminal)]
pub struct CoordFourBar {
    #[default(1.0)]
    pub a: f64,
    #[default(3.0)]
    pub b: f64,
    #[default(2.5)]
    pub c: f64,
    #[default(3.5)]
    pub d: f64,
    #[default(1.0)]
    pub m: f64,
    #[default(9.81)]
    pub g: f64,
}

/// The same crank-rocker as a joint tree: crank and rocker on the ground, the coupler on
/// the crank (relative angle `ph`), the loop closed by a pin (kept in the augmented form).
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[body(crank, joint = revolute(th), com = [a / 2.0, 0.0], mass = m, inertia = m * a * a / 12.0)]
#[body(coupler, parent = crank, joint = revolute(ph), at = [a, 0.0], com = [b / 2.0, 0.0],
       mass = m, inertia = m * b * b / 12.0)]
#[body(rocker, joint = revolute(ps), at = [d, 0.0], com = [c / 2.0, 0.0], mass = m,
       inertia = m * c * c / 12.0)]
#[close(pin, a = coupler, at_a = [b, 0.0], b = rocker, at_b = [c, 0.0])]
pub struct TreeFourBar {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub m: f64,
    pub g: f64,
}

mod support;

use support::Bar4;

const BAR: Bar4 = Bar4 {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 3.5,
    m: 1.0,
    g: 9.81,
};

#[test]
fn four_bar_written_two_ways_matches_lagrange_in_the_crank_angle() {
    let k = CoordFourBar {
        a: 1.0,
        b: 3.0,
        c: 2.5,
        d: 3.5,
        m: 1.0,
        g: 9.81,
    };
    let t = TreeFourBar {
        a: 1.0,
        b: 3.0,
        c: 2.5,
        d: 3.5,
        m: 1.0,
        g: 9.81,
    };
    assert_eq!(CoordFourBar::COORDINATES, ["th"]);
    // The init's elbow is the upper one.
    let (be0, ga0) = BAR.close(0.5, 1.0);
    assert!((be0 - 0.7260165921021776).abs() < 1e-12 && (ga0 - 1.7229599395818342).abs() < 1e-12);
    for (th, thd) in [(0.5, 1.3), (2.0, -0.7), (-2.5, 4.0), (PI, 0.0)] {
        let want = BAR.crank_acceleration(th, thd, 1.0);
        let scale = want.abs().max(1.0);
        let minimal = k
            .acceleration(0.0, &Vector::<1>::new(th), &Vector::<1>::new(thd))
            .unwrap()[0];
        assert!(
            (minimal - want).abs() < 1e-8 * scale,
            "th = {th}: {minimal} vs {want}"
        );
        // The tree: relative coupler angle, assembled on the same elbow.
        let (be, ga) = BAR.close(th, 1.0);
        let (kb, kg) = BAR.rates(th, be, ga);
        let q = Vector::<3>::new(th, be - th, ga);
        let qd = Vector::<3>::new(thd, (kb - 1.0) * thd, kg * thd);
        assert!(Constrained::<3, 2>::phi(&t, 0.0, &q).amax() < 1e-14);
        let tree = t.acceleration(0.0, &q, &qd).unwrap()[0];
        assert!(
            (tree - want).abs() < 1e-8 * scale,
            "th = {th}: {tree} vs {want}"
        );
    }
}

/// An offset slider-crank (crank `r`, rod `l`, the slider's line `e` above the crank's
/// pivot) turned from rest by a constant torque `tau`: it passes its dead centres (crank and
/// rod in line) as ordinary positions, and its kinetic energy equals the work done,
/// `T(th, th') = tau (th - th0)`. `T` by hand: `sin(be) = (r sin th - e) / l`,
/// `be' = r cos(th) th' / (l cos be)`, `x' = -r sin(th) th' - l sin(be) be'`; the rod's
/// mass centre `(r cos th + l/2 cos be, r sin th - l/2 sin be)`, its angle `-be`.
#[derive(Debug, Clone, Mechanism)]
#[coords(th, be, x)]
#[constraint(x == r * cos(th) + l * cos(be))]
#[constraint(r * sin(th) - l * sin(be) == e)]
#[rigid(crank, mass = mc, inertia = jc, at = [0.0, 0.0], angle = th)]
#[rigid(rod, mass = mr, inertia = mr * l * l / 12.0,
        at = [r * cos(th) + l / 2.0 * cos(be), r * sin(th) - l / 2.0 * sin(be)], angle = -be)]
#[particle(piston, mass = mp, at = [x, e])]
#[torque(motor, on = crank, value = tau)]
pub struct OffsetSliderCrank {
    pub r: f64,
    pub l: f64,
    pub e: f64,
    pub mc: f64,
    pub jc: f64,
    pub mr: f64,
    pub mp: f64,
    pub tau: f64,
}

fn slider_crank_energy(p: &OffsetSliderCrank, th: f64, thd: f64) -> f64 {
    let be = ((p.r * th.sin() - p.e) / p.l).asin();
    let bed = p.r * th.cos() * thd / (p.l * be.cos());
    let xd = -p.r * th.sin() * thd - p.l * be.sin() * bed;
    let vx = -p.r * th.sin() * thd - p.l / 2.0 * be.sin() * bed;
    let vy = p.r * th.cos() * thd - p.l / 2.0 * be.cos() * bed;
    0.5 * p.jc * thd * thd
        + 0.5 * p.mr * (vx * vx + vy * vy)
        + 0.5 * p.mr * p.l * p.l / 12.0 * bed * bed
        + 0.5 * p.mp * xd * xd
}

#[test]
fn offset_slider_crank_under_torque_passes_dead_centre_with_the_work_done() {
    let p = OffsetSliderCrank {
        r: 0.1,
        l: 0.4,
        e: 0.05,
        mc: 1.0,
        jc: 0.01,
        mr: 0.5,
        mp: 0.3,
        tau: 0.5,
    };
    assert_eq!(OffsetSliderCrank::COORDINATES, ["th"]);
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let sol = Dopri5::new(opts)
        .solve(&p, 0.0, Vector::<2>::zeros(), 3.0, &[])
        .unwrap();
    // Many turns, so many dead centres passed, always turning forward.
    let y = *sol.y.last().unwrap();
    assert!(y[0] > 20.0 * 2.0 * PI, "{y:?}");
    assert!(sol.y.iter().skip(1).all(|y| y[1] > 0.0));
    let (energy, work) = (slider_crank_energy(&p, y[0], y[1]), p.tau * y[0]);
    assert!((energy - work).abs() < 1e-8 * work, "{energy} vs {work}");
}

/// The crank-rocker driven at a constant rate `w`: no free coordinate is left (the rocker
/// follows the closure), so the motion is kinematic: `ga(t)` is the closed form at `th = w t`.
/// The drive's effort `reaction(th)` supplies the power that changes the kinetic energy
/// (no gravity): `tau w = dT/dt`, `T = J_d(th) w^2 / 2` with `J_d` the inertia of coupler
/// and rocker alone, so `tau = J_d'(th) w^2 / 2`.
#[derive(Debug, Clone, Mechanism)]
#[drive(th = w * t)]
#[coords(be, ga)]
#[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
#[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
#[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
        at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
#[rigid(rocker, mass = m, inertia = m * c * c / 12.0,
        at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
#[output(motor = reaction(th))]
pub struct DrivenFourBar {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub m: f64,
    pub w: f64,
}

#[test]
fn driven_four_bar_follows_the_closure_and_its_drive_supplies_the_power() {
    let p = DrivenFourBar {
        a: 1.0,
        b: 3.0,
        c: 2.5,
        d: 3.5,
        m: 1.0,
        w: 2.0,
    };
    // The crank's own inertia is not in this model: J of the full four-bar minus the crank's.
    let crank = BAR.m * BAR.a * BAR.a / 4.0 + BAR.m * BAR.a * BAR.a / 12.0;
    let driven_inertia = |th: f64| BAR.inertia_and_gravity(th, 1.0).0 - crank;
    let state = |th: f64| {
        let (be, ga) = BAR.close(th, 1.0);
        let (kb, kg) = BAR.rates(th, be, ga);
        Vector::<4>::new(be, ga, kb * p.w, kg * p.w)
    };
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let sol = Dopri5::new(opts)
        .solve(&p, 0.0, state(0.0), 4.0, &[])
        .unwrap();
    for (&t, y) in sol.t.iter().zip(&sol.y).step_by(7) {
        let want = state(p.w * t);
        let wrap = |x: f64| (x + PI).rem_euclid(2.0 * PI) - PI;
        assert!(
            wrap(y[0] - want[0]).abs() < 1e-8 && wrap(y[1] - want[1]).abs() < 1e-8,
            "t = {t}"
        );
        let h = 1e-5;
        let th = p.w * t;
        let dj = (driven_inertia(th + h) - driven_inertia(th - h)) / (2.0 * h);
        let tau = 0.5 * dj * p.w * p.w;
        let motor = p.outputs(t, y).unwrap().motor;
        assert!(
            (motor - tau).abs() < 1e-6 * tau.abs().max(1.0),
            "t = {t}: {motor} vs {tau}"
        );
    }
}

/// A parallelogram four-bar (crank and rocker `a`, coupler and ground `b`) hanging down:
/// the coupler translates, so `T = (2 m a^2 / 3 + mc a^2) th'^2 / 2` and
/// `V = -(m a + mc a) g cos(th + pi/2)`: `w^2 = g (m + mc) / (a (2 m / 3 + mc))` exactly,
/// and `th'' = -w^2 sin(th + pi/2)` at any angle.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(th, be, ga)]
#[constraint(a * cos(th) + b * cos(be) == b + a * cos(ga))]
#[constraint(a * sin(th) + b * sin(be) == a * sin(ga))]
#[rigid(crank, mass = m, inertia = m * a * a / 12.0,
        at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
#[rigid(coupler, mass = mc, inertia = mc * b * b / 12.0,
        at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
#[rigid(rocker, mass = m, inertia = m * a * a / 12.0,
        at = [b + a / 2.0 * cos(ga), a / 2.0 * sin(ga)], angle = ga)]
#[init(th = -1.5707963267948966, be = 0.0, ga = -1.5707963267948966)]
pub struct Parallelogram {
    #[default(1.0)]
    pub a: f64,
    #[default(2.0)]
    pub b: f64,
    #[default(1.0)]
    pub m: f64,
    #[default(3.0)]
    pub mc: f64,
    #[default(9.81)]
    pub g: f64,
}

#[test]
fn hanging_parallelogram_has_the_pendulum_frequency_of_its_closed_form() {
    let p = Parallelogram {
        a: 1.0,
        b: 2.0,
        m: 1.0,
        mc: 3.0,
        g: 9.81,
    };
    let w2 = p.g * (p.m + p.mc) / (p.a * (2.0 * p.m / 3.0 + p.mc));
    let down = Vector::<1>::new(-PI / 2.0);
    let modes = mbd::analysis::linear::undamped_modes(&p, 0.0, &down).unwrap();
    assert_eq!(modes.len(), 1);
    assert!((modes[0].omega_squared - w2).abs() < 1e-12 * w2);
    // On the init's side of the change points th = 0 and th = -pi (all four joints in line).
    for th in [-1.0, -0.3, -2.8] {
        let y = Vector::<2>::new(th, 0.7);
        let thdd = p.rhs(0.0, &y).unwrap()[1];
        assert!(
            (thdd + w2 * (th + PI / 2.0).sin()).abs() < 1e-12 * w2,
            "th = {th}"
        );
    }
    // Away from equilibrium the modes are refused, not computed from a wrong linearisation.
    let off = Vector::<1>::new(-1.0);
    assert!(matches!(
        mbd::analysis::linear::undamped_modes(&p, 0.0, &off),
        Err(Error::InvalidInput { .. })
    ));
    // A NaN length is named as such, not reported as a toggle position of the loop.
    let nan = Parallelogram { a: f64::NAN, ..p };
    match nan.rhs(0.0, &Vector::<2>::new(-1.0, 0.0)) {
        Err(Error::InvalidParameter { what, .. }) => assert_eq!(what, "parameter `a`"),
        other => panic!("{other:?}"),
    }
}

/// The crank-rocker hanging under gravity comes to rest where `V'(th) = 0` (found here by
/// bisection on the analytic `dV/dth` of [`Bar4`]); `static_equilibrium` on the minimal
/// model finds it, and the outputs of the dependent rocker (its angle, and `der(ga)` =
/// `kg th'`) follow the closure.
#[test]
fn crank_rocker_rests_where_gravity_has_no_moment_and_its_rocker_follows() {
    let k = CoordFourBar {
        a: 1.0,
        b: 3.0,
        c: 2.5,
        d: 3.5,
        m: 1.0,
        g: 9.81,
    };
    let dv = |th: f64| BAR.inertia_and_gravity(th, 1.0).1;
    // The stable rest: V' goes from negative to positive; bracketed by a scan.
    let mut lo = -PI;
    while !(dv(lo) < 0.0 && dv(lo + 0.01) >= 0.0) {
        lo += 0.01;
        assert!(lo < PI, "no rest found");
    }
    let mut hi = lo + 0.01;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if dv(mid) < 0.0 { lo = mid } else { hi = mid }
    }
    let opts = mbd::analysis::NewtonOptions::default();
    let q = mbd::analysis::statics::static_equilibrium(&k, 0.0, &Vector::<1>::new(lo + 0.2), &opts)
        .unwrap();
    assert!((q[0] - lo).abs() < 1e-10, "{} vs {lo}", q[0]);
    // Small swings about it: w^2 = V''(th*) / J(th*) (V'' by a central difference of the
    // analytic V'), from the minimal model and from the tree in the augmented form.
    let h = 1e-5;
    let w2 = (dv(lo + h) - dv(lo - h)) / (2.0 * h) / BAR.inertia_and_gravity(lo, 1.0).0;
    let minimal = mbd::analysis::linear::undamped_modes(&k, 0.0, &q).unwrap();
    assert!(
        (minimal[0].omega_squared - w2).abs() < 1e-7 * w2,
        "{minimal:?} vs {w2}"
    );
    let t = TreeFourBar {
        a: 1.0,
        b: 3.0,
        c: 2.5,
        d: 3.5,
        m: 1.0,
        g: 9.81,
    };
    let (be, ga) = BAR.close(lo, 1.0);
    let qt = Vector::<3>::new(lo, be - lo, ga);
    let tree = mbd::analysis::linear::constrained_modes(&t, 0.0, &qt).unwrap();
    let w = tree[0].omega_n;
    assert!((w * w - w2).abs() < 1e-7 * w2, "{tree:?} vs {w2}");
    let (th, thd) = (0.9, -1.7);
    let (be, ga) = BAR.close(th, 1.0);
    let (_, kg) = BAR.rates(th, be, ga);
    let out = k.outputs(0.0, &Vector::<2>::new(th, thd)).unwrap();
    assert!((out.rocker_angle - ga).abs() < 1e-13);
    assert!((out.rocker_rate - kg * thd).abs() < 1e-12);
}

/// Without gravity the crank-rocker coasts with `J(th) th'^2 / 2 = E`, so it reaches crank
/// angle `th1` at `t = int_{th0}^{th1} sqrt(J / (2 E)) dth` (composite Gauss-Legendre, 3
/// points on 400 panels: `J` is smooth on a Grashof crank-rocker). The terminal event on the
/// dependent rocker angle, `ga = 1.8` rising, is located there, `th1` by bisection on the
/// closed form `ga(th)`.
#[test]
fn event_on_the_dependent_rocker_is_located_at_the_quadrature_time() {
    let k = CoordFourBar {
        a: 1.0,
        b: 3.0,
        c: 2.5,
        d: 3.5,
        m: 1.0,
        g: 0.0,
    };
    let free = Bar4 { g: 0.0, ..BAR };
    let (th0, thd0) = (0.5, 3.0);
    let rocker = |th: f64| free.close(th, 1.0).1;
    assert!(rocker(th0) < 1.8);
    // The first crossing going forward: scan, then bisect.
    let mut hi = th0;
    while rocker(hi) < 1.8 {
        hi += 1e-3;
    }
    let mut lo = hi - 1e-3;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if rocker(mid) < 1.8 {
            lo = mid
        } else {
            hi = mid
        }
    }
    let energy = 0.5 * free.inertia_and_gravity(th0, 1.0).0 * thd0 * thd0;
    let (nodes, weights) = (
        [-(0.6f64).sqrt(), 0.0, (0.6f64).sqrt()],
        [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0],
    );
    let panels = 400;
    let width = (lo - th0) / panels as f64;
    let time: f64 = (0..panels)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| {
            let th = th0 + width * (i as f64 + 0.5 + 0.5 * nodes[j]);
            let j_th = free.inertia_and_gravity(th, 1.0).0;
            0.5 * width * weights[j] * (j_th / (2.0 * energy)).sqrt()
        })
        .sum();
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let events = k.events();
    let sol = Dopri5::new(opts)
        .solve(&k, 0.0, Vector::<2>::new(th0, thd0), 10.0, &events)
        .unwrap();
    assert_eq!(sol.events.len(), 1);
    assert!(
        (sol.events[0].t - time).abs() < 1e-9,
        "{} vs {time}",
        sol.events[0].t
    );
    assert!((sol.events[0].y[0] - lo).abs() < 1e-9);
}

/// A pendulum whose pivot is shaken along `x` by a constraint that names time,
/// `xp = A sin(w t)`: the derive solves it for `xp` (the state is `th`), and
/// `l th'' = -g sin th - xp'' cos th` with `xp'' = -A w^2 sin(w t)`.
#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[coords(th, xp)]
#[constraint(xp == amp * sin(w * t))]
#[particle(bob, mass = m, at = [xp + l * sin(th), -l * cos(th)])]
#[particle(pivot, mass = mp, at = [xp, 0.0])]
#[output(pivot_rate = der(xp))]
pub struct ShakenPendulum {
    pub m: f64,
    pub mp: f64,
    pub l: f64,
    pub g: f64,
    pub amp: f64,
    pub w: f64,
}

#[test]
fn pendulum_on_a_pivot_shaken_by_a_constraint_in_time() {
    let p = ShakenPendulum {
        m: 0.7,
        mp: 2.0,
        l: 0.9,
        g: 9.81,
        amp: 0.05,
        w: 12.0,
    };
    assert_eq!(ShakenPendulum::COORDINATES, ["th"]);
    for (t, th, thd) in [(0.1, 0.3, -1.0), (0.77, -2.0, 4.0), (1.3, 3.0, 0.0)] {
        let acc = p
            .acceleration(t, &Vector::<1>::new(th), &Vector::<1>::new(thd))
            .unwrap()[0];
        let xpdd = -p.amp * p.w * p.w * (p.w * t).sin();
        let want = -(p.g * th.sin() + xpdd * th.cos()) / p.l;
        assert!(
            (acc - want).abs() < 1e-12 * want.abs().max(1.0),
            "t = {t}: {acc} vs {want}"
        );
        let out = p.outputs(t, &Vector::<2>::new(th, thd)).unwrap();
        assert!((out.pivot_rate - p.amp * p.w * (p.w * t).cos()).abs() < 1e-13);
    }
}
