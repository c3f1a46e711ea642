//! Coulomb friction at rest as a new user tries it: a block on an incline exactly at its
//! angle of repose, and a pendulum whose pin friction holds a motor torque below breakaway
//! and lets a larger one through. References derived beside each test.

use mbd::integrate::{Dop853, Dopri5, Options, Radau5, Rk4};
use mbd::prelude::*;

/// A block on an incline of angle `a`; `n` normal to it, relaxed, so that `reaction(n)` is
/// the normal force.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[relaxed(n)]
#[particle(block, mass = m, at = [s * cos(a) + n * sin(a), -s * sin(a) + n * cos(a)])]
#[friction(along = s, mu = mu, normal = reaction(n))]
pub struct Incline {
    pub m: f64,
    pub g: f64,
    pub a: f64,
    pub mu: f64,
}

fn tight() -> Options {
    Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    }
}

/// At the angle of repose, `mu = tan(a)`, the load down the slope `m g sin a` equals the
/// friction bound `mu m g cos a`: with equal static and kinetic coefficients the block stays
/// (it sticks at the bound, and sliding it would not accelerate). In floating point
/// `tan(a)` is rounded, so the exact answer for the numbers given is an acceleration of at
/// most `g |sin a - mu cos a| <= 2 eps g`: the block must hold to that, at every angle.
#[test]
fn block_at_its_angle_of_repose_holds() {
    let zero = Vector::<1>::zeros();
    for deg in (1..90).map(f64::from).chain([33.3, 12.5, 71.7]) {
        let a = deg.to_radians();
        let p = Incline {
            m: 3.0,
            g: 9.81,
            a,
            mu: a.tan(),
        };
        let bound = 2.0 * f64::EPSILON * p.g;
        let acc = p.acceleration(0.0, &zero, &zero).unwrap()[0];
        assert!(acc.abs() <= bound, "{deg} deg: {acc}");
        let run = mbd::hybrid::solve(
            &Dopri5::new(tight()),
            &p,
            0.0,
            Vector::<2>::zeros(),
            5.0,
            &[],
        )
        .unwrap();
        let y = run.solution.last().1;
        // Five seconds at that acceleration at most: s <= bound * 25 / 2.
        assert!(
            y[0].abs() <= 12.5 * bound && y[1].abs() <= 5.0 * bound,
            "{deg} deg: {y:?}"
        );
    }
}

/// A bar (mass `m`, centre at `l` from the pin, inertia `m l^2 / 12` about it) hanging from
/// a pin with friction coefficient `mu` on the full magnitude of the pin's force, turned by a
/// motor torque `tau`. At rest hanging down, the pin carries `R = m (l q'', g)` (the centre's
/// acceleration is `l q''` across the bar, and gravity), so the friction bound at rest is
/// `mu m g` and, sliding forward, `I_o q'' = tau - mu m sqrt(l^2 q''^2 + g^2)` with
/// `I_o = m l^2 + m l^2 / 12`. Squared: `(I_o^2 - mu^2 m^2 l^2) q''^2 - 2 tau I_o q'' +
/// tau^2 - mu^2 m^2 g^2 = 0`, whose root with `I_o q'' < tau` is the smaller one.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(q), com = [0.0, -l], mass = m, inertia = m * l * l / 12.0, reaction)]
#[torque(motor, on = arm, value = tau)]
#[friction(along = q, mu = mu, normal = hypot(reaction(arm_rx), reaction(arm_ry)))]
pub struct PinHold {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub mu: f64,
    pub tau: f64,
}

fn breakaway_acceleration(p: &PinHold) -> f64 {
    let io = p.m * p.l * p.l * (1.0 + 1.0 / 12.0);
    let (mm, mg) = (p.mu * p.m * p.l, p.mu * p.m * p.g);
    let (qa, qb, qc) = (
        io * io - mm * mm,
        -2.0 * p.tau * io,
        p.tau * p.tau - mg * mg,
    );
    (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa)
}

#[test]
fn pin_friction_holds_a_torque_below_breakaway_exactly() {
    // Breakaway at mu m g = 0.981 N m.
    let p = PinHold {
        m: 2.0,
        l: 0.5,
        g: 9.81,
        mu: 0.05,
        tau: 0.9,
    };
    let zero = Vector::<1>::zeros();
    assert_eq!(p.acceleration(0.0, &zero, &zero).unwrap()[0], 0.0);
    let y0 = Vector::<2>::zeros();
    let ends = [
        mbd::hybrid::solve(&Dopri5::new(tight()), &p, 0.0, y0, 3.0, &[])
            .map(|r| *r.solution.last().1),
        mbd::hybrid::solve(&Dop853::new(tight()), &p, 0.0, y0, 3.0, &[])
            .map(|r| *r.solution.last().1),
        mbd::hybrid::solve(&Radau5::new(tight()), &p, 0.0, y0, 3.0, &[])
            .map(|r| *r.solution.last().1),
        mbd::hybrid::solve(&Rk4::new(1e-2), &p, 0.0, y0, 3.0, &[]).map(|r| *r.solution.last().1),
    ];
    for end in ends {
        assert_eq!(end.unwrap(), y0, "no creep");
    }
}

#[test]
fn pin_friction_lets_a_torque_above_breakaway_through_at_the_closed_form_rate() {
    for tau in [1.0, 1.5, 4.0, -2.0] {
        let p = PinHold {
            m: 2.0,
            l: 0.5,
            g: 9.81,
            mu: 0.05,
            tau,
        };
        let zero = Vector::<1>::zeros();
        let acc = p.acceleration(0.0, &zero, &zero).unwrap()[0];
        // The backward case is the mirror image of the forward one.
        let want = tau.signum()
            * breakaway_acceleration(&PinHold {
                tau: tau.abs(),
                ..p
            });
        assert!(
            (acc - want).abs() < 1e-12 * want.abs(),
            "tau = {tau}: {acc} vs {want}"
        );
    }
}
