//! mbd: write a mechanism once as a `#[derive(Mechanism)]` on a parameter struct; get its
//! equations of motion, constraint Jacobians and everything the numerics need as
//! specialised straight-line Rust at compile time.

pub use mbd_core::*;
pub use mbd_derive::Mechanism;
pub use nalgebra;

/// What a mechanism file needs in scope.
pub mod prelude {
    pub use crate::Mechanism;
    pub use mbd_core::{
        Constrained, Error, Matrix, Mechanism as MechanismModel, OdeSystem, Options, Vector,
    };
}

/// Items generated code calls. Not part of the public API.
#[doc(hidden)]
pub mod __private {
    pub use mbd_core::*;
    pub use nalgebra;
}
