use mbd::Mechanism;

// A belt written with friction along the driven belt position instead of the block's
// place on it.
#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[drive(b = v * t)]
#[particle(block, mass = m, at = [b + s, 0.0])]
#[friction(along = b, mu = 0.3, normal = m * g)]
pub struct Belt {
    pub m: f64,
    pub g: f64,
    pub v: f64,
}

fn main() {}
