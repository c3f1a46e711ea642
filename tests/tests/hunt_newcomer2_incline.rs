//! A block thrown up a rough incline, written from the language reference's friction
//! section (`relaxed` normal coordinate, `friction` with `mu_k`, `mu_s`, normal force
//! `reaction(n)`), checked against the constant-acceleration closed forms.
//!
//! Hand derivation. `s` runs down the slope (angle `a`), `n` along its outward normal. The
//! normal force is `N = m g cos a`. Moving up (`s' < 0`) gravity and kinetic friction both
//! act down the slope: `s'' = g (sin a + mu_k cos a) = a_up`; from `s = 0`, `s' = v0 < 0` it
//! stops at `t1 = -v0 / a_up`, at `s1 = -v0^2 / (2 a_up)`. There, if `tan a > mu_s`, it
//! breaks away down the slope with `s'' = g (sin a - mu_k cos a) = a_dn` and
//! `s = s1 + a_dn (t - t1)^2 / 2`; if `tan a <= mu_s` it stays at `s1` for good.

use mbd::prelude::*;

/// A block on an incline of angle `a`, thrown up the slope at `v0 < 0`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[relaxed(n)]
#[particle(block, mass = m, at = [s * cos(a) + n * sin(a), -s * sin(a) + n * cos(a)])]
#[friction(along = s, mu_k = mu_k, mu_s = mu_s, normal = reaction(n))]
#[init(der(s) = v0)]
#[output(normal = reaction(n))]
pub struct Incline {
    pub m: f64,
    pub g: f64,
    pub a: f64,
    pub mu_k: f64,
    pub mu_s: f64,
    pub v0: f64,
}

const STEEP: Incline = Incline {
    m: 3.0,
    g: 9.81,
    a: 0.6, // tan a = 0.684
    mu_k: 0.3,
    mu_s: 0.5,
    v0: -4.0,
};

fn opts() -> Options {
    Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    }
}

#[test]
fn the_normal_force_is_m_g_cos_a() {
    let y = Vector::<2>::new(0.3, -1.0);
    let n = STEEP.outputs(0.0, &y).unwrap().normal;
    let want = STEEP.m * STEEP.g * STEEP.a.cos();
    assert!((n - want).abs() < 1e-13, "{n} vs {want}");
}

#[test]
fn on_a_steep_slope_it_stops_and_slides_back() {
    let p = &STEEP;
    let (sa, ca) = (p.a.sin(), p.a.cos());
    let a_up = p.g * (sa + p.mu_k * ca);
    let a_dn = p.g * (sa - p.mu_k * ca);
    let (t1, s1) = (-p.v0 / a_up, -p.v0 * p.v0 / (2.0 * a_up));
    let sol = Dopri5::new(opts())
        .solve(p, 0.0, p.initial_state(), 2.0, &[])
        .unwrap();
    let last = sol.switches.last().unwrap();
    assert!((last.t - t1).abs() < 1e-12, "stop at {} vs {t1}", last.t);
    assert_eq!(last.to.get(), Some(&[Slip::Forward]));
    for t in [0.1, 0.3, t1 - 1e-3, t1 + 1e-3, 1.0, 2.0] {
        let y = sol.at(t).unwrap();
        let (s, sd) = if t < t1 {
            (p.v0 * t + a_up * t * t / 2.0, p.v0 + a_up * t)
        } else {
            (s1 + a_dn * (t - t1).powi(2) / 2.0, a_dn * (t - t1))
        };
        assert!(
            (y[0] - s).abs() < 1e-10 && (y[1] - sd).abs() < 1e-10,
            "t = {t}"
        );
    }
}

#[test]
fn on_a_gentle_slope_it_stops_and_stays() {
    let p = Incline { a: 0.4, ..STEEP }; // tan a = 0.423 < mu_s
    let a_up = p.g * (p.a.sin() + p.mu_k * p.a.cos());
    let (t1, s1) = (-p.v0 / a_up, -p.v0 * p.v0 / (2.0 * a_up));
    let sol = Dopri5::new(opts())
        .solve(&p, 0.0, p.initial_state(), 3.0, &[])
        .unwrap();
    assert_eq!(sol.switches.len(), 1);
    assert!((sol.switches[0].t - t1).abs() < 1e-12);
    assert_eq!(sol.switches[0].to.get(), Some(&[Slip::Stick]));
    let (_, y) = sol.last();
    assert!((y[0] - s1).abs() < 1e-12 && y[1] == 0.0, "{y:?}");
}
