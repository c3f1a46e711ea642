use mbd::Mechanism;

/// A free joint's arguments are the names of its coordinates.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[body(sat, joint = free(x, y, 0.0, s1, s2, s3), mass = 1.0, inertia = diag(0.1, 0.2, 0.3))]
pub struct Sat {}

fn main() {}
