use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[spring(s, from = bob, to = [0.0, 0.0], k = m, length = position(bob)[0])]
pub struct Bad {
    pub m: f64,
}

fn main() {}
