use mbd::Mechanism;

// A Stribeck-like coefficient written with the velocity: coefficients are constants.
#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = m0 + c * der(x) * der(x), normal = m * g)]
pub struct Slider {
    pub m: f64,
    pub g: f64,
    pub m0: f64,
    pub c: f64,
}

fn main() {}
