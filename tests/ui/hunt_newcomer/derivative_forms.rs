use mbd::Mechanism;

/// `der` takes one argument (the derivative is in time), `powi` an integer exponent (`2.5` is not one).
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[output(v = der(x, t))]
#[output(p = x.powi(2.5))]
pub struct Block {}

fn main() {}
