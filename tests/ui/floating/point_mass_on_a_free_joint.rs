use mbd::Mechanism;

/// A point mass alone on a free joint: nothing resists its turning about the line through
/// the joint origin and its mass centre.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -9.81)]
#[body(pm, joint = free(x, y, z, s1, s2, s3), com = [0.1, 0.0, 0.0], mass = 1.0)]
pub struct PointMass {}

fn main() {}
