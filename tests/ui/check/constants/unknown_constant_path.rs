use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(th)]
#[rigid(disc, mass = 1.0, inertia = 0.5, at = [0.0, 0.0], angle = th + std::f64::consts::HALF_PI)]
pub struct Disc {}

fn main() {}
