use mbd::Mechanism;

#[derive(Mechanism)]
#[chain(link, n = 1, joint = revolute, length = 1.0, mass = 1.0)]
#[relaxed(link_q1)]
pub struct Chain {}

fn main() {}
