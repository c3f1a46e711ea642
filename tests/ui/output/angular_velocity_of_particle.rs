use mbd::Mechanism;

/// A particle has no orientation, so no angular velocity either.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, 0.0])]
#[output(spin = angular_velocity(bob))]
pub struct Slider {}

fn main() {}
