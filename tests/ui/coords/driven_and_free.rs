use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(theta)]
#[drive(theta = omega * t)]
#[rigid(disc, mass = m, inertia = j, at = [0.0, 0.0], angle = theta)]
pub struct Disc {
    pub m: f64,
    pub j: f64,
    pub omega: f64,
}

fn main() {}
