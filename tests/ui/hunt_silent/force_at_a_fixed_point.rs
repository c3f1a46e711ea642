use mbd::Mechanism;

/// The force is applied at a ground position, not at the bob: it does no work.
#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[force(push, at = [1.0, 0.0], value = [f, 0.0])]
pub struct Pushed {
    pub m: f64,
    pub f: f64,
}

fn main() {}
