use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[partcle(bob, mass = m, at = [x, 0.0])]
pub struct Slider {
    pub m: f64,
}

fn main() {}
