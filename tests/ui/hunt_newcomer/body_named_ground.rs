use mbd::Mechanism;

/// A body called `ground` would be a second meaning of the fixed frame's name.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x)]
#[particle(ground, mass = 1.0, at = [x, 0.0])]
pub struct Cart {}

fn main() {}
