use mbd::Mechanism;

/// A damper between two positions that no coordinate moves: it damps nothing.
#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[damper(d, from = [0.0, 0.0], to = [1.0, 0.0], c = c)]
pub struct Damped {
    pub m: f64,
    pub c: f64,
}

fn main() {}
