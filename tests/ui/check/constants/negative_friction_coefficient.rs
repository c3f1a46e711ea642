use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[friction(along = x, mu = -0.3, normal = 9.81)]
pub struct Block {}

fn main() {}
