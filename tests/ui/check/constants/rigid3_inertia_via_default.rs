use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[coords(a)]
#[rigid3(top, mass = 1.0, inertia = diag(ia, ia, ic), at = [0.0, 0.0, 0.0], rotation = rot_z(a))]
pub struct Top {
    #[default(1.0)]
    ia: f64,
    #[default(0.0)]
    ic: f64,
}

fn main() {}
