use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[friction(along = x, mu = mu)]
pub struct Slider {
    pub m: f64,
    pub g: f64,
    pub mu: f64,
}

fn main() {}
