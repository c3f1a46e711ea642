use mbd::Mechanism;

#[derive(Mechanism)]
#[drive(th = 2.0 * t)]
#[coords(x)]
#[rigid(disc, mass = 1.0, inertia = 0.5, at = [x, 0.0], angle = th)]
#[generalized_force(push, along = th, value = 3.0)]
pub struct Driven {}

fn main() {}
