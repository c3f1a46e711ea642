//! A machine-written model with thousands of outputs must not crash rustc: the derive's
//! outputs struct compared field by field (`a == b && ..`, as `#[derive(PartialEq)]` writes
//! it) overflowed rustc's stack from about 5500 fields ("rustc unexpectedly overflowed its
//! stack"); 6000 outputs of a repeat are past that.

use mbd::prelude::*;

/// A block at `x`; output `o_i = i x` for `i` in `0..6000`.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[repeat(i in 0..6000, output(o[i] = x * i))]
pub struct ManyOutputs {}

#[test]
fn six_thousand_outputs_compile_and_compare() {
    let p = ManyOutputs {};
    let y = Vector::<2>::new(2.0, 0.5);
    let out = p.outputs(0.0, &y).unwrap();
    assert_eq!((out.o0, out.o1, out.o5999), (0.0, 2.0, 2.0 * 5999.0));
    let values = p.output_values(0.0, &y).unwrap();
    assert!(values.iter().enumerate().all(|(i, v)| *v == 2.0 * i as f64));
    assert_eq!(ManyOutputs::OUTPUTS.len(), 6000);
    // Equality is field by field.
    let other = p.outputs(0.0, &Vector::<2>::new(2.0, 0.0)).unwrap();
    assert_eq!(out, other);
    assert_ne!(out, p.outputs(0.0, &Vector::<2>::new(1.0, 0.5)).unwrap());
    assert_eq!(ManyOutputsState::from(&y), ManyOutputsState::from(&y));
}
