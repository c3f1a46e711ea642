use mbd::Mechanism;

/// A slider-crank whose rod (0.5) is shorter than its crank (1) with these defaults and the
/// crank at 90 degrees: `l sin(beta) == r sin(theta)` has no `beta`.
#[derive(Mechanism)]
#[coords(theta, beta, x)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(crank, mass = 1.0, inertia = 0.1, at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[particle(piston, mass = 1.0, at = [x, 0.0])]
#[init(theta = 1.5707963267948966)]
pub struct Short {
    #[default(1.0)]
    pub r: f64,
    #[default(0.5)]
    pub l: f64,
}

fn main() {}
