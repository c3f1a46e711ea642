use mbd::Mechanism;

/// `sin(x) == 2` has no solution.
#[derive(Mechanism)]
#[coords(x, y)]
#[particle(a, mass = 1.0, at = [cos(x), y])]
#[constraint(sin(x) == 2.0)]
pub struct Never {}

fn main() {}
