use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, 0.0, -g)]
#[coords(theta)]
#[rigid(disc, mass = m, inertia = j, at = [0.0, 0.0, 0.0], angle = theta)]
pub struct Disc {
    pub m: f64,
    pub j: f64,
    pub g: f64,
}

fn main() {}
