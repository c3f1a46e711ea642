//! What a mechanism looks like at a state: the shapes a model generated with
//! `#[mechanism(geometry)]` returns (`Drawable`), for reports that draw and animate it.
//!
//! Every point is in ground coordinates (`z = 0` in a planar mechanism). A rigid body of the
//! explicit form is drawn as the slender bar with its mass and central moment of inertia
//! (half-length `sqrt(3 I / m)`) along its body x axis, since the language gives a body no
//! extent; a joint-tree body as the segment from its joint to twice its mass-centre offset.

use crate::{Result, Vector};

/// What a [`Shape`] stands for; it decides how it is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeKind {
    /// A particle: one point.
    Particle,
    /// A rigid body: its mass centre, then the two ends of its bar (planar), or the ends of
    /// its three body axes (spatial, `inertia = diag(..)`; none for other inertia forms).
    Rigid,
    /// A named point (`#[point]`): one point.
    Point,
    /// A joint-tree body: its joint, its mass centre, its far end.
    Link,
    /// A spring: its two ends.
    Spring,
    /// A damper: its two ends.
    Damper,
}

impl ShapeKind {
    /// Lower-case name, for reports.
    pub fn name(self) -> &'static str {
        match self {
            ShapeKind::Particle => "particle",
            ShapeKind::Rigid => "rigid",
            ShapeKind::Point => "point",
            ShapeKind::Link => "link",
            ShapeKind::Spring => "spring",
            ShapeKind::Damper => "damper",
        }
    }
}

/// One drawn element of a mechanism at a state.
#[derive(Debug, Clone, PartialEq)]
pub struct Shape {
    pub kind: ShapeKind,
    /// The body's, point's, spring's or damper's name in the model.
    pub name: &'static str,
    /// Its points in ground coordinates, in the order [`ShapeKind`] gives.
    pub points: Vec<[f64; 3]>,
}

/// A model that can say what it looks like (`#[mechanism(geometry)]`).
pub trait Drawable<const D: usize> {
    /// The shapes at `(t, y)`, in declaration order: bodies, points, springs, dampers.
    fn geometry(&self, t: f64, y: &Vector<D>) -> Result<Vec<Shape>>;
}
