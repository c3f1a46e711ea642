use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(th)]
#[rigid(disc, mass = 1.0, inertia = i, at = [0.0, 0.0], angle = th)]
pub struct Disc {
    #[default(0.0)]
    i: f64,
}

fn main() {}
