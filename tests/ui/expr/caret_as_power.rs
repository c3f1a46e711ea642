use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[potential(0.5 * k * x ^ 2)]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
}

fn main() {}
