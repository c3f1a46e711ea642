use mbd::Mechanism;

/// `powi` wants a constant integer; a fraction or a parameter exponent is `powf`'s.
#[derive(Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[output(p = x.powi(2.5), q = powi(x, n))]
pub struct Block {
    pub n: f64,
}

fn main() {}
