use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[event(wall = x - 1.0, rising)]
#[event(wall = x + 1.0, falling)]
pub struct Slider {
    pub m: f64,
}

fn main() {}
