use mbd::Mechanism;

/// `sqrt` is never negative, nor a fourth power below one when one is added.
#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = 1.0, at = [x, y])]
#[constraint(sqrt(x * x + y * y) == -1.0)]
#[constraint(y.powi(4) + 1.0 == 0.5)]
pub struct Never {}

fn main() {}
