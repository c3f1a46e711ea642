use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(y)]
#[particle(rocket, mass = m0 - 0.1 * t, at = [0.0, y])]
pub struct Rocket {
    m0: f64,
}

fn main() {}
