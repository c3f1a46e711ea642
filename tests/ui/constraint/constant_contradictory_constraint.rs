use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(a, mass = m, at = [x, y])]
#[constraint(x == 0.0)]
#[constraint(x == 1.0)]
pub struct Contradiction {
    pub m: f64,
}

fn main() {}
