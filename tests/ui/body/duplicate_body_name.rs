use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[particle(bob, mass = m, at = [0.0, y])]
pub struct Pair {
    pub m: f64,
}

fn main() {}
