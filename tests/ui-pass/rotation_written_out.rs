//! A rotation written out as a matrix of the coordinates is accepted when it is one.
use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[coords(a)]
#[rigid3(top, mass = 1.0, inertia = diag(1.0, 1.0, 2.0), at = [0.0, 0.0, 0.0],
         rotation = [[cos(a), -sin(a), 0.0], [sin(a), cos(a), 0.0], [0.0, 0.0, 1.0]] * rot_x(0.3))]
pub struct Top {}

fn main() {
    let _ = Top {}.initial_state();
}
