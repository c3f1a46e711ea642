//! Meanings the checks must not refuse: the constants of `std::f64::consts` by path or bare
//! name, and a `drive` of a chain's generated angle (driving that joint).
use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[chain(link, n = 2, joint = revolute, length = 1.0, mass = 1.0, inertia = 0.1)]
#[drive(link_q1 = std::f64::consts::FRAC_PI_4 * (TAU * t).sin())]
#[init(link_q2 = core::f64::consts::FRAC_PI_6)]
#[output(tip = position(link_2, [0.0, -1.0])[0])]
pub struct Driven {}

fn main() {
    let m = Driven {};
    let y = m.initial_state();
    assert!(m.outputs(0.0, &y).is_ok());
}
