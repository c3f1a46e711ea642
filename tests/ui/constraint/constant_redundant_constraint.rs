use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y, z)]
#[particle(a, mass = m, at = [x, y])]
#[particle(b, mass = m, at = [z, 0.0])]
#[constraint(x == y)]
#[constraint(2.0 * x == 2.0 * y)]
pub struct Twice {
    pub m: f64,
}

fn main() {}
