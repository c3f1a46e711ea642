use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[coords(a)]
#[rigid3(top, mass = 1.0, inertia = diag(1.0, 1.0, 3.0), at = [0.0, 0.0, 0.0], rotation = rot_z(a))]
pub struct Top {}

fn main() {}
