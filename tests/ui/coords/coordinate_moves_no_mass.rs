use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, 0.0])]
pub struct Slider {
    pub m: f64,
    pub g: f64,
}

fn main() {}
