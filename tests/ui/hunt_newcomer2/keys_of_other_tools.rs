// Keys as other tools and textbooks name them: each says the key meant, and the key it
// stands for is not reported missing a second time.
use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(cart, m = m, at = [x, 0.0])]
#[spring(s, from = [0.0, 0.0], to = cart, stiffness = k, rest_length = 0.5)]
#[force(push, on = cart, value = [u, 0.0])]
#[generalized_force(drag, on = x, value = -c * der(x))]
pub struct Cart {
    pub m: f64,
    pub k: f64,
    pub u: f64,
    pub c: f64,
}

fn main() {}
