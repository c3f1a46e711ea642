use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, abs(x)])]
pub struct Vee {
    pub m: f64,
    pub g: f64,
}

fn main() {}
