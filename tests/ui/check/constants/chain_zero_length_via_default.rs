// A chain of zero-length links puts every link at one point: no mechanism.
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 3, joint = revolute, length = l, mass = m, inertia = 0.1)]
pub struct ChainZeroLen {
    #[default(0.0)]
    pub l: f64,
    pub m: f64,
    pub g: f64,
}

fn main() {}
