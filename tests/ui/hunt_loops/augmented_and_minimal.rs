use mbd::Mechanism;

/// `augmented` and `minimal` contradict each other; the slider-crank has a closed form, so
/// neither would be refused on its own.
#[derive(Mechanism)]
#[mechanism(augmented, minimal)]
#[coords(theta, beta, x)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(crank, mass = 1.0, inertia = 0.1, at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[particle(piston, mass = 1.0, at = [x, 0.0])]
pub struct Both {
    pub r: f64,
    pub l: f64,
}

fn main() {}
