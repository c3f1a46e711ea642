// A coordinate's rate spelled as other tools do (`dth`, `thd`): the hint is `der(th)`, not
// the nearest name `th`.
use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(th)]
#[particle(bob, mass = m, at = [l * sin(th), -l * cos(th)])]
#[generalized_force(drag, along = th, value = -c * dth)]
#[output(spin = thd)]
pub struct Damped {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
}

fn main() {}
