use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(b1, joint = universal(x1, y1), com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(a, a, c))]
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

#[test]
fn probe() {
    eprintln!(
        "{:?} {}",
        Binary31::GENERATED.parts,
        Binary31::COORDINATES.len()
    );
}
