//! Hunting big-model defects: long planar chains (unrolled and rolled) against the chain's
//! equations of motion written by hand in absolute angles, and a spatial chain of ball
//! joints against its conservation laws through a tumbling motion.

use mbd::integrate::{Dop853, Integrator, Vern9};
use mbd::nalgebra::{DMatrix, DVector};
use mbd::prelude::*;

/// `n` uniform bars (mass `m`, length `l`, inertia `m l^2 / 12`) hanging from a pin, by
/// hand, in absolute angles `th_i` from the downward vertical. Bar `i` (1-based) is
/// followed by `n - i` bars, so with `c_ii = 1/3 + (n - i)` and `c_ij = 1/2 + (n - max(i,
/// j))`, `T = m l^2 / 2 sum c_ij cos(th_i - th_j) th_i' th_j'` and
/// `V = -m g l sum (n - i + 1/2) cos th_i`; Lagrange's equations:
/// `sum_j c_ij (cos(th_i - th_j) th_j'' + sin(th_i - th_j) th_j'^2) =
/// -(g / l) (n - i + 1/2) sin th_i`.
/// Returns the relative angles' accelerations (`q_1 = th_1`, `q_k = th_k - th_{k-1}`) at a
/// state given in relative angles.
fn chain_by_hand(g_over_l: f64, q: &[f64], qd: &[f64]) -> Vec<f64> {
    let n = q.len();
    let cum = |v: &[f64]| -> Vec<f64> {
        v.iter()
            .scan(0.0, |s, x| {
                *s += x;
                Some(*s)
            })
            .collect()
    };
    let (th, thd) = (cum(q), cum(qd));
    let c = |i: usize, j: usize| {
        let far = n - 1 - i.max(j); // bars after the later of the two (0-based)
        if i == j {
            1.0 / 3.0 + far as f64
        } else {
            0.5 + far as f64
        }
    };
    let a = DMatrix::from_fn(n, n, |i, j| c(i, j) * (th[i] - th[j]).cos());
    let b = DVector::from_fn(n, |i, _| {
        let centripetal: f64 = (0..n)
            .map(|j| c(i, j) * (th[i] - th[j]).sin() * thd[j] * thd[j])
            .sum();
        -centripetal - g_over_l * ((n - 1 - i) as f64 + 0.5) * th[i].sin()
    });
    let thdd = a.lu().solve(&b).unwrap();
    (0..n)
        .map(|k| thdd[k] - if k > 0 { thdd[k - 1] } else { 0.0 })
        .collect()
}

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 5, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
pub struct Chain5 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 64, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
pub struct Chain64 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// A state away from every symmetry: angles and rates that vary along the chain.
fn state<const N: usize>() -> (Vector<N>, Vector<N>) {
    let q =
        Vector::<N>::from_fn(|i, _| 0.9 * (1.7 * i as f64 + 0.3).sin() / (1.0 + 0.1 * i as f64));
    let qd = Vector::<N>::from_fn(|i, _| 1.3 * (0.7 * i as f64 - 0.4).cos());
    (q, qd)
}

fn compare<const N: usize>(acc: &Vector<N>, q: &Vector<N>, qd: &Vector<N>, g_over_l: f64) {
    let want = chain_by_hand(g_over_l, q.as_slice(), qd.as_slice());
    let scale = want.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (k, w) in want.iter().enumerate() {
        assert!(
            (acc[k] - w).abs() < 1e-9 * scale,
            "link {}: {} vs {w} (scale {scale})",
            k + 1,
            acc[k]
        );
    }
}

#[test]
fn long_chains_match_their_equations_of_motion_written_by_hand() {
    let (m, l, g) = (0.3, 0.25, 9.81);
    let p5 = Chain5 { m, l, g };
    let (q, qd) = state::<5>();
    compare(&p5.acceleration(0.0, &q, &qd).unwrap(), &q, &qd, g / l);
    let p64 = Chain64 { m, l, g };
    assert!(Chain64::GENERATED.parts.contains(&"rolled_chain"));
    let (q, qd) = state::<64>();
    compare(&p64.acceleration(0.0, &q, &qd).unwrap(), &q, &qd, g / l);
    // At rest in a bent shape only gravity acts.
    let rest = Vector::<64>::zeros();
    compare(&p64.acceleration(0.0, &q, &rest).unwrap(), &q, &rest, g / l);
}

/// Five bodies on ball joints, each a point mass `m` at `[0, 0, -l]` of its frame with an
/// isotropic inertia `a` about it, hanging from the ground's origin. Gravity along `-z` and
/// the pivot on the `z` axis: the energy and the angular momentum about `z`,
/// `L_z = sum m (x v_y - y v_x) + a w_z` (isotropic inertia: `R I R^T w = a w`), are kept.
#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(b1, joint = ball(sa1, sb1, sc1), com = [0.0, 0.0, -l], mass = m, inertia = diag(a, a, a))]
#[repeat(i in 2..=5,
    body(b[i], parent = b[i - 1], joint = ball(sa[i], sb[i], sc[i]), at = [0.0, 0.0, -l],
         com = [0.0, 0.0, -l], mass = m, inertia = diag(a, a, a)),
    output(p[i] = position(b[i]), v[i] = velocity(b[i]), w[i] = angular_velocity(b[i])))]
#[output(p1 = position(b1), v1 = velocity(b1), w1 = angular_velocity(b1))]
pub struct BallChain {
    pub m: f64,
    pub l: f64,
    pub a: f64,
    pub g: f64,
}

fn momentum_z(p: &BallChain, y: &Vector<30>) -> f64 {
    let o = p.outputs(0.0, y).unwrap();
    [
        [o.p1_x, o.p1_y, o.v1_x, o.v1_y, o.w1_z],
        [o.p2_x, o.p2_y, o.v2_x, o.v2_y, o.w2_z],
        [o.p3_x, o.p3_y, o.v3_x, o.v3_y, o.w3_z],
        [o.p4_x, o.p4_y, o.v4_x, o.v4_y, o.w4_z],
        [o.p5_x, o.p5_y, o.v5_x, o.v5_y, o.w5_z],
    ]
    .iter()
    .map(|[x, y, vx, vy, wz]| p.m * (x * vy - y * vx) + p.a * wz)
    .sum()
}

#[test]
fn ball_joint_chain_keeps_its_energy_and_vertical_momentum_while_tumbling() {
    let p = BallChain {
        m: 0.4,
        l: 0.3,
        a: 0.002,
        g: 9.81,
    };
    // Joint parameters well away from rest and rates that spin every body: the chain
    // tumbles through large rotations (the parameters switch to their shadow set on the way).
    let y0 = Vector::<30>::from_fn(|i, _| {
        if i < 15 {
            0.35 * (1.3 * i as f64 + 0.2).sin()
        } else {
            3.0 * (0.9 * i as f64 - 0.5).cos()
        }
    });
    let energy = |y: &Vector<30>| {
        let q = y.fixed_rows::<15>(0).into_owned();
        let qd = y.fixed_rows::<15>(15).into_owned();
        p.energy(0.0, &q, &qd).unwrap()
    };
    let (e0, l0) = (energy(&y0), momentum_z(&p, &y0));
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    for (name, sol) in [
        (
            "DOP853",
            Dop853::new(opts.clone()).solve(&p, 0.0, y0, 2.0, &[]),
        ),
        (
            "Vern9",
            Vern9::new(opts.clone()).solve(&p, 0.0, y0, 2.0, &[]),
        ),
    ] {
        let sol = sol.unwrap();
        let y = sol.last().1;
        let (e1, l1) = (energy(y), momentum_z(&p, y));
        assert!(
            (e1 - e0).abs() < 1e-8 * e0.abs().max(1.0),
            "{name}: energy {e0} -> {e1}"
        );
        assert!(
            (l1 - l0).abs() < 1e-8 * l0.abs().max(1.0),
            "{name}: L_z {l0} -> {l1}"
        );
        // It did tumble: some joint parameter left the start by a large turn.
        assert!((y - y0).fixed_rows::<15>(0).amax() > 0.3, "{name}");
    }
}
