use mbd::Mechanism;

/// The derive generates `BlockOutputs` for a model with outputs: a user's item of that name
/// clashes, and rustc names both.
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[output(v = der(x))]
pub struct Block {}

pub struct BlockOutputs;

fn main() {}
