use mbd::Mechanism;

/// A spherical close (the default in space) has no axis.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -9.81)]
#[body(arm, joint = spherical(a, b, c), com = [0.0, 0.0, -0.5], mass = 1.0, inertia = diag(0.1, 0.1, 0.01))]
#[body(fore, parent = arm, joint = revolute(d, x), at = [0.0, 0.0, -1.0], com = [0.0, 0.0, -0.5], mass = 1.0,
       inertia = diag(0.1, 0.1, 0.01))]
#[close(tip, a = fore, at_a = [0.0, 0.0, -1.0], axis_a = [1.0, 0.0, 0.0], b = ground, at_b = [0.0, 1.0, -1.0])]
pub struct Arm {}

fn main() {}
