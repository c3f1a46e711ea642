use mbd::Mechanism;

/// `x * x == -1` has no real solution (issue 14: a constraint no configuration satisfies).
#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = 1.0, at = [x, y])]
#[constraint(x * x == -1.0)]
pub struct Never {}

fn main() {}
