use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(theta)]
#[rigid3(top, mass = m, inertia = diag(a, a, c), at = [0.0, 0.0, 0.0], rotation = theta)]
pub struct Top {
    pub m: f64,
    pub a: f64,
    pub c: f64,
}

fn main() {}
