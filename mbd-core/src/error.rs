//! The one error type of mbd's runtime. Every failure a user can cause is a variant here;
//! library code never panics on user input and never passes a NaN on.

use std::fmt;

/// What went wrong, with the numbers needed to understand it.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// Newton's method on the position constraints `Phi(q, t) = 0` did not converge.
    /// `detail`: where (the last configuration `q`, and the constraint rows that lost rank
    /// there when they did), or empty.
    AssemblyFailed {
        t: f64,
        iterations: usize,
        residual: f64,
        detail: String,
    },
    /// The mass matrix (or the augmented matrix `[M Phi_q^T; Phi_q 0]`) is singular at `t`.
    SingularMassMatrix { t: f64 },
    /// The constraint Jacobian `Phi_q` lost rank at `t` (a toggle / dead-centre position,
    /// or redundant constraints). `detail`: where (the configuration `q` and the rows that
    /// lost rank, as the assembly and the kinematic analysis give them), or empty.
    SingularConstraintJacobian { t: f64, detail: String },
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
    /// A model's parameter, or a value made of parameters (`what`: "the mass of `bob`",
    /// "parameter `m`"), is not what its meaning needs (`requirement`: "finite", "positive").
    InvalidParameter {
        what: String,
        value: f64,
        requirement: &'static str,
    },
    /// The mass matrix is not positive definite at `t` (an `L D L^T` pivot is negative): a
    /// negative mass or inertia, which no mechanism has.
    MassMatrixNotPositiveDefinite { t: f64 },
    /// An event function failed (`cause`) or was NaN or infinite (`cause: None`) at `t`: the
    /// integration stops rather than never firing the event.
    EventFailed {
        event: String,
        t: f64,
        cause: Option<Box<Error>>,
    },
    /// An ordinary `Integrator::solve` of a system whose right-hand side switches between
    /// modes (`OdeSystem::HYBRID`) but that does not hand over its modes
    /// (`OdeSystem::hybrid`, which generated friction models do) failed (`cause`: its steps
    /// collapsed at the discontinuity) at `t`; [`crate::hybrid::solve`] integrates such a
    /// system mode by mode, switching exactly.
    ModeSwitch { t: f64, cause: Box<Error> },
}

/// A number in a message: up to 6 significant figures, in exponent form when very large or
/// small (Rust's `{}` writes `1e-300` with 300 digits).
#[derive(Debug, Clone, Copy)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v == 0.0 || !v.is_finite() {
            return write!(f, "{v}");
        }
        if (1e-4..1e6).contains(&v.abs()) {
            // 6 significant figures, trailing zeros trimmed.
            let decimals = (5 - v.abs().log10().floor() as i32).max(0) as usize;
            let s = format!("{v:.decimals$}");
            let s = if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.')
            } else {
                &s
            };
            write!(f, "{s}")
        } else {
            write!(f, "{v:.5e}")
        }
    }
}

/// An error's optional `detail`, written after `": "` when there is one.
struct Detail<'a>(&'a str);

impl fmt::Display for Detail<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            "" => Ok(()),
            d => write!(f, ": {d}"),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::AssemblyFailed {
                t,
                iterations,
                residual,
                detail,
            } => write!(
                f,
                "assembly did not converge at t = {}: residual {residual:.3e} after {iterations} Newton iterations{} (start from a guess closer to an assembled configuration, or check that the constraints can hold there)",
                Num(*t),
                Detail(detail)
            ),
            Error::SingularMassMatrix { t } => write!(
                f,
                "singular mass matrix at t = {} (a coordinate that moves no mass, or a zero mass or inertia)",
                Num(*t)
            ),
            Error::SingularConstraintJacobian { t, detail } => write!(
                f,
                "constraint Jacobian lost rank at t = {} (toggle or dead-centre position, or redundant constraints){}",
                Num(*t),
                Detail(detail)
            ),
            Error::StepSizeUnderflow { t, h } => {
                write!(
                    f,
                    "step size underflow at t = {} (h = {h:.3e}): the solution cannot be followed past t (a jump, a singularity or a blow-up of the model there); check the model near t",
                    Num(*t)
                )
            }
            Error::TooManySteps { t, steps } => write!(
                f,
                "stopped at t = {} after the limit of {steps} steps: raise `Options::max_steps`, or loosen `rtol`/`atol`",
                Num(*t)
            ),
            Error::Stiff { t } => write!(
                f,
                "problem is stiff at t = {}: use an implicit method (Radau5)",
                Num(*t)
            ),
            Error::NewtonFailed { t, h } => write!(
                f,
                "Newton iteration failed at t = {} even with h = {h:.3e}: the model is not smooth or not defined near this state (check it there)",
                Num(*t)
            ),
            Error::NonFinite { t } => {
                write!(
                    f,
                    "a state or derivative became NaN or infinite at t = {} (check the model's expressions at this state: a division by zero, `sqrt`, `ln`, `asin`, `acos` outside their domain, or a solution that blows up)",
                    Num(*t)
                )
            }
            Error::StaticsFailed {
                t,
                iterations,
                residual,
            } => write!(
                f,
                "static equilibrium not found at t = {}: residual {residual:.3e} after {iterations} Newton iterations (start from a guess closer to the equilibrium; a neutral one has no isolated solution)",
                Num(*t)
            ),
            Error::SingularPosition { t, detail } => {
                write!(
                    f,
                    "singular position of a closed loop at t = {}: {detail}",
                    Num(*t)
                )
            }
            Error::InvalidInput { what, detail } => write!(f, "invalid `{what}`: {detail}"),
            Error::InvalidParameter {
                what,
                value,
                requirement,
            } => write!(f, "{what} is {}: it must be {requirement}", Num(*value)),
            Error::MassMatrixNotPositiveDefinite { t } => write!(
                f,
                "mass matrix not positive definite at t = {} (a negative mass or inertia?)",
                Num(*t)
            ),
            Error::EventFailed { event, t, cause } => match cause {
                Some(c) => write!(
                    f,
                    "event `{event}` could not be evaluated at t = {}: {c}",
                    Num(*t)
                ),
                None => write!(f, "event `{event}` is NaN or infinite at t = {}", Num(*t)),
            },
            Error::ModeSwitch { t, cause } => write!(
                f,
                "the model switches modes (Coulomb friction sticks or breaks away) near t = {}, where the ordinary solve failed ({cause}): integrate it with `mbd::hybrid::solve`, which switches modes exactly",
                Num(*t)
            ),
        }
    }
}

impl std::error::Error for Error {}

/// Shorthand used throughout the runtime.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_messages_are_short() {
        assert_eq!(Num(0.1 + 0.2).to_string(), "0.3");
        assert_eq!(Num(1e-300).to_string(), "1.00000e-300");
        assert_eq!(Num(123456.7).to_string(), "123457");
        assert_eq!(Num(2.5e7).to_string(), "2.50000e7");
        assert_eq!(Num(-2.0).to_string(), "-2");
        assert_eq!(Num(0.000123456789).to_string(), "0.000123457");
        let e = Error::StepSizeUnderflow {
            t: 1.0 / 3.0,
            h: 1e-300,
        };
        assert!(
            e.to_string()
                .starts_with("step size underflow at t = 0.333333 (h = 1.000e-300): "),
            "{e}"
        );
        let e = Error::TooManySteps { t: 2.5, steps: 100 };
        assert!(!e.to_string().contains("stiff"), "{e}");
    }
}
