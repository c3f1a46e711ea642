use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = sqrt(-1.0), at = [x, 0.0])]
pub struct Slider {}

fn main() {}
