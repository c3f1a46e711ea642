//! The one error type of mbd's runtime. Every failure a user can cause is a variant here;
//! library code never panics on user input and never passes a NaN on.

use std::fmt;

/// What went wrong, with the numbers needed to understand it.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// Newton's method on the position constraints `Phi(q, t) = 0` did not converge.
    AssemblyFailed {
        t: f64,
        iterations: usize,
        residual: f64,
    },
    /// The mass matrix (or the augmented matrix `[M Phi_q^T; Phi_q 0]`) is singular at `t`.
    SingularMassMatrix { t: f64 },
    /// The constraint Jacobian `Phi_q` lost rank at `t` (a toggle / dead-centre position,
    /// or redundant constraints).
    SingularConstraintJacobian { t: f64 },
    /// The step size fell below what floating point can resolve at `t`.
    StepSizeUnderflow { t: f64, h: f64 },
    /// `max_steps` were taken before reaching the end (often a sign of stiffness for an explicit method).
    TooManySteps { t: f64, steps: usize },
    /// The explicit method's stiffness detector fired repeatedly at `t`.
    Stiff { t: f64 },
    /// The Newton iteration of an implicit method kept failing even at tiny steps.
    NewtonFailed { t: f64, h: f64 },
    /// A state or a right-hand side value became NaN or infinite at `t`.
    NonFinite { t: f64 },
    /// Newton's method on the static equilibrium `f(q, 0, t) = 0` (with `Phi = 0` for closed
    /// loops) did not converge, or met a singular stiffness (a neutral equilibrium).
    StaticsFailed {
        t: f64,
        iterations: usize,
        residual: f64,
    },
    /// A closed loop reached a position where its closure has no regular solution: in
    /// minimal coordinates, an `asin`/`acos` argument of the closed form reached or left
    /// `[-1, 1]` (the loop cannot assemble there, or sits at a toggle or limit position
    /// where two branches meet). `detail` names the coordinate and the configuration.
    SingularPosition { t: f64, detail: String },
    /// An option or an argument is out of its domain (`what` names it).
    InvalidInput { what: &'static str, detail: String },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::AssemblyFailed {
                t,
                iterations,
                residual,
            } => write!(
                f,
                "assembly did not converge at t = {t}: residual {residual:.3e} after {iterations} Newton iterations"
            ),
            Error::SingularMassMatrix { t } => write!(f, "singular mass matrix at t = {t}"),
            Error::SingularConstraintJacobian { t } => write!(
                f,
                "constraint Jacobian lost rank at t = {t} (toggle or dead-centre position, or redundant constraints)"
            ),
            Error::StepSizeUnderflow { t, h } => {
                write!(f, "step size underflow at t = {t} (h = {h:.3e})")
            }
            Error::TooManySteps { t, steps } => {
                write!(
                    f,
                    "gave up after {steps} steps at t = {t} (is the problem stiff?)"
                )
            }
            Error::Stiff { t } => write!(f, "problem is stiff at t = {t}: use an implicit method"),
            Error::NewtonFailed { t, h } => {
                write!(
                    f,
                    "Newton iteration failed at t = {t} even with h = {h:.3e}"
                )
            }
            Error::NonFinite { t } => write!(f, "state became NaN or infinite at t = {t}"),
            Error::StaticsFailed {
                t,
                iterations,
                residual,
            } => write!(
                f,
                "static equilibrium not found at t = {t}: residual {residual:.3e} after {iterations} Newton iterations"
            ),
            Error::SingularPosition { t, detail } => {
                write!(f, "singular position of a closed loop at t = {t}: {detail}")
            }
            Error::InvalidInput { what, detail } => write!(f, "invalid `{what}`: {detail}"),
        }
    }
}

impl std::error::Error for Error {}

/// Shorthand used throughout the runtime.
pub type Result<T, E = Error> = std::result::Result<T, E>;
