//! Kinematics in full coordinates: every body's position and orientation (free-standing
//! bodies, then the joint trees), the body frames that body-fixed points are measured in,
//! and `Kin`, which answers user expressions' body queries and total time derivatives.

use super::{Coord, CoordKind};
use crate::lower::{self, Value};
use crate::parse::Dim;
use crate::sym::{Expr, Func, Graph, Sym};
use crate::{spatial, tree};
use std::collections::HashMap;

/// Everything the mechanics knows about the motion, before any force: the coordinates and
/// the bodies, with the joint trees' own descriptions for their recursions and closures.
pub(super) struct Kinematics {
    pub coords: Vec<Coord>,
    pub bodies: Vec<BodyKin>,
    pub planar: PlanarTree,
    pub spatial: SpatialTree,
}

/// A planar joint tree: its nodes in declaration order, and each body's node by name.
#[derive(Default)]
pub(super) struct PlanarTree {
    pub nodes: Vec<tree::Node>,
    pub node_of: HashMap<String, usize>,
    /// Each prismatic joint's axis, by its body's name (checked non-zero at run time).
    pub axes: Vec<(String, Vec<Expr>)>,
}

/// A spatial joint tree: each body's frame by name, and the one-degree-of-freedom steps of
/// its joints for the recursions.
#[derive(Default)]
pub(super) struct SpatialTree {
    pub frames: Vec<Frame>,
    pub frame_of: HashMap<String, usize>,
    pub steps: Vec<spatial::Node>,
    /// Each prismatic joint's axis, by its body's name (checked non-zero at run time).
    pub axes: Vec<(String, Vec<Expr>)>,
}

impl Kinematics {
    /// The answerer of body queries, collecting the reactions that outputs ask for.
    pub fn kin<'a>(&'a self, t: Expr, dim: Dim, reactions: &'a mut Vec<(usize, Expr)>) -> Kin<'a> {
        Kin {
            coords: &self.coords,
            bodies: &self.bodies,
            t,
            dim,
            reactions,
        }
    }

    /// The symbols of the full coordinates' positions.
    pub fn z_syms(&self, g: &Graph) -> Vec<Sym> {
        self.coords
            .iter()
            .map(|c| g.as_sym(c.z).expect("symbol"))
            .collect()
    }

    /// The symbols of the full coordinates' velocities.
    pub fn zd_syms(&self, g: &Graph) -> Vec<Sym> {
        self.coords
            .iter()
            .map(|c| g.as_sym(c.zd).expect("symbol"))
            .collect()
    }
}

/// One body's kinematics in full coordinates.
pub(super) struct BodyKin {
    pub mass: Expr,
    /// Planar: `[[I]]`-like scalar in `inertia[0][0]`; spatial: the body-frame tensor.
    pub inertia: Option<[[Expr; 3]; 3]>,
    pub r: Vec<Expr>,
    /// Planar angle.
    pub angle: Option<Expr>,
    /// Spatial rotation (world from body).
    pub rot: Option<[[Expr; 3]; 3]>,
    /// The body frame, which body-fixed offsets (`position(b, [..])`) are measured in and
    /// from: origin, and planar angle or spatial rotation (with its angular velocity when a
    /// tree composed it; else it is derived from the rotation). A free body's frame is at its mass centre (`at`); a tree body's at
    /// its joint. Present even when the body has no rotational inertia.
    pub origin: Vec<Expr>,
    pub frame_angle: Option<Expr>,
    pub frame_rot: Option<[[Expr; 3]; 3]>,
    pub frame_omega: Option<[Expr; 3]>,
}

/// A spatial tree body's frame: origin and rotation (ground from body), and its angular
/// velocity in its own axes.
#[derive(Clone, Copy)]
pub(super) struct Frame {
    pub origin: [Expr; 3],
    pub rot: [[Expr; 3]; 3],
    pub omega: [Expr; 3],
}

pub(super) struct Kin<'a> {
    pub coords: &'a [Coord],
    pub bodies: &'a [BodyKin],
    pub t: Expr,
    pub dim: Dim,
    /// Reaction symbols requested by outputs: coordinate index -> placeholder symbol.
    pub reactions: &'a mut Vec<(usize, Expr)>,
}

impl Kin<'_> {
    /// Total time derivative in full coordinates.
    pub fn tder(&self, g: &mut Graph, e: Expr) -> Expr {
        let mut terms = Vec::new();
        for c in self.coords {
            for (x, dx) in [(c.z, c.zd), (c.zd, c.zdd), (c.zdd, c.zddd)] {
                let s = g.as_sym(x).expect("coordinate symbol");
                let d = g.diff(e, s);
                if !g.is_zero(d) {
                    terms.push(g.mul(d, dx));
                }
            }
        }
        let ts = g.as_sym(self.t).expect("time symbol");
        terms.push(g.diff(e, ts));
        g.sum(terms)
    }

    fn tder_value(&self, g: &mut Graph, v: &Value) -> Value {
        match v {
            Value::Scalar(s) => Value::Scalar(self.tder(g, *s)),
            Value::Vector(v) => Value::Vector(v.iter().map(|x| self.tder(g, *x)).collect()),
            Value::Matrix(m) => Value::Matrix(m.map(|row| row.map(|x| self.tder(g, x)))),
        }
    }

    /// Position of a body-fixed point (`offset` in the body frame's axes, from the body
    /// frame's origin; `None`: the mass centre).
    fn point(&self, g: &mut Graph, b: &BodyKin, offset: Option<&[Expr]>) -> Vec<Expr> {
        let Some(d) = offset else { return b.r.clone() };
        let r = &b.origin;
        match (self.dim, b.frame_angle, b.frame_rot) {
            (Dim::Planar, Some(phi), _) => {
                let (c, s) = (g.call(Func::Cos, phi), g.call(Func::Sin, phi));
                let (xc, ys) = (g.mul(c, d[0]), g.mul(s, d[1]));
                let (xs, yc) = (g.mul(s, d[0]), g.mul(c, d[1]));
                let dx = g.sub(xc, ys);
                let dy = g.add(xs, yc);
                vec![g.add(r[0], dx), g.add(r[1], dy)]
            }
            (Dim::Spatial, _, Some(rot)) => (0..3)
                .map(|i| {
                    let rd = g.dot(&rot[i], d);
                    g.add(r[i], rd)
                })
                .collect(),
            _ => r.iter().zip(d).map(|(r, d)| g.add(*r, *d)).collect(),
        }
    }

    /// Body-frame angular velocity `vee(R^T dR/dt)` of a spatial body.
    /// A spatial body's angular velocity in its own frame: the tree's, or `vee(R^T R')`.
    pub fn omega_body(&self, g: &mut Graph, b: &BodyKin) -> Vec<Expr> {
        if let Some(w) = b.frame_omega {
            return w.to_vec();
        }
        let rot = b.frame_rot.expect("a spatial body");
        let rdot = rot.map(|row| row.map(|x| self.tder(g, x)));
        let mut s = [[g.zero(); 3]; 3];
        for (i, row) in s.iter_mut().enumerate() {
            for (j, sij) in row.iter_mut().enumerate() {
                let col_i = [rot[0][i], rot[1][i], rot[2][i]];
                let col_j = [rdot[0][j], rdot[1][j], rdot[2][j]];
                *sij = g.dot(&col_i, &col_j);
            }
        }
        vec![s[2][1], s[0][2], s[1][0]]
    }
}

impl lower::Model for Kin<'_> {
    fn der(&mut self, g: &mut Graph, v: &Value) -> Value {
        self.tder_value(g, v)
    }

    fn body(
        &mut self,
        g: &mut Graph,
        query: &str,
        body: usize,
        offset: Option<Vec<Expr>>,
    ) -> Result<Value, String> {
        let b = &self.bodies[body];
        if offset.is_some() && b.frame_angle.is_none() && b.frame_rot.is_none() {
            return Err(format!(
                "a particle has no orientation, so no body-fixed offset: use `{query}(..)` without one, or a `rigid` body"
            ));
        }
        match query {
            "position" | "velocity" | "acceleration" => {
                let mut v = Value::Vector(self.point(g, b, offset.as_deref()));
                for _ in 0..["position", "velocity", "acceleration"]
                    .iter()
                    .position(|q| *q == query)
                    .unwrap_or(0)
                {
                    v = self.tder_value(g, &v);
                }
                Ok(v)
            }
            "angle" if b.frame_rot.is_some() => Err(
                "`angle` is planar: a spatial body has `angular_velocity` and `angular_acceleration`"
                    .to_string(),
            ),
            _ => {
                let order = ["angle", "angular_velocity", "angular_acceleration"]
                    .iter()
                    .position(|q| *q == query)
                    .unwrap_or(0);
                Ok(match (b.frame_angle, b.frame_rot) {
                    (Some(phi), _) => {
                        let mut v = Value::Scalar(phi);
                        for _ in 0..order {
                            v = self.tder_value(g, &v);
                        }
                        v
                    }
                    (None, Some(rot)) => {
                        // World-frame angular velocity R w_b; its derivative is R dw_b/dt.
                        let w_b = self.omega_body(g, b);
                        let w = if order == 2 {
                            w_b.iter().map(|x| self.tder(g, *x)).collect()
                        } else {
                            w_b
                        };
                        Value::Vector((0..3).map(|i| g.dot(&rot[i], &w)).collect())
                    }
                    (None, None) => {
                        return Err(format!(
                            "`{query}` needs a rigid body: a particle has no orientation"
                        ));
                    }
                })
            }
        }
    }

    fn reaction(&mut self, g: &mut Graph, coord: Expr) -> Option<Expr> {
        let idx = self.coords.iter().position(|c| c.z == coord)?;
        if matches!(self.coords[idx].kind, CoordKind::Free) {
            return None;
        }
        if let Some((_, s)) = self.reactions.iter().find(|(i, _)| *i == idx) {
            return Some(*s);
        }
        let s = g.symbol(&format!("reaction:{}", self.coords[idx].name));
        self.reactions.push((idx, s));
        Some(s)
    }
}

/// `[d/dt e]` without its `zdd` terms: the acceleration-like part that does not depend on
/// the unknown accelerations (`a0`, `alpha0`).
pub(super) fn drop_qdd(g: &mut Graph, kin: &Kin<'_>, v: Expr) -> Expr {
    let mut terms = Vec::new();
    for c in kin.coords {
        let s = g.as_sym(c.z).expect("symbol");
        let d = g.diff(v, s);
        if !g.is_zero(d) {
            terms.push(g.mul(d, c.zd));
        }
    }
    let ts = g.as_sym(kin.t).expect("symbol");
    terms.push(g.diff(v, ts));
    g.sum(terms)
}
