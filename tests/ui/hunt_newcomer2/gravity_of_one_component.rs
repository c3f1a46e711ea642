// Gravity written as a magnitude: it is a vector, and the message shows both forms.
use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(-g)]
#[coords(y)]
#[particle(ball, mass = m, at = [0.0, y])]
pub struct Falling {
    pub m: f64,
    pub g: f64,
}

fn main() {}
