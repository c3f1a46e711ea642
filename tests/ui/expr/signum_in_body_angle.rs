use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(theta)]
#[rigid(disc, mass = m, inertia = j, at = [0.0, 0.0], angle = theta.signum())]
pub struct Disc {
    pub m: f64,
    pub j: f64,
}

fn main() {}
