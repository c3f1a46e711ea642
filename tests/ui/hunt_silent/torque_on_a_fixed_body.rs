use mbd::Mechanism;

/// The torque names the wheel, whose angle is a constant: it turns nothing (the user
/// meant the arm).
#[derive(Mechanism)]
#[coords(th)]
#[rigid(arm, mass = m, inertia = j, at = [0.0, 0.0], angle = th)]
#[rigid(wheel, mass = m, inertia = j, at = [1.0, 0.0], angle = 0.0)]
#[torque(motor, on = wheel, value = tau)]
pub struct Motor {
    pub m: f64,
    pub j: f64,
    pub tau: f64,
}

fn main() {}
