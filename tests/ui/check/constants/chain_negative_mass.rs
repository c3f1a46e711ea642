use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[chain(link, n = 3, joint = revolute, length = 1.0, mass = -m)]
pub struct Chain {
    #[default(1.0)]
    m: f64,
}

fn main() {}
