//! The 30-joint-coordinate humanoid-like tree of `hunt_big_humanoid` on a floating base (the
//! torso on `free(bx, by, bz, t1, t2, t3)`: 33 degrees of freedom, 14 bodies): its generated
//! articulated-body recursion against the floating-base reference of `support/floating.rs`
//! (Kane's equations in generalised speeds, every spherical and universal joint split into
//! elementary hinges, the numbers typed again), and without gravity its total linear and
//! angular momentum by hand, conserved.

use mbd::integrate::{Dop853, Integrator, Options};
use mbd::nalgebra::{Matrix3, Vector3};
use mbd::prelude::*;

#[path = "support/floating.rs"]
mod floating;
#[path = "support/floating_humanoid.rs"]
mod floating_humanoid;
use floating::{Part, hinges, momenta, reference};
use floating_humanoid::FloatingHumanoid;

const N: usize = 33;

/// The model's index of a coordinate.
fn at(name: &str) -> usize {
    FloatingHumanoid::COORDINATES
        .iter()
        .position(|c| *c == name)
        .expect("a coordinate of the model")
}

/// The floating humanoid, hinge by hinge (the same numbers as the attributes, typed again).
fn parts() -> Vec<Part> {
    let d = |a: f64, b: f64, c: f64| Matrix3::from_diagonal(&Vector3::new(a, b, c));
    let (x, y, z) = (0, 1, 2);
    let mut p = vec![Part {
        parent: None,
        axis: 0,
        coord: 0,
        at: [0.0, 0.0, 1.0],
        com: [0.0, 0.01, 0.25],
        mass: 20.0,
        inertia: Matrix3::new(0.6, 0.01, 0.02, 0.01, 0.5, 0.03, 0.02, 0.03, 0.2),
    }];
    let sph = |a: &str, b: &str, c: &str| [(z, at(a)), (y, at(b)), (x, at(c))];
    let two = |a: &str, b: &str| [(x, at(a)), (y, at(b))];
    hinges(
        &mut p,
        0,
        [0.0, 0.0, 0.5],
        &sph("h1", "h2", "h3"),
        (5.0, [0.01, 0.0, 0.1], d(0.03, 0.03, 0.02)),
    );
    type Names = [&'static str; 6];
    let arms: [(f64, Names); 2] = [
        (1.0, ["sl1", "sl2", "sl3", "el", "wl1", "wl2"]),
        (-1.0, ["sr1", "sr2", "sr3", "er", "wr1", "wr2"]),
    ];
    for (side, n) in arms {
        let arm = hinges(
            &mut p,
            0,
            [0.0, 0.2 * side, 0.45],
            &sph(n[0], n[1], n[2]),
            (2.0, [0.0, 0.02 * side, -0.15], d(0.02, 0.02, 0.004)),
        );
        let fore = hinges(
            &mut p,
            arm,
            [0.0, 0.0, -0.3],
            &[(y, at(n[3]))],
            (1.2, [0.0, 0.0, -0.12], d(0.01, 0.01, 0.002)),
        );
        hinges(
            &mut p,
            fore,
            [0.0, 0.0, -0.25],
            &two(n[4], n[5]),
            (0.4, [0.01, 0.0, -0.05], d(0.001, 0.0012, 0.0005)),
        );
    }
    let legs: [(f64, Names); 2] = [
        (1.0, ["hl1", "hl2", "hl3", "kl", "al1", "al2"]),
        (-1.0, ["hr1", "hr2", "hr3", "kr", "ar1", "ar2"]),
    ];
    for (side, n) in legs {
        let thigh = hinges(
            &mut p,
            0,
            [0.0, 0.1 * side, -0.05],
            &sph(n[0], n[1], n[2]),
            (8.0, [0.0, 0.0, -0.2], d(0.15, 0.15, 0.03)),
        );
        let shank = hinges(
            &mut p,
            thigh,
            [0.0, 0.0, -0.45],
            &[(y, at(n[3]))],
            (3.5, [0.0, 0.0, -0.2], d(0.05, 0.05, 0.006)),
        );
        hinges(
            &mut p,
            shank,
            [0.0, 0.0, -0.42],
            &two(n[4], n[5]),
            (1.0, [0.05, 0.0, -0.04], d(0.002, 0.005, 0.005)),
        );
    }
    p
}

/// A spread of states: Euler pitches inside `(-1, 1)` rad, the base's parameters inside
/// the unit ball.
fn state(seed: f64) -> (Vector<N>, Vector<N>) {
    let q = Vector::<N>::from_fn(|i, _| {
        let k = if (3..6).contains(&i) { 0.5 } else { 0.9 };
        k * (1.7 * i as f64 + seed).sin()
    });
    let qd = Vector::<N>::from_fn(|i, _| 2.5 * (0.8 * i as f64 - 2.0 * seed).cos());
    (q, qd)
}

#[test]
fn the_floating_humanoid_equals_the_hand_written_floating_base_reference() {
    assert_eq!(
        FloatingHumanoid::COORDINATES[..6],
        ["bx", "by", "bz", "t1", "t2", "t3"]
    );
    assert!(
        FloatingHumanoid::GENERATED
            .parts
            .contains(&"articulated_body")
    );
    let parts = parts();
    assert_eq!(parts.iter().filter(|p| p.mass > 0.0).count(), 14);
    for g in [0.0, 9.81] {
        let p = FloatingHumanoid { g };
        for seed in [0.0, 0.7, 1.9, 3.1] {
            let (q, qd) = state(seed);
            let acc = p.acceleration(0.0, &q, &qd).unwrap();
            let want = reference(&parts, g, q.as_slice(), qd.as_slice());
            let scale = want.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
            for k in 0..N {
                assert!(
                    (acc[k] - want[k]).abs() < 1e-10 * scale,
                    "g = {g}, seed {seed}: {} = {} against {} by hand",
                    FloatingHumanoid::COORDINATES[k],
                    acc[k],
                    want[k]
                );
            }
            // The mass-matrix form of the same model (composite rigid bodies) agrees.
            let solved = p
                .mass_matrix(0.0, &q)
                .unwrap()
                .lu()
                .solve(&p.forces(0.0, &q, &qd).unwrap())
                .unwrap();
            assert!((solved - acc).amax() < 1e-10 * scale);
            // The generated inverse dynamics (Newton-Euler) is `M qdd - f` at any `qdd`,
            // and zero at the free motion's.
            let qdd_any = Vector::<N>::from_fn(|i, _| 3.0 * (2.1 * i as f64 + seed).sin());
            let (m, f) = (
                p.mass_matrix(0.0, &q).unwrap(),
                p.forces(0.0, &q, &qd).unwrap(),
            );
            let tau = p.inverse_dynamics(0.0, &q, &qd, &qdd_any).unwrap();
            let want = m * qdd_any - f;
            assert!((tau - want).amax() < 1e-10 * want.amax());
            let rest = p.inverse_dynamics(0.0, &q, &qd, &acc).unwrap();
            assert!(rest.amax() < 1e-10 * f.amax().max(1.0), "{rest:?}");
        }
    }
}

/// Without gravity, the humanoid flailing in space for 2 s (DOP853 at 1e-12): total linear
/// and angular momentum and kinetic energy, by hand from the positions and velocities,
/// conserved to 1e-9.
#[test]
fn the_floating_humanoid_conserves_its_momenta_in_space() {
    let (p, parts) = (FloatingHumanoid { g: 0.0 }, parts());
    let (q0, qd0) = state(0.4);
    let qd0 = qd0 * 0.4;
    let mut y0 = Vector::<66>::zeros();
    y0.fixed_rows_mut::<N>(0).copy_from(&q0);
    y0.fixed_rows_mut::<N>(N).copy_from(&qd0);
    let split = |y: &Vector<66>| (y.as_slice()[..N].to_vec(), y.as_slice()[N..].to_vec());
    let (l0, h0, t0) = momenta(&parts, q0.as_slice(), qd0.as_slice());
    assert!(l0.norm() > 1.0 && h0.norm() > 1.0);
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let sol = Dop853::new(opts).solve(&p, 0.0, y0, 2.0, &[]).unwrap();
    for y in &sol.y {
        let (q, qd) = split(y);
        let (l, h, t) = momenta(&parts, &q, &qd);
        assert!((l - l0).norm() < 1e-9 * l0.norm(), "{l:?} {l0:?}");
        assert!((h - h0).norm() < 1e-9 * h0.norm(), "{h:?} {h0:?}");
        assert!((t - t0).abs() < 1e-9 * t0, "{t} {t0}");
    }
    let y1 = sol.last().1;
    assert!((y1 - y0).fixed_rows::<N>(6).amax() > 0.3, "it moved");
}
