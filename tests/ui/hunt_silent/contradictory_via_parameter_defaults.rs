use mbd::Mechanism;

/// `x == a` and `x == b` with defaults 0 and 1 (issue 14: contradictory rows through
/// parameters).
#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = 1.0, at = [x, y])]
#[constraint(x == a)]
#[constraint(x == b)]
pub struct Twice {
    #[default(0.0)]
    pub a: f64,
    #[default(1.0)]
    pub b: f64,
}

fn main() {}
