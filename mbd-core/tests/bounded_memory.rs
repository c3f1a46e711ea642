//! A million RK4 steps of a 32-state model hold memory bounded by what the caller asked to
//! keep. Alone in its test binary, whose allocator counts the bytes held (`peak_alloc`), so
//! the peak of the heap over the run is this run's, on any platform.

use mbd_core::integrate::{Integrator, Record, Rk4};
use mbd_core::{OdeSystem, Result, Vector};
use peak_alloc::PeakAlloc;

#[global_allocator]
static HEAP: PeakAlloc = PeakAlloc;

/// Sixteen uncoupled oscillators of different frequencies (D = 32), standing in for a big
/// model's state.
struct Big;

impl OdeSystem<32> for Big {
    fn rhs(&self, _t: f64, y: &Vector<32>) -> Result<Vector<32>> {
        Ok(Vector::<32>::from_fn(|i, _| {
            let w2 = 1.0 + (i / 2) as f64;
            if i % 2 == 0 { y[i + 1] } else { -w2 * y[i - 1] }
        }))
    }
}

/// Keeping every step would hold 1e6 * (32 + 1) * 8 B = 264 MB, and the Hermite segments
/// eight times the states more. With `Record::Final` and no dense output the heap's peak
/// grows by less than 8 MB over the run; with
/// `Every(100_000)` 11 points are kept; both end at the same state (the same steps).
#[test]
fn a_million_rk4_steps_hold_bounded_memory() {
    let y0 = Vector::<32>::from_fn(|i, _| if i % 2 == 0 { 1.0 } else { 0.0 });
    let rk = |record| Rk4::new(1e-5).recording(record, false);
    HEAP.reset_peak_usage();
    let before = HEAP.current_usage();
    let fin = rk(Record::Final).solve(&Big, 0.0, y0, 10.0, &[]).unwrap();
    let grown = HEAP.peak_usage().saturating_sub(before) / 1024;
    println!("heap {before} B before, peak grew by {grown} kB over 1e6 steps");
    assert_eq!(fin.stats.n_accepted, 1_000_000);
    assert_eq!((fin.t.len(), fin.segments.len()), (2, 0));
    assert!(grown < 8 * 1024, "{grown} kB");
    let sparse = rk(Record::Every(100_000))
        .solve(&Big, 0.0, y0, 10.0, &[])
        .unwrap();
    assert_eq!(sparse.t.len(), 11);
    assert_eq!(sparse.last(), fin.last());
}
