use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m1 - m2, at = [x, 0.0])]
pub struct Slider {
    #[default(1.0)]
    m1: f64,
    #[default(2.0)]
    m2: f64,
}

fn main() {}
