use mbd::Mechanism;

// Friction written along the normal direction (the relaxed coordinate) by mistake.
#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[relaxed(n)]
#[particle(block, mass = m, at = [x, n])]
#[friction(along = n, mu = 0.3, normal = reaction(n))]
pub struct Slider {
    pub m: f64,
    pub g: f64,
}

fn main() {}
