use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, 0.0])]
#[output(side = position(bob, [0.1, 0.0])[0])]
pub struct Slider {}

fn main() {}
