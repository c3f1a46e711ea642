use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, 0.0])]
#[spring(s, from = [0.0, 0.0], to = bob, k = 10.0, length = -0.5)]
pub struct Oscillator {}

fn main() {}
