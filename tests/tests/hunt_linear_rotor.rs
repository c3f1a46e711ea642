//! Hunting linear analysis on a spinning rotor: a disc on a flexible mount, its Campbell
//! diagram (whirl frequencies against spin) and the forward/backward split. The reference
//! is derived beside the test.

use mbd::analysis::linear::{ModeKind, linearize, modes};
use mbd::prelude::*;

/// A disc (polar moment `ip`, diametral `id` about its centre, which sits on the pivot)
/// spinning freely on a revolute joint `c` about its axis, carried by a massless gimbal on
/// a universal joint `rot_x(a) rot_y(b)` held by torsional springs `kt` on both gimbal
/// angles: the tilt stiffness of a shaft's bearing, the overhung rotor of a Campbell
/// diagram.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, jacobian)]
#[body(gimbal, joint = universal(a, b), mass = m0)]
#[body(disc, parent = gimbal, joint = revolute(c, z), mass = m, inertia = diag(id, id, ip))]
#[generalized_force(tilt_a, along = a, value = -kt * a)]
#[generalized_force(tilt_b, along = b, value = -kt * b)]
pub struct Rotor {
    pub m0: f64,
    pub m: f64,
    pub id: f64,
    pub ip: f64,
    pub kt: f64,
}

const ROTOR: Rotor = Rotor {
    m0: 0.1,
    m: 4.0,
    id: 0.03,
    ip: 0.05,
    kt: 800.0,
};

/// Spinning at `W` about its axis, small tilts obey `id a'' + ip W b' + kt a = 0`,
/// `id b'' - ip W a' + kt b = 0` (the gyroscopic moment `ip W` times the tilt rate,
/// skew; its sign only decides which of the two is forward). With `z = a + i b` (or its
/// conjugate), `id z'' - i ip W z' + kt z = 0`; `z = e^{i w t}` gives
/// `id w^2 - ip W w - kt = 0`: `w = (ip W +- R) / (2 id)`, `R = sqrt(ip^2 W^2 + 4 id kt)`.
/// The whirl frequencies are `w_f = (R + ip W) / (2 id)` (forward: the axis whirls with the
/// spin, stiffened) and `w_b = (R - ip W) / (2 id)` (backward, softened), `w_f w_b = kt /
/// id`; at rest both are `sqrt(kt / id)`, spun fast `w_f -> ip W / id`, `w_b -> kt / (ip W)`.
fn whirl(spin: f64) -> [f64; 2] {
    let Rotor { id, ip, kt, .. } = ROTOR;
    let r = (ip * ip * spin * spin + 4.0 * id * kt).sqrt();
    [(r - ip * spin) / (2.0 * id), (r + ip * spin) / (2.0 * id)]
}

/// The Campbell diagram from rest to 30000 rpm: at each spin, `A` about the steady spin has
/// the spin angle's double zero (cyclic: neutral) and the two whirls, undamped
/// (`zeta = 0`, stable), within `1e-10` of the closed form; the forward one turns the
/// axis with the spin. The axis `rot_x(a) rot_y(b) e_z = (b, -a, 1)` to first order, so
/// its tip `(X, Y) = (b, -a)` turns counterclockwise (the spin's sense, `+z`) in a mode
/// `Re(v e^{i w t})` when `Im(conj(X) Y) < 0`.
#[test]
fn campbell_diagram_has_the_closed_form_forward_and_backward_whirls() {
    for rpm in [0.0, 100.0, 1000.0, 3000.0, 10000.0, 30000.0] {
        let spin = rpm * std::f64::consts::TAU / 60.0;
        let y = Vector::<6>::new(0.0, 0.0, 0.0, 0.0, 0.0, spin);
        let f = ROTOR.rhs(0.0, &y).unwrap();
        assert!(
            f.fixed_rows::<3>(3).amax() <= 1e-12 * (1.0 + spin),
            "not steady at {rpm} rpm: {f}"
        );
        let found = modes(&linearize(&ROTOR, 0.0, &y).unwrap()).unwrap();
        let whirls: Vec<_> = found
            .iter()
            .filter(|m| m.kind != ModeKind::Neutral)
            .collect();
        let neutral = found.len() - whirls.len();
        assert_eq!(neutral, 2, "{rpm} rpm: {found:?}");
        assert_eq!(whirls.len(), 2, "{rpm} rpm: {found:?}");
        let [wb, wf] = whirl(spin);
        for (m, w) in whirls.iter().zip([wb, wf]) {
            assert_eq!(m.kind, ModeKind::Oscillatory, "{rpm} rpm: {m:?}");
            assert!(
                (m.omega_d - w).abs() <= 1e-10 * w,
                "{rpm} rpm: {} vs {w}",
                m.omega_d
            );
            assert!(m.damping_ratio.unwrap().abs() <= 1e-10, "{m:?}");
            assert!(!m.unstable);
        }
        if spin > 0.0 {
            for (m, forward) in whirls.iter().zip([false, true]) {
                let (x, yy) = (m.shape[1], -m.shape[0]);
                let turn = (x.conj() * yy).im;
                assert!(
                    (turn < 0.0) == forward && turn.abs() > 1e-3 * x.norm() * yy.norm(),
                    "{rpm} rpm, {} whirl turns the wrong way: {}",
                    if forward { "forward" } else { "backward" },
                    m.shape
                );
            }
        }
    }
}

/// The rotor with viscous dampers `ct` on the gimbal angles beside the springs (bearing
/// damping, non-rotating).
#[derive(Debug, Mechanism)]
#[mechanism(spatial, jacobian)]
#[body(gimbal, joint = universal(a, b), mass = m0)]
#[body(disc, parent = gimbal, joint = revolute(c, z), mass = m, inertia = diag(id, id, ip))]
#[generalized_force(tilt_a, along = a, value = -kt * a - ct * der(a))]
#[generalized_force(tilt_b, along = b, value = -kt * b - ct * der(b))]
pub struct DampedRotor {
    pub m0: f64,
    pub m: f64,
    pub id: f64,
    pub ip: f64,
    pub kt: f64,
    pub ct: f64,
}

/// With the dampers, `id z'' + (ct - i ip W) z' + kt z = 0`, so `z = e^{lambda t}` with
/// `id lambda^2 + (ct - i ip W) lambda + kt = 0`: `lambda = (-(ct - i ip W) +- sqrt((ct -
/// i ip W)^2 - 4 id kt)) / (2 id)`; the real state's eigenvalues are these two and their
/// conjugates (the conjugate equation, the other sign of the gyroscopic term). Each whirl
/// decays at its own rate: damping ratios differ between forward and backward whirl
/// (gyroscopic coupling with damping), checked against these roots to `1e-10`.
#[test]
fn damped_whirls_have_the_roots_of_the_complex_quadratic() {
    let p = DampedRotor {
        m0: 0.1,
        m: 4.0,
        id: 0.03,
        ip: 0.05,
        kt: 800.0,
        ct: 0.6,
    };
    for rpm in [0.0, 3000.0, 30000.0] {
        let spin = rpm * std::f64::consts::TAU / 60.0;
        let y = Vector::<6>::new(0.0, 0.0, 0.0, 0.0, 0.0, spin);
        let found = modes(&linearize(&p, 0.0, &y).unwrap()).unwrap();
        let whirls: Vec<_> = found
            .iter()
            .filter(|m| m.kind != ModeKind::Neutral)
            .collect();
        assert_eq!(whirls.len(), 2, "{rpm} rpm: {found:?}");
        let b = mbd::nalgebra::Complex::new(p.ct, -p.ip * spin);
        let root = (b * b - 4.0 * p.id * p.kt).sqrt();
        // Both roots, reflected into the upper half-plane (a mode is reported once).
        let mut want: Vec<_> = [(-b + root) / (2.0 * p.id), (-b - root) / (2.0 * p.id)]
            .iter()
            .map(|z| if z.im < 0.0 { z.conj() } else { *z })
            .collect();
        want.sort_by(|x, y| x.norm().total_cmp(&y.norm()));
        for (m, z) in whirls.iter().zip(&want) {
            assert!(
                (m.eigenvalue - z).norm() < 1e-10 * z.norm(),
                "{rpm} rpm: {} vs {z}",
                m.eigenvalue
            );
            assert!((m.damping_ratio.unwrap() - (-z.re / z.norm())).abs() < 1e-10);
        }
    }
}
