use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[event(x - 1.0, rising)]
pub struct Slider {
    pub m: f64,
}

fn main() {}
