use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(a, mass = m, at = [x, y])]
#[constraint(x == x + 1.0)]
pub struct Never {
    pub m: f64,
}

fn main() {}
