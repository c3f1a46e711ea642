use mbd::Mechanism;

/// Both ends are ground points (the user meant `to = bob`): the spring acts on nothing.
#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[point(wall, at = [0.0, 0.0])]
#[point(rest, at = [1.0, 0.0])]
#[spring(s, from = wall, to = rest, k = k)]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
}

fn main() {}
