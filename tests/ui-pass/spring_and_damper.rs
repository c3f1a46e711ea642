//! A mass on a line, tied to a fixed anchor by a spring of natural length `l0` and a
//! dashpot in parallel.
use mbd::prelude::*;

#[derive(Mechanism)]
#[coords(x)]
#[point(anchor, at = [0.0, 0.0])]
#[particle(bob, mass = m, at = [x, 0.0])]
#[spring(s, from = anchor, to = bob, k = k, length = l0)]
#[damper(d, from = anchor, to = bob, c = c)]
#[init(x = 1.5 * l0)]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
    pub l0: f64,
    pub c: f64,
}

fn main() {
    let osc = Oscillator {
        m: 1.0,
        k: 100.0,
        l0: 0.5,
        c: 0.3,
    };
    let _ = osc.initial_state();
}
