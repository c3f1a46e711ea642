use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(t)]
#[particle(bob, mass = m, at = [t, 0.0])]
pub struct Slider {
    pub m: f64,
}

fn main() {}
