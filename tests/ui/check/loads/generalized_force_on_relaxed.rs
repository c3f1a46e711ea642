use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[relaxed(u)]
#[particle(bob, mass = 1.0, at = [x, u])]
#[generalized_force(push, along = u, value = 3.0)]
#[output(hold = reaction(u))]
pub struct Relaxed {}

fn main() {}
