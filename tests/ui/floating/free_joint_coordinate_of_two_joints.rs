use mbd::Mechanism;

/// A coordinate of a free joint moved by another joint too.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[body(base, joint = free(x, y, z, s1, s2, s3), mass = 10.0, inertia = diag(1.0, 2.0, 3.0))]
#[body(arm, parent = base, joint = revolute(x, z), at = [0.5, 0.0, 0.0], com = [0.2, 0.0, 0.0], mass = 1.0, inertia = diag(0.01, 0.1, 0.1))]
pub struct Sat {}

fn main() {}
