use mbd::Mechanism;

// A kinematics mistake only the mechanics sees (a vector for a planar angle), and in a
// torque, an output and an event mistakes the lowering sees before any mechanics: all
// four are reported at once (the mechanics stop after the kinematics' errors, so the
// last three were not reported before the whole model was lowered up front).
#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[rigid(rod, mass = m, inertia = j, at = [l * sin(theta), -l * cos(theta)], angle = [theta, 0.0])]
#[torque(drag, on = rod, value = -c * der(theta) ^ 2)]
#[output(height = -l * cosine(theta))]
#[event(stop = theta - bound, falling)]
pub struct Pendulum {
    pub m: f64,
    pub j: f64,
    pub l: f64,
    pub g: f64,
    pub c: f64,
}

fn main() {}
