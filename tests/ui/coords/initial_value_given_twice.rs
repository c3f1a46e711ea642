use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[init(x = 1.0, x = 2.0)]
pub struct Slider {
    pub m: f64,
}

fn main() {}
