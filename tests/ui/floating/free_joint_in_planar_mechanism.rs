use mbd::Mechanism;

/// A free joint is spatial (its rotation is a ball's).
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(puck, joint = free(x, y, z, s1, s2, s3), com = [0.0, 0.0], mass = 1.0, inertia = 0.1)]
pub struct Puck {}

fn main() {}
