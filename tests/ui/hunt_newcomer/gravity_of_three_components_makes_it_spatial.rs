use mbd::Mechanism;

/// A planar model written with a 3-component gravity: the mechanism becomes spatial, so a
/// planar position is refused, and the message says why the mechanism is spatial.
#[derive(Mechanism)]
#[gravity(0.0, -9.81, 0.0)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
pub struct Block {}

fn main() {}
