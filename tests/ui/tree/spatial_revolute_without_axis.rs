use mbd::Mechanism;

/// A spatial revolute joint must name the axis it turns about.
#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[body(arm, joint = revolute(a), com = [0.0, 0.0, -0.5], mass = 1.0, inertia = diag(0.1, 0.1, 0.01))]
pub struct Arm {}

fn main() {}
