//! Hunting linear-analysis defects as a new user: repeated eigenvalues, rigid-body (zero
//! frequency) modes, proportional damping, a state space with a feed-through, frequency
//! responses, and operating points that are not equilibria. Each reference is derived
//! beside its test.

use mbd::analysis::linear::{
    ModeKind, constrained_modes, constrained_state_space, linearize, modes, state_space,
    undamped_modes,
};
use mbd::prelude::*;
use nalgebra::{Complex, DMatrix};

/// Two identical pendulums (point masses on massless rods), not coupled: the same
/// frequency twice, `w^2 = g / l`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(a, b)]
#[particle(p1, mass = m, at = [l * sin(a), -l * cos(a)])]
#[particle(p2, mass = m, at = [d + l * sin(b), -l * cos(b)])]
pub struct Twins {
    pub m: f64,
    pub l: f64,
    pub d: f64,
    pub g: f64,
}

const TWINS: Twins = Twins {
    m: 0.5,
    l: 0.8,
    d: 2.0,
    g: 9.81,
};

/// A repeated eigenvalue `+-i sqrt(g / l)` of multiplicity two (semisimple: the
/// pendulums swing independently). `modes` must report the pair twice with two
/// independent shapes spanning its eigenspace (each satisfying `A v = lambda v`), as
/// `undamped_modes` does with two `M`-orthonormal shapes.
#[test]
fn a_repeated_frequency_has_two_independent_shapes() {
    let w = (TWINS.g / TWINS.l).sqrt();
    let a = linearize(&TWINS, 0.0, &Vector::<4>::zeros()).unwrap();
    let found = modes(&a).unwrap();
    assert_eq!(found.len(), 2);
    let ad = DMatrix::from_iterator(4, 4, a.iter().copied()).map(|v| Complex::new(v, 0.0));
    for m in &found {
        assert_eq!(m.kind, ModeKind::Oscillatory);
        assert!((m.omega_d - w).abs() < 1e-12 * w, "{}", m.omega_d);
        let residual = (&ad * &m.shape - &m.shape * m.eigenvalue).norm();
        assert!(residual < 1e-10, "A v - lambda v = {residual:.3e}");
    }
    // Independent: the 4 x 2 matrix of the two shapes has rank two (its smallest singular
    // value is of the order of the shapes themselves, which are scaled to a largest entry 1).
    let s = DMatrix::from_columns(&[found[0].shape.clone(), found[1].shape.clone()]);
    let sv = s.singular_values();
    assert!(sv.min() > 1e-3, "the two shapes are parallel: {sv}");

    let normal = undamped_modes(&TWINS, 0.0, &Vector::<2>::zeros()).unwrap();
    let mass = TWINS.m * TWINS.l * TWINS.l;
    for nm in &normal {
        assert!((nm.omega_squared - w * w).abs() < 1e-12 * w * w);
    }
    let cross = normal[0].shape.dot(&normal[1].shape) * mass;
    assert!(cross.abs() < 1e-12, "not M-orthogonal: {cross}");
}

/// Two masses on a line joined by a spring `k` of rest length `l0`, free otherwise: a
/// rigid-body translation (`w = 0`, shape `(1, 1) / sqrt(m1 + m2)` mass-normalised) and
/// the stretch at `w^2 = k (1 / m1 + 1 / m2)`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x1, x2)]
#[particle(p1, mass = m1, at = [x1, 0.0])]
#[particle(p2, mass = m2, at = [x2, 0.0])]
#[spring(s, from = p1, to = p2, k = k, length = l0)]
pub struct FreePair {
    pub m1: f64,
    pub m2: f64,
    pub k: f64,
    pub l0: f64,
}

/// The rigid-body mode is a mode at zero frequency, not an unstable one: its
/// `frequency_hz` is `Some(0)` (to rounding), and `modes` of `A` calls its double zero
/// neutral and stable.
#[test]
fn a_free_pair_has_a_zero_frequency_rigid_body_mode() {
    for (m1, m2, k, l0) in [
        (1.5, 0.7, 12.0, 0.4),
        (1.0, 1.0, 1.0, 1.0),
        (0.3, 7.0, 1e4, 2.5),
        (1e-3, 2.0, 5.0, 0.1),
        (3.7, 0.11, 0.9, 3.3),
    ] {
        rigid_body_mode(&FreePair { m1, m2, k, l0 });
    }
}

fn rigid_body_mode(pair: &FreePair) {
    let rest = Vector::<2>::new(0.0, pair.l0);
    let found = undamped_modes(pair, 0.0, &rest).unwrap();
    let stretch = pair.k * (1.0 / pair.m1 + 1.0 / pair.m2);
    assert!(found[0].omega_squared.abs() < 1e-12 * stretch);
    let hz = found[0].frequency_hz();
    assert!(
        hz.is_some_and(|f| f.abs() < 1e-6),
        "rigid-body mode: {hz:?} (w^2 = {:e})",
        found[0].omega_squared
    );
    let rigid = 1.0 / (pair.m1 + pair.m2).sqrt();
    let sign = found[0].shape[0].signum();
    assert!((found[0].shape[0] * sign - rigid).abs() < 1e-12);
    assert!((found[0].shape[1] * sign - rigid).abs() < 1e-12);
    assert!((found[1].omega_squared - stretch).abs() < 1e-12 * stretch);
    let want_hz = stretch.sqrt() / std::f64::consts::TAU;
    assert!((found[1].frequency_hz().unwrap() - want_hz).abs() < 1e-12 * want_hz);

    let y = Vector::<4>::new(0.0, pair.l0, 0.0, 0.0);
    let m = modes(&linearize(pair, 0.0, &y).unwrap()).unwrap();
    assert_eq!(m.len(), 3);
    assert_eq!(
        (m[0].kind, m[1].kind),
        (ModeKind::Neutral, ModeKind::Neutral)
    );
    assert!(m.iter().all(|m| !m.unstable));
    assert_eq!(m[2].kind, ModeKind::Oscillatory);
    assert!((m[2].omega_d - stretch.sqrt()).abs() < 1e-12 * stretch.sqrt());
}

/// An upright pendulum (`q` from the upward vertical): `q'' = (g / l) sin q`, so about
/// `q = 0` the eigenvalues are `+-sqrt(g / l)`, one unstable, and `undamped_modes` gives
/// `w^2 = -g / l` with no frequency.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(q)]
#[particle(bob, mass = m, at = [l * sin(q), l * cos(q)])]
pub struct Upright {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn an_inverted_pendulum_diverges_at_the_closed_form_rate() {
    let p = Upright {
        m: 0.3,
        l: 0.6,
        g: 9.81,
    };
    let s = (p.g / p.l).sqrt();
    let a = linearize(&p, 0.0, &Vector::<2>::zeros()).unwrap();
    assert_eq!((a[(0, 0)], a[(0, 1)], a[(1, 1)]), (0.0, 1.0, 0.0));
    assert!((a[(1, 0)] - s * s).abs() < 1e-14 * s * s);
    let found = modes(&a).unwrap();
    assert_eq!(found.len(), 2);
    let (down, up) = if found[0].eigenvalue.re < 0.0 {
        (&found[0], &found[1])
    } else {
        (&found[1], &found[0])
    };
    assert_eq!((down.kind, up.kind), (ModeKind::Real, ModeKind::Real));
    assert!((up.eigenvalue.re - s).abs() < 1e-13 * s && up.unstable);
    assert!((down.eigenvalue.re + s).abs() < 1e-13 * s && !down.unstable);
    assert_eq!(up.damping_ratio, Some(-1.0));
    let normal = undamped_modes(&p, 0.0, &Vector::<1>::zeros()).unwrap();
    assert!((normal[0].omega_squared + s * s).abs() < 1e-13 * s * s);
    assert_eq!(normal[0].frequency_hz(), None);
}

/// Two equal masses `m` in a row from a wall, springs `k` (wall to 1, 1 to 2) with dampers
/// `c = beta k` beside them (stiffness-proportional damping). `K = k [[2, -1], [-1, 1]]`,
/// `M = m I`: `w^2 = (k / m) (3 -+ sqrt(5)) / 2`, and since `C = beta K` the modes decouple
/// with `2 zeta w = beta w^2`, `zeta = beta w / 2`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x1, x2)]
#[point(wall, at = [0.0, 0.0])]
#[particle(p1, mass = m, at = [x1, 0.0])]
#[particle(p2, mass = m, at = [x2, 0.0])]
#[spring(s1, from = wall, to = p1, k = k, length = l0)]
#[spring(s2, from = p1, to = p2, k = k, length = l0)]
#[damper(d1, from = wall, to = p1, c = beta * k)]
#[damper(d2, from = p1, to = p2, c = beta * k)]
pub struct DampedRow {
    pub m: f64,
    pub k: f64,
    pub l0: f64,
    pub beta: f64,
}

#[test]
fn proportional_damping_has_the_closed_form_damping_ratios() {
    let p = DampedRow {
        m: 2.0,
        k: 50.0,
        l0: 1.0,
        beta: 0.04,
    };
    let y = Vector::<4>::new(p.l0, 2.0 * p.l0, 0.0, 0.0);
    let found = modes(&linearize(&p, 0.0, &y).unwrap()).unwrap();
    assert_eq!(found.len(), 2);
    let s5 = 5f64.sqrt();
    for (m, r) in found.iter().zip([(3.0 - s5) / 2.0, (3.0 + s5) / 2.0]) {
        let w = (p.k / p.m * r).sqrt();
        let zeta = p.beta * w / 2.0;
        assert_eq!(m.kind, ModeKind::Oscillatory);
        assert!((m.omega_n - w).abs() < 1e-12 * w, "{} vs {w}", m.omega_n);
        let z = m.damping_ratio.unwrap();
        assert!((z - zeta).abs() < 1e-12, "{z} vs {zeta}");
        assert!((m.omega_d - w * (1.0 - zeta * zeta).sqrt()).abs() < 1e-12 * w);
    }
    // Damped: the undamped analysis refuses and says which to use.
    match undamped_modes(&p, 0.0, &Vector::<2>::new(p.l0, 2.0 * p.l0)) {
        Err(Error::InvalidInput { detail, .. }) => assert!(detail.contains("modes"), "{detail}"),
        other => panic!("{other:?}"),
    }
}

/// A block on a spring and a damper to a wall, pushed by an input force `u`, with its
/// position, velocity and acceleration as outputs. By hand, `m x'' = -k (x - l0) - c x' + u`:
/// `A = [[0, 1], [-k/m, -c/m]]`, `B = [0, 1/m]`; the position has `C = [1, 0]`, the velocity
/// `[0, 1]`, the acceleration `[-k/m, -c/m]` with a feed-through `D = 1/m`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x)]
#[point(wall, at = [0.0, 0.0])]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(s, from = wall, to = block, k = k, length = l0)]
#[damper(d, from = wall, to = block, c = c)]
#[generalized_force(push, along = x, value = u)]
#[input(u)]
#[output(pos = x, vel = der(x), acc = acceleration(block)[0])]
pub struct Pushed {
    pub m: f64,
    pub k: f64,
    pub c: f64,
    pub l0: f64,
    pub u: f64,
}

const PUSHED: Pushed = Pushed {
    m: 2.0,
    k: 18.0,
    c: 1.2,
    l0: 0.5,
    u: 0.0,
};

#[test]
fn a_pushed_block_has_the_hand_state_space_with_feed_through() {
    let p = &PUSHED;
    let ss = state_space(p, 0.0, &Vector::<2>::new(p.l0, 0.0)).unwrap();
    assert_eq!(ss.inputs, vec!["u"]);
    assert_eq!(ss.outputs, vec!["pos", "vel", "acc"]);
    let (km, cm) = (p.k / p.m, p.c / p.m);
    let want_a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -km, -cm]);
    let want_b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0 / p.m]);
    let want_c = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 0.0, 1.0, -km, -cm]);
    let want_d = DMatrix::from_row_slice(3, 1, &[0.0, 0.0, 1.0 / p.m]);
    for (got, want, name) in [
        (&ss.a, &want_a, "A"),
        (&ss.b, &want_b, "B"),
        (&ss.c, &want_c, "C"),
        (&ss.d, &want_d, "D"),
    ] {
        assert!((got - want).amax() < 1e-14, "{name}: {got} vs {want}");
    }
}

/// The frequency response `G(i w) = C (i w I - A)^-1 B + D` of the pushed block: the
/// receptance `x / u = 1 / (k - m w^2 + i c w)`, the mobility `i w` times it and the
/// accelerance `-w^2` times it. At resonance of the undamped block (`c = 0`, `w^2 = k/m`)
/// `i w` is an eigenvalue of `A`: a typed error, not an infinity.
#[test]
fn the_frequency_response_is_the_receptance_by_hand() {
    let p = &PUSHED;
    let ss = state_space(p, 0.0, &Vector::<2>::new(p.l0, 0.0)).unwrap();
    for w in [0.0, 0.5, 3.0, 2.9, 40.0] {
        let g = ss.frequency_response(w).unwrap();
        assert_eq!((g.nrows(), g.ncols()), (3, 1));
        let iw = Complex::new(0.0, w);
        let x = Complex::new(1.0, 0.0) / Complex::new(p.k - p.m * w * w, p.c * w);
        for (got, want) in [
            (g[(0, 0)], x),
            (g[(1, 0)], iw * x),
            (g[(2, 0)], iw * iw * x),
        ] {
            assert!(
                (got - want).norm() < 1e-13 * (1.0 + want.norm()),
                "w = {w}: {got} vs {want}"
            );
        }
    }
    let undamped = Pushed { c: 0.0, ..PUSHED };
    let ss = state_space(&undamped, 0.0, &Vector::<2>::new(p.l0, 0.0)).unwrap();
    match ss.frequency_response((p.k / p.m).sqrt()) {
        Err(Error::InvalidInput { what, .. }) => assert_eq!(what, "frequency_response"),
        other => panic!("{other:?}"),
    }
    assert!(ss.frequency_response(f64::NAN).is_err());
}

/// A pendulum in Cartesian coordinates held on its circle by a constraint (augmented
/// form). On the circle the motion is `q'' = -(g / l) sin q` in the angle `q` from the
/// downward vertical, so at rest at `q0` the linearisation on the manifold is
/// `dq'' = -(g / l) cos(q0) dq`: `lambda^2 = -(g / l) cos q0`.
#[derive(Debug, Mechanism)]
#[mechanism(augmented, jacobian)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[constraint(x * x + y * y == l * l)]
#[particle(bob, mass = m, at = [x, y])]
pub struct CartesianPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

const CART: CartesianPendulum = CartesianPendulum {
    m: 0.4,
    l: 1.3,
    g: 9.81,
};

/// Hanging at rest: one oscillatory mode at `sqrt(g / l)`, its shape along the circle's
/// tangent (`x` only).
#[test]
fn a_cartesian_pendulum_has_its_frequency_on_the_constraint() {
    let w = (CART.g / CART.l).sqrt();
    let found = constrained_modes(&CART, 0.0, &Vector::<2>::new(0.0, -CART.l)).unwrap();
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].kind, ModeKind::Oscillatory);
    assert!((found[0].omega_d - w).abs() < 1e-12 * w);
    assert!(found[0].shape[1].norm() < 1e-12, "{}", found[0].shape);
}

/// At rest off the bottom the point is not an equilibrium (the bob accelerates along the
/// circle), but the linearisation there still has a meaning in one coordinate: the
/// restriction to the tangent space must be `lambda^2 = -(g / l) cos q0`, oscillatory
/// below the horizontal and a real pair `+-sqrt(g |cos q0| / l)` above it.
#[test]
fn constrained_modes_at_rest_off_equilibrium_linearise_along_the_circle() {
    for q0 in [0.6f64, 1.2, 2.0, 2.9] {
        let q = Vector::<2>::new(CART.l * q0.sin(), -CART.l * q0.cos());
        let found = constrained_modes(&CART, 0.0, &q).unwrap();
        let w2 = CART.g / CART.l * q0.cos();
        let rate = w2.abs().sqrt();
        if w2 > 0.0 {
            assert_eq!(found.len(), 1);
            assert_eq!(found[0].kind, ModeKind::Oscillatory);
            assert!((found[0].omega_d - rate).abs() < 1e-12 * rate, "q0 = {q0}");
        } else {
            assert_eq!(found.len(), 2);
            for m in &found {
                assert_eq!(m.kind, ModeKind::Real);
                assert!(
                    (m.eigenvalue.re.abs() - rate).abs() < 1e-12 * rate,
                    "q0 = {q0}"
                );
                assert_eq!(m.unstable, m.eigenvalue.re > 0.0);
            }
        }
    }
}

/// A spherical pendulum (bob `m` on a rod `l`, `th` from the downward vertical, `ph` about
/// it) in steady conical motion: `th = th0`, `ph' = W` with `W^2 = g / (l cos th0)`.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, jacobian)]
#[gravity(0.0, 0.0, -g)]
#[coords(th, ph)]
#[particle(bob, mass = m, at = [l * sin(th) * cos(ph), l * sin(th) * sin(ph), -l * cos(th)])]
pub struct Spherical {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// Linearised about the steady motion (not a rest point: `ph` turns): with
/// `h = sin^2(th) ph'` conserved, `th'' = h^2 cos th / sin^3 th - (g / l) sin th`, whose
/// derivative in `th` at the steady state, with `h^2 = W^2 sin^4 th0`, is
/// `-W^2 (sin^2 + 3 cos^2) - (g / l) cos = -W^2 (1 + 3 cos^2 th0)`. `ph` is cyclic and `h`
/// conserved, so `A` has a double zero and `+-i w`, `w^2 = W^2 (1 + 3 cos^2 th0)`.
#[test]
fn a_conical_pendulum_nutates_at_the_closed_form_rate() {
    let p = Spherical {
        m: 0.8,
        l: 0.9,
        g: 9.81,
    };
    for th0 in [0.3f64, 0.8, 1.3] {
        let big_w = (p.g / (p.l * th0.cos())).sqrt();
        let y = Vector::<4>::new(th0, 0.4, 0.0, big_w);
        // A steady motion: th'' = 0 there.
        assert!(p.rhs(0.0, &y).unwrap()[2].abs() < 1e-13 * big_w * big_w);
        let found = modes(&linearize(&p, 0.0, &y).unwrap()).unwrap();
        let w = big_w * (1.0 + 3.0 * th0.cos().powi(2)).sqrt();
        assert_eq!(found.len(), 3, "th0 = {th0}: {found:?}");
        assert_eq!(
            (found[0].kind, found[1].kind),
            (ModeKind::Neutral, ModeKind::Neutral)
        );
        assert_eq!(found[2].kind, ModeKind::Oscillatory);
        assert!((found[2].omega_d - w).abs() < 1e-12 * w, "th0 = {th0}");
        assert!(found[2].damping_ratio.unwrap().abs() < 1e-12);
    }
}

/// The bead in a turning slot (horizontal plane) with Coulomb friction whose normal force
/// is the slot's push, `N = 2 m w r'`, and its Jacobian generated.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(r)]
#[relaxed(n)]
#[drive(th = w * t)]
#[particle(bead, mass = m, at = [r * cos(th) - n * sin(th), r * sin(th) + n * cos(th)])]
#[friction(along = r, mu = mu, normal = reaction(n))]
pub struct RoughSlot {
    pub m: f64,
    pub w: f64,
    pub mu: f64,
}

/// Sliding either way, `r'' = w^2 r - mu |2 w r'| sign(r') = w^2 r - 2 mu w r'`: the
/// friction force depends on the velocity through the normal force, so
/// `A = [[0, 1], [w^2, -2 mu w]]`, not the `[[0, 1], [w^2, 0]]` of a constant friction.
#[test]
fn a_velocity_dependent_normal_force_enters_the_sliding_jacobian() {
    let p = RoughSlot {
        m: 0.3,
        w: 2.0,
        mu: 0.4,
    };
    for v in [0.7, -0.7] {
        let y = Vector::<2>::new(1.1, v);
        let a = linearize(&p, 0.5, &y).unwrap();
        let want = Matrix::<2, 2>::new(0.0, 1.0, p.w * p.w, -2.0 * p.mu * p.w);
        assert!((a - want).amax() < 1e-13, "v = {v}: {a} vs {want}");
    }
}

/// A pendulum (point mass `m` on a massless arm `l`, a joint tree) with pin friction on the
/// pin's force along the arm, `R_r = m (g cos th + l th'^2)` (the projection of the joint's
/// reaction; its tangential part, which carries `th''`, drops out). Sliding,
/// `m l^2 th'' = -m g l sin th - c m (g cos th + l th'^2) s`, `s = sign(th')`, so
/// `d th''/d th = (-g cos th + s c g sin th / l) / l` and `d th''/d th' = -2 s c th' / l`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(th), com = [0.0, -l], mass = m, inertia = 0.0, reaction)]
#[friction(along = th, mu = c, normal = reaction(arm_rx) * sin(th) - reaction(arm_ry) * cos(th))]
pub struct PinJ {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
}

#[test]
fn pin_friction_on_a_reaction_has_the_closed_form_sliding_jacobian() {
    let p = PinJ {
        m: 1.5,
        l: 0.8,
        g: 9.81,
        c: 0.1,
    };
    for (th, thd) in [(0.4, 1.3), (-0.2, -0.9), (1.0, -2.0)] {
        let s = f64::signum(thd);
        let a = linearize(&p, 0.0, &Vector::<2>::new(th, thd)).unwrap();
        let d_th = (-p.g * th.cos() + s * p.c * p.g * th.sin() / p.l) / p.l;
        let d_thd = -2.0 * s * p.c * thd / p.l;
        assert_eq!((a[(0, 0)], a[(0, 1)]), (0.0, 1.0));
        assert!(
            (a[(1, 0)] - d_th).abs() < 1e-12 * d_th.abs().max(1.0),
            "({th}, {thd}): {} vs {d_th}",
            a[(1, 0)]
        );
        assert!(
            (a[(1, 1)] - d_thd).abs() < 1e-12 * d_thd.abs().max(1.0),
            "({th}, {thd}): {} vs {d_thd}",
            a[(1, 1)]
        );
    }
}

/// A bead on a hoop of radius `R` spun about its vertical diameter by a drive
/// `ph = W t`; `th` is the bead's angle from the bottom.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, jacobian)]
#[gravity(0.0, 0.0, -g)]
#[coords(th)]
#[drive(ph = big_w * t)]
#[particle(bead, mass = m, at = [r * sin(th) * cos(ph), r * sin(th) * sin(ph), -r * cos(th)])]
pub struct Hoop {
    pub m: f64,
    pub r: f64,
    pub g: f64,
    pub big_w: f64,
}

/// `th'' = sin th (W^2 cos th - g / R)`, so the bottom is stable with `w^2 = g / R - W^2`
/// below the critical spin `W^2 = g / R`; above it the bottom diverges at
/// `sqrt(W^2 - g / R)` and the bead rests at `cos th0 = g / (R W^2)`, where
/// `d th''/d th = cos th0 (W^2 cos th0 - g / R) - W^2 sin^2 th0 = -W^2 sin^2 th0`:
/// `w^2 = W^2 sin^2 th0`.
#[test]
fn a_bead_on_a_spun_hoop_has_the_closed_form_frequencies_at_its_rest_points() {
    let slow = Hoop {
        m: 0.1,
        r: 0.5,
        g: 9.81,
        big_w: 3.0,
    };
    let w2 = slow.g / slow.r - slow.big_w * slow.big_w;
    let found = undamped_modes(&slow, 0.0, &Vector::<1>::zeros()).unwrap();
    assert!((found[0].omega_squared - w2).abs() < 1e-12 * w2);

    let fast = Hoop { big_w: 8.0, ..slow };
    let spin2 = fast.big_w * fast.big_w;
    let bottom = undamped_modes(&fast, 0.0, &Vector::<1>::zeros()).unwrap();
    let diverge = spin2 - fast.g / fast.r;
    assert!((bottom[0].omega_squared + diverge).abs() < 1e-12 * diverge);
    let th0 = (fast.g / (fast.r * spin2)).acos();
    for t in [0.0, 0.37] {
        let found = undamped_modes(&fast, t, &Vector::<1>::new(th0)).unwrap();
        let want = spin2 * th0.sin().powi(2);
        assert!(
            (found[0].omega_squared - want).abs() < 1e-12 * want,
            "t = {t}: {} vs {want}",
            found[0].omega_squared
        );
    }
    // Off its rest point the bead accelerates: refused, not a frequency.
    match undamped_modes(&fast, 0.0, &Vector::<1>::new(0.5 * th0)) {
        Err(Error::InvalidInput { detail, .. }) => {
            assert!(detail.contains("not an equilibrium"), "{detail}")
        }
        other => panic!("{other:?}"),
    }
}

/// A critically damped block (`c = 2 sqrt(k m)`): `lambda = -w` twice (a Jordan block),
/// `zeta = 1`. Rounding splits a defective double eigenvalue by `O(sqrt(eps) w)`, maybe
/// into a complex pair: the modes must still say `zeta = 1` and `w_n = w` to that
/// accuracy, and must not invent an oscillation.
#[test]
fn a_critically_damped_block_is_reported_with_unit_damping_ratio() {
    for (m, k) in [
        (2.0, 18.0),
        (0.7, 3.1),
        (1.3, 1e4),
        (5e-3, 0.37),
        (3.3, 0.011),
    ] {
        critical(m, k);
    }
}

fn critical(m: f64, k: f64) {
    let p = Pushed {
        m,
        k,
        c: 2.0 * (k * m).sqrt(),
        l0: 0.5,
        u: 0.0,
    };
    let w = (k / m).sqrt();
    let found = modes(&linearize(&p, 0.0, &Vector::<2>::new(p.l0, 0.0)).unwrap()).unwrap();
    let count: usize = found
        .iter()
        .map(|m| {
            if m.kind == ModeKind::Oscillatory {
                2
            } else {
                1
            }
        })
        .sum();
    assert_eq!(count, 2, "{found:?}");
    for m in &found {
        assert!((m.omega_n - w).abs() < 1e-6 * w, "{m:?}");
        assert!((m.damping_ratio.unwrap() - 1.0).abs() < 1e-6, "{m:?}");
        assert!(m.omega_d < 1e-6 * w, "{m:?}");
        assert!(!m.unstable);
    }
}

/// A puck held to the centre of a turntable by an isotropic spring `k` (zero rest length),
/// in coordinates `(u, v)` that turn with the table (`ph = W t`, a drive).
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(u, v)]
#[drive(ph = big_w * t)]
#[particle(puck, mass = m, at = [u * cos(ph) - v * sin(ph), u * sin(ph) + v * cos(ph)])]
#[potential(k * (u * u + v * v) / 2.0)]
pub struct Turntable {
    pub m: f64,
    pub k: f64,
    pub big_w: f64,
}

/// In the turning frame `z = u + i v` obeys `z'' + 2 i W z' + (w0^2 - W^2) z = 0`
/// (`w0^2 = k / m`; Coriolis and centrifugal terms), so `z = e^{s t}` with
/// `s = i (-W +- w0)`: the frequencies seen on the table are `|w0 - W|` and `w0 + W`,
/// undamped. The velocity terms are gyroscopic (skew), not damping: `undamped_modes`
/// cannot take them and must say so, and `modes` gives the two frequencies.
#[test]
fn a_puck_on_a_turntable_splits_its_frequency_by_the_spin() {
    let p = Turntable {
        m: 0.5,
        k: 8.0,
        big_w: 1.5,
    };
    let w0 = (p.k / p.m).sqrt();
    let found = modes(&linearize(&p, 0.3, &Vector::<4>::zeros()).unwrap()).unwrap();
    assert_eq!(found.len(), 2, "{found:?}");
    for (m, want) in found.iter().zip([w0 - p.big_w, w0 + p.big_w]) {
        assert_eq!(m.kind, ModeKind::Oscillatory);
        assert!(
            (m.omega_d - want).abs() < 1e-12 * want,
            "{} vs {want}",
            m.omega_d
        );
        assert!(m.damping_ratio.unwrap().abs() < 1e-12);
    }
    match undamped_modes(&p, 0.3, &Vector::<2>::zeros()) {
        Err(Error::InvalidInput { detail, .. }) => {
            assert!(detail.contains("gyroscopic"), "{detail}");
            assert!(detail.contains("`modes`"), "{detail}");
        }
        other => panic!("{other:?}"),
    }
}

/// The Cartesian pendulum pushed sideways at the bob by an input force `f`, its `x` as
/// output, for the state space in independent coordinates.
#[derive(Debug, Mechanism)]
#[mechanism(augmented, jacobian)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[constraint(x * x + y * y == l * l)]
#[particle(bob, mass = m, at = [x, y])]
#[generalized_force(push, along = x, value = f)]
#[input(f)]
#[output(sway = x)]
pub struct PushedCartesian {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub f: f64,
}

/// Hanging at rest, small swings `x = l q`: `m l q'' = -m g q + f`, so the receptance is
/// `x / f = 1 / (m (g / l - w^2))` (static gain `l / (m g)`), whatever basis the reduced
/// state uses.
#[test]
fn a_constrained_state_space_has_the_pendulum_receptance() {
    let p = PushedCartesian {
        m: 0.4,
        l: 1.3,
        g: 9.81,
        f: 0.0,
    };
    let (ss, t) = constrained_state_space(&p, 0.0, &Vector::<2>::new(0.0, -p.l)).unwrap();
    assert_eq!((ss.a.nrows(), t.nrows(), t.ncols()), (2, 4, 2));
    for w in [0.0, 1.0, 2.5, 7.0] {
        let g = ss.frequency_response(w).unwrap();
        let want = 1.0 / (p.m * (p.g / p.l - w * w));
        assert!(
            (g[(0, 0)] - Complex::new(want, 0.0)).norm() < 1e-12 * want.abs(),
            "w = {w}: {} vs {want}",
            g[(0, 0)]
        );
    }
}
