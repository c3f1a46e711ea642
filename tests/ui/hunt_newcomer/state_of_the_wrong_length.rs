use mbd::prelude::*;

/// The state is `[q; q']`, twice the coordinates: a state of the coordinates' length is a
/// type error at the call, with both lengths.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x, y)]
#[particle(block, mass = 1.0, at = [x, y])]
pub struct Block {}

fn main() {
    let _ = Block {}.rhs(0.0, &Vector::<2>::zeros());
}
