use mbd::Mechanism;

/// In a planar mechanism every revolute joint turns about the plane's normal.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(arm, joint = revolute(a, x), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
pub struct Arm {}

fn main() {}
