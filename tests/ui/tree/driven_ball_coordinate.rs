use mbd::Mechanism;

/// A ball joint's three coordinates are one rotation: none of them can be driven.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -9.81)]
#[drive(s2 = 0.1 * t)]
#[body(bob, joint = ball(s1, s2, s3), com = [0.0, 0.0, -0.5], mass = 1.0, inertia = diag(0.1, 0.1, 0.01))]
pub struct Bob {}

fn main() {}
