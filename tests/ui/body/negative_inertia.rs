use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(theta)]
#[rigid(disc, mass = m, inertia = -0.5, at = [0.0, 0.0], angle = theta)]
pub struct Disc {
    pub m: f64,
}

fn main() {}
