use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint(l == 1.0)]
pub struct Slider {
    pub m: f64,
    pub l: f64,
}

fn main() {}
