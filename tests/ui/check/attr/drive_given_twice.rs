use mbd::Mechanism;

#[derive(Mechanism)]
#[drive(s = t)]
#[drive(s = 2.0 * t)]
#[coords(x)]
#[particle(ball, mass = 1.0, at = [x + s, 0.0])]
pub struct Ball {}

fn main() {}
