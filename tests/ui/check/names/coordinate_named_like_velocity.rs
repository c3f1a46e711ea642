use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, x_dot)]
#[particle(a, mass = 1.0, at = [x, 0.0])]
#[particle(b, mass = 1.0, at = [x_dot, 1.0])]
pub struct Two {}

fn main() {}
