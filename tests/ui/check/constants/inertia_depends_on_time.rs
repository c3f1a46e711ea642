use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(th)]
#[rigid(wheel, mass = 1.0, inertia = 0.5 + t, at = [0.0, 0.0], angle = th)]
pub struct Wheel {}

fn main() {}
