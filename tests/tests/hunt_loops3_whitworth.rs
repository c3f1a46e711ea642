//! Hunt: a Whitworth quick-return: a crank `a` about the origin carries a block at its tip
//! sliding in a slotted lever pivoted at `(0, -d)` with `d < a`, so the lever turns full
//! circles with the crank (unlike the crank-shaper's rocking lever, `d > a`, of
//! `hunt_loops_quick_return.rs`), fast on one half of the turn and slow on the other.
//! Coordinates `th` (crank), `phi` (lever), `s` (the block along the lever); loop:
//! `a cos th = s cos phi`, `a sin th + d = s sin phi`. Free, no gravity, a flywheel on the
//! crank; the lever passes `phi = +-pi` every turn. The closure's only closed form is from
//! the slide `s`, so the default form is augmented; every method.
//!
//! Reference, by hand: `phi = atan2(a sin th + d, a cos th)` (continued through `+-pi`),
//! `s = hypot(..)`, `s` between `a - d` and `a + d` (never zero); with
//! `phi' = a (a + d sin th) th' / s^2` and `s' = a d cos th th' / s` the kinetic energy
//! `T = (Ic th'^2 + Il phi'^2 + mb (a th')^2 + ib phi'^2) / 2` is conserved.

use mbd::integrate::{
    Dop853, Dopri5, Gauss, GeneralizedAlpha, Integrator, Options, Radau5, Rk4, Vern9,
};
use mbd::prelude::*;
use std::f64::consts::{PI, TAU};

#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[coords(th, phi, s)]
#[constraint(a * cos(th) == s * cos(phi))]
#[constraint(a * sin(th) + d == s * sin(phi))]
#[rigid(crank, mass = m, inertia = ic, at = [0.0, 0.0], angle = th)]
#[rigid(lever, mass = ml, inertia = il, at = [0.0, -d], angle = phi)]
#[rigid(block, mass = mb, inertia = ib, at = [a * cos(th), a * sin(th)], angle = phi)]
#[init(th = 0.0, phi = 0.4636476090008061, s = 1.118033988749895, der(th) = 5.0)]
pub struct Whitworth {
    pub a: f64,
    pub d: f64,
    pub m: f64,
    pub ic: f64,
    pub ml: f64,
    pub il: f64,
    pub mb: f64,
    pub ib: f64,
}

const A: f64 = 1.0;
const D: f64 = 0.5;
const IC: f64 = 2.0;
const IL: f64 = 0.6;
const MB: f64 = 0.4;
const IB: f64 = 0.02;

fn model() -> Whitworth {
    Whitworth {
        a: A,
        d: D,
        m: 3.0,
        ic: IC,
        ml: 1.5,
        il: IL,
        mb: MB,
        ib: IB,
    }
}

fn close(th: f64) -> (f64, f64) {
    let (x, y) = (A * th.cos(), A * th.sin() + D);
    (y.atan2(x), x.hypot(y))
}

fn energy(th: f64, thd: f64) -> f64 {
    let (_, s) = close(th);
    let phid = A * (A + D * th.sin()) * thd / (s * s);
    (IC * thd * thd + (IL + IB) * phid * phid + MB * (A * thd).powi(2)) / 2.0
}

fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(TAU) - PI
}

#[test]
fn the_init_is_on_the_closure_and_the_form_is_augmented() {
    let (phi, s) = close(0.0);
    assert!((phi - 0.4636476090008061).abs() < 1e-15 && (s - 1.118033988749895).abs() < 1e-15);
    assert!(Whitworth::GENERATED.parts.contains(&"augmented"));
    assert_eq!(Whitworth::COORDINATES, ["th", "phi", "s"]);
    let y = model().initial_state();
    // phi' = a (a + d sin 0) th' / s^2, s' = a d cos 0 th' / s
    let (phid, sd) = (A * A * 5.0 / (s * s), A * D * 5.0 / s);
    assert!(
        (y[4] - phid).abs() < 1e-12 && (y[5] - sd).abs() < 1e-12,
        "{y}"
    );
}

fn opts(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    }
}

/// Five crank turns: the lever turns with it (five times through `+-pi`), the energy by hand
/// is conserved and the state stays on the hand closure, on every method.
#[test]
fn the_lever_turns_full_circles_on_every_method() {
    let p = model();
    let y0 = p.initial_state();
    let e0 = energy(0.0, 5.0);
    let t_end = 7.5;
    let alpha = GeneralizedAlpha::new(1.0, 2.5e-4);
    let runs: Vec<(&str, mbd::Result<Solution<6>>, f64)> = vec![
        (
            "dopri5",
            Dopri5::new(opts(1e-10)).solve(&p, 0.0, y0, t_end, &[]),
            1e-8,
        ),
        (
            "dop853",
            Dop853::new(opts(1e-10)).solve(&p, 0.0, y0, t_end, &[]),
            1e-8,
        ),
        (
            "vern9",
            Vern9::new(opts(1e-10)).solve(&p, 0.0, y0, t_end, &[]),
            1e-8,
        ),
        (
            "radau5",
            Radau5::new(opts(1e-8)).solve(&p, 0.0, y0, t_end, &[]),
            1e-5,
        ),
        ("rk4", Rk4::new(1e-3).solve(&p, 0.0, y0, t_end, &[]), 1e-7),
        (
            "gauss",
            Gauss::new(2e-3).solve(&p, 0.0, y0, t_end, &[]),
            1e-7,
        ),
        (
            "alpha",
            Integrator::solve(&alpha, &p, 0.0, y0, t_end, &[]),
            1e-4,
        ),
    ];
    for (name, run, tol) in runs {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let last = sol.y.last().unwrap();
        assert!(last[0] > 5.0 * TAU, "{name}: th = {}", last[0]);
        assert!(
            (last[1] - last[0]).abs() < PI,
            "{name}: the lever turned with the crank: th {} phi {}",
            last[0],
            last[1]
        );
        let (mut de, mut off) = (0.0f64, 0.0f64);
        for y in &sol.y {
            de = de.max((energy(y[0], y[3]) - e0).abs() / e0);
            let (phi, s) = close(y[0]);
            off = off.max(wrap(y[1] - phi).abs()).max((y[2] - s).abs());
        }
        println!(
            "{name}: {} states, energy {de:.2e}, closure {off:.2e}",
            sol.y.len()
        );
        assert!(
            de < tol && off < tol.max(1e-9),
            "{name}: {de:.2e} {off:.2e}"
        );
    }
}

/// The quick return's geometry: with `sin(al) = d / a` the lever is horizontal
/// (`sin phi = 0`) where the crank is at `pi + al` and `2 pi - al` (the block on the pivot's
/// level `y = -d`), so one half turn of the lever takes `pi + 2 al` of crank angle and the
/// other `pi - 2 al`. Events on `sin(phi)` (a dependent coordinate) are located there.
#[test]
fn the_lever_is_horizontal_where_the_crank_is_at_the_hand_angles() {
    #[derive(Debug, Clone, Mechanism)]
    #[coords(th, phi, s)]
    #[constraint(a * cos(th) == s * cos(phi))]
    #[constraint(a * sin(th) + d == s * sin(phi))]
    #[rigid(crank, mass = 3.0, inertia = 2.0, at = [0.0, 0.0], angle = th)]
    #[rigid(lever, mass = 1.5, inertia = 0.6, at = [0.0, -d], angle = phi)]
    #[rigid(block, mass = 0.4, inertia = 0.02, at = [a * cos(th), a * sin(th)], angle = phi)]
    #[init(th = 0.0, phi = 0.4636476090008061, s = 1.118033988749895, der(th) = 5.0)]
    #[event(horizontal = sin(phi))]
    pub struct Horizontal {
        pub a: f64,
        pub d: f64,
    }
    let p = Horizontal { a: A, d: D };
    let events = p.events();
    let sol = Dopri5::new(opts(1e-12))
        .solve(&p, 0.0, p.initial_state(), 3.0, &events)
        .unwrap();
    let al = (D / A).asin();
    let mut want = Vec::new();
    for k in 0..6 {
        let base = k as f64 * TAU;
        want.extend([base + PI + al, base + TAU - al]);
    }
    let got: Vec<f64> = sol.events.iter().map(|h| h.y[0]).collect();
    assert!(got.len() >= 4, "{got:?}");
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-9, "{got:?} vs {want:?}");
    }
}
