use mbd::Mechanism;

/// A spherical joint turns about three axes: it needs a spatial mechanism.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(bob, joint = spherical(a, b, c), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
pub struct Bob {}

fn main() {}
