//! Spellings from other languages get a message that says what to write here: `**`, `%`,
//! `&&`, `log`, `log10`, `pow`, `cbrt` and a field of a vector.
use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(b, mass = 1.0, at = [x, 0.0])]
#[output(a = x ** 2.0, c = x % 2.0, d = x && x)]
#[output(e = log(x), f = log10(x), h = pow(x, 2), i = cbrt(x))]
#[output(j = position(b).x)]
pub struct Hints {}

fn main() {}
