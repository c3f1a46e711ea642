use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[drive(phi = omega * t + x)]
#[particle(slider, mass = m, at = [x, 0.0])]
#[rigid(crank, mass = m, inertia = j, at = [0.0, 0.0], angle = phi)]
pub struct Crank {
    pub m: f64,
    pub j: f64,
    pub omega: f64,
}

fn main() {}
