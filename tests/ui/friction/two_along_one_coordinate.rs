use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[relaxed(n)]
#[particle(block, mass = m, at = [x, n])]
#[friction(along = x, mu = 0.3, normal = reaction(n))]
#[friction(along = x, mu = 0.2, normal = reaction(n))]
pub struct Slider {
    pub m: f64,
    pub g: f64,
}

fn main() {}
