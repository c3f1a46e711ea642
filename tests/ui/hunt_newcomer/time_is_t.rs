use mbd::Mechanism;

/// Time is `t`, not `time`.
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = m, at = [x, 0.0])]
#[generalized_force(push, along = x, value = f * sin(w * time))]
pub struct Shaken {
    pub m: f64,
    pub f: f64,
    pub w: f64,
}

fn main() {}
