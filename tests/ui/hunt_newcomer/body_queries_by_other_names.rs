use mbd::Mechanism;

/// Names of body queries from other tools: each gets the language's spelling.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(arm, joint = revolute(q), com = [0.0, -0.5], mass = 1.0, inertia = 0.1)]
#[output(w = omega(arm), v = speed(arm), e = kinetic_energy(arm), r = d(q))]
pub struct Arm {}

fn main() {}
