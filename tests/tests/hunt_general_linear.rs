//! Hunting linear-analysis defects as a new user: joint trees (planar recursion, spatial
//! universal/revolute and ball joints) linearised from their generated Jacobians, against
//! small-oscillation frequencies, a gyroscopic stability limit and sensitivities derived by
//! hand beside each test.

use mbd::analysis::linear::{ModeKind, linearize, modes, state_space, undamped_modes};
use mbd::analysis::sensitivity::{Sensitivity, equilibrium_sensitivity};
use mbd::integrate::{Dop853, Integrator};
use mbd::prelude::*;

/// Three equal point masses on massless rods of equal length, as a planar joint tree
/// (relative angles; the articulated-body recursion evaluates it).
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[body(b1, joint = revolute(q1), com = [0.0, -l], mass = m)]
#[body(b2, parent = b1, joint = revolute(q2), at = [0.0, -l], com = [0.0, -l], mass = m)]
#[body(b3, parent = b2, joint = revolute(q3), at = [0.0, -l], com = [0.0, -l], mass = m)]
pub struct Triple {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// The roots of `mu^3 - 9 mu^2 + 18 mu - 6 = 0`, `mu = w^2 l / g`: in absolute angles the
/// triple pendulum's `M = m l^2 [[3, 2, 1], [2, 2, 1], [1, 1, 1]]` (mass `i` moves with
/// the angles `1 ..= i`) and `K = m g l diag(3, 2, 1)` (rod `j` carries `4 - j` masses),
/// and `det(K - mu M) = -(mu^3 - 9 mu^2 + 18 mu - 6)` (expanded by hand). Newton from
/// inside each root's basin.
fn triple_roots() -> [f64; 3] {
    [0.4, 2.3, 6.3].map(|mut mu: f64| {
        for _ in 0..50 {
            let p = ((mu - 9.0) * mu + 18.0) * mu - 6.0;
            let dp = (3.0 * mu - 18.0) * mu + 18.0;
            mu -= p / dp;
        }
        mu
    })
}

#[test]
fn triple_pendulum_tree_has_the_closed_form_frequencies() {
    let p = Triple {
        m: 0.7,
        l: 0.4,
        g: 9.81,
    };
    assert!(Triple::GENERATED.parts.contains(&"articulated_body"));
    let found = undamped_modes(&p, 0.0, &Vector::<3>::zeros()).unwrap();
    for (mode, mu) in found.iter().zip(triple_roots()) {
        let want = mu * p.g / p.l;
        assert!(
            (mode.omega_squared - want).abs() < 1e-10 * want,
            "{} vs {want}",
            mode.omega_squared
        );
    }
    // The same from the non-symmetric A: three oscillatory pairs, undamped, stable.
    let a = linearize(&p, 0.0, &Vector::<6>::zeros()).unwrap();
    let found = modes(&a).unwrap();
    assert_eq!(found.len(), 3);
    for (mode, mu) in found.iter().zip(triple_roots()) {
        assert_eq!(mode.kind, ModeKind::Oscillatory);
        assert!(!mode.unstable);
        let want = (mu * p.g / p.l).sqrt();
        assert!((mode.omega_d - want).abs() < 1e-10 * want);
    }
}

/// A symmetric top on a fixed point, upright: a massless-in-effect gimbal (a point mass
/// at the pivot) on a universal joint `rot_x(a) rot_y(b)`, the top spinning on it about
/// its own `z` axis, mass centre `l` above the pivot, moments `ia, ia, ic` about it.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, jacobian)]
#[gravity(0.0, 0.0, -g)]
#[body(gimbal, joint = universal(a, b), mass = m0)]
#[body(top, parent = gimbal, joint = revolute(c, z), com = [0.0, 0.0, l], mass = m,
       inertia = diag(ia, ia, ic))]
pub struct SleepingTop {
    pub m0: f64,
    pub m: f64,
    pub l: f64,
    pub ia: f64,
    pub ic: f64,
    pub g: f64,
}

const TOP: SleepingTop = SleepingTop {
    m0: 0.1,
    m: 1.2,
    l: 0.15,
    ia: 0.004,
    ic: 0.006,
    g: 9.81,
};

/// Spinning upright at `w` the top is a steady motion (the spin angle is cyclic). With
/// `A = ia + m l^2` about the pivot and `C = ic`, small tilts `(x, y)` obey
/// `A x'' + C w y' - m g l x = 0`, `A y'' - C w x' - m g l y = 0`, so with `z = x + i y`:
/// `A z'' - i C w z' - m g l z = 0` and `z = e^{i W t}` gives `A W^2 - C w W + m g l = 0`:
/// `W = (C w +- sqrt(C^2 w^2 - 4 A m g l)) / (2 A)`, two real frequencies (stable) when
/// `C^2 w^2 > 4 A m g l`, otherwise a pair with a positive real part (it falls).
#[test]
fn sleeping_top_on_a_joint_tree_has_the_gyroscopic_frequencies_and_limit() {
    let p = TOP;
    let big_a = p.ia + p.m * p.l * p.l;
    let limit = (4.0 * big_a * p.m * p.g * p.l).sqrt() / p.ic;
    for spin in [1.5 * limit, 3.0 * limit] {
        let y = Vector::<6>::from_column_slice(&[0.0, 0.0, 0.3, 0.0, 0.0, spin]);
        // A steady motion: no acceleration.
        let acc = p.rhs(0.0, &y).unwrap().fixed_rows::<3>(3).amax();
        assert!(acc < 1e-12, "{acc}");
        let a = linearize(&p, 0.0, &y).unwrap();
        let found = modes(&a).unwrap();
        let disc = (p.ic * spin).powi(2) - 4.0 * big_a * p.m * p.g * p.l;
        let want = [
            (p.ic * spin - disc.sqrt()) / (2.0 * big_a),
            (p.ic * spin + disc.sqrt()) / (2.0 * big_a),
        ];
        let osc: Vec<f64> = found
            .iter()
            .filter(|m| m.kind == ModeKind::Oscillatory)
            .map(|m| m.omega_d)
            .collect();
        assert_eq!(osc.len(), 2, "{found:?}");
        for (got, want) in osc.iter().zip(want) {
            assert!(
                (got - want).abs() < 1e-10 * want,
                "spin {spin}: {got} vs {want}"
            );
        }
        assert!(found.iter().all(|m| !m.unstable));
        // The spin angle and rate: a neutral double zero.
        assert_eq!(
            found.iter().filter(|m| m.kind == ModeKind::Neutral).count(),
            2
        );
    }
    // Below the limit it falls: `W = (C w +- i sqrt(4 A m g l - C^2 w^2)) / (2 A)`, so the
    // eigenvalues `i W` are `+-sqrt(..) / (2 A) + i C w / (2 A)` (and conjugates). nalgebra's
    // Schur iteration alone did not converge on this `A` (`modes` returned InvalidInput).
    let spin = 0.5 * limit;
    let y = Vector::<6>::from_column_slice(&[0.0, 0.0, 0.0, 0.0, 0.0, spin]);
    let found = modes(&linearize(&p, 0.0, &y).unwrap()).unwrap();
    let growth = (4.0 * big_a * p.m * p.g * p.l - (p.ic * spin).powi(2)).sqrt() / (2.0 * big_a);
    let unstable: Vec<_> = found.iter().filter(|m| m.unstable).collect();
    assert!(!unstable.is_empty(), "{found:?}");
    let turn = p.ic * spin / (2.0 * big_a);
    for m in unstable {
        assert!((m.eigenvalue.re - growth).abs() < 1e-10 * growth);
        assert!((m.eigenvalue.im.abs() - turn).abs() < 1e-10 * turn);
    }
}

/// A bar hanging from a ball joint: at rest it swings about `x` and `y` with
/// `w^2 = m g l / (a + m l^2)` and turns freely about its axis (`w = 0`).
#[derive(Debug, Mechanism)]
#[mechanism(spatial, jacobian)]
#[gravity(0.0, 0.0, -g)]
#[body(bob, joint = ball(s1, s2, s3), com = [0.0, 0.0, -l], mass = m, inertia = diag(a, a, c))]
pub struct BallPendulum {
    pub m: f64,
    pub l: f64,
    pub a: f64,
    pub c: f64,
    pub g: f64,
}

#[test]
fn ball_joint_pendulum_linearises_to_its_two_swings_and_a_free_spin() {
    let p = BallPendulum {
        m: 1.5,
        l: 0.8,
        a: 0.02,
        c: 0.01,
        g: 9.81,
    };
    let want = p.m * p.g * p.l / (p.a + p.m * p.l * p.l);
    let found = undamped_modes(&p, 0.0, &Vector::<3>::zeros()).unwrap();
    assert!(found[0].omega_squared.abs() < 1e-12, "{found:?}");
    for mode in &found[1..] {
        assert!(
            (mode.omega_squared - want).abs() < 1e-10 * want,
            "{found:?}"
        );
    }
}

/// A point mass on a rod, pushed sideways by a constant horizontal force `f` at the bob:
/// it rests at `tan q = f / (m g)`. The parameters are `(m, l, g, f)`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(q), com = [0.0, -l], mass = m)]
#[force(push, at = position(arm), value = [f, 0.0])]
#[output(x = position(arm)[0])]
pub struct Pushed {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub f: f64,
}

/// `q = atan(f / (m g))`: with `s = m^2 g^2 + f^2`, `dq/dm = -f g / s`, `dq/dl = 0`,
/// `dq/dg = -f m / s`, `dq/df = m g / s`; `x = l sin q`: `dx/dp = l cos q dq/dp`, plus
/// `sin q` for `l`.
#[test]
fn equilibrium_sensitivities_of_a_pushed_pendulum_are_the_closed_form() {
    let p = Pushed {
        m: 2.0,
        l: 0.9,
        g: 9.81,
        f: 7.0,
    };
    let q = (p.f / (p.m * p.g)).atan();
    let s = (p.m * p.g).powi(2) + p.f * p.f;
    let dq = [-p.f * p.g / s, 0.0, -p.f * p.m / s, p.m * p.g / s];
    let (got_q, got_x) = equilibrium_sensitivity(&p, 0.0, &[q]).unwrap();
    for j in 0..4 {
        assert!((got_q[(0, j)] - dq[j]).abs() < 1e-12, "dq/dp{j}");
        let dx = p.l * q.cos() * dq[j] + if j == 1 { q.sin() } else { 0.0 };
        assert!((got_x[(0, j)] - dx).abs() < 1e-12, "dx/dp{j}");
    }
}

/// A mass on a spring: `x = x0 cos(w t)`, `w = sqrt(k / m)`, so
/// `dx/dp = -x0 t sin(w t) dw/dp` with `dw/dk = 1 / (2 sqrt(k m))`, `dw/dm = -w / (2 m)`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[point(wall, at = [0.0, 0.0])]
#[spring(s, from = wall, to = block, k = k)]
pub struct Spring {
    pub k: f64,
    pub m: f64,
}

#[test]
fn forward_sensitivities_along_an_oscillation_are_the_closed_form() {
    let p = Spring { k: 9.0, m: 0.5 };
    let w = (p.k / p.m).sqrt();
    let dw = [1.0 / (2.0 * (p.k * p.m).sqrt()), -w / (2.0 * p.m)];
    let sens = Sensitivity::new(&p, [0, 1]).unwrap();
    let x0 = 0.3;
    let ya = sens.initial::<6>(&Vector::<2>::new(x0, 0.0));
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let t1 = 2.0;
    let sol = Dop853::new(opts).solve(&sens, 0.0, ya, t1, &[]).unwrap();
    let s = sens.sensitivities(sol.last().1);
    for j in 0..2 {
        let dx = -x0 * t1 * (w * t1).sin() * dw[j];
        let dv = -x0 * ((w * t1).sin() + w * t1 * (w * t1).cos()) * dw[j];
        assert!(
            (s[(0, j)] - dx).abs() < 1e-9,
            "dx/dp{j}: {} vs {dx}",
            s[(0, j)]
        );
        assert!(
            (s[(1, j)] - dv).abs() < 1e-9,
            "dv/dp{j}: {} vs {dv}",
            s[(1, j)]
        );
    }
}

/// A block on a spring on a rough floor, with its Jacobian generated. Sliding, Coulomb
/// friction is a constant force, so `A = [[0, 1], [-k/m, 0]]` exactly. At rest the contact
/// sticks or breaks away by the load: the accelerations have no derivative there, and the
/// frictionless model's `A` (what the generated Jacobian returned with the friction
/// direction 0, with `undamped_modes` reporting `w^2 = k/m` about a point the friction
/// holds) must not come back as `Ok`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[point(wall, at = [0.0, 0.0])]
#[spring(s, from = wall, to = block, k = k)]
#[friction(along = x, mu = mu, normal = m * g)]
#[output(reach = x)]
pub struct RoughSpring {
    pub m: f64,
    pub g: f64,
    pub k: f64,
    pub mu: f64,
}

#[test]
fn friction_at_rest_is_not_linearised_as_if_it_were_not_there() {
    let p = RoughSpring {
        m: 2.0,
        g: 9.81,
        k: 8.0,
        mu: 0.1,
    };
    for v in [0.3, -0.3] {
        let y = Vector::<2>::new(0.5, v);
        let a = linearize(&p, 0.0, &y).unwrap();
        assert_eq!((a[(0, 0)], a[(0, 1)], a[(1, 1)]), (0.0, 1.0, 0.0));
        assert!((a[(1, 0)] + p.k / p.m).abs() < 1e-15);
    }
    let at_rest = |err: Error| match err {
        Error::InvalidInput { what, detail } => {
            assert_eq!(what, "friction at rest");
            assert!(detail.contains("`x`"), "{detail}");
        }
        other => panic!("{other:?}"),
    };
    // Held by friction (k x = 0.8 N < mu m g = 1.96 N), and breaking away (k x = 8 N).
    for x in [0.1, 1.0] {
        at_rest(linearize(&p, 0.0, &Vector::<2>::new(x, 0.0)).unwrap_err());
        at_rest(undamped_modes(&p, 0.0, &Vector::<1>::new(x)).unwrap_err());
        at_rest(equilibrium_sensitivity(&p, 0.0, &[x]).unwrap_err());
    }
}

/// A bead on a rod turned by a drive `th = w t` whose rate `w` is an input (the docs'
/// bead, with its Jacobian). Along the rod `s'' = w^2 s - g sin(w t)`, and the drive's
/// torque is `2 m s s' w + g cos(w t) (ma r + m s)`, so at `(t, s, s')`:
/// `A = [[0, 1], [w^2, 0]]`, `B = [0, 2 w s - g t cos(w t)]`,
/// `C_motor = [2 m s' w + m g cos(w t), 2 m s w]`,
/// `D_motor = 2 m s s' - g t sin(w t) (ma r + m s)`; the output `s` has `C = [1, 0]`.
#[derive(Debug, Mechanism)]
#[mechanism(planar, jacobian)]
#[gravity(0.0, -g)]
#[drive(th = w * t)]
#[body(rod, joint = revolute(th), com = [r, 0.0], mass = ma, inertia = ia)]
#[body(bead, parent = rod, joint = prismatic(s, [1.0, 0.0]), mass = m)]
#[input(w)]
#[output(motor = reaction(th), pos = s)]
pub struct TurnedBead {
    pub m: f64,
    pub ma: f64,
    pub ia: f64,
    pub r: f64,
    pub w: f64,
    pub g: f64,
}

#[test]
fn a_drive_rate_as_input_has_the_closed_form_state_space() {
    let p = TurnedBead {
        m: 0.2,
        ma: 1.0,
        ia: 0.1,
        r: 0.5,
        w: 3.0,
        g: 9.81,
    };
    let (t, s, sd) = (0.4, 0.3, 0.7);
    let ss = state_space(&p, t, &Vector::<2>::new(s, sd)).unwrap();
    assert_eq!(
        (ss.inputs.clone(), ss.outputs.clone()),
        (vec!["w"], vec!["motor", "pos"])
    );
    let wt = p.w * t;
    let close = |a: f64, b: f64| (a - b).abs() < 1e-13 * (1.0 + b.abs());
    assert!(close(ss.a[(0, 0)], 0.0) && close(ss.a[(0, 1)], 1.0));
    assert!(close(ss.a[(1, 0)], p.w * p.w) && close(ss.a[(1, 1)], 0.0));
    assert!(close(ss.b[(0, 0)], 0.0));
    assert!(close(ss.b[(1, 0)], 2.0 * p.w * s - p.g * t * wt.cos()));
    assert!(close(
        ss.c[(0, 0)],
        2.0 * p.m * sd * p.w + p.m * p.g * wt.cos()
    ));
    assert!(close(ss.c[(0, 1)], 2.0 * p.m * s * p.w));
    assert!(close(ss.c[(1, 0)], 1.0) && close(ss.c[(1, 1)], 0.0));
    let d = 2.0 * p.m * s * sd - p.g * t * wt.sin() * (p.ma * p.r + p.m * s);
    assert!(close(ss.d[(0, 0)], d) && close(ss.d[(1, 0)], 0.0));
}
