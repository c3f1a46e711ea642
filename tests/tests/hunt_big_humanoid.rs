//! Hunting big-model defects: a 30-dof spatial humanoid-like tree (a torso on a spherical
//! joint on a stand, a head, two arms and two legs of spherical, revolute and universal
//! joints, full inertia tensors and offset mass centres), its articulated-body recursion
//! against an independent reference written here: every joint split into elementary hinges,
//! the mass matrix from the bodies' Jacobians and the bias from the velocity-product
//! accelerations (Kane's form, `M qdd = sum J^T (F - m a0)`), and the energy of a long
//! tumbling run from that reference's own `T + V`.

use mbd::integrate::{Dop853, Integrator};
use mbd::nalgebra::{Matrix3, Vector3};
use mbd::prelude::*;

#[path = "support/hinges.rs"]
mod hinges;
#[path = "support/humanoid.rs"]
mod humanoid;
use hinges::{Hinge, frames, joint, order, reference, to_hinges};
use humanoid::Humanoid;

/// The humanoid above, hinge by hinge (the same numbers, typed again).
fn hinges() -> Vec<Hinge> {
    let d = |a: f64, b: f64, c: f64| Matrix3::from_diagonal(&Vector3::new(a, b, c));
    let (x, y, z) = (0, 1, 2);
    let mut h = Vec::new();
    let torso_i = Matrix3::new(0.6, 0.01, 0.02, 0.01, 0.5, 0.03, 0.02, 0.03, 0.2);
    let sph = |a: &str, b: &str, c: &str| [(z, a.into()), (y, b.into()), (x, c.into())];
    let one = |axis: usize, a: &str| [(axis, a.to_string())];
    let two = |a: &str, b: &str| [(x, a.into()), (y, b.into())];
    let torso = joint(
        &mut h,
        None,
        [0.0, 0.0, 1.0],
        &sph("t1", "t2", "t3"),
        20.0,
        [0.0, 0.01, 0.25],
        torso_i,
    );
    joint(
        &mut h,
        Some(torso),
        [0.0, 0.0, 0.5],
        &sph("h1", "h2", "h3"),
        5.0,
        [0.01, 0.0, 0.1],
        d(0.03, 0.03, 0.02),
    );
    type Names = [&'static str; 6];
    let arms: [(f64, Names); 2] = [
        (1.0, ["sl1", "sl2", "sl3", "el", "wl1", "wl2"]),
        (-1.0, ["sr1", "sr2", "sr3", "er", "wr1", "wr2"]),
    ];
    for (side, n) in arms {
        let arm = joint(
            &mut h,
            Some(torso),
            [0.0, 0.2 * side, 0.45],
            &sph(n[0], n[1], n[2]),
            2.0,
            [0.0, 0.02 * side, -0.15],
            d(0.02, 0.02, 0.004),
        );
        let fore = joint(
            &mut h,
            Some(arm),
            [0.0, 0.0, -0.3],
            &one(y, n[3]),
            1.2,
            [0.0, 0.0, -0.12],
            d(0.01, 0.01, 0.002),
        );
        joint(
            &mut h,
            Some(fore),
            [0.0, 0.0, -0.25],
            &two(n[4], n[5]),
            0.4,
            [0.01, 0.0, -0.05],
            d(0.001, 0.0012, 0.0005),
        );
    }
    let legs: [(f64, Names); 2] = [
        (1.0, ["hl1", "hl2", "hl3", "kl", "al1", "al2"]),
        (-1.0, ["hr1", "hr2", "hr3", "kr", "ar1", "ar2"]),
    ];
    for (side, n) in legs {
        let thigh = joint(
            &mut h,
            Some(torso),
            [0.0, 0.1 * side, -0.05],
            &sph(n[0], n[1], n[2]),
            8.0,
            [0.0, 0.0, -0.2],
            d(0.15, 0.15, 0.03),
        );
        let shank = joint(
            &mut h,
            Some(thigh),
            [0.0, 0.0, -0.45],
            &one(y, n[3]),
            3.5,
            [0.0, 0.0, -0.2],
            d(0.05, 0.05, 0.006),
        );
        joint(
            &mut h,
            Some(shank),
            [0.0, 0.0, -0.42],
            &two(n[4], n[5]),
            1.0,
            [0.05, 0.0, -0.04],
            d(0.002, 0.005, 0.005),
        );
    }
    h
}

/// A spread of states: every Euler pitch inside `(-1, 1)` rad, away from gimbal lock.
fn state(seed: f64) -> (Vector<30>, Vector<30>) {
    let q = Vector::<30>::from_fn(|i, _| 0.9 * (1.7 * i as f64 + seed).sin());
    let qd = Vector::<30>::from_fn(|i, _| 2.5 * (0.8 * i as f64 - 2.0 * seed).cos());
    (q, qd)
}

#[test]
fn a_thirty_dof_humanoid_tree_equals_its_hand_written_jacobian_form() {
    assert_eq!(Humanoid::COORDINATES.len(), 30);
    assert!(Humanoid::GENERATED.parts.contains(&"articulated_body"));
    let (p, h) = (Humanoid { g: 9.81 }, hinges());
    let perm = order(&h, &Humanoid::COORDINATES);
    for seed in [0.0, 0.7, 1.9, 3.1] {
        let (q, qd) = state(seed);
        let acc = p.acceleration(0.0, &q, &qd).unwrap();
        let (qh, qdh) = (
            to_hinges(&perm, q.as_slice()),
            to_hinges(&perm, qd.as_slice()),
        );
        let (m, f, _) = reference(&h, p.g, &qh, &qdh);
        let want = m
            .clone()
            .cholesky()
            .expect("a positive definite mass matrix")
            .solve(&f);
        let scale = want.amax();
        for (k, &i) in perm.iter().enumerate() {
            assert!(
                (acc[k] - want[i]).abs() < 1e-10 * scale,
                "seed {seed}: {} = {} against {} by hand",
                Humanoid::COORDINATES[k],
                acc[k],
                want[i]
            );
        }
        // The model's own mass matrix is the reference's, entry by entry.
        let mm = p.mass_matrix(0.0, &q).unwrap();
        for (k, &i) in perm.iter().enumerate() {
            for (l, &j) in perm.iter().enumerate() {
                assert!(
                    (mm[(k, l)] - m[(i, j)]).abs() < 1e-12 * m.amax(),
                    "M[{k},{l}]"
                );
            }
        }
    }
}

#[test]
fn the_tumbling_humanoid_keeps_the_energy_of_the_hand_written_reference() {
    let (p, h) = (Humanoid { g: 9.81 }, hinges());
    let perm = order(&h, &Humanoid::COORDINATES);
    // Moderate angles and rates: the limbs swing through large motions without reaching
    // an Euler pitch of pi/2 in the second run.
    let q0 = Vector::<30>::from_fn(|i, _| 0.3 * (1.7 * i as f64).sin());
    let qd0 = Vector::<30>::from_fn(|i, _| 1.0 * (0.8 * i as f64).cos());
    let mut y0 = Vector::<60>::zeros();
    y0.fixed_rows_mut::<30>(0).copy_from(&q0);
    y0.fixed_rows_mut::<30>(30).copy_from(&qd0);
    let energy = |y: &Vector<60>| {
        let (q, qd) = (y.fixed_rows::<30>(0), y.fixed_rows::<30>(30));
        let qh = to_hinges(&perm, q.as_slice());
        let qdh = to_hinges(&perm, qd.as_slice());
        reference(&h, p.g, &qh, &qdh).2
    };
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let sol = Dop853::new(opts).solve(&p, 0.0, y0, 1.0, &[]).unwrap();
    let y1 = sol.last().1;
    let (e0, e1) = (energy(&y0), energy(y1));
    assert!((e1 - e0).abs() < 1e-8 * e0.abs(), "energy {e0} -> {e1}");
    assert!((y1 - y0).fixed_rows::<30>(0).amax() > 0.3, "it moved");
}

/// A point `d` (body frame) of the body on hinge `b`: position, velocity and acceleration
/// (with the hinges' accelerations `qdd`), `p = o + R d`, `v = v_o + w x (R d)`,
/// `a = a0 + al x (R d) + w x (w x R d) + sum_j (u_j x (p - o_j)) qdd_j` over the ancestors.
fn point(h: &[Hinge], f: &hinges::Frames, b: usize, d: [f64; 3], qdd: &[f64]) -> [Vector3<f64>; 3] {
    let rd = f.r[b] * Vector3::from(d);
    let p = f.o[b] + rd;
    let mut a = f.a[b] + f.al[b].cross(&rd) + f.w[b].cross(&f.w[b].cross(&rd));
    let mut j = Some(b);
    while let Some(i) = j {
        a += f.u[i].cross(&(p - f.o[i])) * qdd[i];
        j = h[i].parent;
    }
    [p, f.v[b] + f.w[b].cross(&rd), a]
}

/// The outputs (body points, angular velocity and acceleration) and the generated inverse
/// dynamics against the reference's kinematics and `M qdd - f`.
#[test]
fn the_humanoids_outputs_and_inverse_dynamics_equal_the_reference() {
    let (p, h) = (Humanoid { g: 9.81 }, hinges());
    let perm = order(&h, &Humanoid::COORDINATES);
    let body = |c: &str| h.iter().position(|x| x.coord == c).unwrap();
    let (hand, foot, head) = (body("wl2"), body("ar2"), body("h3"));
    let close = |a: f64, b: f64, what: &str| {
        assert!(
            (a - b).abs() < 1e-10 * b.abs().max(1.0),
            "{what}: {a} against {b}"
        )
    };
    for seed in [0.3, 2.2] {
        let (q, qd) = state(seed);
        let (qh, qdh) = (
            to_hinges(&perm, q.as_slice()),
            to_hinges(&perm, qd.as_slice()),
        );
        let (m, f, _) = reference(&h, p.g, &qh, &qdh);
        let qdd = m.clone().cholesky().unwrap().solve(&f);
        let fr = frames(&h, &qh, &qdh);
        let mut y = Vector::<60>::zeros();
        y.fixed_rows_mut::<30>(0).copy_from(&q);
        y.fixed_rows_mut::<30>(30).copy_from(&qd);
        let o = p.outputs(0.0, &y).unwrap();
        let [tip, tip_v, tip_a] = point(&h, &fr, hand, [0.0, 0.0, -0.1], qdd.as_slice());
        let [_, toe_v, _] = point(&h, &fr, foot, [0.1, 0.0, -0.05], qdd.as_slice());
        let mut head_alpha = fr.al[head];
        let mut j = Some(head);
        while let Some(i) = j {
            head_alpha += fr.u[i] * qdd[i];
            j = h[i].parent;
        }
        for (got, want, what) in [
            ([o.tip_x, o.tip_y, o.tip_z], tip, "tip"),
            ([o.tip_v_x, o.tip_v_y, o.tip_v_z], tip_v, "tip_v"),
            ([o.tip_a_x, o.tip_a_y, o.tip_a_z], tip_a, "tip_a"),
            ([o.toe_v_x, o.toe_v_y, o.toe_v_z], toe_v, "toe_v"),
            ([o.foot_w_x, o.foot_w_y, o.foot_w_z], fr.w[foot], "foot_w"),
            (
                [o.head_alpha_x, o.head_alpha_y, o.head_alpha_z],
                head_alpha,
                "head_alpha",
            ),
        ] {
            for k in 0..3 {
                close(got[k], want[k], what);
            }
        }
        // Inverse dynamics at accelerations other than the free ones: M qdd - f.
        let qdd_any = Vector::<30>::from_fn(|i, _| 3.0 * (2.1 * i as f64 + seed).sin());
        let tau = p.inverse_dynamics(0.0, &q, &qd, &qdd_any).unwrap();
        let want = &m
            * mbd::nalgebra::DVector::from_column_slice(&to_hinges(&perm, qdd_any.as_slice()))
            - &f;
        for (k, &i) in perm.iter().enumerate() {
            close(
                tau[k] / want.amax(),
                want[i] / want.amax(),
                Humanoid::COORDINATES[k],
            );
        }
    }
}

/// A non-finite parameter or state is a typed error from every evaluation and method of the
/// big tree, never a NaN handed back.
#[test]
fn non_finite_inputs_to_the_humanoid_are_typed_errors() {
    let (q, qd) = state(0.4);
    let mut y = Vector::<60>::zeros();
    y.fixed_rows_mut::<30>(0).copy_from(&q);
    y.fixed_rows_mut::<30>(30).copy_from(&qd);
    for g in [f64::NAN, f64::INFINITY] {
        let p = Humanoid { g };
        for r in [
            p.check_parameters().err(),
            p.acceleration(0.0, &q, &qd).err(),
            p.rhs(0.0, &y).err(),
        ] {
            assert!(
                matches!(r, Some(Error::InvalidParameter { .. })),
                "g = {g}: {r:?}"
            );
        }
        let run = mbd::integrate::Dopri5::default().solve(&p, 0.0, y, 1.0, &[]);
        assert!(
            matches!(run, Err(Error::InvalidParameter { .. })),
            "{run:?}"
        );
    }
    let p = Humanoid { g: 9.81 };
    let mut bad = y;
    bad[40] = f64::NAN;
    let r = p.rhs(0.0, &bad);
    assert!(r.is_err(), "{r:?}");
    let (qb, qdb) = (
        bad.fixed_rows::<30>(0).into_owned(),
        bad.fixed_rows::<30>(30).into_owned(),
    );
    assert!(p.acceleration(0.0, &qb, &qdb).is_err());
    for run in [
        mbd::integrate::Dopri5::default().solve(&p, 0.0, bad, 1.0, &[]),
        mbd::integrate::Radau5::default().solve(&p, 0.0, bad, 1.0, &[]),
    ] {
        assert!(
            matches!(run, Err(Error::InvalidInput { what: "y0", .. })),
            "{run:?}"
        );
    }
}
