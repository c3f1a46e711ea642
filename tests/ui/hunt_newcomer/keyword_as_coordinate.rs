use mbd::Mechanism;

/// A Rust keyword cannot name a coordinate (it could not name the state's field either).
#[derive(Mechanism)]
#[coords(type)]
#[particle(block, mass = 1.0, at = [type, 0.0])]
pub struct Block {}

fn main() {}
