use mbd::Mechanism;

/// A crank pinned to the ground at its own pivot by a `close`: the two points coincide for
/// every angle, so both rows are identically zero (the loop closes nothing).
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(crank, joint = revolute(th), com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[close(pin, a = crank, at_a = [0.0, 0.0], b = ground, at_b = [0.0, 0.0])]
pub struct Pinned {}

fn main() {}
