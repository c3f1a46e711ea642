use mbd::Mechanism;

/// `n` counts links: zero links is no chain, and `n` must be a literal.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[chain(link, n = 0, joint = revolute, length = 1.0, mass = 1.0)]
#[chain(rope, n = k, joint = revolute, length = 1.0, mass = 1.0)]
pub struct Chain {
    pub k: f64,
}

fn main() {}
