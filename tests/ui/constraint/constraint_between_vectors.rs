use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint([x, y] == [l, 0.0])]
pub struct Fixed {
    pub m: f64,
    pub l: f64,
}

fn main() {}
