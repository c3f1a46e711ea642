use mbd::Mechanism;

/// Each of a free joint's six degrees of freedom needs its own coordinate.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[body(sat, joint = free(x, y, z, s1, s1, s3), com = [0.0, 0.0, 0.1], mass = 1.0, inertia = diag(0.1, 0.2, 0.3))]
pub struct Sat {}

fn main() {}
