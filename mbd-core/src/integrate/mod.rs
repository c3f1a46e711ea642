//! Time integration: shared options, statistics, dense output and the solution record.
//!
//! Every method advances an [`OdeSystem`](crate::OdeSystem) of fixed dimension `D` and
//! returns a [`Solution`]: the accepted steps, the dense output between them (one
//! [`Segment`] per step), the events found, and the work done ([`Stats`]).

/// Step size and tolerance settings shared by all methods. `Default` gives Hairer's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Relative tolerance (adaptive methods).
    pub rtol: f64,
    /// Absolute tolerance (adaptive methods).
    pub atol: f64,
    /// Initial step; `None` lets the method choose (Hairer's `HINIT`).
    pub h0: Option<f64>,
    /// Fixed step for fixed-step methods; largest step for adaptive ones (`None`: `t1 - t0`).
    pub h_max: Option<f64>,
    /// Steps allowed before [`Error::TooManySteps`](crate::Error::TooManySteps).
    pub max_steps: usize,
    /// Keep one dense-output [`Segment`] per step in the [`Solution`].
    pub dense: bool,
    /// Call [`OdeSystem::project`](crate::OdeSystem::project) after each accepted step.
    pub project: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            rtol: 1e-6,
            atol: 1e-6,
            h0: None,
            h_max: None,
            max_steps: 100_000,
            dense: true,
            project: true,
        }
    }
}

/// Work counters (Hairer's `IWORK(17..20)`), read by the work-precision report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations.
    pub n_rhs: usize,
    /// Jacobian evaluations.
    pub n_jac: usize,
    /// LU decompositions.
    pub n_lu: usize,
    /// Steps attempted (accepted + rejected).
    pub n_steps: usize,
    /// Steps accepted.
    pub n_accepted: usize,
    /// Steps rejected.
    pub n_rejected: usize,
}
