//! Ensembles: many runs of one model at once, one run per thread at a time (rayon, behind
//! the default feature `parallel`; without it the same functions run the members in turn).
//!
//! A parameter study or a Monte-Carlo set of initial conditions is a list of independent
//! problems. Each is integrated exactly as a serial run would integrate it, on one thread,
//! from start to end: nothing is shared between members and nothing is reduced across them,
//! so every member's result is bitwise the result of the serial run, whatever the number of
//! threads or the order in which they happen to finish. Results come back in input order.
//!
//! Errors are values: a member that fails (a singular mass matrix, too many steps) returns
//! its [`Error`](crate::Error) in its slot and the other members run to their end. A *panic*
//! inside a member (a bug, not an error) is re-raised by rayon in the caller after the other
//! members finish, as a serial loop would raise it.
//!
//! Threads come from rayon's global pool (as many as cores, or `RAYON_NUM_THREADS`). To use
//! a pool of your own, call these functions inside `pool.install(|| ...)`.
//!
//! ```
//! use mbd_core::ensemble;
//! let squares = ensemble::map(&[1.0, 2.0, 3.0], |x: &f64| x * x);
//! assert_eq!(squares, vec![1.0, 4.0, 9.0]);
//! ```

use crate::error::Result;
use crate::integrate::{Integrator, Solution};
use crate::model::{OdeSystem, Vector};
#[cfg(feature = "parallel")]
use rayon::prelude::*;

/// `f` applied to every input, in parallel; the results are in input order.
///
/// Work is split by rayon's work stealing, so members of very different cost (a run that
/// stops at an early event next to one that goes the whole way) still keep every core busy.
pub fn map<I, R, F>(inputs: &[I], f: F) -> Vec<R>
where
    I: Sync,
    R: Send,
    F: Fn(&I) -> R + Sync,
{
    #[cfg(feature = "parallel")]
    return inputs.par_iter().map(&f).collect();
    #[cfg(not(feature = "parallel"))]
    return inputs.iter().map(&f).collect();
}

/// The number of threads [`map`] runs on here: the size of the current rayon pool (the
/// global one unless called inside `pool.install`); 1 without the feature `parallel`.
pub fn threads() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    return 1;
}

/// One member of an ensemble: a model (its parameters) and its initial state.
#[derive(Debug, Clone, PartialEq)]
pub struct Member<S, const D: usize> {
    /// The model, i.e. one variation of the parameters.
    pub model: S,
    /// The state at `t0`.
    pub y0: Vector<D>,
}

impl<S, const D: usize> Member<S, D> {
    /// A member from its model and initial state.
    pub fn new(model: S, y0: Vector<D>) -> Self {
        Member { model, y0 }
    }
}

/// Integrate every member from `t0` to `t1` with `method` (its own options), in parallel.
///
/// Returns one result per member, in input order: the member's [`Solution`], or the error
/// that stopped it. No events are located (an event list borrows its model and is not
/// shareable between threads); for events, call [`map`] with a closure that builds each
/// member's events and calls [`Integrator::solve`] itself. Set `Options::dense = false` in
/// the method's options when only the steps are wanted: a large ensemble's dense output is
/// the bulk of its memory.
pub fn integrate<S, M, const D: usize>(
    method: &M,
    members: &[Member<S, D>],
    t0: f64,
    t1: f64,
) -> Vec<Result<Solution<D>>>
where
    S: OdeSystem<D> + Sync,
    M: Integrator + Sync,
{
    map(members, |m| method.solve(&m.model, t0, m.y0, t1, &[]))
}

/// [`integrate`], keeping only each member's final state: the end time and the state there.
/// The end time is `t1` unless the run failed (then the error is returned instead).
pub fn final_states<S, M, const D: usize>(
    method: &M,
    members: &[Member<S, D>],
    t0: f64,
    t1: f64,
) -> Vec<Result<(f64, Vector<D>)>>
where
    S: OdeSystem<D> + Sync,
    M: Integrator + Sync,
{
    map(members, |m| {
        let sol = method.solve(&m.model, t0, m.y0, t1, &[])?;
        let (t, y) = sol.last();
        Ok((t, *y))
    })
}
