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

/// The soft block hangs on the stiff one: wall, stiff spring `k1`, block `m1`, soft spring
/// `k2`, block `m2` (a machine on a stiff mount carrying a softly suspended part). With
/// `M = diag(m1, m2)`, `K = [[k1 + k2, -k2], [-k2, k2]]`,
/// `det(K - w^2 M) = m1 m2 w^4 - b w^2 + k1 k2`, `b = m1 k2 + m2 (k1 + k2)`: the slow root
/// in the cancellation-free form `w^2 = 2 k1 k2 / (b + sqrt(b^2 - 4 m1 m2 k1 k2))`, the
/// fast one `k1 k2 / (m1 m2 w_slow^2)` (product of the roots).
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x1, x2)]
#[point(wall, at = [0.0, 0.0])]
#[particle(p1, mass = m1, at = [x1, 0.0])]
#[particle(p2, mass = m2, at = [x2, 0.0])]
#[spring(s1, from = wall, to = p1, k = k1, length = l0)]
#[spring(s2, from = p1, to = p2, k = k2, length = l0)]
pub struct Hung {
    pub m1: f64,
    pub m2: f64,
    pub k1: f64,
    pub k2: f64,
    pub l0: f64,
}

fn hung_reference(p: &Hung) -> [f64; 2] {
    let b = p.m1 * p.k2 + p.m2 * (p.k1 + p.k2);
    let slow = 2.0 * p.k1 * p.k2 / (b + (b * b - 4.0 * p.m1 * p.m2 * p.k1 * p.k2).sqrt());
    let fast = p.k1 * p.k2 / (p.m1 * p.m2 * slow);
    [slow.sqrt() / TAU, fast.sqrt() / TAU]
}

/// Coupled, 1 mHz under 1 MHz: both analyses give both frequencies (relative `1e-10`),
/// and the slow shape moves the soft block (`x1 / x2 ~ k2 / k1`) with velocities
/// `i w` times the positions.
#[test]
fn a_millihertz_part_on_a_megahertz_mount() {
    let p = Hung {
        m1: 3.0,
        m2: 0.5,
        k1: 3.0 * (TAU * 1e6).powi(2),
        k2: 0.5 * (TAU * 1e-3).powi(2),
        l0: 1.0,
    };
    let want = hung_reference(&p);
    let y = Vector::<4>::new(p.l0, 2.0 * p.l0, 0.0, 0.0);
    let found = modes(&linearize(&p, 0.0, &y).unwrap()).unwrap();
    assert_eq!(found.len(), 2, "{found:?}");
    for (m, f) in found.iter().zip(want) {
        assert_eq!(m.kind, ModeKind::Oscillatory, "{m:?}");
        assert!(
            (m.frequency_hz() - f).abs() <= 1e-10 * f,
            "{} Hz for {f} Hz",
            m.frequency_hz()
        );
    }
    let v = &found[0].shape;
    let iw = mbd::nalgebra::Complex::new(0.0, found[0].omega_n);
    assert!((v[1].norm() - 1.0).abs() < 1e-12, "{v}");
    assert!(v[0].norm() < 1e-12, "{v}");
    assert!((v[3] - iw * v[1]).norm() < 1e-12 * v[3].norm(), "{v}");
    let normal = undamped_modes(&p, 0.0, &Vector::<2>::new(p.l0, 2.0 * p.l0)).unwrap();
    for (m, f) in normal.iter().zip(want) {
        let got = m.frequency_hz().unwrap();
        assert!((got - f).abs() <= 1e-10 * f, "{got} Hz for {f} Hz");
        // Mass-normalised.
        let vmv = p.m1 * m.shape[0].powi(2) + p.m2 * m.shape[1].powi(2);
        assert!((vmv - 1.0).abs() < 1e-12, "{vmv}");
    }
}

/// A block on a damper to the wall (no spring: it creeps and stays where it stops) beside
/// an independent block on a stiff spring: `A` has the creep's simple zero (neutral: the
/// block rests anywhere), its decay `lambda = -c1 / m1` (real, time constant `m1 / c1`) and
/// the stiff pair `+-i sqrt(k2 / m2)`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x1, x2)]
#[point(wall, at = [0.0, 0.0])]
#[particle(p1, mass = m1, at = [x1, 0.0])]
#[particle(p2, mass = m2, at = [x2, 0.0])]
#[damper(d1, from = wall, to = p1, c = c1)]
#[spring(s2, from = wall, to = p2, k = k2, length = l0)]
pub struct CreepAndRing {
    pub m1: f64,
    pub m2: f64,
    pub c1: f64,
    pub k2: f64,
    pub l0: f64,
}

/// Time constants of 1000 s and 1 s beside a 1 MHz ring: the decay is a real mode at
/// `-c1 / m1` (not neutral, not unstable), the zero neutral, the ring at 1 MHz.
#[test]
fn a_slow_creep_beside_a_megahertz_ring() {
    for rate in [1e-3, 1.0] {
        let p = CreepAndRing {
            m1: 2.0,
            m2: 1.0,
            c1: 2.0 * rate,
            k2: (TAU * 1e6).powi(2),
            l0: 1.0,
        };
        let y = Vector::<4>::new(0.3, p.l0, 0.0, 0.0);
        let found = modes(&linearize(&p, 0.0, &y).unwrap()).unwrap();
        let kinds: Vec<_> = found.iter().map(|m| m.kind).collect();
        assert_eq!(
            kinds,
            [ModeKind::Neutral, ModeKind::Real, ModeKind::Oscillatory],
            "rate {rate}: {found:?}"
        );
        let decay = &found[1];
        assert!(
            (decay.eigenvalue.re + rate).abs() < 1e-10 * rate && decay.eigenvalue.im == 0.0,
            "{decay:?}"
        );
        assert_eq!(decay.damping_ratio, Some(1.0));
        // The creeping block alone, its velocity `-rate` times its position.
        let v = &decay.shape;
        assert!((v[2] / v[0] + rate).norm() < 1e-12 * rate, "{v}");
        assert!(v[1].norm() + v[3].norm() < 1e-12 * v[0].norm(), "{v}");
        assert!(!decay.unstable);
        assert!((found[2].frequency_hz() - 1e6).abs() < 1e-10 * 1e6);
    }
}
