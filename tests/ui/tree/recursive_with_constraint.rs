use mbd::Mechanism;

/// The articulated-body recursion is for open trees: a loop closure needs the mass matrix.
#[derive(Mechanism)]
#[mechanism(recursive)]
#[gravity(0.0, -9.81)]
#[body(crank, joint = revolute(a), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
#[body(rod, parent = crank, joint = revolute(b), at = [0.0, -1.0], com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
#[constraint(sin(a) + sin(a + b) == 1.5)]
pub struct Closed {}

fn main() {}
