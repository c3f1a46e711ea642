use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(y)]
#[particle(ball, mass = 1.0, at = [0.0, y])]
#[event(ground = y, rising, falling)]
pub struct Ball {}

fn main() {}
