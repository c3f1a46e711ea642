use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint(x == l)]
#[constraint(y == 0.0)]
#[constraint(x + y == l)]
pub struct Fixed {
    pub m: f64,
    pub l: f64,
}

fn main() {}
