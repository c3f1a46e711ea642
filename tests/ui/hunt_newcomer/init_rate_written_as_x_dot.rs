use mbd::Mechanism;

/// A newcomer gives the initial rate by the state's name `theta_dot`: `init` takes
/// `der(theta) = ..`, and the message says so.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(theta)]
#[particle(bob, mass = m, at = [l * theta.sin(), -l * theta.cos()])]
#[init(theta = 0.5, theta_dot = 1.0)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
}

fn main() {}
