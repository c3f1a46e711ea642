use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[repeat(i in 0..3, particle(bob[i / 2], mass = m, at = [x + i, 0.0]))]
pub struct Twice {
    pub m: f64,
    pub g: f64,
}

fn main() {}
