use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(bob, mass = m, at = [x, 0.0])]
#[force(drag, at = [x, 0.0], value = -c * acceleration(bob))]
pub struct Drag {
    pub m: f64,
    pub c: f64,
}

fn main() {}
