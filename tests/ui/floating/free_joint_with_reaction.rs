use mbd::Mechanism;

/// A free joint transmits no force: there is no reaction to free.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -9.81)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [0.0, 0.0, 0.1], mass = 1.0, inertia = diag(0.1, 0.2, 0.3), reaction)]
pub struct Sat {}

fn main() {}
