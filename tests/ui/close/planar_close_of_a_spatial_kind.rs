use mbd::Mechanism;

/// A planar `close` is a revolute joint: `prismatic` and an axis are spatial.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(crank, joint = revolute(a), com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[body(coupler, parent = crank, joint = revolute(b), at = [1.0, 0.0], com = [1.0, 0.0], mass = 1.0, inertia = 0.1)]
#[body(rocker, joint = revolute(c), at = [2.0, 0.0], com = [0.0, 0.5], mass = 1.0, inertia = 0.1)]
#[close(pin, joint = prismatic, a = coupler, at_a = [2.0, 0.0], b = rocker, at_b = [0.0, 1.0])]
#[close(pin2, a = coupler, at_a = [2.0, 0.0], axis_a = [0.0, 0.0, 1.0], b = rocker, at_b = [0.0, 1.0])]
pub struct FourBar {}

fn main() {}
