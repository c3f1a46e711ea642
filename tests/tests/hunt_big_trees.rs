//! Hunting big spatial trees: a binary tree of 31 bodies (62 coordinates) stamped by one
//! `#[repeat]` (`parent = b[i / 2]`), and a chain of 40 bodies on universal joints whose
//! 20th link differs by its mass alone (the identical tail after it is rolled into loops,
//! the link must not be taken for one of them), each against the hinge-by-hinge Jacobian
//! reference of `support/hinges.rs` at spread states.

use mbd::nalgebra::{Matrix3, Vector3};
use mbd::prelude::*;

#[path = "support/hinges.rs"]
mod hinges;
use hinges::{Hinge, accelerations, joint, order};

#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(b1, joint = universal(x1, y1), com = [0.0, 0.0, -l / 2.0], mass = m,
       inertia = diag(a, a, c))]
#[repeat(i in 2..32,
    body(b[i], parent = b[i / 2], joint = universal(x[i], y[i]), at = [0.0, 0.0, -l],
         com = [0.1 * l, 0.0, -l / 2.0], mass = m, inertia = diag(a, a, c)))]
pub struct Binary31 {
    pub m: f64,
    pub l: f64,
    pub a: f64,
    pub c: f64,
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(u1, joint = universal(x1, y1), com = [0.0, 0.0, -l / 2.0], mass = m,
       inertia = diag(a, a, c))]
#[repeat(i in 2..20,
    body(u[i], parent = u[i - 1], joint = universal(x[i], y[i]), at = [0.0, 0.0, -l],
         com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(a, a, c)))]
#[body(u20, parent = u19, joint = universal(x20, y20), at = [0.0, 0.0, -l],
       com = [0.0, 0.0, -l / 2.0], mass = 3.0 * m, inertia = diag(a, a, c))]
#[repeat(i in 21..=40,
    body(u[i], parent = u[i - 1], joint = universal(x[i], y[i]), at = [0.0, 0.0, -l],
         com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(a, a, c)))]
pub struct Chain40 {
    pub m: f64,
    pub l: f64,
    pub a: f64,
    pub c: f64,
    pub g: f64,
}

const M: f64 = 0.7;
const L: f64 = 0.3;
const A: f64 = 0.006;
const C: f64 = 0.001;
const G: f64 = 9.81;

/// The universal joint `rot_x(x) rot_y(y)` as two hinges.
fn universal(k: usize) -> [(usize, String); 2] {
    [(0, format!("x{k}")), (1, format!("y{k}"))]
}

fn inertia() -> Matrix3<f64> {
    Matrix3::from_diagonal(&Vector3::new(A, A, C))
}

/// Body `k` (1-based) of the binary tree hangs from body `k / 2`, at its parent's far end.
fn binary_hinges() -> Vec<Hinge> {
    let mut h = Vec::new();
    let mut body_hinge = vec![0usize; 32];
    body_hinge[1] = joint(
        &mut h,
        None,
        [0.0; 3],
        &universal(1),
        M,
        [0.0, 0.0, -L / 2.0],
        inertia(),
    );
    for k in 2..32 {
        let parent = Some(body_hinge[k / 2]);
        let com = [0.1 * L, 0.0, -L / 2.0];
        body_hinge[k] = joint(
            &mut h,
            parent,
            [0.0, 0.0, -L],
            &universal(k),
            M,
            com,
            inertia(),
        );
    }
    h
}

fn chain_hinges() -> Vec<Hinge> {
    let mut h = Vec::new();
    let mut last = None;
    for k in 1..=40 {
        let mass = if k == 20 { 3.0 * M } else { M };
        let at = if k == 1 { [0.0; 3] } else { [0.0, 0.0, -L] };
        last = Some(joint(
            &mut h,
            last,
            at,
            &universal(k),
            mass,
            [0.0, 0.0, -L / 2.0],
            inertia(),
        ));
    }
    h
}

/// The model's accelerations against the reference's at three spread states.
fn against_reference<S: MechanismModel<N>, const N: usize>(
    name: &str,
    model: &S,
    coords: &[&str],
    h: &[Hinge],
) {
    let perm = order(h, coords);
    for seed in [0.0, 1.1, 2.3] {
        let q = Vector::<N>::from_fn(|i, _| 0.5 * (1.9 * i as f64 + seed).sin());
        let qd = Vector::<N>::from_fn(|i, _| 1.5 * (0.6 * i as f64 - seed).cos());
        let acc = model.acceleration(0.0, &q, &qd).unwrap();
        let want = accelerations(h, &perm, G, q.as_slice(), qd.as_slice());
        let scale = want.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for k in 0..N {
            assert!(
                (acc[k] - want[k]).abs() < 1e-9 * scale,
                "{name} seed {seed}: {} = {} against {} by hand",
                coords[k],
                acc[k],
                want[k]
            );
        }
    }
}

#[test]
fn a_binary_tree_of_31_bodies_equals_the_hand_written_reference() {
    assert!(Binary31::GENERATED.parts.contains(&"articulated_body"));
    let p = Binary31 {
        m: M,
        l: L,
        a: A,
        c: C,
        g: G,
    };
    against_reference("binary tree", &p, &Binary31::COORDINATES, &binary_hinges());
}

#[test]
fn a_chain_with_one_heavier_link_equals_the_hand_written_reference() {
    let p = Chain40 {
        m: M,
        l: L,
        a: A,
        c: C,
        g: G,
    };
    against_reference("chain", &p, &Chain40::COORDINATES, &chain_hinges());
}
