use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[gravity(0.0, -1.62)]
#[coords(y)]
#[particle(ball, mass = 1.0, at = [0.0, y])]
pub struct Ball {}

fn main() {}
