use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, der(x)])]
pub struct Slider {
    pub m: f64,
}

fn main() {}
