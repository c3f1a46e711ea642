//! Hunting linear analysis across scales: a very stiff and a very soft mode in one model
//! (a stiff mount beside a soft suspension), as a vibration engineer meets them. Each
//! reference is derived beside its test.

use mbd::analysis::linear::{ModeKind, linearize, modes, undamped_modes};
use mbd::prelude::*;
use std::f64::consts::TAU;

/// Two blocks on a line, each on its own spring to a wall (not coupled): `w_i^2 = k_i / m_i`
/// exactly, whatever the ratio of the two.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x1, x2)]
#[point(wall, at = [0.0, 0.0])]
#[particle(p1, mass = m1, at = [x1, 0.0])]
#[particle(p2, mass = m2, at = [x2, 0.0])]
#[spring(s1, from = wall, to = p1, k = k1, length = l0)]
#[spring(s2, from = wall, to = p2, k = k2, length = l0)]
pub struct TwoScales {
    pub m1: f64,
    pub m2: f64,
    pub k1: f64,
    pub k2: f64,
    pub l0: f64,
}

/// Blocks of 1 kg tuned to `f1` (soft) and `f2` (stiff) Hz.
fn two_scales(f1: f64, f2: f64) -> TwoScales {
    TwoScales {
        m1: 1.0,
        m2: 1.0,
        k1: (TAU * f1).powi(2),
        k2: (TAU * f2).powi(2),
        l0: 1.0,
    }
}

/// Both modes as oscillatory pairs at their own frequencies, from `modes` of `A` and from
/// `undamped_modes`, for frequency ratios a drivetrain or a structure on a stiff mount
/// has: 1 Hz beside 10 kHz, 0.1 Hz beside 100 kHz, 1 mHz beside 1 MHz.
fn check(f1: f64, f2: f64, tol: f64) {
    let p = two_scales(f1, f2);
    let y = Vector::<4>::new(p.l0, p.l0, 0.0, 0.0);
    let found = modes(&linearize(&p, 0.0, &y).unwrap()).unwrap();
    let kinds: Vec<_> = found.iter().map(|m| m.kind).collect();
    assert_eq!(
        kinds,
        [ModeKind::Oscillatory, ModeKind::Oscillatory],
        "{f1} Hz beside {f2} Hz: {found:?}"
    );
    for (m, f) in found.iter().zip([f1, f2]) {
        assert!(
            (m.frequency_hz() - f).abs() <= tol * f,
            "{} Hz for {f} Hz",
            m.frequency_hz()
        );
        assert!(m.damping_ratio.unwrap().abs() <= tol, "{m:?}");
        assert!(!m.unstable);
    }
    let normal = undamped_modes(&p, 0.0, &Vector::<2>::new(p.l0, p.l0)).unwrap();
    for (m, f) in normal.iter().zip([f1, f2]) {
        let got = m.frequency_hz().unwrap();
        assert!((got - f).abs() <= tol * f, "{got} Hz for {f} Hz");
    }
}

#[test]
fn one_hertz_beside_ten_kilohertz() {
    check(1.0, 1e4, 1e-12);
}

#[test]
fn a_tenth_of_a_hertz_beside_a_hundred_kilohertz() {
    check(0.1, 1e5, 1e-12);
}

#[test]
fn a_millihertz_beside_a_megahertz() {
    check(1e-3, 1e6, 1e-10);
}
