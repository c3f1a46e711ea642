use mbd::Mechanism;

// An input must be a parameter (a field): `force` is not one, and `p` is named twice.
#[derive(Mechanism)]
#[mechanism(jacobian)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = p)]
#[input(force, p, p)]
pub struct Slider {
    pub m: f64,
    pub p: f64,
}

fn main() {}
