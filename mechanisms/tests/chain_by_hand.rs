//! The hand-written articulated-body chain against independent references: the derive's
//! explicit-expression models of the same chains (written out here by hand, Kane's method
//! with a mass-matrix solve: a different algorithm), the compound pendulum's closed form, and
//! the conservation of energy computed from the kinematics alone.

use mbd::integrate::{Dopri5, Integrator};
use mbd::prelude::*;
use mechanisms::chain_by_hand::ChainByHand;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(q1)]
#[rigid(link1, mass = m, inertia = m * l * l / 12.0,
        at = [l / 2.0 * sin(q1), -l / 2.0 * cos(q1)], angle = q1)]
pub struct Chain1 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(q1, q2)]
#[rigid(link1, mass = m, inertia = m * l * l / 12.0,
        at = [l / 2.0 * sin(q1), -l / 2.0 * cos(q1)], angle = q1)]
#[rigid(link2, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l / 2.0 * sin(q1 + q2), -l * cos(q1) - l / 2.0 * cos(q1 + q2)],
        angle = q1 + q2)]
pub struct Chain2 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(q1, q2, q3)]
#[rigid(link1, mass = m, inertia = m * l * l / 12.0,
        at = [l / 2.0 * sin(q1), -l / 2.0 * cos(q1)], angle = q1)]
#[rigid(link2, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l / 2.0 * sin(q1 + q2), -l * cos(q1) - l / 2.0 * cos(q1 + q2)],
        angle = q1 + q2)]
#[rigid(link3, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l * sin(q1 + q2) + l / 2.0 * sin(q1 + q2 + q3),
              -l * cos(q1) - l * cos(q1 + q2) - l / 2.0 * cos(q1 + q2 + q3)],
        angle = q1 + q2 + q3)]
pub struct Chain3 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(q1, q2, q3, q4, q5)]
#[rigid(link1, mass = m, inertia = m * l * l / 12.0,
        at = [l / 2.0 * sin(q1), -l / 2.0 * cos(q1)], angle = q1)]
#[rigid(link2, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l / 2.0 * sin(q1 + q2), -l * cos(q1) - l / 2.0 * cos(q1 + q2)],
        angle = q1 + q2)]
#[rigid(link3, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l * sin(q1 + q2) + l / 2.0 * sin(q1 + q2 + q3),
              -l * cos(q1) - l * cos(q1 + q2) - l / 2.0 * cos(q1 + q2 + q3)],
        angle = q1 + q2 + q3)]
#[rigid(link4, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l * sin(q1 + q2) + l * sin(q1 + q2 + q3)
                  + l / 2.0 * sin(q1 + q2 + q3 + q4),
              -l * cos(q1) - l * cos(q1 + q2) - l * cos(q1 + q2 + q3)
                  - l / 2.0 * cos(q1 + q2 + q3 + q4)],
        angle = q1 + q2 + q3 + q4)]
#[rigid(link5, mass = m, inertia = m * l * l / 12.0,
        at = [l * sin(q1) + l * sin(q1 + q2) + l * sin(q1 + q2 + q3)
                  + l * sin(q1 + q2 + q3 + q4) + l / 2.0 * sin(q1 + q2 + q3 + q4 + q5),
              -l * cos(q1) - l * cos(q1 + q2) - l * cos(q1 + q2 + q3)
                  - l * cos(q1 + q2 + q3 + q4) - l / 2.0 * cos(q1 + q2 + q3 + q4 + q5)],
        angle = q1 + q2 + q3 + q4 + q5)]
pub struct Chain5 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// A reproducible stream of numbers in [-1, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// `|a - b|_inf <= tol |b|_inf`.
fn assert_rel<const N: usize>(a: &Vector<N>, b: &Vector<N>, tol: f64, what: &str) {
    let err = (a - b).amax();
    let scale = b.amax();
    assert!(
        err <= tol * scale,
        "{what}: |a - b| = {err:.3e} > {tol:.0e} * {scale:.3e}\n a = {a:?}\n b = {b:?}"
    );
}

/// Random states (angles in [-pi, pi), rates in [-3, 3)) and parameters; the hand-written
/// accelerations against the generated model's, to 1e-12 relative.
fn compare<const N: usize, const D: usize, G: MechanismModel<N>>(
    make: impl Fn(f64, f64, f64) -> G,
    seed: u64,
) {
    let mut rng = Lcg(seed);
    for trial in 0..50 {
        let (m, l, g) = (1.0 + 0.9 * rng.next(), 1.0 + 0.5 * rng.next(), 9.81);
        let generated = make(m, l, g);
        let by_hand = ChainByHand::<N>::new(m, l, g);
        let q = Vector::<N>::from_fn(|_, _| std::f64::consts::PI * rng.next());
        let qd = Vector::<N>::from_fn(|_, _| 3.0 * rng.next());
        let reference = generated.acceleration(0.0, &q, &qd).unwrap();
        let ours = by_hand.acceleration(&q, &qd).unwrap();
        assert_rel(&ours, &reference, 1e-12, &format!("N = {N}, trial {trial}"));
        // The first-order form the integrators see.
        let y = Vector::<D>::from_fn(|i, _| if i < N { q[i] } else { qd[i - N] });
        let f = by_hand.rhs(0.0, &y).unwrap();
        assert_eq!(f.rows(0, N), qd.rows(0, N));
        assert_eq!(f.rows(N, N), ours.rows(0, N));
    }
}

#[test]
fn one_link_equals_the_generated_model() {
    compare::<1, 2, _>(|m, l, g| Chain1 { m, l, g }, 1);
}

#[test]
fn two_links_equal_the_generated_model() {
    compare::<2, 4, _>(|m, l, g| Chain2 { m, l, g }, 2);
}

#[test]
fn three_links_equal_the_generated_model() {
    compare::<3, 6, _>(|m, l, g| Chain3 { m, l, g }, 3);
}

#[test]
fn five_links_equal_the_generated_model() {
    compare::<5, 10, _>(|m, l, g| Chain5 { m, l, g }, 5);
}

/// A uniform rod pinned at one end: `I_O = m l^2 / 3`, gravity's moment `-m g (l/2) sin q`,
/// so `q'' = -(3 g / (2 l)) sin q` whatever the rate.
#[test]
fn one_link_is_the_compound_pendulum() {
    let (m, l, g) = (2.5, 0.8, 9.81);
    let chain = ChainByHand::<1>::new(m, l, g);
    for q in [-3.0, -1.2, -0.1, 0.0, 0.4, std::f64::consts::FRAC_PI_2, 2.9] {
        for qd in [-4.0, 0.0, 2.5] {
            let qdd = chain
                .acceleration(&Vector::<1>::new(q), &Vector::<1>::new(qd))
                .unwrap()[0];
            let exact = -3.0 * g / (2.0 * l) * f64::sin(q);
            assert!(
                (qdd - exact).abs() <= 1e-14 * (3.0 * g / (2.0 * l)),
                "q = {q}, qd = {qd}: {qdd} vs {exact}"
            );
        }
    }
    // Energy of the rod: (1/2)(m l^2 / 3) qd^2 - m g (l / 2) cos q.
    let (q, qd) = (0.7, -1.3);
    let e = chain.energy(&Vector::<1>::new(q), &Vector::<1>::new(qd));
    let exact = 0.5 * m * l * l / 3.0 * qd * qd - m * g * l / 2.0 * f64::cos(q);
    assert!((e - exact).abs() <= 1e-14 * exact.abs());
}

/// Four links released from a bent, spinning state: DOPRI5 at 1e-12 keeps the energy
/// (computed from the kinematics, not from the algorithm) to 1e-9 of `N m g l`.
#[test]
fn four_links_conserve_energy_under_dopri5() {
    let (m, l, g) = (1.1, 0.6, 9.81);
    let chain = ChainByHand::<4>::new(m, l, g);
    let y0 = Vector::<8>::from_column_slice(&[1.2, -0.7, 0.5, 0.9, 0.0, 1.5, -2.0, 0.3]);
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let sol = Dopri5::new(opts).solve(&chain, 0.0, y0, 5.0, &[]).unwrap();
    let energy = |y: &Vector<8>| {
        chain.energy(
            &Vector::<4>::from_column_slice(&y.as_slice()[..4]),
            &Vector::<4>::from_column_slice(&y.as_slice()[4..]),
        )
    };
    let e0 = energy(&y0);
    let scale = 4.0 * m * g * l;
    let drift = sol
        .y
        .iter()
        .map(|y| (energy(y) - e0).abs())
        .fold(0.0, f64::max);
    assert!(sol.t.len() > 100, "a real run: {} steps", sol.t.len());
    assert!(drift <= 1e-9 * scale, "energy drift {drift:.3e}");
    // The motion is not trivial: the chain moves far from where it started.
    let (_, y_end) = sol.last();
    assert!((y_end - y0).amax() > 0.5);
}

#[test]
fn bad_parameters_are_errors() {
    let z = Vector::<2>::zeros();
    for (m, l, g) in [(0.0, 1.0, 9.81), (1.0, -1.0, 9.81), (1.0, 1.0, f64::NAN)] {
        let chain = ChainByHand::<2>::new(m, l, g);
        assert!(matches!(
            chain.acceleration(&z, &z),
            Err(Error::InvalidInput { .. })
        ));
        assert!(OdeSystem::<4>::rhs(&chain, 0.0, &Vector::<4>::zeros()).is_err());
    }
}
