use mbd::Mechanism;

#[derive(Mechanism)]
#[body(arm, parent = ground, joint = revolute(th), com = [0.0, -0.5], mass = 1.0, inertia = 0.1, reaction)]
#[spring(arm_ry, from = [0.0, 1.0], to = arm, k = 10.0)]
pub struct Arm {}

fn main() {}
