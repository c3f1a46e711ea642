use mbd::Mechanism;

/// `x + y == 1` and `2 x + 2 y == 4` cannot hold together.
#[derive(Mechanism)]
#[coords(x, y, z)]
#[particle(a, mass = 1.0, at = [x, y])]
#[particle(b, mass = 1.0, at = [z, 0.0])]
#[constraint(x + y == 1.0)]
#[constraint(2.0 * x + 2.0 * y == 4.0)]
pub struct Contradiction {}

fn main() {}
