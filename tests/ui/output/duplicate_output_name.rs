use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[output(v = der(x), v = x)]
pub struct Slider {
    pub m: f64,
}

fn main() {}
