use mbd::Mechanism;

/// A potential of time and parameters alone: `-dV/dq` is zero, it exerts no force.
#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[potential(0.5 * k * (l * sin(t)).powi(2))]
pub struct Vanishing {
    pub m: f64,
    pub k: f64,
    pub l: f64,
}

fn main() {}
