use mbd::Mechanism;

/// `=` where `==` is meant: the error points at the `=`.
#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint(x * x + y * y = l * l)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

fn main() {}
