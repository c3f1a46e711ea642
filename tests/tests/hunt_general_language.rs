//! Hunting language defects as a new user writing from the docs alone: body-fixed points of
//! a spatial tree body for a spring and a force, vector outputs at an offset, named
//! constants by every documented path, against closed forms written beside them.

use mbd::prelude::*;

/// A bar hinged about the ground `x` axis (`revolute(q, x)`: its frame is `rot_x(q)`), mass
/// centre `[0, 0, -l/2]`, moment `jx` about its centre along `x`. A zero-length spring
/// `k` from its body-fixed point `h = [0, d, -l]` to the ground point `(0, 0, -c)`, a force
/// `[0, fy, 0]` (ground frame) at the same point and a ground-frame torque `[tx, 1, 1]`.
///
/// By hand: `h(q) = rot_x(q) [0, d, -l] = (0, d cos q + l sin q, d sin q - l cos q)`, so
/// `|h - P|^2 = d^2 + l^2 + c^2 + 2 c (d sin q - l cos q)` and the spring's moment is
/// `-k c (d cos q + l sin q)`; gravity `V = -m g (l/2) cos q`; the force does
/// `fy dh_y/dq = fy (l cos q - d sin q)`; the torque about `x` is `tx` (its other
/// components load the bearing only). With `J = jx + m l^2 / 4`:
/// `J q'' = -k c (d cos q + l sin q) - m g (l/2) sin q + fy (l cos q - d sin q) + tx`.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(bar, joint = revolute(q, x), com = [0.0, 0.0, -l / 2.0], mass = m,
       inertia = diag(jx, jx, 1e-3))]
#[point(hook, on = bar, at = [0.0, d, -l])]
#[spring(s, from = hook, to = [0.0, 0.0, -c], k = k)]
#[force(pull, at = position(bar, [0.0, d, -l]), value = [0.0, fy, 0.0])]
#[torque(motor, on = bar, value = [tx, 1.0, 1.0])]
#[output(hv = velocity(bar, [0.0, d, -l]), ha = acceleration(bar, [0.0, d, -l]))]
#[output(w = angular_velocity(bar), reach = norm(hook))]
#[output(lever = cross(hook, [0.0, fy, 0.0])[0])]
pub struct Hinged {
    pub m: f64,
    pub l: f64,
    pub jx: f64,
    pub d: f64,
    pub c: f64,
    pub k: f64,
    pub fy: f64,
    pub tx: f64,
    pub g: f64,
}

const HINGED: Hinged = Hinged {
    m: 1.3,
    l: 0.8,
    jx: 0.05,
    d: 0.2,
    c: 0.5,
    k: 40.0,
    fy: 3.0,
    tx: 0.7,
    g: 9.81,
};

#[test]
fn body_fixed_points_of_a_spatial_tree_body_carry_a_spring_and_a_force() {
    let p = HINGED;
    let (l, d) = (p.l, p.d);
    for (q, qd) in [(0.0, 0.0), (0.6, -1.1), (-2.3, 2.0)] {
        let (s, co) = (f64::sin(q), f64::cos(q));
        let big_j = p.jx + p.m * l * l / 4.0;
        let qdd = (-p.k * p.c * (d * co + l * s) - p.m * p.g * l / 2.0 * s
            + p.fy * (l * co - d * s)
            + p.tx)
            / big_j;
        let acc = p
            .acceleration(0.0, &Vector::<1>::new(q), &Vector::<1>::new(qd))
            .unwrap()[0];
        assert!(
            (acc - qdd).abs() < 1e-12 * (1.0 + qdd.abs()),
            "q {q}: {acc} vs {qdd}"
        );
        // Velocity and acceleration of the body-fixed point, ground frame:
        // h' = (0, l cos q - d sin q, d cos q + l sin q) q', h'' = dh/dq q'' + d2h/dq2 q'^2.
        let out = p.outputs(0.0, &Vector::<2>::new(q, qd)).unwrap();
        let (dy, dz) = (l * co - d * s, d * co + l * s);
        let (ddy, ddz) = (-l * s - d * co, -d * s + l * co);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12 * (1.0 + b.abs());
        assert!(close(out.hv_x, 0.0) && close(out.hv_y, dy * qd) && close(out.hv_z, dz * qd));
        assert!(close(out.ha_x, 0.0));
        assert!(close(out.ha_y, dy * qdd + ddy * qd * qd));
        assert!(close(out.ha_z, dz * qdd + ddz * qd * qd));
        assert!(close(out.w_x, qd) && close(out.w_y, 0.0) && close(out.w_z, 0.0));
        assert!(close(out.reach, (d * d + l * l).sqrt()));
        // (h x F)_x = h_y F_z - h_z F_y = -(d sin q - l cos q) fy.
        assert!(close(out.lever, -(d * s - l * co) * p.fy));
    }
    assert_eq!(
        Hinged::OUTPUTS,
        [
            "hv_x", "hv_y", "hv_z", "ha_x", "ha_y", "ha_z", "w_x", "w_y", "w_z", "reach", "lever"
        ]
    );
}

/// Every documented path to a named constant, in a body's `at`, a drive law, `init` and an
/// output: a bead on a rod turned at `w` about a pivot at `(cos(pi/3), sin(pi/3))`.
#[derive(Debug, Mechanism)]
#[drive(th = w * t + std::f64::consts::FRAC_PI_4)]
#[body(rod, joint = revolute(th), at = [core::f64::consts::FRAC_PI_3.cos(), consts::FRAC_PI_3.sin()],
       mass = 1.0, inertia = 0.1)]
#[body(bead, parent = rod, joint = prismatic(s, [1.0, 0.0]), mass = m)]
#[init(s = f64::consts::SQRT_2, der(s) = FRAC_1_SQRT_2)]
#[output(tau = TAU, e = std::f64::consts::E, ln2 = LN_2.exp())]
pub struct Constants {
    pub m: f64,
    pub w: f64,
}

#[test]
fn named_constants_by_every_documented_path_mean_std_values() {
    use std::f64::consts as c;
    let p = Constants { m: 0.4, w: 2.0 };
    let y0 = p.initial_state();
    assert_eq!(y0[0], c::SQRT_2);
    assert_eq!(y0[1], c::FRAC_1_SQRT_2);
    let out = p.outputs(0.0, &y0).unwrap();
    assert_eq!((out.tau, out.e), (c::TAU, c::E));
    assert!((out.ln2 - 2.0).abs() < 1e-15);
    // Along the turning rod, free of gravity: s'' = w^2 s (the drive's phase and the
    // pivot's place do not enter).
    let acc = p
        .acceleration(0.3, &Vector::<1>::new(0.9), &Vector::<1>::new(0.5))
        .unwrap()[0];
    assert!((acc - 4.0 * 0.9).abs() < 1e-14, "{acc}");
}
