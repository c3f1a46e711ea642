use mbd::Mechanism;

#[derive(Mechanism)]
#[mechanism(jacobian, jacobian)]
#[coords(x)]
#[particle(ball, mass = 1.0, at = [x, 0.0])]
pub struct Ball {}

fn main() {}
