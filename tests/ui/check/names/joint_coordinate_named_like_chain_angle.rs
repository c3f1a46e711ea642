use mbd::Mechanism;

#[derive(Mechanism)]
#[chain(link, n = 2, joint = revolute, length = 1.0, mass = 1.0)]
#[body(arm, parent = ground, joint = revolute(link_q1), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
pub struct Chain {}

fn main() {}
