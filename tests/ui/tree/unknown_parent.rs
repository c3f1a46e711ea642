use mbd::Mechanism;

/// `lower` names a parent declared after it (or not at all): a tree is declared root first.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(lower, parent = upper, joint = revolute(b), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
#[body(upper, joint = revolute(a), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
pub struct Double {}

fn main() {}
