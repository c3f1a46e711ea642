use mbd::Mechanism;

/// A spatial revolute `close` of a crank to the ground at its own joint, about its own
/// axis: every one of the five rows vanishes whatever the angle (the tree's joint already
/// is that hinge), so the `close` closes no loop. Rows that vanish beside others that do
/// not are dropped (a Sarrus linkage's hinge); a joint all of whose rows vanish is refused.
#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[body(crank, joint = revolute(th, x), com = [0.0, 0.5, 0.0], mass = 1.0, inertia = diag(0.1, 0.1, 0.1))]
#[close(hinge, joint = revolute, a = crank, at_a = [0.0, 0.0, 0.0], axis_a = [1.0, 0.0, 0.0],
        b = ground, at_b = [0.0, 0.0, 0.0], axis_b = [1.0, 0.0, 0.0])]
pub struct Hinged {}

fn main() {}
