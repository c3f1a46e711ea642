use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[output(heading = atan2(y))]
pub struct Planar {
    pub m: f64,
}

fn main() {}
