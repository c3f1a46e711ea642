//! What the ordinary `Integrator::solve` of a friction model pays for reaching the hybrid
//! driver through object-safe hooks: each mode's system is a `hybrid::View`, one virtual call
//! from the model's `rhs_in`, where `hybrid::InMode` is the same system monomorphized.
//! Same algorithm both sides, same model (the stick-slip belt, whose rhs is a few
//! nanoseconds: the worst case for a fixed per-call cost), so the difference is the dispatch.
//!
//! `cargo bench -p mechanisms --bench hybrid_dispatch`. Prints, as the least time over
//! interleaved batches: one rhs call in a sliding and in a stuck mode, a DOPRI5 run in
//! one sliding mode per rhs evaluation, and a whole `hybrid::solve` of the belt with its
//! kink events (the normal force's sign, watched at every step end; constant here, so pure
//! cost) against the same driver with them hidden.

use mbd::hybrid::{self, InMode, View};
use mbd::integrate::{Dopri5, Integrator};
use mbd::prelude::*;
use mbd::{Hybrid, Slip};
use mechanisms::stick_slip;
use std::hint::black_box;
use std::time::Instant;

/// The least time per call (ns) of `a` and `b` over interleaved batches of `n` calls.
fn interleaved(n: usize, a: &dyn Fn(), b: &dyn Fn()) -> (f64, f64) {
    let batch = |run: &dyn Fn()| {
        let start = Instant::now();
        for _ in 0..n {
            run();
        }
        start.elapsed().as_secs_f64() * 1e9 / n as f64
    };
    let (mut ta, mut tb) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..(2_000_000 / n).max(20) {
        ta = ta.min(batch(a));
        tb = tb.min(batch(b));
    }
    (ta, tb)
}

fn main() {
    let belt = stick_slip::belt();
    let y = Vector::<2>::new(0.3, -0.2);
    for mode in [[Slip::Backward], [Slip::Stick]] {
        let frozen = InMode { sys: &belt, mode };
        let view = View::new(&frozen);
        assert_eq!(frozen.rhs(0.1, &y), view.rhs(0.1, &y));
        let (direct, erased) = interleaved(
            1000,
            &|| drop(black_box(frozen.rhs(0.1, black_box(&y)))),
            &|| drop(black_box(view.rhs(0.1, black_box(&y)))),
        );
        println!(
            "rhs in {mode:?}: InMode {direct:.2} ns, View {erased:.2} ns, +{:.2} ns per call ({:+.1} %)",
            erased - direct,
            100.0 * (erased / direct - 1.0)
        );
    }
    // A whole DOPRI5 run in one sliding mode (no switching events: the method's own cost).
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        dense: false,
        record: mbd::integrate::Record::Final,
        ..Options::default()
    };
    let dopri = Dopri5::new(opts);
    let frozen = InMode {
        sys: &belt,
        mode: [Slip::Backward],
    };
    let view = View::new(&frozen);
    let y0 = belt.initial_state();
    let n_rhs = dopri.solve(&frozen, 0.0, y0, 2.0, &[]).unwrap().stats.n_rhs;
    let same = dopri.solve(&view, 0.0, y0, 2.0, &[]).unwrap();
    assert_eq!(same.stats.n_rhs, n_rhs);
    let (direct, erased) = interleaved(
        20,
        &|| {
            drop(black_box(dopri.solve(
                &frozen,
                0.0,
                black_box(y0),
                2.0,
                &[],
            )))
        },
        &|| drop(black_box(dopri.solve(&view, 0.0, black_box(y0), 2.0, &[]))),
    );
    let per = |t: f64| t / n_rhs as f64;
    println!(
        "DOPRI5 run, {n_rhs} rhs: InMode {:.2} ns/rhs, View {:.2} ns/rhs, +{:.2} ns per rhs ({:+.1} %)",
        per(direct),
        per(erased),
        per(erased - direct),
        100.0 * (erased / direct - 1.0)
    );
    kink_cost(&belt, &dopri);
}

/// The belt with its kink functions hidden (the driver as it was before them).
struct NoKinks<'a>(&'a stick_slip::Belt);

impl Hybrid<2> for NoKinks<'_> {
    type Mode = [Slip; 1];
    const SWITCHES: usize = 1;
    fn rhs_in(&self, t: f64, y: &Vector<2>, m: &[Slip; 1]) -> mbd::Result<Vector<2>> {
        self.0.rhs_in(t, y, m)
    }
    fn switching(&self, t: f64, y: &Vector<2>, m: &[Slip; 1], k: usize) -> f64 {
        self.0.switching(t, y, m, k)
    }
    fn mode_at(&self, t: f64, y: &Vector<2>) -> mbd::Result<[Slip; 1]> {
        self.0.mode_at(t, y)
    }
    fn switch(&self, t: f64, y: &mut Vector<2>, m: &[Slip; 1], k: usize) -> mbd::Result<[Slip; 1]> {
        self.0.switch(t, y, m, k)
    }
    fn switching_state(&self, m: &[Slip; 1], k: usize) -> Option<(usize, f64)> {
        self.0.switching_state(m, k)
    }
}

/// `hybrid::solve` of the belt over 20 s (about six stick-slip cycles) with and without
/// its kink events: the same steps and switches, so the difference is watching the kink.
fn kink_cost(belt: &stick_slip::Belt, dopri: &Dopri5) {
    let y0 = belt.initial_state();
    let with = hybrid::solve(dopri, belt, 0.0, y0, 20.0, &[]).unwrap();
    let without = hybrid::solve(dopri, &NoKinks(belt), 0.0, y0, 20.0, &[]).unwrap();
    assert_eq!(with.solution.stats, without.solution.stats);
    assert_eq!(with.switches.len(), without.switches.len());
    // The least time of 200 interleaved runs each (`interleaved` repeats far more).
    let time = |run: &dyn Fn()| {
        let start = Instant::now();
        run();
        start.elapsed().as_secs_f64() * 1e9
    };
    let (mut a, mut b) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..200 {
        a = a.min(time(&|| {
            drop(black_box(hybrid::solve(
                dopri,
                belt,
                0.0,
                black_box(y0),
                20.0,
                &[],
            )))
        }));
        b = b.min(time(&|| {
            drop(black_box(hybrid::solve(
                dopri,
                &NoKinks(belt),
                0.0,
                black_box(y0),
                20.0,
                &[],
            )))
        }));
    }
    println!(
        "hybrid::solve 20 s, {} steps, {} switches: kinks watched {:.1} us, hidden {:.1} us ({:+.1} %)",
        with.solution.stats.n_steps,
        with.switches.len(),
        a / 1e3,
        b / 1e3,
        100.0 * (a / b - 1.0)
    );
}
