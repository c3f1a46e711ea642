use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, 1.0 / (2.0 - 2.0)])]
pub struct Slider {}

fn main() {}
