use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[torque(spin, on = bob, value = tau)]
pub struct Slider {
    pub m: f64,
    pub tau: f64,
}

fn main() {}
