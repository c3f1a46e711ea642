//! The language's conveniences, each checked against a closed form written beside it:
//! vector outputs (components `p_x`, `p_y`, `p_z`); body-fixed points (`#[point(.., on =
//! body, ..)]`, `position(b, [..])`) as spring, damper and force ends on joint-tree bodies.

use mbd::Vector;
use mbd::prelude::*;

/// A planar pendulum as a tree body, its bob's position and velocity as vector outputs.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(q), com = [0.0, -l], mass = m)]
#[output(p = position(arm), v = velocity(arm), tip = position(arm, [0.0, -l / 2.0]))]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// A spatial particle: `position` has three components.
#[derive(Debug, Mechanism)]
#[gravity(0.0, 0.0, -g)]
#[coords(x, y, z)]
#[particle(ball, mass = m, at = [x, y, z])]
#[output(r = position(ball), speed = norm(velocity(ball)))]
pub struct Ball {
    pub m: f64,
    pub g: f64,
}

#[test]
fn vector_outputs_are_their_components() -> Result<(), mbd::Error> {
    assert_eq!(
        Pendulum::OUTPUTS,
        ["p_x", "p_y", "v_x", "v_y", "tip_x", "tip_y"]
    );
    let p = Pendulum {
        m: 1.5,
        l: 0.8,
        g: 9.81,
    };
    for (q, w) in [(0.3, -1.2), (-2.0, 0.7), (1.0, 0.0)] {
        let o = p.outputs(0.0, &Vector::<2>::new(q, w))?;
        // Closed form: the bob at l (sin q, -cos q), its velocity l w (cos q, sin q).
        let (s, c) = f64::sin_cos(q);
        let tol = 1e-15;
        assert!((o.p_x - p.l * s).abs() < tol && (o.p_y + p.l * c).abs() < tol);
        assert!((o.v_x - p.l * w * c).abs() < tol && (o.v_y - p.l * w * s).abs() < tol);
        assert!((o.tip_x - p.l / 2.0 * s).abs() < tol && (o.tip_y + p.l / 2.0 * c).abs() < tol);
        assert_eq!(p.output_values(0.0, &Vector::<2>::new(q, w))?[0], o.p_x);
    }
    let b = Ball { m: 2.0, g: 9.81 };
    assert_eq!(Ball::OUTPUTS, ["r_x", "r_y", "r_z", "speed"]);
    let y = Vector::<6>::from_column_slice(&[1.0, -2.0, 3.0, 3.0, 4.0, 12.0]);
    let o = b.outputs(0.0, &y)?;
    assert_eq!([o.r_x, o.r_y, o.r_z, o.speed], [1.0, -2.0, 3.0, 13.0]);
    Ok(())
}

/// A pendulum (point mass `m` at `l`) with a zero-length spring from the body-fixed point
/// `[e, -d]` (body frame, from the joint) to the ground point `A = (0, -c)`.
///
/// Independent derivation: the point is `P = R(q) [e, -d] = (e cos q + d sin q,
/// e sin q - d cos q)`, `|P - A|^2 = e^2 + d^2 + c^2 + 2 c (e sin q - d cos q)`, so the
/// spring's potential is `k c (e sin q - d cos q)` + const and
/// `m l^2 q'' = -m g l sin q - k c (d sin q + e cos q)`; equilibrium at
/// `tan q* = -k c e / (m g l + k c d)`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(q), com = [0.0, -l], mass = m)]
#[point(hook, on = arm, at = [e, -d])]
#[spring(s, from = hook, to = [0.0, -c], k = k)]
pub struct SprungPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub e: f64,
    pub d: f64,
    pub c: f64,
    pub k: f64,
}

/// A body turning about the ground's `z` (spatial tree, revolute about `z`), mass centre at
/// `[l, 0, 0]`, with a zero-length spring from the body-fixed point `[a, b, h]` to
/// `A = (c, 0, h)`, written with `position(b, [..])` as the spring's end.
///
/// Independent derivation: `P = (a cos q - b sin q, a sin q + b cos q, h)`,
/// `|P - A|^2 = a^2 + b^2 + c^2 - 2 c (a cos q - b sin q)`, so
/// `(m l^2 + izz) q'' = -k c (a sin q + b cos q)` (gravity along `z` does no work).
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(disc, joint = revolute(q, z), com = [l, 0.0, 0.0], mass = m, inertia = diag(ixx, iyy, izz))]
#[spring(s, from = position(disc, [a, b, h]), to = [c, 0.0, h], k = k)]
pub struct SprungTurntable {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub ixx: f64,
    pub iyy: f64,
    pub izz: f64,
    pub a: f64,
    pub b: f64,
    pub h: f64,
    pub c: f64,
    pub k: f64,
}

#[test]
fn body_fixed_spring_on_a_tree_body_matches_the_closed_form() -> Result<(), mbd::Error> {
    let p = SprungPendulum {
        m: 1.3,
        l: 0.9,
        g: 9.81,
        e: 0.2,
        d: 0.5,
        c: 1.4,
        k: 30.0,
    };
    for (q, w) in [(0.3, -1.2), (-2.0, 0.7), (1.0, 0.0)] {
        let qdd = p.acceleration(0.0, &Vector::<1>::new(q), &Vector::<1>::new(w))?[0];
        let (s, c) = f64::sin_cos(q);
        let want = (-p.m * p.g * p.l * s - p.k * p.c * (p.d * s + p.e * c)) / (p.m * p.l * p.l);
        assert!(
            (qdd - want).abs() < 1e-13 * want.abs().max(1.0),
            "{qdd} vs {want}"
        );
    }
    let q_eq = f64::atan(-p.k * p.c * p.e / (p.m * p.g * p.l + p.k * p.c * p.d));
    let at_rest = p.acceleration(0.0, &Vector::<1>::new(q_eq), &Vector::<1>::zeros())?[0];
    assert!(at_rest.abs() < 1e-13, "{at_rest}");

    let t = SprungTurntable {
        m: 2.0,
        l: 0.4,
        g: 9.81,
        ixx: 0.01,
        iyy: 0.02,
        // At most ixx + iyy (a disc's moments; 0.05 had no mass distribution, refused since).
        izz: 0.025,
        a: 0.3,
        b: -0.1,
        h: 0.25,
        c: 1.1,
        k: 12.0,
    };
    for (q, w) in [(0.3, -1.2), (-2.0, 0.7), (2.5, 3.0)] {
        let qdd = t.acceleration(0.0, &Vector::<1>::new(q), &Vector::<1>::new(w))?[0];
        let (s, c) = f64::sin_cos(q);
        let want = -t.k * t.c * (t.a * s + t.b * c) / (t.m * t.l * t.l + t.izz);
        assert!(
            (qdd - want).abs() < 1e-13 * want.abs().max(1.0),
            "{qdd} vs {want}"
        );
    }
    Ok(())
}

/// A double pendulum of tree bodies with a spring and a damper from a point of the second
/// link (`[e, -d]` in its frame) to the ground, and a force at another point of it.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(upper, joint = revolute(q1), com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[body(lower, parent = upper, joint = revolute(q2), at = [0.0, -l], com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
#[point(hook, on = lower, at = [e, -d])]
#[spring(s, from = hook, to = [c, 0.0], k = k, length = l0)]
#[damper(r, from = hook, to = [c, 0.0], c = b)]
#[force(push, at = position(lower, [0.0, -l]), value = [f, 0.0])]
pub struct SprungDouble {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub e: f64,
    pub d: f64,
    pub c: f64,
    pub k: f64,
    pub l0: f64,
    pub b: f64,
    pub f: f64,
}

/// The same written out in ground coordinates through the chain of rotations (the
/// independent derivation): rigid bodies at their mass centres, angles `q1`, `q1 + q2`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(q1, q2)]
#[point(knee, at = [l * sin(q1), -l * cos(q1)])]
#[rigid(upper, mass = m, inertia = m * l * l / 12.0, at = [l / 2.0 * sin(q1), -l / 2.0 * cos(q1)], angle = q1)]
#[rigid(lower, mass = m, inertia = m * l * l / 12.0, at = knee + [l / 2.0 * sin(q1 + q2), -l / 2.0 * cos(q1 + q2)], angle = q1 + q2)]
#[point(hook, at = knee + [e * cos(q1 + q2) + d * sin(q1 + q2), e * sin(q1 + q2) - d * cos(q1 + q2)])]
#[spring(s, from = hook, to = [c, 0.0], k = k, length = l0)]
#[damper(r, from = hook, to = [c, 0.0], c = b)]
#[force(push, at = knee + [l * sin(q1 + q2), -l * cos(q1 + q2)], value = [f, 0.0])]
pub struct SprungDoubleByHand {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub e: f64,
    pub d: f64,
    pub c: f64,
    pub k: f64,
    pub l0: f64,
    pub b: f64,
    pub f: f64,
}

#[test]
fn body_fixed_ends_deep_in_a_chain_match_the_written_out_model() -> Result<(), mbd::Error> {
    let (m, l, g, e, d, c, k, l0, b, f) = (1.1, 0.7, 9.81, 0.15, 0.4, 0.9, 25.0, 0.3, 0.8, 2.0);
    let tree = SprungDouble {
        m,
        l,
        g,
        e,
        d,
        c,
        k,
        l0,
        b,
        f,
    };
    let hand = SprungDoubleByHand {
        m,
        l,
        g,
        e,
        d,
        c,
        k,
        l0,
        b,
        f,
    };
    for (q, w) in [([0.3, -0.5], [1.0, -2.0]), ([2.0, 1.0], [-0.3, 0.4])] {
        let (q, w) = (Vector::<2>::from(q), Vector::<2>::from(w));
        let a = tree.acceleration(0.0, &q, &w)?;
        let r = hand.acceleration(0.0, &q, &w)?;
        assert!((a - r).norm() < 1e-12 * r.norm().max(1.0), "{a} vs {r}");
    }
    Ok(())
}
