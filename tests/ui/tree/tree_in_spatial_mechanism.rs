use mbd::Mechanism;

/// Joint trees are planar.
#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[body(arm, joint = revolute(a), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
pub struct Arm {}

fn main() {}
