use mbd::Mechanism;

// `B = d(y')/du` comes from the generated derivatives: inputs need them.
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = p)]
#[input(p)]
pub struct Slider {
    pub m: f64,
    pub p: f64,
}

fn main() {}
