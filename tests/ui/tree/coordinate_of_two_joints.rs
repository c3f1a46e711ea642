use mbd::Mechanism;

/// Each joint brings its own coordinate; two joints cannot share one.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(upper, joint = revolute(a), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
#[body(lower, parent = upper, joint = revolute(a), at = [0.0, -1.0], com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
pub struct Double {}

fn main() {}
