use mbd::Mechanism;

// Both torques would be applied: the second name is refused, its message naming the first.
#[derive(Mechanism)]
#[coords(theta)]
#[rigid(rod, mass = m, inertia = j, at = [0.0, 0.0], angle = theta)]
#[torque(tq, on = rod, value = a)]
#[torque(tq, on = rod, value = b)]
pub struct Wheel {
    pub m: f64,
    pub j: f64,
    pub a: f64,
    pub b: f64,
}

fn main() {}
