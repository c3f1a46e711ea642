use mbd::Mechanism;

/// A typo of a known function (`sqr` aside, `atna2`), a path call (`f64::sin`) and a
/// function the language has no spelling for (`erf`, answered with the list).
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[output(a = atna2(x, 1.0), b = f64::sin(x), c = erf(x))]
pub struct Block {}

fn main() {}
