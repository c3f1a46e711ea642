use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = y, mu = 0.3, normal = m * g)]
pub struct Slider {
    pub m: f64,
    pub g: f64,
}

fn main() {}
