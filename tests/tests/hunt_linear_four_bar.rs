//! Hunting linear analysis on a closed loop: a crank-rocker four-bar held by a torsional
//! spring on its crank under gravity, about its equilibrium, in minimal coordinates and in
//! the augmented form (`constrained_modes`, `constrained_state_space`), against a hand
//! reduction by the energy method. The reference is derived beside the test.

use mbd::analysis::linear::{
    constrained_modes, constrained_state_space, constrained_undamped_modes, linearize, modes,
    state_space, undamped_modes,
};
use mbd::analysis::{NewtonOptions, static_equilibrium};
use mbd::prelude::*;

macro_rules! sprung_four_bar {
    ($name:ident, $($form:ident),*) => {
        /// Crank `a` at `phi` from the ground pivot `(0, 0)`, coupler `b` at `psi`, rocker
        /// `c` at `chi` from `(d, 0)`; uniform bars of mass `m`; a torsional spring `kt`
        /// (free at `phi0`) and an input torque `tau` on the crank; the rocker angle as
        /// output.
        #[derive(Debug, Clone, Mechanism)]
        #[mechanism($($form),*)]
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
        #[generalized_force(spring, along = phi, value = tau - kt * (phi - phi0))]
        #[generalized_force(rocker_torque, along = chi, value = tau_r)]
        #[input(tau, tau_r)]
        #[output(rocker_angle = chi)]
        #[init(phi = 0.5, psi = 0.7260165921021776, chi = 1.7229599395818342)]
        pub struct $name {
            #[default(1.0)]
            pub a: f64,
            #[default(3.0)]
            pub b: f64,
            #[default(2.5)]
            pub c: f64,
            #[default(3.5)]
            pub d: f64,
            pub m: f64,
            pub g: f64,
            pub kt: f64,
            pub phi0: f64,
            pub tau: f64,
            pub tau_r: f64,
        }
    };
}
sprung_four_bar!(Minimal, jacobian);
sprung_four_bar!(Augmented, jacobian, augmented);

const MIN: Minimal = Minimal {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 3.5,
    m: 1.0,
    g: 9.81,
    kt: 60.0,
    phi0: 0.5,
    tau: 0.0,
    tau_r: 0.0,
};

const AUG: Augmented = Augmented {
    a: 1.0,
    b: 3.0,
    c: 2.5,
    d: 3.5,
    m: 1.0,
    g: 9.81,
    kt: 60.0,
    phi0: 0.5,
    tau: 0.0,
    tau_r: 0.0,
};

/// `(psi, chi)` at crank angle `phi` on the init's branch by Newton's method, and the
/// velocity ratios `(psi', chi') / phi'` from the differentiated loop equations by
/// Cramer's rule: `-b sin(psi) psi' + c sin(chi) chi' = a sin(phi)`,
/// `b cos(psi) psi' - c cos(chi) chi' = -a cos(phi)`.
fn close(phi: f64) -> [f64; 4] {
    let (a, b, c, d) = (MIN.a, MIN.b, MIN.c, MIN.d);
    let (mut psi, mut chi): (f64, f64) = (0.7260165921021776, 1.7229599395818342);
    let jac = |psi: f64, chi: f64| (-b * psi.sin(), c * chi.sin(), b * psi.cos(), -c * chi.cos());
    for _ in 0..60 {
        let f1 = a * phi.cos() + b * psi.cos() - d - c * chi.cos();
        let f2 = a * phi.sin() + b * psi.sin() - c * chi.sin();
        let (j11, j12, j21, j22) = jac(psi, chi);
        let det = j11 * j22 - j12 * j21;
        psi -= (f1 * j22 - j12 * f2) / det;
        chi -= (j11 * f2 - j21 * f1) / det;
    }
    let (j11, j12, j21, j22) = jac(psi, chi);
    let (r1, r2) = (a * phi.sin(), -a * phi.cos());
    let det = j11 * j22 - j12 * j21;
    [
        psi,
        chi,
        (r1 * j22 - j12 * r2) / det,
        (j11 * r2 - j21 * r1) / det,
    ]
}

/// The potential along the loop: `V = m g (y_crank + y_coupler + y_rocker) + kt (phi -
/// phi0)^2 / 2`.
fn potential(phi: f64) -> f64 {
    let p = MIN;
    let [psi, chi, ..] = close(phi);
    let y =
        p.a / 2.0 * phi.sin() + (p.a * phi.sin() + p.b / 2.0 * psi.sin()) + p.c / 2.0 * chi.sin();
    p.m * p.g * y + 0.5 * p.kt * (phi - p.phi0).powi(2)
}

/// The reduced inertia `m_eff = sum m |dr/dphi|^2 + I (dtheta/dphi)^2` from the velocity
/// ratios: crank centre `(a/2)(-sin, cos)`, coupler centre `a (-sin phi, cos phi) +
/// (b/2) psi' (-sin psi, cos psi)`, rocker centre `(c/2) chi' (-sin chi, cos chi)`.
fn reduced_inertia(phi: f64) -> f64 {
    let p = MIN;
    let [psi, chi, dpsi, dchi] = close(phi);
    let crank = (p.a / 2.0).powi(2);
    let cx = -p.a * phi.sin() - p.b / 2.0 * dpsi * psi.sin();
    let cy = p.a * phi.cos() + p.b / 2.0 * dpsi * psi.cos();
    let rocker = (p.c / 2.0 * dchi).powi(2);
    let _ = chi;
    p.m * (crank + cx * cx + cy * cy + rocker)
        + p.m / 12.0 * (p.a * p.a + p.b * p.b * dpsi * dpsi + p.c * p.c * dchi * dchi)
}

/// `d^k V / dphi^k` (k = 1, 2) by central differences with one Richardson step
/// (`(4 D(h/2) - D(h)) / 3`, error `O(h^4)`; `h = 1e-2`: truncation and rounding near
/// `1e-9` relative).
fn derivative(k: u32, phi: f64) -> f64 {
    let d = |h: f64| match k {
        1 => (potential(phi + h) - potential(phi - h)) / (2.0 * h),
        _ => (potential(phi + h) - 2.0 * potential(phi) + potential(phi - h)) / (h * h),
    };
    (4.0 * d(5e-3) - d(1e-2)) / 3.0
}

/// About the equilibrium `V'(phi_e) = 0` (found by `static_equilibrium` in minimal
/// coordinates and checked on the hand potential), the energy method gives
/// `w^2 = V''(phi_e) / m_eff(phi_e)` (`V''` includes gravity through the loop's
/// second-order geometry), and a static torque `tau` turns the crank by `tau / V''` and
/// the rocker by `chi' tau / V''`. Minimal coordinates (`modes`, `undamped_modes`,
/// `state_space`) and the augmented form restricted to the loop (`constrained_modes`,
/// `constrained_state_space`) agree with each other to `1e-9` and with the hand
/// reduction to `1e-9` (its differences).
#[test]
fn minimal_and_augmented_forms_have_the_hand_frequency_and_static_gain() {
    let q =
        static_equilibrium(&MIN, 0.0, &Vector::<1>::new(0.5), &NewtonOptions::default()).unwrap();
    let phi = q[0];
    let vpp = derivative(2, phi);
    assert!(
        derivative(1, phi).abs() < 1e-9 * vpp,
        "V' = {}",
        derivative(1, phi)
    );
    let w2 = vpp / reduced_inertia(phi);
    assert!(w2 > 0.0);
    let w = w2.sqrt();

    let y = Vector::<2>::new(phi, 0.0);
    let minimal = modes(&linearize(&MIN, 0.0, &y).unwrap()).unwrap();
    assert_eq!(minimal.len(), 1, "{minimal:?}");
    assert!(
        (minimal[0].omega_d - w).abs() < 1e-9 * w,
        "{} vs {w}",
        minimal[0].omega_d
    );
    let normal = undamped_modes(&MIN, 0.0, &q).unwrap();
    assert!(
        (normal[0].omega_squared - w2).abs() < 1e-9 * w2,
        "{} vs {w2}",
        normal[0].omega_squared
    );

    let [psi, chi, _, dchi] = close(phi);
    let q3 = Vector::<3>::new(phi, psi, chi);
    let augmented = constrained_modes(&AUG, 0.0, &q3).unwrap();
    assert_eq!(augmented.len(), 1, "{augmented:?}");
    assert!(
        (augmented[0].omega_d - minimal[0].omega_d).abs() < 1e-9 * w,
        "{} vs {}",
        augmented[0].omega_d,
        minimal[0].omega_d
    );

    let gain_phi = 1.0 / vpp;
    let gain_chi = dchi / vpp;
    let ss = state_space(&MIN, 0.0, &y).unwrap();
    let g = ss.frequency_response(0.0).unwrap();
    assert!(
        (g[(0, 0)].re - gain_chi).abs() < 1e-9 * gain_chi.abs(),
        "{} vs {gain_chi}",
        g[(0, 0)]
    );
    let (ssa, _t) = constrained_state_space(&AUG, 0.0, &q3).unwrap();
    let ga = ssa.frequency_response(0.0).unwrap();
    assert!(
        (ga[(0, 0)] - g[(0, 0)]).norm() < 1e-9 * gain_chi.abs(),
        "{} vs {}",
        ga[(0, 0)],
        g[(0, 0)]
    );
    // A torque on the rocker does the virtual work `tau_r chi' dphi`: it turns the crank
    // by `chi' tau_r / V''` and the rocker by `chi'^2 tau_r / V''`.
    let gain_rr = dchi * dchi / vpp;
    for (name, gain) in [("minimal", g[(0, 1)]), ("augmented", ga[(0, 1)])] {
        assert!(
            (gain.re - gain_rr).abs() < 1e-9 * gain_rr.abs() && gain.im == 0.0,
            "{name}: {gain} vs {gain_rr}"
        );
    }
    // Off resonance the two forms give one response.
    for wf in [0.3 * w, 2.0 * w] {
        let (gm, ga) = (
            ss.frequency_response(wf).unwrap(),
            ssa.frequency_response(wf).unwrap(),
        );
        for j in 0..2 {
            assert!((gm[(0, j)] - ga[(0, j)]).norm() < 1e-9 * gm[(0, j)].norm());
        }
    }
    let _ = gain_phi;
}

/// A point mass held on a circle of radius `l` by a constraint (augmented form),
/// hanging at rest at `(0, -l)`: one motion, along the circle, at `w^2 = g / l`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian, augmented)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[constraint(x * x + y * y == l * l)]
#[particle(bob, mass = m, at = [x, y])]
pub struct CartesianPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// `undamped_modes` of a closed loop in the augmented form reported the constraint's
/// direction as a rigid-body mode (`w^2 = 0` along the rod of a hanging pendulum, which
/// cannot move that way), or failed on the four-bar with "K is not symmetric": it must
/// refuse and name the restriction; `constrained_undamped_modes` gives the loop's one
/// mode: `g / l` for the pendulum (shape along `x`, `m v_x^2 = 1`), and the four-bar's
/// `V'' / m_eff` by hand as above.
#[test]
fn undamped_modes_of_an_augmented_loop_are_restricted_to_the_loop() {
    let p = CartesianPendulum {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };
    let q = Vector::<2>::new(0.0, -p.l);
    match undamped_modes(&p, 0.0, &q) {
        Err(Error::InvalidInput { detail, .. }) => {
            assert!(detail.contains("constrained_undamped_modes"), "{detail}")
        }
        other => panic!("{other:?}"),
    }
    let found = constrained_undamped_modes(&p, 0.0, &q).unwrap();
    assert_eq!(found.len(), 1, "{found:?}");
    let w2 = p.g / p.l;
    assert!(
        (found[0].omega_squared - w2).abs() < 1e-14 * w2,
        "{found:?}"
    );
    let v = found[0].shape;
    assert!(
        v[1].abs() < 1e-15 && (p.m * v[0] * v[0] - 1.0).abs() < 1e-14,
        "{v}"
    );

    let qe =
        static_equilibrium(&MIN, 0.0, &Vector::<1>::new(0.5), &NewtonOptions::default()).unwrap();
    let phi = qe[0];
    let [psi, chi, dpsi, dchi] = close(phi);
    let q3 = Vector::<3>::new(phi, psi, chi);
    assert!(undamped_modes(&AUG, 0.0, &q3).is_err());
    let found = constrained_undamped_modes(&AUG, 0.0, &q3).unwrap();
    assert_eq!(found.len(), 1, "{found:?}");
    let w2 = derivative(2, phi) / reduced_inertia(phi);
    assert!(
        (found[0].omega_squared - w2).abs() < 1e-9 * w2,
        "{} vs {w2}",
        found[0].omega_squared
    );
    // The shape moves along the loop: `(1, psi', chi')` times the crank's part.
    let v = found[0].shape;
    assert!((v[1] - dpsi * v[0]).abs() < 1e-12 * v.amax(), "{v}");
    assert!((v[2] - dchi * v[0]).abs() < 1e-12 * v.amax(), "{v}");
}
