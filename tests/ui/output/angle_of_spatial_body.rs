use mbd::Mechanism;

/// A spatial body has no single angle: its orientation is a rotation.
#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[coords(a)]
#[rigid3(top, mass = 1.0, inertia = diag(0.1, 0.1, 0.2), at = [0.0, 0.0, 0.0], rotation = rot_z(a))]
#[output(turned = angle(top))]
pub struct Top {}

fn main() {}
