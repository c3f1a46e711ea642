use mbd::Mechanism;

/// A parameter misspelled in a body (`lenght`) and one only a letter off (`mas`): each is
/// named with the declared one it is a typo of.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(arm, joint = revolute(q), com = [0.0, -lenght / 2.0], mass = mas,
       inertia = mass * length * length / 12.0)]
pub struct Arm {
    pub mass: f64,
    pub length: f64,
}

fn main() {}
