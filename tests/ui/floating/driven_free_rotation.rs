use mbd::Mechanism;

/// The rotation of a free joint is a ball's: none of its three coordinates can be driven
/// (its translation can).
#[derive(Mechanism)]
#[mechanism(spatial)]
#[drive(x = 0.1 * t)]
#[drive(s3 = 0.1 * t)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [0.0, 0.0, 0.1], mass = 1.0, inertia = diag(0.1, 0.2, 0.3))]
pub struct Sat {}

fn main() {}
