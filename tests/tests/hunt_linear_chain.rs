//! Hunting linear analysis on a spring-mass chain as a vibration engineer would: the
//! fixed-free chain's frequencies and mass-normalised shapes, non-proportional damping
//! (complex modes against the hand characteristic polynomial), the frequency response and
//! DC gain against a hand complex solve, the static deflection under load, and the order
//! and names of inputs and outputs. Each reference is derived beside its test.

use mbd::analysis::linear::{
    ModeKind, linearize, mode_sensitivity, modes, state_space, undamped_modes,
};
use mbd::analysis::{NewtonOptions, static_equilibrium};
use mbd::prelude::*;
use nalgebra::{Complex, DMatrix};
use std::f64::consts::PI;

/// Wall, spring, block 1, spring, block 2, spring, block 3 (free end): equal masses `m`
/// and springs `k` of free length `l0`; dampers `c1` (wall to block 1) and `c3` (block 2
/// to block 3), forces `f3` on block 3 and `f1` on block 1 (inputs, declared `f3` first),
/// outputs the tip's and the first block's positions (declared tip first) and the tip's
/// acceleration.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[coords(x1, x2, x3)]
#[point(wall, at = [0.0, 0.0])]
#[particle(b1, mass = m, at = [x1, 0.0])]
#[particle(b2, mass = m, at = [x2, 0.0])]
#[particle(b3, mass = m, at = [x3, 0.0])]
#[spring(s1, from = wall, to = b1, k = k, length = l0)]
#[spring(s2, from = b1, to = b2, k = k, length = l0)]
#[spring(s3, from = b2, to = b3, k = k, length = l0)]
#[damper(d1, from = wall, to = b1, c = c1)]
#[damper(d3, from = b2, to = b3, c = c3)]
#[generalized_force(push1, along = x1, value = f1)]
#[generalized_force(push3, along = x3, value = f3)]
#[input(f3, f1)]
#[output(tip = x3)]
#[output(first = x1)]
#[output(tip_acc = der(der(x3)))]
pub struct Chain {
    pub m: f64,
    pub k: f64,
    pub l0: f64,
    pub c1: f64,
    pub c3: f64,
    pub f1: f64,
    pub f3: f64,
}

const CHAIN: Chain = Chain {
    m: 1.5,
    k: 600.0,
    l0: 0.4,
    c1: 0.0,
    c3: 0.0,
    f1: 0.0,
    f3: 0.0,
};

/// Unloaded, the blocks rest at `x_i = i l0`.
fn rest(p: &Chain) -> Vector<3> {
    Vector::<3>::new(p.l0, 2.0 * p.l0, 3.0 * p.l0)
}

fn state(q: &Vector<3>) -> Vector<6> {
    Vector::<6>::new(q[0], q[1], q[2], 0.0, 0.0, 0.0)
}

/// The hand `M`, `C`, `K` of the chain about rest: `M = m I`,
/// `K = k [[2, -1, 0], [-1, 2, -1], [0, -1, 1]]`, `C = [[c1, 0, 0], [0, c3, -c3],
/// [0, -c3, c3]]`.
fn mck(p: &Chain) -> [DMatrix<f64>; 3] {
    let (k, c1, c3) = (p.k, p.c1, p.c3);
    [
        DMatrix::identity(3, 3) * p.m,
        DMatrix::from_row_slice(3, 3, &[c1, 0.0, 0.0, 0.0, c3, -c3, 0.0, -c3, c3]),
        DMatrix::from_row_slice(3, 3, &[2.0 * k, -k, 0.0, -k, 2.0 * k, -k, 0.0, -k, k]),
    ]
}

/// Fixed-free chain of `n` equal blocks: `x_i = sin(i th)` solves the interior rows
/// `-w^2 m x_i = k (x_{i-1} - 2 x_i + x_{i+1})` with `w^2 = (4 k / m) sin^2(th / 2)`, and
/// the free end (`x_{n+1} = x_n`) needs `sin((n + 1) th) = sin(n th)`:
/// `th_j = (2 j - 1) pi / (2 n + 1)`. For `n = 3`: `w_j = 2 sqrt(k / m) sin((2 j - 1) pi /
/// 14)`, shape `(sin th_j, sin 2 th_j, sin 3 th_j)`, mass-normalised by
/// `sqrt(m sum sin^2(i th_j))`.
#[test]
fn three_blocks_have_the_closed_form_frequencies_and_mass_normalised_shapes() {
    let p = CHAIN;
    let normal = undamped_modes(&p, 0.0, &rest(&p)).unwrap();
    assert_eq!(normal.len(), 3);
    let found = modes(&linearize(&p, 0.0, &state(&rest(&p))).unwrap()).unwrap();
    assert_eq!(found.len(), 3);
    for j in 1..=3 {
        let th = (2 * j - 1) as f64 * PI / 7.0;
        let w = 2.0 * (p.k / p.m).sqrt() * (th / 2.0).sin();
        let nm = &normal[j - 1];
        assert!(
            (nm.omega_squared - w * w).abs() < 1e-12 * w * w,
            "mode {j}: {} vs {}",
            nm.omega_squared,
            w * w
        );
        let raw = Vector::<3>::from_fn(|i, _| ((i + 1) as f64 * th).sin());
        let want = raw / (p.m * raw.norm_squared()).sqrt();
        // The sign of a shape is free.
        let sign = nm.shape.dot(&want).signum();
        assert!(
            (nm.shape * sign - want).amax() < 1e-12,
            "mode {j}: {} vs {want}",
            nm.shape
        );
        let m = &found[j - 1];
        assert_eq!(m.kind, ModeKind::Oscillatory);
        assert!((m.omega_d - w).abs() < 1e-12 * w, "{} vs {w}", m.omega_d);
        let ratio = |a: usize, b: usize| m.shape[a] / m.shape[b];
        let r = ratio(2, 0);
        assert!(
            (r.re - want[2] / want[0]).abs() < 1e-10 && r.im.abs() < 1e-10,
            "mode {j}: x3 / x1 = {r}"
        );
    }
}

/// Roots of a real polynomial (coefficients highest first) by the Durand-Kerner
/// iteration: independent of the library's eigen-solvers.
fn roots(coef: &[f64]) -> Vec<Complex<f64>> {
    let n = coef.len() - 1;
    let eval = |z: Complex<f64>| {
        coef.iter()
            .fold(Complex::new(0.0, 0.0), |acc, &c| acc * z + c / coef[0])
    };
    let mut z: Vec<Complex<f64>> = (0..n)
        .map(|i| Complex::new(0.4, 0.9).powu(i as u32) * 10.0)
        .collect();
    for _ in 0..2000 {
        for i in 0..n {
            let den = (0..n)
                .filter(|&j| j != i)
                .fold(Complex::new(1.0, 0.0), |acc, j| acc * (z[i] - z[j]));
            let step = eval(z[i]) / den;
            z[i] -= step;
        }
    }
    z
}

/// Non-proportional damping: only the first and the last spring have dampers, so `C` is
/// no combination of `M` and `K` and the modes are complex (the blocks do not move in
/// phase). With one damper `c` on the first spring and two blocks (`c3 = 0`, block 3's
/// spring removed by taking the 3-block chain's first two rows is not the same model, so
/// the reference is built for the 3 blocks): `det(lambda^2 M + lambda C + K) = 0`, a
/// polynomial of degree 6 whose coefficients come from expanding the 3 x 3 determinant by
/// hand (below, in powers of `lambda`), its roots by Durand-Kerner. Each mode's shape is
/// checked against the null vector of `lambda^2 M + lambda C + K`: with `x1 = 1`, row 1
/// gives `x2 = (m lambda^2 + c1 lambda + 2 k) / k`, row 3 gives
/// `x3 = (k + c3 lambda) x2 / (m lambda^2 + c3 lambda + k)`.
#[test]
fn non_proportional_damping_has_the_complex_modes_of_the_hand_determinant() {
    let p = Chain {
        c1: 4.0,
        c3: 9.0,
        ..CHAIN
    };
    let (m, k, c1, c3) = (p.m, p.k, p.c1, p.c3);
    // det [[a1, -k, 0], [-k, a2, -b], [0, -b, a3]] with a1 = m s^2 + c1 s + 2k,
    // a2 = m s^2 + c3 s + 2k, a3 = m s^2 + c3 s + k, b = c3 s + k:
    // = a1 (a2 a3 - b^2) - k^2 a3. Polynomials in s as coefficient vectors (lowest first).
    let mul = |x: &[f64], y: &[f64]| {
        let mut r = vec![0.0; x.len() + y.len() - 1];
        for (i, a) in x.iter().enumerate() {
            for (j, b) in y.iter().enumerate() {
                r[i + j] += a * b;
            }
        }
        r
    };
    let sub = |x: &[f64], y: &[f64]| {
        let n = x.len().max(y.len());
        (0..n)
            .map(|i| x.get(i).unwrap_or(&0.0) - y.get(i).unwrap_or(&0.0))
            .collect::<Vec<f64>>()
    };
    let a1 = [2.0 * k, c1, m];
    let a2 = [2.0 * k, c3, m];
    let a3 = [k, c3, m];
    let b = [k, c3];
    let inner = sub(&mul(&a2, &a3), &mul(&b, &b));
    let det = sub(&mul(&a1, &inner), &mul(&[k * k], &a3));
    let high_first: Vec<f64> = det.iter().rev().copied().collect();
    let mut want: Vec<Complex<f64>> = roots(&high_first)
        .into_iter()
        .filter(|z| z.im > 0.0)
        .collect();
    want.sort_by(|x, y| x.norm().total_cmp(&y.norm()));
    assert_eq!(want.len(), 3, "{want:?}");

    let found = modes(&linearize(&p, 0.0, &state(&rest(&p))).unwrap()).unwrap();
    assert_eq!(found.len(), 3, "{found:?}");
    for (md, z) in found.iter().zip(&want) {
        assert_eq!(md.kind, ModeKind::Oscillatory);
        assert!(
            (md.eigenvalue - z).norm() < 1e-11 * z.norm(),
            "{} vs {z}",
            md.eigenvalue
        );
        assert!((md.damping_ratio.unwrap() - (-z.re / z.norm())).abs() < 1e-11);
        let s = md.eigenvalue;
        let x2 = (s * s * m + s * c1 + 2.0 * k) / k;
        let x3 = (s * c3 + k) * x2 / (s * s * m + s * c3 + k);
        let v = &md.shape;
        let (r2, r3) = (v[1] / v[0], v[2] / v[0]);
        assert!((r2 - x2).norm() < 1e-10 * x2.norm(), "{r2} vs {x2}");
        assert!((r3 - x3).norm() < 1e-10 * x3.norm(), "{r3} vs {x3}");
        // A complex mode: the blocks are out of phase (not a real ratio).
        assert!(x3.im.abs() > 1e-3 * x3.norm());
        // Velocities are lambda times positions.
        assert!((v[3] - s * v[0]).norm() < 1e-10 * v[3].norm());
    }
}

/// `state_space` names inputs and outputs in the order declared (`f3, f1`; `tip, first,
/// tip_acc`), and its columns and rows follow those names: `B` column `f3` pushes block 3
/// (`1/m` in `x3''`), the `first` row of `C` reads `x1`.
#[test]
fn inputs_and_outputs_come_in_the_declared_order() {
    let p = CHAIN;
    let ss = state_space(&p, 0.0, &state(&rest(&p))).unwrap();
    assert_eq!(ss.inputs, vec!["f3", "f1"]);
    assert_eq!(ss.outputs, vec!["tip", "first", "tip_acc"]);
    let mut b = DMatrix::<f64>::zeros(6, 2);
    b[(5, 0)] = 1.0 / p.m;
    b[(3, 1)] = 1.0 / p.m;
    assert!((&ss.b - &b).amax() < 1e-15, "{}", ss.b);
    let mut c = DMatrix::<f64>::zeros(3, 6);
    c[(0, 2)] = 1.0;
    c[(1, 0)] = 1.0;
    // x3'' = (k / m)(x2 - x3) about rest: the acceleration row.
    c[(2, 1)] = p.k / p.m;
    c[(2, 2)] = -p.k / p.m;
    assert!((&ss.c - &c).amax() < 1e-12, "{}", ss.c);
    let mut d = DMatrix::<f64>::zeros(3, 2);
    d[(2, 0)] = 1.0 / p.m;
    assert!((&ss.d - &d).amax() < 1e-15, "{}", ss.d);
}

/// The frequency response of the damped chain against a hand complex solve: the position
/// outputs are `e_i^T (K - w^2 M + i w C)^-1 e_j` for a force on block `j`, the tip's
/// acceleration `-w^2` times the tip's position plus nothing else (its feed-through is
/// inside: `x3'' = -w^2 x3` in steady state). The DC gain (`w = 0`) is the static
/// compliance: a force `F` on the tip stretches every spring by `F / k`, so
/// `x1 = F / k`, `x3 = 3 F / k`; on block 1 only the first spring: `x1 = x3 = F / k`.
#[test]
fn frequency_response_and_dc_gain_are_the_hand_receptances() {
    let p = Chain {
        c1: 4.0,
        c3: 9.0,
        ..CHAIN
    };
    let ss = state_space(&p, 0.0, &state(&rest(&p))).unwrap();
    let [mm, cc, kk] = mck(&p);
    let cx = |m: &DMatrix<f64>| m.map(|v| Complex::new(v, 0.0));
    for w in [0.0, 3.0, 11.0, 19.9, 27.5, 60.0, 400.0] {
        let g = ss.frequency_response(w).unwrap();
        let dyn_stiff = cx(&(&kk - &mm * (w * w))) + cx(&cc) * Complex::new(0.0, w);
        let h = dyn_stiff.try_inverse().unwrap();
        for (col, block) in [(0, 2), (1, 0)] {
            let tip = h[(2, block)];
            for (row, want) in [(0, tip), (1, h[(0, block)]), (2, tip * (-w * w))] {
                let got = g[(row, col)];
                // A solve is accurate relative to the largest response to that input
                // (norm-wise; far above resonance `x1` is `1e-4` of `x3`); the acceleration
                // sums `C x` and the feed-through `1 / m`, whose sum vanishes at `w = 0`.
                let big = (0..3).map(|i| h[(i, block)].norm()).fold(0.0, f64::max);
                let terms = if row == 2 {
                    1.0 / p.m + w * w * big
                } else {
                    big
                };
                assert!(
                    (got - want).norm() < 1e-12 * terms,
                    "w = {w}, output {row}, input {col}: {got} vs {want}"
                );
            }
        }
        if w == 0.0 {
            let f = 1.0 / p.k;
            assert!((g[(0, 0)].re - 3.0 * f).abs() < 1e-15 && g[(0, 0)].im == 0.0);
            assert!((g[(1, 0)].re - f).abs() < 1e-16);
            assert!((g[(0, 1)].re - f).abs() < 1e-16);
            assert!((g[(1, 1)].re - f).abs() < 1e-16);
        }
    }
}

/// The static deflection under a load: with a tip force `F = 30 N` the equilibrium is
/// `x_i = i (l0 + F / k)` (each spring carries `F`), with `F` on block 1 only the first
/// spring stretches: `x_i = i l0 + F / k`.
#[test]
fn static_deflection_under_a_tip_load_is_the_hand_compliance() {
    let f = 30.0;
    for (p, want) in [
        (
            Chain { f3: f, ..CHAIN },
            Vector::<3>::from_fn(|i, _| (i + 1) as f64 * (CHAIN.l0 + f / CHAIN.k)),
        ),
        (
            Chain { f1: f, ..CHAIN },
            Vector::<3>::from_fn(|i, _| (i + 1) as f64 * CHAIN.l0 + f / CHAIN.k),
        ),
    ] {
        let q = static_equilibrium(&p, 0.0, &rest(&p), &NewtonOptions::default()).unwrap();
        assert!((q - want).amax() < 1e-12, "{q} vs {want}");
    }
}

/// The chain cut from the wall: three blocks joined by two springs, free to translate, a
/// force `f3` on the tip and `f1` on the first block.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x1, x2, x3)]
#[particle(b1, mass = m, at = [x1, 0.0])]
#[particle(b2, mass = m, at = [x2, 0.0])]
#[particle(b3, mass = m, at = [x3, 0.0])]
#[spring(s2, from = b1, to = b2, k = k, length = l0)]
#[spring(s3, from = b2, to = b3, k = k, length = l0)]
#[generalized_force(push1, along = x1, value = f1)]
#[generalized_force(push3, along = x3, value = f3)]
pub struct FreeChain {
    pub m: f64,
    pub k: f64,
    pub l0: f64,
    pub f1: f64,
    pub f3: f64,
}

/// Free of the wall the chain has a rigid-body mode: `undamped_modes` gives `w^2 = 0`
/// exactly with the shape `(1, 1, 1) / sqrt(3 m)` beside the free-free chain's
/// `w^2 = (k / m)(1, 3)` (`K = k [[1, -1, 0], [-1, 2, -1], [0, -1, 1]]`, `det(K - mu m I)
/// = -mu m (mu m - k)(mu m - 3 k)`). Under a net load (`f3` alone) there is no equilibrium
/// (it accelerates as a whole at `f3 / 3 m`): `static_equilibrium` must not return `Ok`
/// but a typed error. With balanced loads (`f1 = -f3 = -F`) every translate of the chain
/// with both springs stretched by `F / k` is an equilibrium: what it returns must be one
/// (which translate is left to rounding: the stiffness is singular along it).
#[test]
fn a_free_chain_has_a_rigid_body_mode_and_no_unique_equilibrium() {
    let p = FreeChain {
        m: 1.5,
        k: 600.0,
        l0: 0.4,
        f1: 0.0,
        f3: 0.0,
    };
    let q = Vector::<3>::new(0.0, p.l0, 2.0 * p.l0);
    let normal = undamped_modes(&p, 0.0, &q).unwrap();
    assert_eq!(normal[0].omega_squared, 0.0, "{normal:?}");
    let rigid = Vector::<3>::repeat(1.0 / (3.0 * p.m).sqrt());
    let sign = normal[0].shape.dot(&rigid).signum();
    assert!(
        (normal[0].shape * sign - rigid).amax() < 1e-14,
        "{}",
        normal[0].shape
    );
    for (nm, r) in normal[1..].iter().zip([1.0, 3.0]) {
        let w2 = r * p.k / p.m;
        assert!((nm.omega_squared - w2).abs() < 1e-12 * w2, "{nm:?}");
    }
    let found = modes(&linearize(&p, 0.0, &state(&q)).unwrap()).unwrap();
    let kinds: Vec<_> = found.iter().map(|m| m.kind).collect();
    assert_eq!(
        kinds,
        [
            ModeKind::Neutral,
            ModeKind::Neutral,
            ModeKind::Oscillatory,
            ModeKind::Oscillatory
        ],
        "{found:?}"
    );
    let net = FreeChain { f3: 30.0, ..p };
    match static_equilibrium(&net, 0.0, &q, &NewtonOptions::default()) {
        Err(Error::StaticsFailed { .. }) => {}
        other => panic!("net load: {other:?}"),
    }
    let balanced = FreeChain {
        f1: -30.0,
        f3: 30.0,
        ..p
    };
    if let Ok(e) = static_equilibrium(&balanced, 0.0, &q, &NewtonOptions::default()) {
        let stretched = p.l0 + 30.0 / p.k;
        assert!((e[1] - e[0] - stretched).abs() < 1e-12, "{e}");
        assert!((e[2] - e[1] - stretched).abs() < 1e-12, "{e}");
    }
}

/// Eigen-sensitivities of the undamped chain against closed forms. Every `w_j` is
/// `sqrt(k / m)` times a number, so `dlambda/dk = i w / (2 k)` and `dlambda/dm =
/// -i w / (2 m)`. A damper is a first-order perturbation of `lambda^2 M v + lambda C v + K v
/// = 0` at `C = 0`: with `v` mass-normalised, `2 lambda dlambda + lambda v^T dC v = 0`, so
/// `dlambda/dc1 = -v_1^2 / 2` (the damper from the wall to block 1) and `dlambda/dc3 =
/// -(v_2 - v_3)^2 / 2`: the modal damping each damper adds, with the shapes
/// `sin(i th_j)` of the test above.
#[test]
fn eigenvalue_sensitivities_are_the_closed_forms() {
    let p = CHAIN;
    let y = state(&rest(&p));
    let by = |name: &str| mode_sensitivity(&p, 0.0, &y, name).unwrap();
    let (dk, dm, dc1, dc3) = (by("k"), by("m"), by("c1"), by("c3"));
    for j in 1..=3 {
        let th = (2 * j - 1) as f64 * PI / 7.0;
        let w = 2.0 * (p.k / p.m).sqrt() * (th / 2.0).sin();
        let raw = Vector::<3>::from_fn(|i, _| ((i + 1) as f64 * th).sin());
        let v = raw / (p.m * raw.norm_squared()).sqrt();
        let i = j - 1;
        assert!((dk[i].0.omega_d - w).abs() < 1e-12 * w);
        for (got, want, name) in [
            (dk[i].1.unwrap(), Complex::new(0.0, w / (2.0 * p.k)), "k"),
            (dm[i].1.unwrap(), Complex::new(0.0, -w / (2.0 * p.m)), "m"),
            (
                dc1[i].1.unwrap(),
                Complex::new(-v[0] * v[0] / 2.0, 0.0),
                "c1",
            ),
            (
                dc3[i].1.unwrap(),
                Complex::new(-(v[1] - v[2]).powi(2) / 2.0, 0.0),
                "c3",
            ),
        ] {
            assert!(
                (got - want).norm() < 1e-8 * want.norm(),
                "mode {j}, d lambda / d {name}: {got} vs {want}"
            );
        }
    }
    match mode_sensitivity(&p, 0.0, &y, "stiffness") {
        Err(Error::InvalidInput { detail, .. }) => assert!(detail.contains("\"k\""), "{detail}"),
        other => panic!("{other:?}"),
    }
}
