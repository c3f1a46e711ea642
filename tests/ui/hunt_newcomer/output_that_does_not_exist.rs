use mbd::prelude::*;

/// Asking the outputs for a name no `#[output]` declared: rustc lists the ones there are.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[output(v = der(x))]
pub struct Block {}

fn main() {
    let out = Block {}.outputs(0.0, &Vector::<2>::zeros()).unwrap();
    let _ = out.speed;
}
