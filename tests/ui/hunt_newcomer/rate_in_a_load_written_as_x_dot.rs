use mbd::Mechanism;

/// A viscous drag written with `x_dot`: the rate of `x` is `der(x)`.
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(drag, along = x, value = -c * x_dot)]
pub struct Block {
    pub m: f64,
    pub c: f64,
}

fn main() {}
