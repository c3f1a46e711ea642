use mbd::Mechanism;

// Forces, torques and generalised forces share one namespace of load names.
#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[force(push, at = bob, value = [f, 0.0])]
#[generalized_force(push, along = x, value = f)]
#[force(push, at = bob, value = [0.0, f])]
pub struct Slider {
    pub m: f64,
    pub f: f64,
}

fn main() {}
