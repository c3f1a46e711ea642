use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(x, mass = m, at = [x, 0.0])]
pub struct Slider {
    pub m: f64,
}

fn main() {}
