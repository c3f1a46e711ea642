// A chain's links hang straight down at zero angle; a negative length would point them up.
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 2, joint = revolute, length = -1.0, mass = m, inertia = m / 12.0)]
pub struct ChainNegLen {
    pub m: f64,
    pub g: f64,
}

fn main() {}
