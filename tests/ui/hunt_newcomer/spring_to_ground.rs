use mbd::Mechanism;

/// `ground` is not a point a spring can name: a fixed end is a position or a `point`.
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[spring(s, from = ground, to = block, k = k, length = 1.0)]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
}

fn main() {}
