use mbd::Mechanism;

#[derive(Mechanism)]
#[mechanism(spatial)]
#[mechanism(planar)]
#[coords(x)]
#[particle(ball, mass = 1.0, at = [x, 0.0])]
pub struct Ball {}

fn main() {}
