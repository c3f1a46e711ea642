use mbd::Mechanism;

/// A circle whose squared radius is written with the wrong sign: `x^2 + y^2 >= 0` never
/// meets `-l^2 - 0.25`, whatever the parameters.
#[derive(Mechanism)]
#[mechanism(augmented)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint(x * x + y * y == -(l * l) - 0.25)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
}

fn main() {}
