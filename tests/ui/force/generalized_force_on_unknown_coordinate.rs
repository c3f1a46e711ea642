use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = y, value = f)]
pub struct Slider {
    pub m: f64,
    pub f: f64,
}

fn main() {}
