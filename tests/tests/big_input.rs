//! Big input never crashes the derive: a potential of 8192 terms and one nested 770
//! parentheses deep (both overflowed rustc's stack with `SIGSEGV` before the derive ran on
//! its own stack) compile and give the right dynamics. The models are written by
//! `macro_rules!` doubling or nesting tokens, so that this file stays short; the derive sees
//! the expanded tokens exactly as if they were written out. The documented limit past which
//! the derive refuses, with a spanned error, is pinned in `tests/ui/size/`.

use mbd::Vector;
use mbd::prelude::*;

/// `sum!((x x ..), model, t)`: doubles the sum `t` once per `x` (13 times: 8192 terms),
/// then hands it to `model!`.
macro_rules! sum {
    ((), $model:ident, $($t:tt)*) => { $model!{ $($t)* } };
    ((x $($n:tt)*), $model:ident, $($t:tt)*) => { sum!{ ($($n)*), $model, $($t)* + $($t)* } };
}

/// `nest!((x x ..), model, t)`: wraps `t` in ten parentheses once per `x` (77 times: 770
/// deep), then hands it to `model!`.
macro_rules! nest {
    ((), $model:ident, $($t:tt)*) => { $model!{ $($t)* } };
    ((x $($n:tt)*), $model:ident, $($t:tt)*) => {
        nest!{ ($($n)*), $model, (((((((((($($t)*)))))))))) }
    };
}

/// A particle on a spring along x, its potential written as given.
macro_rules! long_sum_model {
    ($($v:tt)*) => {
        #[derive(Debug, Mechanism)]
        #[coords(x)]
        #[particle(p, mass = m, at = [x, 0.0])]
        #[potential($($v)*)]
        pub struct LongSum {
            pub m: f64,
            pub k: f64,
        }
    };
}

macro_rules! deep_model {
    ($($v:tt)*) => {
        #[derive(Debug, Mechanism)]
        #[coords(x)]
        #[particle(p, mass = m, at = [x, 0.0])]
        #[potential($($v)*)]
        pub struct Deep {
            pub m: f64,
            pub k: f64,
        }
    };
}

// 8192 equal terms k x^2 / 16384 sum to k x^2 / 2.
sum!((x x x x x x x x x x x x x), long_sum_model, k * x * x / 16384.0);
// k (x - 1/4)^2 / 2 inside 770 parentheses.
nest!(
    (x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x
     x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x x),
    deep_model, 0.5 * k * (x - 0.25) * (x - 0.25)
);

#[test]
fn a_potential_of_8192_terms_is_a_spring() {
    let model = LongSum { m: 2.0, k: 3.0 };
    let q = Vector::<1>::new(0.7);
    let qd = Vector::<1>::new(-0.3);
    let a = MechanismModel::acceleration(&model, 0.0, &q, &qd).unwrap();
    // m x'' = -k x: 8192 terms k x^2 / 16384 are k x^2 / 2 exactly (powers of two).
    assert!((a[0] + 3.0 * 0.7 / 2.0).abs() <= 1e-15, "{}", a[0]);
}

#[test]
fn a_potential_770_parentheses_deep_is_a_spring() {
    let model = Deep { m: 2.0, k: 3.0 };
    let q = Vector::<1>::new(0.7);
    let qd = Vector::<1>::new(-0.3);
    let a = MechanismModel::acceleration(&model, 0.0, &q, &qd).unwrap();
    // m x'' = -k (x - 1/4).
    assert!((a[0] + 3.0 * (0.7 - 0.25) / 2.0).abs() <= 1e-15, "{}", a[0]);
}
