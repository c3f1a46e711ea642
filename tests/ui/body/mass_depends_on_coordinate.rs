use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m * x, at = [x, 0.0])]
pub struct Slider {
    pub m: f64,
}

fn main() {}
