use mbd::Mechanism;

/// Three constant-coefficient rows of rank two: the third is the sum of the first two.
#[derive(Mechanism)]
#[coords(x, y, z)]
#[particle(a, mass = 1.0, at = [x, y])]
#[particle(b, mass = 1.0, at = [z, 0.0])]
#[constraint(x + y == 1.0)]
#[constraint(x - y == 0.0)]
#[constraint(2.0 * x == 1.0)]
pub struct Dependent {}

fn main() {}
