use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
pub struct Slider {
    pub m: f32,
}

fn main() {}
