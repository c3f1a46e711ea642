use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1e400, at = [x, 0.0])]
pub struct Slider {}

fn main() {}
