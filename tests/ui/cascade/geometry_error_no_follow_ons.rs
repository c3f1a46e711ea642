//! A model asking for its geometry, with one mistake: `geometry` still exists.
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[mechanism(geometry)]
#[coords(x)]
#[particle(bob, mass = -1.0, at = [x, 0.0])]
pub struct Bob {}

fn main() {
    let b = Bob {};
    let _ = b.geometry(0.0, &b.initial_state());
}
