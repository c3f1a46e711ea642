//! Hunt: a toggle press (knuckle joint) near its dead centre under a large load. The upper
//! link `l1` turns about the origin (`th`, from the `x` axis), the lower link `l2` joins the
//! knee `K = l1 (cos th, sin th)` to a ram `B = (x, 0)` sliding on the `x` axis
//! (`B = K + l2 (cos be, -sin be)`); the ram is pushed back by the load `P` (a force `-P`
//! along `x`) and the upper link driven by a torque `tau`. Dead centre: `th = 0`, the links in
//! line, `x = l1 + l2` at its maximum. Written `#[coords(th, be, x)]` with two loop
//! equations, in both forms; and driven, `th = th0 + w t`, through the dead centre.
//!
//! Reference, by hand: `sin be = (l1 / l2) sin th`, `x = l1 cos th + l2 cos be`,
//! `x_th = -l1 sin th - l1 cos th tan be`, and by the chain rule
//! `x_thth = -l1 cos th + l1 sin th tan be - l1 cos th be_th / cos^2 be`,
//! `be_th = l1 cos th / (l2 cos be)`. Statics by virtual work: `tau - P x_th = 0`; near the
//! dead centre `x_th ~ -l1 (1 + l1 / l2) th`, so a small torque holds a large load. The
//! potential `V = P x - tau th` has `V'' = P x_thth < 0` there: the equilibrium is unstable,
//! with the real eigenvalues `+- sqrt(-P x_thth / J)` (`J` the reduced inertia, the masses'
//! and links' by hand, no gravity). Driven at `th' = w` (`th'' = 0`), the drive's effort is
//! `C w^2 + P x_th` with `J th'' + C th'^2` the inertial terms.

use mbd::analysis::{self, NewtonOptions, constrained_modes, linearize, static_equilibrium};
use mbd::integrate::{Dopri5, Integrator, Options, Radau5};
use mbd::prelude::*;

macro_rules! toggle {
    ($name:ident, $($opt:ident),*) => {
        /// The toggle press with a load on its ram and a torque on its upper link.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($opt),*)]
        #[coords(th, be, x)]
        #[constraint(l1 * cos(th) + l2 * cos(be) == x)]
        #[constraint(l1 * sin(th) == l2 * sin(be))]
        #[rigid(upper, mass = m1, inertia = m1 * l1 * l1 / 12.0,
                at = [l1 / 2.0 * cos(th), l1 / 2.0 * sin(th)], angle = th)]
        #[rigid(lower, mass = m2, inertia = m2 * l2 * l2 / 12.0,
                at = [l1 * cos(th) + l2 / 2.0 * cos(be), l1 * sin(th) - l2 / 2.0 * sin(be)],
                angle = -be)]
        #[particle(ram, mass = m3, at = [x, 0.0])]
        #[force(load, at = [x, 0.0], value = [-p, 0.0])]
        #[torque(motor, on = upper, value = tau)]
        #[init(th = 0.2, be = 0.13283653820739802, x = 1.4801111203901853)]
        #[output(ram_rate = der(x))]
        pub struct $name {
            #[default(0.6)] pub l1: f64,
            #[default(0.9)] pub l2: f64,
            pub m1: f64,
            pub m2: f64,
            pub m3: f64,
            pub p: f64,
            pub tau: f64,
        }
    };
}
toggle!(Toggle, jacobian);
toggle!(ToggleAugmented, jacobian, augmented);

/// Driven through its dead centre.
#[derive(Debug, Clone, Mechanism)]
#[drive(th = th0 + w * t)]
#[coords(be, x)]
#[constraint(l1 * cos(th) + l2 * cos(be) == x)]
#[constraint(l1 * sin(th) == l2 * sin(be))]
#[rigid(upper, mass = m1, inertia = m1 * l1 * l1 / 12.0,
        at = [l1 / 2.0 * cos(th), l1 / 2.0 * sin(th)], angle = th)]
#[rigid(lower, mass = m2, inertia = m2 * l2 * l2 / 12.0,
        at = [l1 * cos(th) + l2 / 2.0 * cos(be), l1 * sin(th) - l2 / 2.0 * sin(be)],
        angle = -be)]
#[particle(ram, mass = m3, at = [x, 0.0])]
#[force(load, at = [x, 0.0], value = [-p, 0.0])]
#[output(motor = reaction(th), ram = x)]
pub struct DrivenToggle {
    pub l1: f64,
    pub l2: f64,
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub p: f64,
    pub th0: f64,
    pub w: f64,
}

const L1: f64 = 0.6;
const L2: f64 = 0.9;
const M: [f64; 3] = [2.0, 3.0, 5.0];
const P: f64 = 1e6;
const TAU: f64 = 50.0;

macro_rules! reference {
    ($ty:ident) => {
        $ty {
            l1: L1,
            l2: L2,
            m1: M[0],
            m2: M[1],
            m3: M[2],
            p: P,
            tau: TAU,
        }
    };
}

/// `(be, x, be_th, x_th, x_thth)` at `th`.
fn closure(th: f64) -> [f64; 5] {
    let be = (L1 / L2 * th.sin()).asin();
    let x = L1 * th.cos() + L2 * be.cos();
    let be_th = L1 * th.cos() / (L2 * be.cos());
    let x_th = -L1 * th.sin() - L1 * th.cos() * be.tan();
    let x_thth =
        -L1 * th.cos() + L1 * th.sin() * be.tan() - L1 * th.cos() * be_th / be.cos().powi(2);
    [be, x, be_th, x_th, x_thth]
}

/// `(J, C)`: the inertial terms `J th'' + C th'^2`, `C = J' / 2`.
fn inertial(th: f64) -> (f64, f64) {
    let j = |th: f64| {
        let [be, _, be_th, x_th, _] = closure(th);
        let v_upper = (L1 / 2.0).powi(2);
        // the lower link's mass centre: (l1 cos th + l2/2 cos be, l1 sin th - l2/2 sin be)
        let vx = -L1 * th.sin() - L2 / 2.0 * be.sin() * be_th;
        let vy = L1 * th.cos() - L2 / 2.0 * be.cos() * be_th;
        M[0] * (v_upper + L1 * L1 / 12.0)
            + M[1] * (vx * vx + vy * vy + L2 * L2 / 12.0 * be_th * be_th)
            + M[2] * x_th * x_th
    };
    let h = 1e-4;
    (
        j(th),
        (j(th - 2.0 * h) - 8.0 * j(th - h) + 8.0 * j(th + h) - j(th + 2.0 * h)) / (24.0 * h),
    )
}

/// The equilibrium near the dead centre, `tau = P x_th`, by bisection.
fn equilibrium() -> f64 {
    let (mut lo, mut hi) = (-0.1, 0.0);
    let r = |th: f64| TAU - P * closure(th)[3];
    assert!(r(lo) < 0.0 && r(hi) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if r(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn the_init_is_on_the_hand_closure_and_the_forms_are_named() {
    let [be, x, ..] = closure(0.2);
    assert!((be - 0.13283653820739802).abs() < 1e-13 && (x - 1.4801111203901853).abs() < 1e-14);
    assert!(Toggle::GENERATED.parts.contains(&"minimal_closed_form"));
    assert_eq!(Toggle::COORDINATES, ["th"]);
    assert!(ToggleAugmented::GENERATED.parts.contains(&"augmented"));
    // a fully driven loop has no independent coordinate: augmented
    assert!(DrivenToggle::GENERATED.parts.contains(&"augmented"));
}

/// A torque of 50 N m holds a load of 1 MN a few tens of microradians from the dead centre.
///
/// Defect found: the augmented form's statics failed at once (`StaticsFailed`, 0
/// iterations, residual 1e6) though the equilibrium is regular: Newton started from
/// `lambda = 0`, where with configuration-independent loads (the load and the torque) the
/// residual's Jacobian `[[0, -Phi_q^T], [Phi_q, 0]]` is singular. It now starts from the
/// least-squares multipliers at the guess.
#[test]
fn statics_near_the_dead_centre_is_virtual_work_in_both_forms() {
    let th = equilibrium();
    assert!(th < 0.0 && th > -1e-4, "{th}");
    let opts = NewtonOptions::default();
    let p = reference!(Toggle);
    let q = static_equilibrium(&p, 0.0, &Vector::<1>::new(-0.01), &opts).unwrap();
    assert!((q[0] - th).abs() < 1e-12, "minimal {} vs {th}", q[0]);
    let pa = reference!(ToggleAugmented);
    let [be, x, ..] = closure(-0.01);
    let (qa, lambda) = analysis::static_equilibrium_constrained::<_, 3, 2, 5>(
        &pa,
        0.0,
        &Vector::<3>::new(-0.01, be, x),
        &opts,
    )
    .unwrap();
    let [be, x, ..] = closure(th);
    assert!(
        (qa[0] - th).abs() < 1e-12 && (qa[1] - be).abs() < 1e-12 && (qa[2] - x).abs() < 1e-12,
        "augmented {qa} vs ({th}, {be}, {x})"
    );
    // the ram's row of `f - Phi_q^T lambda = 0`: `Phi_1 = l1 cos th + l2 cos be - x` has
    // `d Phi_1 / dx = -1`, so `-P + lambda_1 = 0`: the lower link pushes the ram with `P`
    assert!((lambda[0] - P).abs() < 1e-9 * P, "{lambda}");
}

/// At the equilibrium the load folds the toggle: one real pair `+- sqrt(-P x_thth / J)`.
#[test]
fn the_loaded_dead_centre_is_unstable_with_the_hand_rate_in_both_forms() {
    let th = equilibrium();
    let (j, _) = inertial(th);
    let rate = (-P * closure(th)[4] / j).sqrt();
    let check = |name: &str, ms: &[analysis::Mode]| {
        let unstable: Vec<_> = ms.iter().filter(|m| m.unstable).collect();
        assert_eq!(unstable.len(), 1, "{name}: {ms:?}");
        let l = unstable[0].eigenvalue;
        assert!(
            (l.re - rate).abs() < 1e-7 * rate && l.im == 0.0,
            "{name}: {l} vs {rate}"
        );
    };
    let p = reference!(Toggle);
    let a = linearize(&p, 0.0, &Vector::<2>::new(th, 0.0)).unwrap();
    check("minimal", &analysis::modes(&a).unwrap());
    let pa = reference!(ToggleAugmented);
    let [be, x, ..] = closure(th);
    let ms = constrained_modes::<_, 3, 2, 6>(&pa, 0.0, &Vector::<3>::new(th, be, x)).unwrap();
    check("augmented", &ms);
}

/// Released at `th = 0.2` with the torque reversed (`tau = -50`) and a light load, the
/// toggle is driven through its dead centre; the ram stops at `x = l1 + l2` and comes back,
/// both forms on the same branch (`be` keeps the sign of `th`), against the work done.
#[test]
fn driven_by_torque_through_the_dead_centre_in_both_forms() {
    let mut p = reference!(Toggle);
    let mut pa = reference!(ToggleAugmented);
    (p.p, p.tau, pa.p, pa.tau) = (10.0, -50.0, 10.0, -50.0);
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let t_end = 0.6;
    let sol = Dopri5::new(opts.clone())
        .solve(&p, 0.0, p.initial_state(), t_end, &[])
        .unwrap();
    let y = sol.y.last().unwrap();
    assert!(y[0] < -0.2, "the dead centre is passed: th = {}", y[0]);
    // work: tau (th - th0) - P (x - x0) = T
    let work_energy = |th: f64, thd: f64| {
        let (j, _) = inertial(th);
        j * thd * thd / 2.0 - (-50.0) * (th - 0.2) + 10.0 * (closure(th)[1] - closure(0.2)[1])
    };
    for (&t, y) in sol.t.iter().zip(&sol.y) {
        assert!(work_energy(y[0], y[1]).abs() < 1e-8, "minimal t = {t}");
    }
    let sola = Radau5::new(opts)
        .solve(&pa, 0.0, pa.initial_state(), t_end, &[])
        .unwrap();
    let ya = sola.y.last().unwrap();
    assert!((ya[0] - y[0]).abs() < 1e-7, "{} vs {}", ya[0], y[0]);
    for (&t, y) in sola.t.iter().zip(&sola.y) {
        let [be, x, ..] = closure(y[0]);
        assert!(
            (y[1] - be).abs() < 1e-9 && (y[2] - x).abs() < 1e-9,
            "augmented t = {t}: ({}, {}) vs ({be}, {x})",
            y[1],
            y[2]
        );
        assert!(work_energy(y[0], y[3]).abs() < 1e-6, "augmented t = {t}");
    }
}

/// Driven from `th = -0.3` to `0.3` through the dead centre under the full load: the
/// kinematic sweep and the drive's effort `C w^2 + P x_th` (the load's share dominates and
/// changes sign at the dead centre).
#[test]
fn driven_through_the_dead_centre_the_motor_carries_the_load() {
    let w = 2.0;
    let p = DrivenToggle {
        l1: L1,
        l2: L2,
        m1: M[0],
        m2: M[1],
        m3: M[2],
        p: P,
        th0: -0.3,
        w,
    };
    let times: Vec<f64> = (0..=60).map(|i| i as f64 * 0.3 / 60.0).collect();
    let [be, x, ..] = closure(-0.3);
    let ks = analysis::kinematic_sweep(
        &p,
        &times,
        &Vector::<2>::new(be + 0.05, x - 0.05),
        &NewtonOptions::default(),
    )
    .unwrap();
    for k in &ks {
        let th = -0.3 + w * k.t;
        let [be, x, be_th, x_th, _] = closure(th);
        assert!(
            (k.q[0] - be).abs() < 1e-12 && (k.q[1] - x).abs() < 1e-12,
            "t = {}",
            k.t
        );
        assert!((k.qd[0] - be_th * w).abs() < 1e-10 && (k.qd[1] - x_th * w).abs() < 1e-10);
        let y = Vector::<4>::new(k.q[0], k.q[1], k.qd[0], k.qd[1]);
        let (_, c) = inertial(th);
        let want = c * w * w + P * x_th;
        let got = p.outputs(k.t, &y).unwrap().motor;
        assert!(
            (got - want).abs() < 1e-7 * (P * 0.1),
            "t = {}: {got} vs {want}",
            k.t
        );
    }
}
