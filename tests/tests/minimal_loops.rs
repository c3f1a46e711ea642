//! Closed loops in minimal coordinates: the derive closes a four-bar (two angles from two
//! loop equations) and a slider-crank (a linear and an `asin` closure) in closed form. The
//! references are independent: the same attributes in the augmented form
//! (`#[mechanism(augmented)]`, multipliers and an LU of the augmented matrix), fed with a
//! configuration assembled here by Newton's method; and, for the singular position, the
//! geometry by hand.

use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;

macro_rules! four_bar {
    ($name:ident $(, $form:ident)?) => {
        /// A free crank-rocker under gravity: crank `phi`, coupler `psi`, rocker `chi`.
        #[derive(Debug, Clone, Mechanism)]
        $(#[mechanism($form)])?
        #[gravity(0.0, -g)]
        #[coords(phi, psi, chi)]
        #[constraint(a * cos(phi) + b * cos(psi) == d + c * cos(chi))]
        #[constraint(a * sin(phi) + b * sin(psi) == c * sin(chi))]
        #[rigid(crank, mass = m, inertia = m * a * a / 12.0,
                at = [a / 2.0 * cos(phi), a / 2.0 * sin(phi)], angle = phi)]
        #[rigid(coupler, mass = m, inertia = m * b * b / 12.0,
                at = [a * cos(phi) + b / 2.0 * cos(psi), a * sin(phi) + b / 2.0 * sin(psi)],
                angle = psi)]
        #[rigid(rocker, mass = m, inertia = m * c * c / 12.0,
                at = [d + c / 2.0 * cos(chi), c / 2.0 * sin(chi)], angle = chi)]
        #[init(phi = 0.5, psi = 0.7260165921021776, chi = 1.7229599395818342)]
        #[output(rocker_rate = der(chi))]
        pub struct $name {
            #[default(1.0)]
            pub a: f64,
            #[default(3.0)]
            pub b: f64,
            #[default(2.5)]
            pub c: f64,
            #[default(3.5)]
            pub d: f64,
            #[default(1.0)]
            pub m: f64,
            #[default(9.81)]
            pub g: f64,
        }
    };
}
four_bar!(FourBar);
four_bar!(FourBarAugmented, augmented);

const FB: FourBar = FourBar {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 3.5,
    m: 1.0,
    g: 9.81,
};
const FBA: FourBarAugmented = FourBarAugmented {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 3.5,
    m: 1.0,
    g: 9.81,
};

/// `(psi, chi)` and their rates for crank angle `phi` and rate `rate`, by Newton's method
/// from the init's elbow and the velocity constraint solved by Cramer's rule.
fn close_by_newton(phi: f64, rate: f64, start: (f64, f64)) -> [f64; 4] {
    let (a, b, c, d) = (FB.a, FB.b, FB.c, FB.d);
    let (mut psi, mut chi) = start;
    for _ in 0..50 {
        let f1 = a * phi.cos() + b * psi.cos() - d - c * chi.cos();
        let f2 = a * phi.sin() + b * psi.sin() - c * chi.sin();
        let (j11, j12, j21, j22) = (-b * psi.sin(), c * chi.sin(), b * psi.cos(), -c * chi.cos());
        let det = j11 * j22 - j12 * j21;
        psi -= (f1 * j22 - j12 * f2) / det;
        chi -= (j11 * f2 - j21 * f1) / det;
    }
    let (j11, j12, j21, j22) = (-b * psi.sin(), c * chi.sin(), b * psi.cos(), -c * chi.cos());
    let (r1, r2) = (a * phi.sin() * rate, -a * phi.cos() * rate);
    let det = j11 * j22 - j12 * j21;
    [
        psi,
        chi,
        (r1 * j22 - j12 * r2) / det,
        (j11 * r2 - j21 * r1) / det,
    ]
}

#[test]
fn four_bar_is_generated_in_its_crank_angle() {
    assert!(FourBar::GENERATED.parts.contains(&"minimal_closed_form"));
    assert!(FourBarAugmented::GENERATED.parts.contains(&"augmented"));
    assert_eq!(<FourBar as mbd::Mechanism<1>>::COORDINATES, ["phi"]);
    assert_eq!(FourBar::GENERATED.constraints, 0);
    assert_eq!(FB.initial_state(), Vector::<2>::new(0.5, 0.0));
}

#[test]
fn four_bar_accelerations_match_the_augmented_form() {
    let mut start = (0.7260165921021776, 1.7229599395818342);
    for k in 0..24 {
        let (phi, rate) = (0.5 + 0.26 * f64::from(k), 2.0 - 0.3 * f64::from(k));
        let [psi, chi, psi_d, chi_d] = close_by_newton(phi, rate, start);
        start = (psi, chi);
        let full = Vector::<6>::from([phi, psi, chi, rate, psi_d, chi_d]);
        let augmented = FBA.rhs(0.0, &full).unwrap();
        let minimal = FB.rhs(0.0, &Vector::<2>::new(phi, rate)).unwrap();
        let scale = augmented[3].abs().max(1.0);
        assert!(
            (minimal[1] - augmented[3]).abs() < 1e-11 * scale,
            "phi = {phi}: {} vs {}",
            minimal[1],
            augmented[3]
        );
        let out = FB.outputs(0.0, &Vector::<2>::new(phi, rate)).unwrap();
        assert!((out.rocker_rate - chi_d).abs() < 1e-11 * chi_d.abs().max(1.0));
    }
}

#[test]
fn four_bar_motion_matches_the_augmented_form() {
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    };
    let dopri = Dopri5::new(opts);
    let minimal = dopri.solve(&FB, 0.0, FB.initial_state(), 3.0, &[]).unwrap();
    let [psi, chi, ..] = close_by_newton(0.5, 0.0, (0.7260165921021776, 1.7229599395818342));
    let y0 = Vector::<6>::from([0.5, psi, chi, 0.0, 0.0, 0.0]);
    let augmented = dopri.solve(&FBA, 0.0, y0, 3.0, &[]).unwrap();
    let (ym, ya) = (minimal.y.last().unwrap(), augmented.y.last().unwrap());
    assert!((ym[0] - ya[0]).abs() < 1e-8, "{} vs {}", ym[0], ya[0]);
    assert!((ym[1] - ya[3]).abs() < 1e-7, "{} vs {}", ym[1], ya[3]);
}

/// A slider-crank whose crank is longer than its rod cannot turn round: the closure
/// `l sin(beta) = r sin(theta)` has no solution once `|r sin(theta) / l| > 1`.
#[derive(Debug, Clone, Mechanism)]
#[coords(theta, beta, x)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0, at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[rigid(rod, mass = m, inertia = m * l * l / 12.0,
        at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
        angle = -beta)]
#[particle(piston, mass = m, at = [x, 0.0])]
#[init(der(theta) = 10.0)]
pub struct ShortRod {
    pub r: f64,
    pub l: f64,
    pub m: f64,
}

#[test]
fn a_loop_that_cannot_assemble_is_a_typed_error_not_a_nan() {
    let p = ShortRod {
        r: 1.0,
        l: 0.5,
        m: 1.0,
    };
    // By hand: the limit is theta = asin(l / r) = pi / 6.
    let inside = Vector::<2>::new(0.5, 1.0);
    assert!(p.rhs(0.0, &inside).unwrap().iter().all(|v| v.is_finite()));
    for theta in [0.6, 1.0, -2.0] {
        match p.rhs(1.5, &Vector::<2>::new(theta, 1.0)) {
            Err(mbd::Error::SingularPosition { t, detail }) => {
                assert_eq!(t, 1.5);
                assert!(
                    detail.contains("`beta`") && detail.contains("theta = "),
                    "{detail}"
                );
            }
            other => panic!("theta = {theta}: {other:?}"),
        }
    }
    // Driven towards the limit, the integration stops there with that error.
    let dopri = Dopri5::new(Options::default());
    match dopri.solve(&p, 0.0, p.initial_state(), 1.0, &[]) {
        Err(mbd::Error::SingularPosition { t, .. }) => assert!(t > 0.0 && t < 0.2, "{t}"),
        other => panic!("{other:?}"),
    }
}
