use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, 0.0])]
pub struct Slider(f64);

fn main() {}
