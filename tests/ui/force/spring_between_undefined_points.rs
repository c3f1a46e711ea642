use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[spring(s, from = anchor, to = tip, k = k)]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
}

fn main() {}
