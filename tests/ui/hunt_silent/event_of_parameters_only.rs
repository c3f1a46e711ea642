use mbd::Mechanism;

/// The event compares two parameters (the user meant `x - h`): it never crosses zero.
#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[event(landed = l - h, falling)]
pub struct Watched {
    pub m: f64,
    pub l: f64,
    pub h: f64,
}

fn main() {}
