use mbd::Mechanism;

/// `y == x` is `x - y == 0` again.
#[derive(Mechanism)]
#[coords(x, y, z)]
#[particle(a, mass = 1.0, at = [x, y])]
#[particle(b, mass = 1.0, at = [z, 0.0])]
#[constraint(x - y == 0.0)]
#[constraint(y == x)]
pub struct Twice {}

fn main() {}
