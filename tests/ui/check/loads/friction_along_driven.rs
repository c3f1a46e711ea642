use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[drive(s = t)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x + s, 0.0])]
#[friction(along = s, mu = 0.3, normal = 9.81)]
pub struct Block {}

fn main() {}
