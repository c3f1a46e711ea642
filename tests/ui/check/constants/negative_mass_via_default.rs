use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = -m, at = [x, 0.0])]
pub struct Slider {
    #[default(1.0)]
    m: f64,
}

fn main() {}
