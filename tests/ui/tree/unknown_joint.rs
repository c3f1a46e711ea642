use mbd::Mechanism;

/// A planar tree knows revolute, prismatic and fixed joints.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(bob, joint = spherical(a), com = [0.0, -0.5], mass = 1.0)]
pub struct Pendulum {}

fn main() {}
