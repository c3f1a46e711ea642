// A damper at a pendulum's pivot, written on the angle: a damper acts between two points,
// and the message says how to write a damping torque on a coordinate instead.
use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(th)]
#[particle(bob, mass = m, at = [l * sin(th), -l * cos(th)])]
#[damper(pivot, on = th, c = c)]
pub struct Damped {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
}

fn main() {}
