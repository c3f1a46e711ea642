use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(link_q1)]
#[chain(link, n = 2, joint = revolute, length = 1.0, mass = 1.0)]
#[particle(p, mass = 1.0, at = [link_q1, 0.0])]
pub struct Mixed {}

fn main() {}
