use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(arm_rx)]
#[body(arm, parent = ground, joint = revolute(th), com = [0.0, -0.5], mass = 1.0, inertia = 0.1, reaction)]
#[particle(p, mass = 1.0, at = [arm_rx, 1.0])]
pub struct Arm {}

fn main() {}
