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

/// A slider-crank (crank `r` about the origin, rod `l`, piston on the `x` axis) turned by a
/// motor torque, with Coulomb friction on the piston's guide whose normal force is the
/// guide's reaction (`n`, relaxed). At each dead centre the piston stops and reverses while
/// the crank turns on: the piston cannot stick there (the loop moves it at second order
/// only: sticking it would need `th' = 0`), so the run passes every dead centre. Energy, by
/// hand (`sin(be) = r sin(th) / l`, `be' = r cos(th) th' / (l cos be)`): `T` of the crank
/// (`jc`), the rod (centre `(r cos th + l/2 cos be, r sin th - l/2 sin be)`, angle `-be`)
/// and the piston (`x' = -r sin(th) th' - l sin(be) be'`), `V` the rod's weight. Without
/// friction `T + V` grows by the motor's work `tau (th - th0)`; with it by less.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(th, be, x)]
#[relaxed(n)]
#[constraint(x == r * cos(th) + l * cos(be))]
#[constraint(r * sin(th) - l * sin(be) == n)]
#[rigid(crank, mass = mc, inertia = jc, at = [0.0, 0.0], angle = th)]
#[rigid(rod, mass = mr, inertia = mr * l * l / 12.0,
        at = [r * cos(th) + l / 2.0 * cos(be), r * sin(th) - l / 2.0 * sin(be)], angle = -be)]
#[particle(piston, mass = mp, at = [x, n])]
#[torque(motor, on = crank, value = tau)]
#[friction(along = x, mu = mu, normal = reaction(n))]
pub struct GuidedSliderCrank {
    pub r: f64,
    pub l: f64,
    pub mc: f64,
    pub jc: f64,
    pub mr: f64,
    pub mp: f64,
    pub tau: f64,
    pub mu: f64,
    pub g: f64,
}

fn guided_energy(p: &GuidedSliderCrank, th: f64, thd: f64) -> f64 {
    let be = (p.r * th.sin() / p.l).asin();
    let bed = p.r * th.cos() * thd / (p.l * be.cos());
    let xd = -p.r * th.sin() * thd - p.l * be.sin() * bed;
    let vx = -p.r * th.sin() * thd - p.l / 2.0 * be.sin() * bed;
    let vy = p.r * th.cos() * thd - p.l / 2.0 * be.cos() * bed;
    let height = p.r * th.sin() - p.l / 2.0 * be.sin();
    0.5 * p.jc * thd * thd
        + 0.5 * p.mr * (vx * vx + vy * vy + p.l * p.l / 12.0 * bed * bed)
        + 0.5 * p.mp * xd * xd
        + p.mr * p.g * height
}

#[test]
fn slider_crank_with_guide_friction_passes_its_dead_centres() {
    let th0: f64 = 1.2;
    let be0 = (0.1 * th0.sin() / 0.4).asin();
    let y0 = Vector::<6>::new(th0, be0, 0.1 * th0.cos() + 0.4 * be0.cos(), 0.0, 0.0, 0.0);
    for mu in [0.0, 0.3] {
        let p = GuidedSliderCrank {
            r: 0.1,
            l: 0.4,
            mc: 1.0,
            jc: 0.01,
            mr: 0.5,
            mp: 0.3,
            tau: 1.0,
            mu,
            g: 9.81,
        };
        let opts = Options {
            rtol: 1e-11,
            atol: 1e-11,
            ..Options::default()
        };
        let run = mbd::hybrid::solve(&Dopri5::new(opts), &p, 0.0, y0, 1.0, &[]).unwrap();
        let y = run.solution.last().1;
        // Several turns: the piston reverses at every dead centre, a switch each.
        let turns = (y[0] - th0) / (2.0 * std::f64::consts::PI);
        assert!(turns > 3.0, "mu = {mu}: {turns} turns");
        assert!(
            run.switches.len() as f64 >= 2.0 * turns.floor(),
            "mu = {mu}"
        );
        assert!(
            run.solution.y.iter().skip(1).all(|y| y[3] > 0.0),
            "the crank turns on"
        );
        let gained = guided_energy(&p, y[0], y[3]) - guided_energy(&p, th0, 0.0);
        let work = p.tau * (y[0] - th0);
        if mu == 0.0 {
            assert!((gained - work).abs() < 1e-7 * work, "{gained} vs {work}");
        } else {
            assert!(
                gained < 0.99 * work,
                "friction dissipates: {gained} vs {work}"
            );
        }
    }
}

/// The guided slider-crank at rest at `th = 1.2` under gravity and a motor torque: by
/// virtual work on the crank angle (the piston held), the guide must hold
/// `F = -(tau - mr g dh/dth) / (dx/dth)` along `x` (`h` the rod centre's height,
/// `dbe/dth = r cos th / (l cos be)`, `dx/dth = -r sin th - l sin be dbe/dth`,
/// `dh/dth = r cos th - l/2 cos be dbe/dth`); by virtual work on `n` (`th`, `x` held:
/// `dbe = -dn / (l cos be)`, `dx = tan(be) dn`, `dh = dn / 2`) the guide's normal force is
/// `R = mp g + mr g / 2 - F tan be`. It holds while `|F| <= mu |R|`: the breakaway torque
/// is where `F = mu R`, `F* = mu (mp + mr / 2) g / (1 + mu tan be)`.
#[test]
fn guided_slider_crank_holds_below_its_breakaway_torque_and_slides_above() {
    let p = GuidedSliderCrank {
        r: 0.1,
        l: 0.4,
        mc: 1.0,
        jc: 0.01,
        mr: 0.5,
        mp: 0.3,
        tau: 0.0,
        mu: 0.3,
        g: 9.81,
    };
    let th: f64 = 1.2;
    let be = (p.r * th.sin() / p.l).asin();
    let dbe = p.r * th.cos() / (p.l * be.cos());
    let dx = -p.r * th.sin() - p.l * be.sin() * dbe;
    let dh = p.r * th.cos() - p.l / 2.0 * be.cos() * dbe;
    let hold = p.mu * (p.mp + p.mr / 2.0) * p.g / (1.0 + p.mu * be.tan());
    let breakaway = -hold * dx + p.mr * p.g * dh;
    assert!(breakaway > 0.0);
    let q = Vector::<3>::new(th, be, p.r * th.cos() + p.l * be.cos());
    let rest = Vector::<3>::zeros();
    let below = GuidedSliderCrank {
        tau: (1.0 - 1e-9) * breakaway,
        ..p
    };
    assert_eq!(below.acceleration(0.0, &q, &rest).unwrap(), rest);
    let above = GuidedSliderCrank {
        tau: (1.0 + 1e-9) * breakaway,
        ..p
    };
    let acc = above.acceleration(0.0, &q, &rest).unwrap();
    assert!(
        acc[0] > 0.0 && acc[2] < 0.0,
        "turns forward, the piston moves in: {acc:?}"
    );
}

/// The incline with static and kinetic coefficients, `mu_k = 0.2 < tan(a) = 0.268 < mu_s = 0.35`
/// (15 degrees): kicked up the slope at `v0` (`s` points down it), the block decelerates at
/// `g (sin a + mu_k cos a)`, stops at `t1 = v0 / (g (sin a + mu_k cos a))`,
/// `s1 = -v0 t1 / 2`, and stays: at rest the load `m g sin a` is within `mu_s m g cos a`,
/// although sliding down would accelerate (`tan a > mu_k`).
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[relaxed(n)]
#[particle(block, mass = m, at = [s * cos(a) + n * sin(a), -s * sin(a) + n * cos(a)])]
#[friction(along = s, mu_k = mk, mu_s = ms, normal = reaction(n))]
pub struct TwoCoefficients {
    pub m: f64,
    pub g: f64,
    pub a: f64,
    pub mk: f64,
    pub ms: f64,
}

#[test]
fn kicked_up_a_slope_it_stops_and_static_friction_holds_it() {
    let p = TwoCoefficients {
        m: 4.0,
        g: 9.81,
        a: 15f64.to_radians(),
        mk: 0.2,
        ms: 0.35,
    };
    let v0 = 2.5;
    let decel = p.g * (p.a.sin() + p.mk * p.a.cos());
    let (t1, s1) = (v0 / decel, -v0 * v0 / (2.0 * decel));
    for run in [
        mbd::hybrid::solve(
            &Dopri5::new(tight()),
            &p,
            0.0,
            Vector::<2>::new(0.0, -v0),
            3.0,
            &[],
        ),
        mbd::hybrid::solve(
            &Radau5::new(tight()),
            &p,
            0.0,
            Vector::<2>::new(0.0, -v0),
            3.0,
            &[],
        ),
    ] {
        let run = run.unwrap();
        assert_eq!(run.switches.len(), 1);
        assert_eq!(run.switches[0].to, [mbd::Slip::Stick]);
        assert!(
            (run.switches[0].t - t1).abs() < 1e-12,
            "{} vs {t1}",
            run.switches[0].t
        );
        let y = run.solution.last().1;
        assert!((y[0] - s1).abs() < 1e-9 && y[1] == 0.0, "{y:?}");
    }
}
