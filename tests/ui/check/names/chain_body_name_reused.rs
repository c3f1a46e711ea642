use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[chain(link, n = 2, joint = revolute, length = 1.0, mass = 1.0)]
#[particle(link_2, mass = 1.0, at = [x, 0.0])]
pub struct Mixed {}

fn main() {}
