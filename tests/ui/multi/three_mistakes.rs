use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[particle(a, mass = m, at = [x, cosh(yy)])]
#[particle(b, mass = m, at = [x + l, y.sine()])]
#[particle(c, mass = m ^ 2, at = [x, y])]
pub struct Three {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

fn main() {}
