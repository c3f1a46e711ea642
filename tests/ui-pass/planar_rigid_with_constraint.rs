//! A rod of length `l` hanging from a pin at the origin, in absolute coordinates
//! `(x, y, theta)` of its mass centre, pinned by two constraints.
use mbd::prelude::*;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, y, theta)]
#[rigid(rod, mass = m, inertia = m * l * l / 12.0, at = [x, y], angle = theta)]
#[constraint(x == 0.5 * l * sin(theta))]
#[constraint(y == -0.5 * l * cos(theta))]
#[init(x = 0.0, y = -0.5 * l, theta = 0.0)]
pub struct PinnedRod {
    #[default(1.0)]
    pub m: f64,
    #[default(0.8)]
    pub l: f64,
    #[default(9.81)]
    pub g: f64,
}

fn main() {
    let rod = PinnedRod {
        m: 1.0,
        l: 0.8,
        g: 9.81,
    };
    let _ = rod.initial_state();
}
