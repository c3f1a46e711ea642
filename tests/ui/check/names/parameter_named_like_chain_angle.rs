use mbd::Mechanism;

#[derive(Mechanism)]
#[chain(link, n = 2, joint = revolute, length = 1.0, mass = 1.0)]
pub struct Chain {
    link_q2: f64,
}

fn main() {}
