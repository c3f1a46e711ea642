use mbd::Mechanism;

#[derive(Mechanism)]
#[mechanism(recursive, mass_matrix)]
#[gravity(0.0, -9.81)]
#[chain(link, n = 2, joint = revolute, length = 1.0, mass = 1.0)]
pub struct Chain {}

fn main() {}
