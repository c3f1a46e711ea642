//! What a case's drawing adds to its model's generated geometry (`#[mechanism(geometry)]`):
//! massless links, bodies drawn through their joints, guides and ground pivots. Every added
//! line joins points the model itself generated at that instant, named by shape, so the
//! drawing cannot disagree with the model: a case says *which* generated points a link
//! joins, never *where* they are.

use crate::validation::{Animation, Frame};
use mbd::{Shape, ShapeKind};

/// A point of the generated drawing: shape `.0`'s point `.1` (0: a particle, a named point,
/// a body's mass centre; 1 and 2: the ends of a planar rigid body's bar).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct At(pub &'static str, pub usize);

/// What a case draws beyond its model's bodies, points, springs and dampers.
#[derive(Debug, Clone, Copy, Default)]
pub struct Sketch {
    /// Massless links (a two-force member, a light rod, a polar arm): a bar between two
    /// generated points. The language has no massless body, so the model does not draw them.
    pub links: &'static [(&'static str, At, At)],
    /// Rigid bodies drawn through their joints and mass centre rather than as the bar of
    /// their mass and inertia (which is the body only for a uniform bar): a non-uniform rod,
    /// a platform whose mass centre is off the line of its pins.
    pub bodies: &'static [(&'static str, &'static [At])],
    /// Points that run on a fixed guide (a slider's track, an incline, a floor): the guide
    /// is drawn along the path the point takes over the run.
    pub guides: &'static [At],
    /// Bar ends that connect nothing (a pendulum's free end, a slotted arm's tip).
    pub free: &'static [At],
}

impl Sketch {
    /// Nothing beyond the model's own shapes.
    pub const NONE: Sketch = Sketch {
        links: &[],
        bodies: &[],
        guides: &[],
        free: &[],
    };
}

/// What an added element stands for; it decides how the page draws it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Added {
    /// A massless link: its two ends (the page's `bar`).
    Link,
    /// A rigid body through its joints: its mass centre, then its joints.
    Body,
}

impl Added {
    /// Lower-case name, for the page.
    pub fn name(self) -> &'static str {
        match self {
            Added::Link => "bar",
            Added::Body => "body",
        }
    }
}

/// One added element at an instant, its points copied from the generated shapes.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawn {
    pub kind: Added,
    pub name: &'static str,
    pub points: Vec<[f64; 3]>,
}

/// A guide: the path its point takes over the run's frames.
#[derive(Debug, Clone, PartialEq)]
pub struct Guide {
    pub on: At,
    pub path: Vec<[f64; 3]>,
}

/// The generated point `at` names in `shapes`, or why there is none.
pub fn point(shapes: &[Shape], at: At) -> mbd::Result<[f64; 3]> {
    shapes
        .iter()
        .find(|s| s.name == at.0)
        .and_then(|s| s.points.get(at.1).copied())
        .ok_or_else(|| mbd::Error::InvalidInput {
            what: "sketch",
            detail: format!("the model draws no point {} of `{}`", at.1, at.0),
        })
}

/// The added elements of one frame.
fn added(shapes: &[Shape], sketch: &Sketch) -> mbd::Result<Vec<Drawn>> {
    let mut out = Vec::new();
    for &(name, from, to) in sketch.links {
        out.push(Drawn {
            kind: Added::Link,
            name,
            points: vec![point(shapes, from)?, point(shapes, to)?],
        });
    }
    for &(name, joints) in sketch.bodies {
        let mut points = vec![point(shapes, At(name, 0))?];
        for &j in joints {
            points.push(point(shapes, j)?);
        }
        out.push(Drawn {
            kind: Added::Body,
            name,
            points,
        });
    }
    Ok(out)
}

/// `anim` with the sketch's links and bodies in every frame and still, its guides' paths,
/// and its ground pivots.
pub fn apply(mut anim: Animation, sketch: &Sketch) -> mbd::Result<Animation> {
    for f in anim.frames.iter_mut().chain(anim.stills.iter_mut()) {
        f.added = added(&f.shapes, sketch)?;
    }
    anim.guides = sketch
        .guides
        .iter()
        .map(|&on| {
            let path = anim
                .frames
                .iter()
                .map(|f| point(&f.shapes, on))
                .collect::<mbd::Result<_>>()?;
            Ok(Guide { on, path })
        })
        .collect::<mbd::Result<_>>()?;
    anim.pivots = pivots(&anim.frames);
    Ok(anim)
}

/// The ends of the bars a frame draws, each with what it belongs to: planar rigid bars
/// (not the bodies drawn through their joints), links, and the joints of those bodies.
pub fn ends(f: &Frame) -> Vec<(At, [f64; 3])> {
    let through = |name: &str| {
        f.added
            .iter()
            .any(|d| d.kind == Added::Body && d.name == name)
    };
    let mut out = Vec::new();
    for s in &f.shapes {
        if s.kind == ShapeKind::Rigid && s.points.len() == 3 && !through(s.name) {
            out.extend((1..3).map(|k| (At(s.name, k), s.points[k])));
        }
    }
    for d in &f.added {
        let first = usize::from(d.kind == Added::Body);
        out.extend(
            d.points
                .iter()
                .enumerate()
                .skip(first)
                .map(|(k, p)| (At(d.name, k), *p)),
        );
    }
    out
}

/// The size of a frame's drawing (the largest coordinate's magnitude, at least 1e-3): what
/// "the same point" is measured against.
pub fn size(frames: &[Frame]) -> f64 {
    frames
        .iter()
        .flat_map(|f| f.shapes.iter().flat_map(|s| s.points.iter()))
        .flatten()
        .fold(1e-3, |m, x| m.max(x.abs()))
}

/// Two points are one joint to this fraction of the drawing's size.
pub const SAME: f64 = 1e-9;

/// Ground pivots: bar ends and named points that stay put over the whole run (to [`SAME`]
/// of the drawing's size), once each. A run with one frame has none (nothing shows what
/// stays put).
pub fn pivots(frames: &[Frame]) -> Vec<[f64; 3]> {
    let (Some(first), true) = (frames.first(), frames.len() > 1) else {
        return Vec::new();
    };
    let tol = SAME * size(frames);
    let near = |a: [f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() <= tol);
    let named = first
        .shapes
        .iter()
        .filter(|s| s.kind == ShapeKind::Point)
        .map(|s| (At(s.name, 0), s.points[0]));
    let candidates: Vec<(At, [f64; 3])> = ends(first).into_iter().chain(named).collect();
    let mut out: Vec<[f64; 3]> = Vec::new();
    for (at, p) in candidates {
        let still = frames.iter().all(|f| {
            let q = ends(f)
                .into_iter()
                .find(|(a, _)| *a == at)
                .map(|(_, q)| q)
                .or_else(|| point(&f.shapes, at).ok());
            q.is_some_and(|q| near(p, q))
        });
        if still && !out.iter().any(|&o| near(o, p)) {
            out.push(p);
        }
    }
    out
}
