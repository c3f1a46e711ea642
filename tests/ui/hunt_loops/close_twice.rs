use mbd::Mechanism;

/// A five-bar (two degrees of freedom) whose pin is written twice: four rows for four
/// coordinates, the second pair repeating the first, so the constraint Jacobian is rank
/// deficient at every configuration.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(left, joint = revolute(a), com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[body(left2, parent = left, joint = revolute(b), at = [1.0, 0.0], com = [1.0, 0.0], mass = 1.0, inertia = 0.2)]
#[body(right, joint = revolute(c), at = [3.0, 0.0], com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[body(right2, parent = right, joint = revolute(d), at = [1.0, 0.0], com = [1.0, 0.0], mass = 1.0, inertia = 0.2)]
#[close(pin, a = left2, at_a = [2.0, 0.0], b = right2, at_b = [2.0, 0.0])]
#[close(pin2, a = left2, at_a = [2.0, 0.0], b = right2, at_b = [2.0, 0.0])]
pub struct Twice {}

fn main() {}
