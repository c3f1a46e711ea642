use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, f64::NAN])]
pub struct Slider {}

fn main() {}
