use mbd::Mechanism;

/// A free joint has six coordinates: three of translation, three of the ball's rotation.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[body(sat, joint = free(x, y, z, s1, s2), com = [0.0, 0.0, 0.1], mass = 1.0, inertia = diag(0.1, 0.2, 0.3))]
pub struct Sat {}

fn main() {}
