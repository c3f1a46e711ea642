use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint(y == min(x, 0.0))]
pub struct Ramp {
    pub m: f64,
    pub g: f64,
}

fn main() {}
