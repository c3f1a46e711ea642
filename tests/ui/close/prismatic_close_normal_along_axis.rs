use mbd::Mechanism;

/// A prismatic close's normal must leave the axis: `[0, 0, 2]` is along `[0, 0, 1]`.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -9.81)]
#[body(arm, joint = spherical(a, b, c), com = [0.0, 0.0, -0.5], mass = 1.0, inertia = diag(0.1, 0.1, 0.01))]
#[body(fore, parent = arm, joint = revolute(d, x), at = [0.0, 0.0, -1.0], com = [0.0, 0.0, -0.5], mass = 1.0,
       inertia = diag(0.1, 0.1, 0.01))]
#[close(slot, joint = prismatic, a = fore, at_a = [0.0, 0.0, -1.0], axis_a = [0.0, 0.0, 1.0],
        normal_a = [1.0, 0.0, 0.0], b = ground, axis_b = [0.0, 0.0, 1.0], normal_b = [0.0, 0.0, 2.0])]
pub struct Arm {}

fn main() {}
