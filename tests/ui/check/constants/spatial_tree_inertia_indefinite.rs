use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[body(arm, parent = ground, joint = revolute(a, z), com = [0.5, 0.0, 0.0], mass = 1.0, inertia = diag(0.1, -0.1, 0.1))]
pub struct Arm {}

fn main() {}
