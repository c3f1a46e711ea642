//! The runtime of mbd: the model contract that generated code implements, integrators,
//! kinematic and dynamic analyses, and events.
//!
//! Users normally depend on the facade crate `mbd`, which re-exports this crate and the
//! `#[derive(Mechanism)]`.

pub mod analysis;
pub mod augmented;
pub mod banded;
pub mod chart;
pub mod closure;
pub mod ensemble;
pub mod error;
pub mod friction;
pub mod geometry;
pub mod hybrid;
pub mod integrate;
pub mod jacobian;
pub mod linalg;
pub mod model;
pub mod partition;
pub mod passage;
pub mod solve;
pub mod trig;

pub use error::{Error, Result};
pub use geometry::{Drawable, Shape, ShapeKind};
pub use integrate::{
    Auto, Direction, Dop853, Dopri5, Event, EventHit, Integrator, Options, Record, Rk4, Segment,
    Solution, Stats, Vern9,
};
pub use model::{
    Constrained, Contacts, Frictional, Generated, Hybrid, Matrix, Mechanism, Normals, OdeSystem,
    Slip, Vector,
};
