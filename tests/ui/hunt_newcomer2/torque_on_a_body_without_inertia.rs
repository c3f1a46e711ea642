// A motor torque on a joint-tree `body` given no `inertia` (a point mass): the message
// names the body kind the user wrote and both ways out.
use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(q), com = [0.0, -l], mass = m)]
#[torque(motor, on = arm, value = tau)]
pub struct Arm {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub tau: f64,
}

fn main() {}
