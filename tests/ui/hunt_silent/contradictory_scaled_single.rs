use mbd::Mechanism;

/// `2 x == 2` after `x == 0` (issue 14: a scaled contradictory row).
#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = 1.0, at = [x, y])]
#[constraint(x == 0.0)]
#[constraint(2.0 * x == 2.0)]
pub struct Twice {}

fn main() {}
