use mbd::Mechanism;

/// A body closed on itself: two of its own points, 1 apart, can never meet.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(crank, joint = revolute(th), com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[body(arm, parent = crank, joint = revolute(ph), at = [1.0, 0.0], com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[body(tip, parent = arm, joint = revolute(ps), at = [1.0, 0.0], com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[close(pin, a = arm, at_a = [1.0, 0.0], b = arm, at_b = [0.0, 0.0])]
pub struct Itself {}

fn main() {}
