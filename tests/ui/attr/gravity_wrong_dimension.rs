use mbd::Mechanism;

#[derive(Mechanism)]
#[mechanism(planar)]
#[gravity(0.0, 0.0, -g)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
pub struct Slider {
    pub m: f64,
    pub g: f64,
}

fn main() {}
