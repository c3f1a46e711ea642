use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(arm, parent = ground, joint = revolute(th), com = [0.0, -0.5], mass = -m, inertia = 0.1)]
pub struct Arm {
    #[default(2.0)]
    m: f64,
}

fn main() {}
