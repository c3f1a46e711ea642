use mbd::Mechanism;

#[derive(Mechanism)]
#[chain(link, n = 2, joint = revolute, length = 1.0, mass = 1.0)]
#[point(link_2, at = [1.0, 0.0])]
pub struct Chain {}

fn main() {}
