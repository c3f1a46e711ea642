//! Past the derive's documented size a model stops with a spanned error, quickly, instead
//! of exhausting the machine's memory (1024 links ran out of 6 GB; 10^8 would try to make
//! 10^8 bodies).
use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[chain(link, n = 100000000, joint = revolute, length = 1.0, mass = 1.0)]
pub struct Rope {}

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[chain(upper, n = 500, joint = revolute, length = 1.0, mass = 1.0)]
#[chain(lower, n = 13, joint = revolute, length = 1.0, mass = 1.0, parent = upper_500, at = [0.0, -1.0])]
pub struct TwoRopes {}

fn main() {}
