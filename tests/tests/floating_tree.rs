//! A floating base with revolute appendages (`joint = free(..)` at the root of a spatial
//! tree), against a reference written here without the derive: Kane's equations in the
//! generalised speeds `u = (p', w, qa', qb', qc')` (`w` the base's angular velocity in world
//! axes), each body's mass-centre and angular Jacobians written from the joint axes, the
//! velocity-product accelerations from a forward pass at `u' = 0`:
//! `M_u = sum m Jv^T Jv + Jw^T I Jw`, `f_u = sum Jv^T m (g - a0) - Jw^T (I al0 + w x I w)`.
//! The base's `u'` gives the joint's coordinates' accelerations by
//! `sigma'' = (B R^T w' + B' W) / 4` (`W = R^T w`, body axes; `(R^T)' w = -W x W = 0`).
//! Then, without gravity: total linear and angular momentum (by hand from the positions and
//! velocities) conserved over many turns of the base; the chart's switch leaves positions,
//! velocities and accelerations where they were; a free joint that is not at the root.

use mbd::integrate::{Dopri5, Integrator, Options, Radau5, Vern9};
use mbd::prelude::*;
use mbd::{Matrix, Vector};

#[path = "support/floating.rs"]
mod floating;
use floating::{Part, momenta, mrp_b, mrp_b_dot, mrp_rotation, pass, reference};

type M3 = Matrix<3, 3>;
type V3 = Vector<3>;

/// A base (12 kg, full inertia, mass centre off its joint origin, which starts at `at`), an
/// arm on a `z` hinge, and a two-link arm on `y` and `x` hinges: 9 degrees of freedom.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(base, joint = free(x, y, z, s1, s2, s3), at = [0.0, 0.0, 1.0], com = [0.02, -0.01, 0.03],
       mass = 12.0, inertia = [[0.5, 0.02, -0.01], [0.02, 0.7, 0.03], [-0.01, 0.03, 0.4]])]
#[body(arm_a, parent = base, joint = revolute(qa, z), at = [0.3, 0.1, 0.0],
       com = [0.2, 0.0, 0.05], mass = 1.5, inertia = [[0.004, 0.001, 0.0], [0.001, 0.02, 0.0], [0.0, 0.0, 0.021]])]
#[body(arm_b, parent = base, joint = revolute(qb, y), at = [-0.2, 0.0, 0.25],
       com = [0.0, 0.05, 0.3], mass = 1.0, inertia = diag(0.03, 0.03, 0.002))]
#[body(hand, parent = arm_b, joint = revolute(qc, x), at = [0.0, 0.0, 0.5],
       com = [0.05, 0.0, 0.1], mass = 0.5, inertia = diag(0.002, 0.003, 0.001))]
#[output(tip = position(hand, [0.0, 0.1, 0.2]), tip_v = velocity(hand, [0.0, 0.1, 0.2]),
         hand_w = angular_velocity(hand))]
pub struct Floater {
    pub g: f64,
}

/// The floater's bodies, typed again from the attributes above (the base first).
fn parts() -> Vec<Part> {
    let d = |a: f64, b: f64, c: f64| M3::from_diagonal(&V3::new(a, b, c));
    vec![
        Part {
            parent: None,
            axis: 0,
            coord: 0,
            at: [0.0, 0.0, 1.0],
            com: [0.02, -0.01, 0.03],
            mass: 12.0,
            inertia: M3::new(0.5, 0.02, -0.01, 0.02, 0.7, 0.03, -0.01, 0.03, 0.4),
        },
        Part {
            parent: Some(0),
            axis: 2,
            coord: 6,
            at: [0.3, 0.1, 0.0],
            com: [0.2, 0.0, 0.05],
            mass: 1.5,
            inertia: M3::new(0.004, 0.001, 0.0, 0.001, 0.02, 0.0, 0.0, 0.0, 0.021),
        },
        Part {
            parent: Some(0),
            axis: 1,
            coord: 7,
            at: [-0.2, 0.0, 0.25],
            com: [0.0, 0.05, 0.3],
            mass: 1.0,
            inertia: d(0.03, 0.03, 0.002),
        },
        Part {
            parent: Some(2),
            axis: 0,
            coord: 8,
            at: [0.0, 0.0, 0.5],
            com: [0.05, 0.0, 0.1],
            mass: 0.5,
            inertia: d(0.002, 0.003, 0.001),
        },
    ]
}

fn sample(seed: f64) -> Vector<18> {
    Vector::<18>::from_fn(|i, _| {
        let x = (1.3 * i as f64 + seed).sin();
        if (3..6).contains(&i) {
            0.55 * x
        } else {
            1.5 * x
        }
    })
}

#[test]
fn floating_base_accelerations_equal_kane_by_hand() {
    assert_eq!(
        Floater::COORDINATES,
        ["x", "y", "z", "s1", "s2", "s3", "qa", "qb", "qc"]
    );
    assert!(Floater::GENERATED.parts.contains(&"articulated_body"));
    let parts = parts();
    for g in [0.0, 9.81] {
        let p = Floater { g };
        for seed in [0.0, 0.4, 1.7, 2.9, 4.2] {
            let y = sample(seed);
            let (q, qd) = (
                y.fixed_rows::<9>(0).into_owned(),
                y.fixed_rows::<9>(9).into_owned(),
            );
            let got = p.acceleration(0.0, &q, &qd).unwrap();
            let want = reference(&parts, g, q.as_slice(), qd.as_slice());
            let scale = want.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
            for k in 0..9 {
                assert!(
                    (got[k] - want[k]).abs() < 1e-11 * scale,
                    "g = {g}, seed {seed}: {} = {} against {} by hand",
                    Floater::COORDINATES[k],
                    got[k],
                    want[k]
                );
            }
            // Outputs: the hand's point and its velocity, the hand's angular velocity.
            let o = p.outputs(0.0, &y).unwrap();
            let f = pass(&parts, q.as_slice(), qd.as_slice());
            let arm = f.r[3] * V3::new(0.0, 0.1, 0.2);
            assert!((V3::new(o.tip_x, o.tip_y, o.tip_z) - (f.o[3] + arm)).norm() < 1e-13);
            let v = f.v[3] + f.w[3].cross(&arm);
            assert!(
                (V3::new(o.tip_v_x, o.tip_v_y, o.tip_v_z) - v).norm() < 1e-12 * v.norm().max(1.0)
            );
            assert!(
                (V3::new(o.hand_w_x, o.hand_w_y, o.hand_w_z) - f.w[3]).norm()
                    < 1e-12 * f.w[3].norm().max(1.0)
            );
            // The energy is the kinetic energy by hand plus gravity's potential.
            let (_, _, t) = momenta(&parts, &y.as_slice()[..9], &y.as_slice()[9..]);
            let v_grav: f64 = (0..4)
                .map(|b| {
                    let c = f.o[b] + f.r[b] * V3::from(parts[b].com);
                    parts[b].mass * g * c[2]
                })
                .sum();
            let e = p.energy(0.0, &q, &qd).unwrap();
            assert!((e - t - v_grav).abs() < 1e-12 * (t + v_grav.abs()));
        }
    }
}

fn tight(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Default::default()
    }
}

/// Without gravity the whole system's momenta stay where they started (the base tumbling
/// through many chart switches, the arms swinging): 1e-10 relative over 20 s, DOPRI5,
/// Vern9 and Radau5 at 1e-12/1e-13; every accepted state inside the unit ball.
#[test]
fn floating_base_conserves_linear_and_angular_momentum() {
    let (parts, p) = (parts(), Floater { g: 0.0 });
    let mut y0 = sample(0.9);
    // Spin the base hard enough to switch charts several times.
    for k in 12..15 {
        y0[k] *= 2.0;
    }
    let (l0, h0, t0) = momenta(&parts, &y0.as_slice()[..9], &y0.as_slice()[9..]);
    assert!(l0.norm() > 1.0 && h0.norm() > 1.0, "{l0:?} {h0:?}");
    let t1 = 20.0;
    for (name, sol) in [
        (
            "DOPRI5",
            Dopri5::new(tight(1e-13)).solve(&p, 0.0, y0, t1, &[]),
        ),
        (
            "Vern9",
            Vern9::new(tight(1e-13)).solve(&p, 0.0, y0, t1, &[]),
        ),
        (
            "Radau5",
            Radau5::new(tight(1e-12)).solve(&p, 0.0, y0, t1, &[]),
        ),
    ] {
        let sol = sol.unwrap();
        let mut switches = 0;
        for (k, (t, y)) in sol.t.iter().zip(&sol.y).enumerate() {
            let (l, h, e) = momenta(&parts, &y.as_slice()[..9], &y.as_slice()[9..]);
            assert!((l - l0).norm() < 1e-10 * l0.norm(), "{name} t = {t}: {l:?}");
            assert!((h - h0).norm() < 1e-10 * h0.norm(), "{name} t = {t}: {h:?}");
            assert!(
                (e - t0).abs() < 1e-10 * t0,
                "{name} t = {t}: T {e} against {t0}"
            );
            let sigma = y.fixed_rows::<3>(3);
            assert!(sigma.norm() <= 1.0);
            if k > 0 && (sigma - sol.y[k - 1].fixed_rows::<3>(3)).norm() > 1.0 {
                switches += 1;
            }
        }
        assert!(switches >= 3, "{name}: {switches} switches");
    }
}

/// The switch to the shadow set (`OdeSystem::project`, what the integrators call after
/// each accepted step) changes the base's parameters and their rates, and nothing else:
/// every body's position, velocity and acceleration, by hand from the two states and the
/// model's accelerations, is the same on both sides.
#[test]
fn the_chart_switch_moves_nothing() {
    let (parts, p) = (parts(), Floater { g: 9.81 });
    let mut y = sample(2.2);
    // A rotation past a half turn: |sigma| > 1.
    for k in 3..6 {
        y[k] *= 2.5;
    }
    assert!(y.fixed_rows::<3>(3).norm() > 1.0);
    let mut shadowed = y;
    OdeSystem::project(&p, 0.0, &mut shadowed).unwrap();
    assert!(shadowed.fixed_rows::<3>(3).norm() < 1.0);
    let changed: Vec<usize> = (0..18).filter(|&i| shadowed[i] != y[i]).collect();
    assert_eq!(changed, vec![3, 4, 5, 12, 13, 14]);
    let kin = |y: &Vector<18>| {
        let (q, qd) = (&y.as_slice()[..9], &y.as_slice()[9..]);
        let f = pass(&parts, q, qd);
        let acc = p.rhs(0.0, y).unwrap();
        // The base's body-axes angular acceleration from sigma'': W' = 4 B^-1 (sigma'' -
        // B' W / 4), B^-1 = B^T / (1 + s2)^2.
        let s = V3::new(q[3], q[4], q[5]);
        let sd = V3::new(qd[3], qd[4], qd[5]);
        let sdd = V3::new(acc[12], acc[13], acc[14]);
        let w_body = f.r[0].transpose() * f.w[0];
        let wd = 4.0 * mrp_b(&s).transpose() * (sdd - mrp_b_dot(&s, &sd) * w_body / 4.0)
            / (1.0 + s.norm_squared()).powi(2);
        let al = f.r[0] * wd;
        (f, al, acc)
    };
    let ((a, al_a, acc_a), (b, al_b, acc_b)) = (kin(&y), kin(&shadowed));
    for i in 0..4 {
        assert!((a.r[i] - b.r[i]).norm() < 1e-14);
        assert!((a.o[i] - b.o[i]).norm() < 1e-14);
        assert!((a.w[i] - b.w[i]).norm() < 1e-13);
        assert!((a.v[i] - b.v[i]).norm() < 1e-13);
    }
    assert!(
        (al_a - al_b).norm() < 1e-12 * al_a.norm(),
        "{al_a:?} {al_b:?}"
    );
    for k in [9, 10, 11, 15, 16, 17] {
        assert!((acc_a[k] - acc_b[k]).abs() < 1e-12 * acc_a.amax(), "{k}");
    }
}

/// A free joint below a moving body (a drone hovering off a swinging arm: free relative to
/// the arm's frame), and a free joint whose translation is driven: the recursion equals the
/// mass-matrix form (Kane's projections) of the same model; the undriven one conserves its
/// energy under gravity (1e-10 over 2 s, the drone falling some 20 m off the arm); the
/// driven one equals Euler's equation about its moving joint origin by hand.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, recursive)]
#[gravity(0.0, 0.0, -g)]
#[body(arm, joint = revolute(th, y), at = [0.0, 0.0, 1.0], com = [0.3, 0.0, 0.0], mass = 2.0,
       inertia = diag(0.01, 0.08, 0.08))]
#[body(drone, parent = arm, joint = free(dx, dy, dz, r1, r2, r3), at = [0.6, 0.0, 0.0],
       com = [0.0, 0.02, -0.03], mass = 0.7, inertia = [[0.01, 0.001, 0.0], [0.001, 0.012, 0.002], [0.0, 0.002, 0.02]])]
pub struct Hover {
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(arm, joint = revolute(th, y), at = [0.0, 0.0, 1.0], com = [0.3, 0.0, 0.0], mass = 2.0,
       inertia = diag(0.01, 0.08, 0.08))]
#[body(drone, parent = arm, joint = free(dx, dy, dz, r1, r2, r3), at = [0.6, 0.0, 0.0],
       com = [0.0, 0.02, -0.03], mass = 0.7, inertia = [[0.01, 0.001, 0.0], [0.001, 0.012, 0.002], [0.0, 0.002, 0.02]])]
pub struct HoverKane {
    pub g: f64,
}

/// The base's origin driven along a circle in the ground's `x`-`y` plane, its rotation free.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, recursive)]
#[gravity(0.0, 0.0, -g)]
#[drive(bx = 0.5 * cos(2.0 * t))]
#[drive(by = 0.5 * sin(2.0 * t))]
#[drive(bz = 0.0)]
#[body(carried, joint = free(bx, by, bz, c1, c2, c3), com = [0.1, 0.0, -0.2], mass = 1.0,
       inertia = [[0.02, 0.0, 0.001], [0.0, 0.03, 0.0], [0.001, 0.0, 0.01]])]
pub struct Carried {
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[drive(bx = 0.5 * cos(2.0 * t))]
#[drive(by = 0.5 * sin(2.0 * t))]
#[drive(bz = 0.0)]
#[body(carried, joint = free(bx, by, bz, c1, c2, c3), com = [0.1, 0.0, -0.2], mass = 1.0,
       inertia = [[0.02, 0.0, 0.001], [0.0, 0.03, 0.0], [0.001, 0.0, 0.01]])]
pub struct CarriedKane {
    pub g: f64,
}

#[test]
fn a_free_joint_off_the_root_and_a_driven_free_joint_equal_their_mass_matrix_forms() {
    let (h, hk) = (Hover { g: 9.81 }, HoverKane { g: 9.81 });
    assert_eq!(Hover::COORDINATES.len(), 7);
    for seed in [0.0, 1.1, 2.3] {
        let q = Vector::<7>::from_fn(|i, _| 0.6 * (0.9 * i as f64 + seed).sin());
        let qd = Vector::<7>::from_fn(|i, _| 1.2 * (0.7 * i as f64 - seed).cos());
        let (a, b) = (
            h.acceleration(0.0, &q, &qd).unwrap(),
            hk.acceleration(0.0, &q, &qd).unwrap(),
        );
        assert!((a - b).amax() < 1e-11 * b.amax(), "{a:?} {b:?}");
    }
    let y0 = Vector::<14>::from_fn(|i, _| 0.4 * (1.7 * i as f64).sin());
    let e = |y: &Vector<14>| {
        let (q, qd) = (
            y.fixed_rows::<7>(0).into_owned(),
            y.fixed_rows::<7>(7).into_owned(),
        );
        h.energy(0.0, &q, &qd).unwrap()
    };
    let sol = Dopri5::new(tight(1e-12))
        .solve(&h, 0.0, y0, 2.0, &[])
        .unwrap();
    for y in &sol.y {
        assert!(
            (e(y) - e(&y0)).abs() < 1e-10 * e(&y0).abs(),
            "{} {}",
            e(y),
            e(&y0)
        );
    }

    let (c, ck) = (Carried { g: 9.81 }, CarriedKane { g: 9.81 });
    assert_eq!(Carried::COORDINATES, ["c1", "c2", "c3"]);
    for t in [0.0, 0.3, 1.4] {
        let q = Vector::<3>::new(0.2, -0.4, 0.3);
        let qd = Vector::<3>::new(1.0, 0.5, -2.0);
        let (a, b) = (
            c.acceleration(t, &q, &qd).unwrap(),
            ck.acceleration(t, &q, &qd).unwrap(),
        );
        assert!((a - b).amax() < 1e-11 * b.amax(), "{a:?} {b:?}");
        let want = carried_by_hand(t, &q, &qd, 9.81);
        assert!((a - want).amax() < 1e-12 * want.amax(), "{a:?} {want:?}");
    }
}

/// The carried body by hand: about its joint origin `O`, whose acceleration `a_O` is the
/// drive's `(-2 sin 2t, 2 cos 2t, 0)' = -4 (0.5 cos 2t, 0.5 sin 2t, 0)`, Euler's equation in
/// body axes reads `I_O W' + W x I_O W = m c x R^T (g - a_O)` with
/// `I_O = I_c + m (|c|^2 1 - c c^T)`; then `sigma'' = (B W' + B' W) / 4`.
fn carried_by_hand(t: f64, q: &Vector<3>, qd: &Vector<3>, g: f64) -> Vector<3> {
    let (m, c) = (1.0, V3::new(0.1, 0.0, -0.2));
    let ic = M3::new(0.02, 0.0, 0.001, 0.0, 0.03, 0.0, 0.001, 0.0, 0.01);
    let io = ic + m * (c.norm_squared() * M3::identity() - c * c.transpose());
    let r = mrp_rotation(q);
    let w = 4.0 * mrp_b(q).transpose() * qd / (1.0 + q.norm_squared()).powi(2);
    let a_o = -4.0 * V3::new(0.5 * (2.0 * t).cos(), 0.5 * (2.0 * t).sin(), 0.0);
    let torque = m * c.cross(&(r.transpose() * (V3::new(0.0, 0.0, -g) - a_o)));
    let wd = io.try_inverse().unwrap() * (torque - w.cross(&(io * w)));
    (mrp_b(q) * wd + mrp_b_dot(q, qd) * w) / 4.0
}
