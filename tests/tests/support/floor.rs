//! A block launched at `v0` on a rough level floor, the model of the friction-solve tests:
//! friction `-mu m g sign(v)` decelerates it at `mu g` until it stops and sticks.

use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu, normal = m * g)]
#[init(x = 0.0, der(x) = v0)]
pub struct Floor {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
    pub v0: f64,
}

/// The block the tests launch: 2 kg at 4 m/s, `mu = 0.3`.
pub const FLOOR: Floor = Floor {
    m: 2.0,
    g: 9.81,
    mu: 0.3,
    v0: 4.0,
};
