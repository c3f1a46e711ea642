use mbd::Mechanism;

// Friction on the full reaction of a pin is implicit (solved with the accelerations); the
// generated Jacobian differentiates the forces, which do not hold it: refused.
#[derive(Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(th), com = [0.0, -l], mass = m, inertia = 0.0, reaction)]
#[friction(along = th, mu = 0.05, normal = hypot(reaction(arm_rx), reaction(arm_ry)))]
pub struct Pin {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

fn main() {}
