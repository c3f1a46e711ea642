use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[point(p, at = [1.0, 0.0])]
#[point(hook, on = p, at = [0.0, 1.0])]
#[point(peg, on = bob, at = [0.0, 1.0])]
pub struct Bad {
    pub m: f64,
    pub g: f64,
}

fn main() {}
