use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, 0.0])]
#[damper(d, from = [0.0, 0.0], to = bob, c = -0.2)]
pub struct Oscillator {}

fn main() {}
