//! Stage 3: the AST -> the equations of motion, as symbolic expressions.
//!
//! Everything is first derived in *full* coordinates `z = (free, driven, relaxed)` with
//! symbols for `z`, `zd`, `zdd` and `t`, then *reduced*: a driven coordinate becomes its
//! law `s(t)` (with `s'`, `s''`), a relaxed one becomes 0. Reducing after differentiating
//! keeps every time derivative exact, and the rows of the full equations that belong to
//! driven and relaxed coordinates are exactly their reactions:
//! `r_u = (M zdd - f + Phi_z^T lambda)_u` (Kane's projection form; docs/ARCHITECTURE.md, Mechanics).

use crate::closure;
use crate::lower::{self, Binding, Context, Lowerer, Value};
use crate::parse::{self, BodyKind, Dim, End, Errors, Load, Mechanism};
use crate::sym::{Expr, Func, Graph, Sym, schedule};
use crate::{spatial, tree};
use proc_macro2::Span;
use std::collections::HashMap;
use syn::Ident;
use syn::spanned::Spanned;

/// What a symbol stands for in generated code.
#[derive(Clone, Debug, PartialEq)]
pub enum Role {
    Time,
    Param(Ident),
    /// Free coordinate `i`: position, velocity, acceleration.
    Q(usize),
    Qd(usize),
    Qdd(usize),
    /// Multiplier of constraint `k`.
    Lambda(usize),
    /// Sliding direction (+1 or -1) of friction `k`: `sign(qd_s)` in the model itself,
    /// a fixed mode in its sliding view, so that no step integrates through `sign(0)`.
    FrictionDirection(usize),
    /// A loop-local value of a rolled joint chain ([`tree::Rolled`]): read as the variable
    /// itself, or (`per_link`) at the link's index of the array of that name.
    RunLocal {
        per_link: bool,
    },
}

#[derive(Clone, Debug)]
pub enum CoordKind {
    Free,
    /// A driven coordinate with its law `s(t)`.
    Driven(Expr),
    Relaxed,
    /// A coordinate the closure fixes in closed form (minimal coordinates): its position,
    /// velocity and acceleration in the independent coordinates.
    Dependent([Expr; 3]),
}

pub struct Coord {
    pub name: Ident,
    pub kind: CoordKind,
    pub z: Expr,
    pub zd: Expr,
    pub zdd: Expr,
    /// Third derivative: only reachable through `der(..)` of an acceleration in outputs.
    pub zddd: Expr,
}

/// One body's kinematics in full coordinates.
struct BodyKin {
    mass: Expr,
    /// Planar: `[[I]]`-like scalar in `inertia[0][0]`; spatial: the body-frame tensor.
    inertia: Option<[[Expr; 3]; 3]>,
    r: Vec<Expr>,
    /// Planar angle.
    angle: Option<Expr>,
    /// Spatial rotation (world from body).
    rot: Option<[[Expr; 3]; 3]>,
    /// The body frame, which body-fixed offsets (`position(b, [..])`) are measured in and
    /// from: origin, and planar angle or spatial rotation (with its angular velocity when a
    /// tree composed it; else it is derived from the rotation). A free body's frame is at its mass centre (`at`); a tree body's at
    /// its joint. Present even when the body has no rotational inertia.
    origin: Vec<Expr>,
    frame_angle: Option<Expr>,
    frame_rot: Option<[[Expr; 3]; 3]>,
    frame_omega: Option<[Expr; 3]>,
}

/// A spatial tree body's frame: origin and rotation (ground from body), and its angular
/// velocity in its own axes.
#[derive(Clone, Copy)]
struct Frame {
    origin: [Expr; 3],
    rot: [[Expr; 3]; 3],
    omega: [Expr; 3],
}

/// Coulomb friction along free coordinate `coord` with the (reduced) normal force `normal`.
pub struct FrictionEq {
    pub coord: usize,
    pub mu: Expr,
    pub mu_static: Expr,
    pub normal: Expr,
    pub span: Span,
}

/// A value of parameters alone whose sign the mechanics needs (a mass, an inertia, a
/// stiffness, ..): checked at run time by the generated `check_parameters` when it did not
/// fold to a constant at compile time (a constant is checked by the `check` stage).
pub struct ParamCheck {
    /// What it is, for the message: "the mass of `bob`".
    pub what: String,
    pub expr: Expr,
    /// `> 0` (else `>= 0`).
    pub positive: bool,
    /// Checked on every acceleration: no solve would notice it (a negative stiffness,
    /// damping or friction coefficient), where a wrong mass or inertia makes the mass matrix
    /// fail its `L D L^T` and is named on that error path only.
    pub eager: bool,
}

pub struct OutputEq {
    pub name: Ident,
    pub expr: Expr,
}

pub struct EventEq {
    pub name: Ident,
    pub expr: Expr,
    pub direction: parse::Direction,
    pub terminal: bool,
}

/// The derived model, ready for code generation.
pub struct Equations {
    pub g: Graph,
    pub roles: HashMap<Sym, Role>,
    /// Names of the free coordinates, in state order.
    pub free: Vec<Ident>,
    pub mass: Vec<Vec<Expr>>,
    pub forces: Vec<Expr>,
    pub energy: Expr,
    pub phi: Vec<Expr>,
    pub phi_q: Vec<Vec<Expr>>,
    pub phi_t: Vec<Expr>,
    pub gamma: Vec<Expr>,
    /// `(dR/dq, dR/dqd, dC/dq, dC/dqd)` of the residuals `R = M qdd + Phi_q^T lambda - f`
    /// and `C = Phi_q qdd - gamma`, when exact Jacobians are asked for.
    pub jacobian: Option<ResidualJacobian>,
    pub outputs: Vec<OutputEq>,
    pub events: Vec<EventEq>,
    pub frictions: Vec<FrictionEq>,
    /// The forces without friction, for the stick test (present when there is friction).
    pub frictionless: Option<Vec<Expr>>,
    /// `qdd` of a joint tree by the articulated-body recursion, when that evaluates the
    /// accelerations instead of the mass matrix.
    pub recursive_qdd: Option<Vec<Expr>>,
    /// `(M qdd)_i` over the free coordinates (the `qdd` symbols standing for a column of the
    /// identity): a long tree's mass matrix, formed column by column at run time.
    pub mass_times: Option<Vec<Expr>>,
    /// `qdd` of a one-coordinate model without constraints, `f / m` with shared factors
    /// cancelled.
    pub single_qdd: Option<Expr>,
    /// The same recursion with a run of identical links rolled into loops (long chains),
    /// and the free-coordinate index of the run's first joint; `recursive_qdd` then holds
    /// the other free coordinates' accelerations, and zeros at the run's.
    pub rolled: Option<(tree::Rolled, usize)>,
    /// Initial positions and velocities of the free coordinates (parameters allowed).
    pub init_q: Vec<Expr>,
    pub init_qd: Vec<Expr>,
    /// Minimal coordinates of a closed loop (closure.rs): the `asin`/`acos` arguments the
    /// generated code checks, `None` when the model is not one (no loop, or augmented).
    pub closure_domain: Option<Vec<closure::Domain>>,
    /// Parameter values to check at run time.
    pub checks: Vec<ParamCheck>,
    zero: Expr,
    one: Expr,
}

pub struct ResidualJacobian {
    pub r_q: Vec<Vec<Expr>>,
    pub r_qd: Vec<Vec<Expr>>,
    pub c_q: Vec<Vec<Expr>>,
    pub c_qd: Vec<Vec<Expr>>,
}

struct Kin<'a> {
    coords: &'a [Coord],
    bodies: &'a [BodyKin],
    t: Expr,
    dim: Dim,
    /// Reaction symbols requested by outputs: coordinate index -> placeholder symbol.
    reactions: &'a mut Vec<(usize, Expr)>,
}

impl Kin<'_> {
    /// Total time derivative in full coordinates.
    fn tder(&self, g: &mut Graph, e: Expr) -> Expr {
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
    fn omega_body(&self, g: &mut Graph, b: &BodyKin) -> Vec<Expr> {
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

/// Names bound in user expressions.
type Names = HashMap<String, Binding>;

/// From how many tree bodies the articulated-body recursion replaces the mass-matrix solve
/// (measured with `cargo bench -p mechanisms --bench rhs`: see docs/ARCHITECTURE.md).
const RECURSIVE_FROM_BODIES: usize = 2;

/// From how many free coordinates a pure tree's mass matrix is formed at run time, column
/// by column (`Equations::mass_times`), instead of written out entry by entry: the entries
/// are O(n d) code, what bounds the build of long chains (`scaling`).
const LAZY_MASS_FROM: usize = 12;

/// Up to how many full coordinates Lagrange's form of the forces is derived as well, to take
/// it when it is shorter than Kane's (its Christoffel symbols are O(n^3)).
const LAGRANGE_MAX_COORDINATES: usize = 8;

/// Which form of the inertial forces `derive` builds (Kane's and Lagrange's are the same
/// functions, differently factored).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum InertialForm {
    /// Lagrange's when the system is scleronomic and it is shorter, else Kane's.
    Shorter,
    #[cfg(test)]
    Kane,
    #[cfg(test)]
    Lagrange,
}

pub fn derive(ast: &Mechanism) -> syn::Result<Equations> {
    derive_with(ast, InertialForm::Shorter)
}

fn derive_with(ast: &Mechanism, form: InertialForm) -> syn::Result<Equations> {
    let mut errors = Errors::default();
    let mut g = Graph::new();
    let mut names: Names = HashMap::new();
    let mut roles: HashMap<Sym, Role> = HashMap::new();
    let struct_name = ast.ident.to_string();
    let t = g.symbol("t");
    roles.insert(g.as_sym(t).expect("symbol"), Role::Time);

    let declare = |names: &mut Names, errors: &mut Errors, id: &Ident, b: Binding| {
        let key = id.to_string();
        if key == "t" {
            errors.at(id.span(), "`t` is time and cannot be redefined");
        } else if let std::collections::hash_map::Entry::Vacant(slot) = names.entry(key.clone()) {
            slot.insert(b);
        } else {
            errors.at(id.span(), format!("duplicate name `{key}`"));
        }
    };

    for p in &ast.params {
        let s = g.symbol(&p.name.to_string());
        roles.insert(g.as_sym(s).expect("symbol"), Role::Param(p.name.clone()));
        declare(
            &mut names,
            &mut errors,
            &p.name,
            Binding::Value(Value::Scalar(s)),
        );
    }

    for p in &ast.params {
        let Some(d) = &p.default else { continue };
        let mut scratch = Errors::default();
        let no_names = HashMap::new();
        let v = Lowerer {
            g: &mut g,
            names: &no_names,
            struct_name: &struct_name,
            model: None,
            errors: &mut scratch,
        }
        .scalar(d, Context::Constant);
        if v.and_then(|v| g.as_const(v)).is_none() {
            errors.over(
                d,
                format!(
                    "the default of `{}` must be a number or a constant expression of numbers",
                    p.name
                ),
            );
        }
    }

    // Parameters' defaults by name, for checks at the default values.
    let param_names: std::collections::HashSet<String> =
        ast.params.iter().map(|p| p.name.to_string()).collect();
    let defaults: HashMap<String, f64> = ast
        .params
        .iter()
        .filter_map(|p| {
            Some((
                p.name.to_string(),
                crate::check::fold(p.default.as_ref()?, &HashMap::new())?,
            ))
        })
        .collect();

    // Coordinates: free, driven, relaxed.
    let mut coords: Vec<Coord> = Vec::new();
    let new_coord = |g: &mut Graph, name: &Ident, kind: CoordKind| {
        let base = name.to_string();
        Coord {
            name: name.clone(),
            kind,
            z: g.symbol(&base),
            zd: g.symbol(&format!("{base}'")),
            zdd: g.symbol(&format!("{base}''")),
            zddd: g.symbol(&format!("{base}'''")),
        }
    };
    for (i, id) in ast.coords.iter().enumerate() {
        if ast.drives.iter().any(|d| d.name == *id) {
            errors.at(
                id.span(),
                format!("coordinate `{id}` is both free (in `coords`) and driven (in `drive`): a driven coordinate is a known function of time, remove it from `coords`"),
            );
        }
        let c = new_coord(&mut g, id, CoordKind::Free);
        for (s, role) in [
            (c.z, Role::Q(i)),
            (c.zd, Role::Qd(i)),
            (c.zdd, Role::Qdd(i)),
        ] {
            roles.insert(g.as_sym(s).expect("symbol"), role);
        }
        declare(&mut names, &mut errors, id, Binding::Coord(c.z));
        coords.push(c);
    }
    for d in &ast.drives {
        if ast.coords.contains(&d.name) {
            continue;
        }
        let law = Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        }
        .scalar(&d.expr, Context::Constant);
        let c = new_coord(&mut g, &d.name, CoordKind::Driven(law.unwrap_or(t)));
        declare(&mut names, &mut errors, &d.name, Binding::Coord(c.z));
        coords.push(c);
    }
    for id in &ast.relaxed {
        let c = new_coord(&mut g, id, CoordKind::Relaxed);
        declare(&mut names, &mut errors, id, Binding::Coord(c.z));
        coords.push(c);
    }
    let dim = ast.dim;

    // Points, in order: a point may use the points before it.
    for p in &ast.points {
        let v = Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        }
        .vector(&p.at, Context::Kinematics, dim.len());
        if let Some(v) = v {
            declare(
                &mut names,
                &mut errors,
                &p.name,
                Binding::Value(Value::Vector(v)),
            );
        }
    }

    // Bodies.
    let mut bodies: Vec<BodyKin> = Vec::new();
    for b in &ast.bodies {
        let mut lw = Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        };
        let mass = b
            .mass
            .as_ref()
            .and_then(|m| lw.scalar(m, Context::Constant));
        if let Some(m) = mass
            && lw.g.as_const(m).is_some_and(|v| v <= 0.0)
        {
            lw.errors.at(
                b.mass.as_ref().expect("mass").span(),
                format!("body `{}` has no positive mass", b.name),
            );
        }
        let r =
            b.at.as_ref()
                .and_then(|e| lw.vector(e, Context::Kinematics, dim.len()));
        let (mut inertia, mut angle, mut rot) = (None, None, None);
        match b.kind {
            BodyKind::Particle => {}
            BodyKind::Rigid => {
                if dim == Dim::Spatial {
                    lw.errors.at(b.name.span(), format!("`rigid` body `{}` is planar but the mechanism is spatial: use `rigid3`", b.name));
                }
                match &b.inertia {
                    Some(e) => {
                        if let Some(i) = lw.scalar(e, Context::Constant) {
                            if lw.g.as_const(i).is_some_and(|v| v <= 0.0) {
                                lw.errors
                                    .over(e, format!("body `{}` has no positive inertia", b.name));
                            }
                            let z = lw.g.zero();
                            inertia = Some([[i, z, z], [z, z, z], [z, z, z]]);
                        }
                    }
                    None => lw.errors.at(
                        b.name.span(),
                        format!("rigid body `{}` has no `inertia`", b.name),
                    ),
                }
                match &b.orientation {
                    Some(e) => angle = lw.scalar(e, Context::Kinematics),
                    None => lw.errors.at(
                        b.name.span(),
                        format!("rigid body `{}` has no `angle`", b.name),
                    ),
                }
            }
            BodyKind::Rigid3 => {
                match &b.inertia {
                    Some(e) => match lw.lower(e, Context::Constant) {
                        Some(Value::Matrix(m)) => inertia = Some(m),
                        Some(_) => lw.errors.at(
                            e.span(),
                            "a spatial inertia is `diag(a, b, c)` or a 3x3 matrix",
                        ),
                        None => {}
                    },
                    None => lw.errors.at(
                        b.name.span(),
                        format!("rigid body `{}` has no `inertia`", b.name),
                    ),
                }
                match &b.orientation {
                    Some(e) => match lw.lower(e, Context::Kinematics) {
                        Some(Value::Matrix(m)) => {
                            if crate::check::is_rotation(lw.g, &m, &defaults, &param_names)
                                == Some(false)
                            {
                                lw.errors.over(e, format!("the rotation of `{}` is not a rotation (R^T R = I, det R = 1): build it from `rot_x`, `rot_y`, `rot_z`", b.name));
                            }
                            rot = Some(m)
                        }
                        Some(_) => lw.errors.at(
                            e.span(),
                            "a rotation is a product of `rot_x`, `rot_y`, `rot_z` or a 3x3 matrix",
                        ),
                        None => {}
                    },
                    None => lw.errors.at(
                        b.name.span(),
                        format!("rigid body `{}` has no `rotation`", b.name),
                    ),
                }
            }
        }
        let idx = bodies.len();
        if let (Some(mass), Some(r)) = (mass, r) {
            bodies.push(BodyKin {
                mass,
                inertia,
                origin: r.clone(),
                r,
                angle,
                rot,
                frame_angle: angle,
                frame_rot: rot,
                frame_omega: None,
            });
            declare(&mut names, &mut errors, &b.name, Binding::Body(idx));
        }
    }
    // Joint-tree bodies: each frame is its parent's, moved by the joint.
    let mut nodes: Vec<tree::Node> = Vec::new();
    let mut node_of: HashMap<String, usize> = HashMap::new();
    for tb in ast.tree.iter().filter(|_| dim == Dim::Planar) {
        match &tb.joint {
            parse::Joint::Revolute { axis: Some(a), .. } => {
                errors.at(a.span(), "a planar revolute joint turns about the plane's normal: write `revolute(q)` without an axis");
                continue;
            }
            parse::Joint::Universal(..) | parse::Joint::Spherical(..) => {
                errors.at(tb.joint_span, "a `universal` or `spherical` joint needs a spatial mechanism: `#[mechanism(spatial)]`");
                continue;
            }
            _ => {}
        }
        let Ok(parent) = tree_parent(tb, &node_of, &mut errors) else {
            continue;
        };
        let mut lw = Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        };
        let vec2 = |lw: &mut Lowerer<'_>, e: &Option<syn::Expr>| {
            tree_vector(lw, e, 2).map(|v| [v[0], v[1]])
        };
        let (at, com) = (vec2(&mut lw, &tb.at), vec2(&mut lw, &tb.com));
        let offset = match &tb.angle {
            Some(e) => lw.scalar(e, Context::Constant),
            None => Some(lw.g.zero()),
        };
        let mass = tree_mass(&mut lw, tb);
        let inertia = match &tb.inertia {
            Some(e) => lw.scalar(e, Context::Constant),
            None => Some(lw.g.zero()),
        };
        let coord = tb
            .joint
            .coords()
            .first()
            .map(|c| coords.iter().position(|k| k.name == **c));
        let axis = match &tb.joint {
            parse::Joint::Prismatic { axis, .. } => lw
                .vector(axis, Context::Constant, 2)
                .map(|v| Some([v[0], v[1]])),
            _ => Some(None),
        };
        let (Some(at), Some(com), Some(offset), Some(mass), Some(inertia), Some(axis)) =
            (at, com, offset, mass, inertia, axis)
        else {
            continue;
        };
        let (p_origin, p_angle) = match parent {
            Some(p) => (nodes[p].origin, nodes[p].angle),
            None => ([g.zero(), g.zero()], g.zero()),
        };
        let mut local = at;
        let mut relative = offset;
        let joint = match (&tb.joint, coord.flatten(), axis) {
            (parse::Joint::Revolute { .. }, Some(j), _) => {
                relative = g.add(relative, coords[j].z);
                tree::JointKin::Revolute { coord: j }
            }
            (parse::Joint::Prismatic { .. }, Some(j), Some(axis)) => {
                for (l, a) in local.iter_mut().zip(axis) {
                    let d = g.mul(a, coords[j].z);
                    *l = g.add(*l, d);
                }
                tree::JointKin::Prismatic { coord: j, axis }
            }
            _ => tree::JointKin::Fixed,
        };
        let angle = g.add(p_angle, relative);
        let moved = tree::rotate(&mut g, p_angle, local);
        let mut origin = [g.add(p_origin[0], moved[0]), g.add(p_origin[1], moved[1])];
        free_joint(&mut g, &mut origin, tb, &coords);
        let arm = tree::rotate(&mut g, angle, com);
        let com_world = [g.add(origin[0], arm[0]), g.add(origin[1], arm[1])];
        let z = g.zero();
        let rigid = !g.is_zero(inertia);
        bodies.push(BodyKin {
            mass,
            inertia: rigid.then_some([[inertia, z, z], [z, z, z], [z, z, z]]),
            r: com_world.to_vec(),
            angle: rigid.then_some(angle),
            rot: None,
            origin: origin.to_vec(),
            frame_angle: Some(angle),
            frame_rot: None,
            frame_omega: None,
        });
        declare(
            &mut names,
            &mut errors,
            &tb.name,
            Binding::Body(bodies.len() - 1),
        );
        node_of.insert(tb.name.to_string(), nodes.len());
        nodes.push(tree::Node {
            parent,
            joint,
            at: local,
            relative,
            com,
            origin,
            angle,
            mass,
            inertia,
        });
    }
    // Spatial joint trees: composed the same way with rotation matrices; each joint also
    // becomes one-degree-of-freedom steps for the recursions (`spatial`).
    let mut frames: Vec<Frame> = Vec::new();
    let mut frame_of: HashMap<String, usize> = HashMap::new();
    // The spatial recursion's frames, and the one of each body (its joint's last step).
    let mut steps: Vec<spatial::Node> = Vec::new();
    let mut step_of_frame: Vec<usize> = Vec::new();
    for tb in ast.tree.iter().filter(|_| dim == Dim::Spatial) {
        if let Some(e) = &tb.angle {
            errors.over(
                e,
                "`angle` is planar: a spatial tree body's orientation comes from its joints",
            );
        }
        let Ok(parent) = tree_parent(tb, &frame_of, &mut errors) else {
            continue;
        };
        let z: Vec<(Expr, Expr)> = tb
            .joint
            .coords()
            .iter()
            .filter_map(|c| coords.iter().find(|k| k.name == **c).map(|k| (k.z, k.zd)))
            .collect();
        let mut lw = Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        };
        let (at, com) = (
            tree_vector(&mut lw, &tb.at, 3),
            tree_vector(&mut lw, &tb.com, 3),
        );
        let mass = tree_mass(&mut lw, tb);
        let inertia = match &tb.inertia {
            Some(e) => match lw.lower(e, Context::Constant) {
                Some(Value::Matrix(m)) => Some(Some(m)),
                Some(_) => {
                    lw.errors
                        .over(e, "a spatial inertia is `diag(a, b, c)` or a 3x3 matrix");
                    None
                }
                None => None,
            },
            None => Some(None),
        };
        let prismatic_axis = match &tb.joint {
            parse::Joint::Prismatic { axis, .. } => lw.vector(axis, Context::Constant, 3),
            _ => Some(Vec::new()),
        };
        let (Some(mut at), Some(com), Some(mass), Some(inertia), Some(axis)) =
            (at, com, mass, inertia, prismatic_axis)
        else {
            continue;
        };
        let (o, zero) = (g.one(), g.zero());
        let identity = [[o, zero, zero], [zero, o, zero], [zero, zero, o]];
        // The joint as elementary rotations `R_1(q_1) R_2(q_2) ..` (axis 0/1/2 for x/y/z,
        // angle, rate).
        let turns: Vec<(usize, Expr, Expr)> = match (&tb.joint, z.as_slice()) {
            (parse::Joint::Revolute { axis: None, .. }, _) => {
                errors.at(
                    tb.joint_span,
                    "a spatial revolute joint names its axis: `revolute(q, x | y | z)` (`chain` is planar)",
                );
                continue;
            }
            (parse::Joint::Revolute { axis: Some(a), .. }, &[q]) => {
                let axis = ["x", "y", "z"]
                    .iter()
                    .position(|n| a == n)
                    .expect("parse admits x, y, z");
                vec![(axis, q.0, q.1)]
            }
            (parse::Joint::Universal(..), &[a, b]) => vec![(0, a.0, a.1), (1, b.0, b.1)],
            (parse::Joint::Spherical(..), &[a, b, c]) => {
                vec![(2, a.0, a.1), (1, b.0, b.1), (0, c.0, c.1)]
            }
            (parse::Joint::Prismatic { .. }, &[s]) => {
                for (l, a) in at.iter_mut().zip(&axis) {
                    let d = g.mul(*a, s.0);
                    *l = g.add(*l, d);
                }
                Vec::new()
            }
            _ => Vec::new(),
        };
        // R_joint, and the joint's angular velocity in the child's frame,
        // sum_i (R_{i+1} .. R_k)^T e_i q_i' (built from the last rotation back).
        let mut relative = identity;
        let mut omega_joint = [zero; 3];
        for &(e, angle, rate) in turns.iter().rev() {
            for (k, w) in omega_joint.iter_mut().enumerate() {
                // (P^T e)_k = P[e][k] for P = R_{i+1} .. R_k.
                let term = g.mul(relative[e][k], rate);
                *w = g.add(*w, term);
            }
            let r = lower::rotation(&mut g, ["rot_x", "rot_y", "rot_z"][e], angle);
            relative = lower::matmul(&mut g, &r, &relative);
        }
        let parent_frame = parent;
        let parent = match parent {
            Some(p) => frames[p],
            None => Frame {
                origin: [zero; 3],
                rot: identity,
                omega: [zero; 3],
            },
        };
        // omega = R_joint^T omega_parent + omega_joint, in the body's frame: O(1) per body
        // over its parent's, where vee(R^T R') would differentiate the whole product.
        let omega: [Expr; 3] = std::array::from_fn(|k| {
            let col = [relative[0][k], relative[1][k], relative[2][k]];
            let carried = g.dot(&col, &parent.omega);
            g.add(carried, omega_joint[k])
        });
        let rot = lower::matmul(&mut g, &parent.rot, &relative);
        let mut origin: [Expr; 3] = std::array::from_fn(|i| {
            let moved = g.dot(&parent.rot[i], &at);
            g.add(parent.origin[i], moved)
        });
        free_joint(&mut g, &mut origin, tb, &coords);
        let r: Vec<Expr> = (0..3)
            .map(|i| {
                let arm = g.dot(&rot[i], &com);
                g.add(origin[i], arm)
            })
            .collect();
        bodies.push(BodyKin {
            mass,
            rot: inertia.is_some().then_some(rot),
            inertia,
            r,
            angle: None,
            origin: origin.to_vec(),
            frame_angle: None,
            frame_rot: Some(rot),
            frame_omega: Some(omega),
        });
        declare(
            &mut names,
            &mut errors,
            &tb.name,
            Binding::Body(bodies.len() - 1),
        );
        let coord_of: Vec<usize> = tb
            .joint
            .coords()
            .iter()
            .filter_map(|c| coords.iter().position(|k| k.name == **c))
            .collect();
        let joint_steps: Vec<(spatial::Step, Option<(usize, Expr)>)> =
            match (&tb.joint, coord_of.as_slice()) {
                (parse::Joint::Prismatic { .. }, &[coord]) if axis.len() == 3 => {
                    vec![(
                        spatial::Step::Prismatic {
                            coord,
                            axis: [axis[0], axis[1], axis[2]],
                        },
                        None,
                    )]
                }
                _ if turns.len() == coord_of.len() && !turns.is_empty() => turns
                    .iter()
                    .zip(&coord_of)
                    .map(|(&(axis, angle, _), &coord)| {
                        (spatial::Step::Revolute { coord, axis }, Some((axis, angle)))
                    })
                    .collect(),
                _ => vec![(spatial::Step::Fixed, None)],
            };
        let mut step_parent = parent_frame.map(|p| step_of_frame[p]);
        let last = joint_steps.len() - 1;
        for (k, (step, turn)) in joint_steps.into_iter().enumerate() {
            let body = k == last;
            steps.push(spatial::Node {
                parent: step_parent,
                step,
                turn,
                at: if k == 0 {
                    std::array::from_fn(|i| at[i])
                } else {
                    [zero; 3]
                },
                com: if body {
                    std::array::from_fn(|i| com[i])
                } else {
                    [zero; 3]
                },
                mass: if body { mass } else { zero },
                inertia: match inertia {
                    Some(i) if body => i,
                    _ => [[zero; 3]; 3],
                },
            });
            step_parent = Some(steps.len() - 1);
        }
        step_of_frame.push(steps.len() - 1);
        frame_of.insert(tb.name.to_string(), frames.len());
        frames.push(Frame { origin, rot, omega });
    }
    // Springs and dampers are named too; their names must not clash with anything else.
    let mut element_names = std::collections::HashSet::new();
    for id in ast
        .springs
        .iter()
        .map(|s| &s.name)
        .chain(ast.dampers.iter().map(|d| &d.name))
    {
        if names.contains_key(&id.to_string()) || !element_names.insert(id.to_string()) {
            errors.at(id.span(), format!("duplicate name `{id}`"));
        }
    }
    errors.finish()?;
    let mut errors = Errors::default();
    let mut checks = body_checks(&names, &bodies);

    let mut reactions: Vec<(usize, Expr)> = Vec::new();
    let zero = g.zero();

    // Constraints (full coordinates).
    let mut phi_full = Vec::new();
    let mut phi_spans = Vec::new();
    let mut phi_tokens = Vec::new();
    for c in &ast.constraints {
        let mut lw = Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        };
        if let (Some(l), Some(r)) = (
            lw.scalar(&c.lhs, Context::Kinematics),
            lw.scalar(&c.rhs, Context::Kinematics),
        ) {
            phi_full.push(g.sub(l, r));
            phi_spans.push(c.span);
            phi_tokens.push(&c.tokens);
        }
    }
    // Loop-closing joints: two coincident points; two equations (planar: a revolute joint),
    // three (spatial: a spherical joint).
    let point = |g: &mut Graph,
                 errors: &mut Errors,
                 body: &Option<Ident>,
                 at: &Option<syn::Expr>|
     -> Option<Vec<Expr>> {
        let local = match at {
            Some(e) => Lowerer {
                g,
                names: &names,
                struct_name: &struct_name,
                model: None,
                errors,
            }
            .vector(e, Context::Constant, dim.len())?,
            None => vec![g.zero(); dim.len()],
        };
        let unknown = |errors: &mut Errors, b: &Ident| {
            errors.at(
                b.span(),
                format!(
                    "unknown tree body `{b}`: a closure joins `body`/`chain` bodies or `ground`"
                ),
            );
        };
        match (body, dim) {
            (None, _) => Some(local),
            (Some(b), Dim::Planar) => {
                let Some(&i) = node_of.get(&b.to_string()) else {
                    unknown(errors, b);
                    return None;
                };
                let arm = tree::rotate(g, nodes[i].angle, [local[0], local[1]]);
                let origin = nodes[i].origin;
                Some(vec![g.add(origin[0], arm[0]), g.add(origin[1], arm[1])])
            }
            (Some(b), Dim::Spatial) => {
                let Some(&i) = frame_of.get(&b.to_string()) else {
                    unknown(errors, b);
                    return None;
                };
                let Frame { origin, rot, .. } = frames[i];
                Some(
                    (0..3)
                        .map(|k| {
                            let arm = g.dot(&rot[k], &local);
                            g.add(origin[k], arm)
                        })
                        .collect(),
                )
            }
        }
    };
    for cl in &ast.closures {
        let pa = point(&mut g, &mut errors, &cl.a, &cl.at_a);
        let pb = point(&mut g, &mut errors, &cl.b, &cl.at_b);
        if let (Some(pa), Some(pb)) = (pa, pb) {
            for (a, b) in pa.into_iter().zip(pb) {
                phi_full.push(g.sub(a, b));
                phi_spans.push(cl.name.span());
                phi_tokens.push(&cl.tokens);
            }
        }
    }

    // Minimal coordinates where the closure has a closed form (closure.rs).
    let loops = LoopParts {
        phi: &mut phi_full,
        spans: &mut phi_spans,
        tokens: &mut phi_tokens,
    };
    let closure_domain = minimal_coordinates(
        ast,
        &mut g,
        &mut coords,
        &mut roles,
        &mut names,
        &mut bodies,
        loops,
        t,
        &mut errors,
    );

    // Generalised forces (full coordinates) and potential energy.
    let nz = coords.len();
    let mut q_full = vec![zero; nz];
    let mut potential = zero;
    // Gravity enters the forces directly; its potential only the energy.
    let mut gravity_energy = zero;
    let mut kin = Kin {
        coords: &coords,
        bodies: &bodies,
        t,
        dim,
        reactions: &mut reactions,
    };
    let zsyms: Vec<Sym> = coords
        .iter()
        .map(|c| g.as_sym(c.z).expect("symbol"))
        .collect();
    let zdsyms: Vec<Sym> = coords
        .iter()
        .map(|c| g.as_sym(c.zd).expect("symbol"))
        .collect();
    let add_force_at = |g: &mut Graph, q_full: &mut Vec<Expr>, at: &[Expr], force: &[Expr]| {
        // Virtual work F . dr/dz_j.
        for (j, zs) in zsyms.iter().enumerate() {
            let col: Vec<Expr> = at.iter().map(|x| g.diff(*x, *zs)).collect();
            let w = g.dot(force, &col);
            q_full[j] = g.add(q_full[j], w);
        }
    };
    let gravity = match &ast.gravity {
        Some(e) => Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        }
        .vector(e, Context::Constant, dim.len()),
        None => None,
    };
    let end_position = |g: &mut Graph, errors: &mut Errors, end: &End| -> Option<Vec<Expr>> {
        match end {
            End::Named(id) => match names.get(&id.to_string()) {
                Some(Binding::Value(Value::Vector(v))) => Some(v.clone()),
                Some(Binding::Body(b)) => Some(bodies[*b].r.clone()),
                _ => {
                    errors.at(id.span(), format!("unknown point or body `{id}`"));
                    None
                }
            },
            End::At(e) => Lowerer {
                g,
                names: &names,
                struct_name: &struct_name,
                model: None,
                errors,
            }
            .vector(e, Context::Kinematics, dim.len()),
        }
    };
    let length = |g: &mut Graph, a: &[Expr], b: &[Expr]| {
        let d: Vec<Expr> = a.iter().zip(b).map(|(x, y)| g.sub(*y, *x)).collect();
        let s = g.dot(&d, &d);
        g.call(Func::Sqrt, s)
    };
    for s in &ast.springs {
        let (a, b) = (
            end_position(&mut g, &mut errors, &s.from),
            end_position(&mut g, &mut errors, &s.to),
        );
        let mut lw = Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        };
        let k = lw.scalar(&s.k, Context::Constant);
        let l0 = match &s.length {
            Some(e) => lw.scalar(e, Context::Constant),
            None => Some(lw.g.zero()),
        };
        if let (Some(a), Some(b), Some(k), Some(l0)) = (a, b, k, l0) {
            checks.push(check(
                format!("the stiffness of spring `{}`", s.name),
                k,
                false,
            ));
            checks.push(check(
                format!("the length of spring `{}`", s.name),
                l0,
                false,
            ));
            let l = length(&mut g, &a, &b);
            let stretch = g.sub(l, l0);
            let s2 = g.powi(stretch, 2);
            let half = g_half(&mut g);
            let half_k = g.mul(half, k);
            let v = g.mul(half_k, s2);
            potential = g.add(potential, v);
        }
    }
    for p in &ast.potentials {
        if let Some(v) = (Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        })
        .scalar(p, Context::Kinematics)
        {
            potential = g.add(potential, v);
        }
    }
    for (j, zs) in zsyms.iter().enumerate() {
        let dv = g.diff(potential, *zs);
        q_full[j] = g.sub(q_full[j], dv);
    }
    for d in &ast.dampers {
        let (a, b) = (
            end_position(&mut g, &mut errors, &d.from),
            end_position(&mut g, &mut errors, &d.to),
        );
        let c = (Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        })
        .scalar(&d.c, Context::Constant);
        if let (Some(a), Some(b), Some(c)) = (a, b, c) {
            checks.push(check(format!("the damping of `{}`", d.name), c, false));
            // Rayleigh dissipation D = c ldot^2 / 2; Q_j = -dD/dzd_j = -c ldot dldot/dzd_j.
            let l = length(&mut g, &a, &b);
            let ldot = kin.tder(&mut g, l);
            let cl = g.mul(c, ldot);
            for (j, zds) in zdsyms.iter().enumerate() {
                let dl = g.diff(ldot, *zds);
                let w = g.mul(cl, dl);
                q_full[j] = g.sub(q_full[j], w);
            }
        }
    }
    for load in &ast.loads {
        match load {
            Load::Force { at, value } => {
                let mut lw = Lowerer {
                    g: &mut g,
                    names: &names,
                    struct_name: &struct_name,
                    model: Some(&mut kin),
                    errors: &mut errors,
                };
                let at = lw.vector(at, Context::Kinematics, dim.len());
                let f = lw.vector(value, Context::Force, dim.len());
                if let (Some(at), Some(f)) = (at, f) {
                    add_force_at(&mut g, &mut q_full, &at, &f);
                }
            }
            Load::Torque { body, value } => {
                let Some(Binding::Body(bi)) = names.get(&body.to_string()) else {
                    errors.at(body.span(), format!("unknown body `{body}`"));
                    continue;
                };
                let b = &bodies[*bi];
                let mut lw = Lowerer {
                    g: &mut g,
                    names: &names,
                    struct_name: &struct_name,
                    model: Some(&mut kin),
                    errors: &mut errors,
                };
                match (b.angle, b.rot) {
                    (Some(phi), _) => {
                        if let Some(tau) = lw.scalar(value, Context::Force) {
                            for (j, zs) in zsyms.iter().enumerate() {
                                let d = g.diff(phi, *zs);
                                let w = g.mul(tau, d);
                                q_full[j] = g.add(q_full[j], w);
                            }
                        }
                    }
                    (None, Some(rot)) => {
                        if let Some(tau) = lw.vector(value, Context::Force, 3) {
                            // World torque . d(w_world)/dzd_j.
                            let w_b = kin.omega_body(&mut g, b);
                            let w: Vec<Expr> = (0..3).map(|i| g.dot(&rot[i], &w_b)).collect();
                            for (j, zds) in zdsyms.iter().enumerate() {
                                let col: Vec<Expr> = w.iter().map(|x| g.diff(*x, *zds)).collect();
                                let p = g.dot(&tau, &col);
                                q_full[j] = g.add(q_full[j], p);
                            }
                        }
                    }
                    _ => errors.at(
                        body.span(),
                        format!("`{body}` is a particle: a torque needs a rigid body"),
                    ),
                }
            }
            Load::Generalized { coord, value } => {
                let Some(j) = coords.iter().position(|c| c.name == *coord) else {
                    errors.at(coord.span(), format!("unknown coordinate `{coord}`"));
                    continue;
                };
                if let Some(v) = (Lowerer {
                    g: &mut g,
                    names: &names,
                    struct_name: &struct_name,
                    model: Some(&mut kin),
                    errors: &mut errors,
                })
                .scalar(value, Context::Force)
                {
                    // Along a dependent coordinate `x = h(q)`: virtual work `v dh/dq_k`.
                    if let CoordKind::Dependent([h, ..]) = coords[j].kind {
                        for (k, zs) in zsyms.iter().enumerate() {
                            let d = g.diff(h, *zs);
                            let w = g.mul(v, d);
                            q_full[k] = g.add(q_full[k], w);
                        }
                    } else {
                        q_full[j] = g.add(q_full[j], v);
                    }
                }
            }
        }
    }

    // Applied forces other than gravity: the joint efforts of the recursive evaluation.
    let q_applied = q_full.clone();
    if let Some(grav) = &gravity {
        for b in &bodies {
            let w: Vec<Expr> = grav.iter().map(|gc| g.mul(b.mass, *gc)).collect();
            add_force_at(&mut g, &mut q_full, &b.r, &w);
            let h = g.dot(&w, &b.r);
            gravity_energy = g.sub(gravity_energy, h);
        }
    }

    // The articulated-body recursion, for a pure joint tree when it pays or is asked for.
    let eligible = !(nodes.is_empty() && steps.is_empty())
        && ast.bodies.is_empty()
        && phi_full.is_empty()
        && closure_domain.is_none()
        && ast.frictions.is_empty();
    let recursive = match ast.evaluation {
        parse::Evaluation::MassMatrix => false,
        parse::Evaluation::Recursive if !eligible => {
            errors.at(ast.evaluation_span, "`recursive` evaluation needs a joint tree (`body`, `chain`) without constraints, friction or free-standing `particle`/`rigid` bodies");
            false
        }
        parse::Evaluation::Recursive => true,
        parse::Evaluation::Auto => eligible && nodes.len() + frames.len() >= RECURSIVE_FROM_BODIES,
    };
    // A pure joint tree's M, f and kinetic energy by recursion (composite rigid bodies,
    // Newton-Euler: O(n^2) and O(n) terms), when every coordinate is a joint's; Kane's
    // projections otherwise (O(n^3) for a chain).
    let velocity: Vec<Expr> = coords.iter().map(|c| c.zd).collect();
    let prescribed: Vec<Option<Expr>> = coords
        .iter()
        .map(|c| (!matches!(c.kind, CoordKind::Free)).then_some(c.zdd))
        .collect();
    let frames3 = match dim {
        Dim::Planar => spatial::from_planar(&mut g, &nodes),
        Dim::Spatial => std::mem::take(&mut steps),
    };
    let by_recursion = (recursive && spatial::covers(&frames3, nz)).then(|| {
        let inputs = spatial::Inputs {
            velocity: &velocity,
            prescribed: &prescribed,
            tau: &q_applied,
            gravity: match &gravity {
                Some(v) => std::array::from_fn(|i| v.get(i).copied().unwrap_or(zero)),
                None => [zero; 3],
            },
        };
        spatial::mass_and_forces(&mut g, &frames3, &inputs)
    });
    let m_by_recursion = by_recursion.is_some();
    let steps = frames3;

    // Kane's projection: M_jk = sum m J_j . J_k + Jw_j^T I Jw_k;
    // f_j = Q_j - sum J_j . m a0 - Jw_j^T (I alpha0 + w x I w).
    let mut m_full = vec![vec![zero; nz]; nz];
    let applied_full = q_full.clone();
    let mut f_full = q_full;
    let mut kinetic = zero;
    let kane = by_recursion.is_none();
    if let Some(rec) = by_recursion {
        m_full = rec.mass;
        f_full = rec.forces;
        kinetic = rec.twice_kinetic;
    }
    for b in bodies.iter().filter(|_| kane) {
        let v: Vec<Expr> = b.r.iter().map(|x| kin.tder(&mut g, *x)).collect();
        let jac: Vec<Vec<Expr>> = zdsyms
            .iter()
            .map(|s| v.iter().map(|x| g.diff(*x, *s)).collect())
            .collect();
        let a0: Vec<Expr> = v.iter().map(|x| drop_qdd(&mut g, &kin, *x)).collect();
        let vv = g.dot(&v, &v);
        let mv = g.mul(b.mass, vv);
        kinetic = g.add(kinetic, mv);
        for j in 0..nz {
            if jac[j].iter().all(|x| g.is_zero(*x)) {
                continue;
            }
            for k in j..nz {
                let d = g.dot(&jac[j], &jac[k]);
                let md = g.mul(b.mass, d);
                m_full[j][k] = g.add(m_full[j][k], md);
            }
            let d = g.dot(&jac[j], &a0);
            let md = g.mul(b.mass, d);
            f_full[j] = g.sub(f_full[j], md);
        }
        // Rotation: planar scalar, or spatial body-frame vector.
        let (w, inertia): (Vec<Expr>, [[Expr; 3]; 3]) = match (b.angle, b.rot, b.inertia) {
            (Some(phi), _, Some(i)) => {
                let z = g.zero();
                let w = kin.tder(&mut g, phi);
                (vec![w], [[i[0][0], z, z], [z, z, z], [z, z, z]])
            }
            (None, Some(_), Some(i)) => (kin.omega_body(&mut g, b), i),
            _ => continue,
        };
        let nw = w.len();
        let iw: Vec<Expr> = (0..nw).map(|r| g.dot(&inertia[r][..nw], &w)).collect();
        let wiw = g.dot(&w, &iw);
        kinetic = g.add(kinetic, wiw);
        let jw: Vec<Vec<Expr>> = zdsyms
            .iter()
            .map(|s| w.iter().map(|x| g.diff(*x, *s)).collect())
            .collect();
        let alpha0: Vec<Expr> = w.iter().map(|x| drop_qdd(&mut g, &kin, *x)).collect();
        let mut inertial: Vec<Expr> = (0..nw).map(|r| g.dot(&inertia[r][..nw], &alpha0)).collect();
        if nw == 3 {
            let gyro = lower::cross(&mut g, &w, &iw);
            for r in 0..3 {
                inertial[r] = g.add(inertial[r], gyro[r]);
            }
        }
        for j in 0..nz {
            if jw[j].iter().all(|x| g.is_zero(*x)) {
                continue;
            }
            let ij: Vec<Expr> = (0..nw).map(|r| g.dot(&inertia[r][..nw], &jw[j])).collect();
            for k in j..nz {
                let d = g.dot(&ij, &jw[k]);
                m_full[j][k] = g.add(m_full[j][k], d);
            }
            let d = g.dot(&jw[j], &inertial);
            f_full[j] = g.sub(f_full[j], d);
        }
    }
    // Symmetric: fill the lower triangle from the upper one.
    for j in 1..nz {
        let (upper, lower) = m_full.split_at_mut(j);
        for (k, row) in upper.iter().enumerate() {
            lower[0][k] = row[j];
        }
    }
    // Lagrange's form of the same forces, taken instead of Kane's when it is shorter.
    let time = g.as_sym(t).expect("symbol");
    let scleronomic = bodies.iter().all(|b| {
        let rot = b.rot.iter().flatten().flatten();
        b.r.iter()
            .chain(&b.angle)
            .chain(rot)
            .all(|&e| !g.depends_on(e, time))
    });
    match form {
        InertialForm::Shorter if kane && scleronomic && nz <= LAGRANGE_MAX_COORDINATES => {
            let lagrange = lagrange_forces(&mut g, &m_full, &applied_full, &zsyms, &coords);
            let cost = |g: &Graph, f: &[Expr]| {
                let roots: Vec<Expr> = m_full.iter().flatten().chain(f).copied().collect();
                schedule(g, &roots).len()
            };
            if cost(&g, &lagrange) < cost(&g, &f_full) {
                f_full = lagrange;
            }
        }
        #[cfg(test)]
        InertialForm::Lagrange => {
            assert!(scleronomic, "Lagrange's form needs time-free kinematics");
            f_full = lagrange_forces(&mut g, &m_full, &applied_full, &zsyms, &coords);
        }
        _ => {}
    }
    let half = g_half(&mut g);
    let kinetic = g.mul(half, kinetic);
    let potential_all = g.add(potential, gravity_energy);
    let energy_full = g.add(kinetic, potential_all);

    let mut rolled: Option<tree::Rolled> = None;
    let qdd_recursive: Vec<Option<Expr>> = if recursive {
        if dim == Dim::Spatial {
            let inputs = spatial::Inputs {
                velocity: &velocity,
                prescribed: &prescribed,
                tau: &q_applied,
                gravity: match &gravity {
                    Some(v) => [v[0], v[1], v[2]],
                    None => [zero; 3],
                },
            };
            spatial::articulated_body(&mut g, &steps, &inputs)
        } else {
            let gravity = match &gravity {
                Some(v) => [v[0], v[1]],
                None => [zero, zero],
            };
            let inputs = tree::Inputs {
                velocity: &velocity,
                prescribed: &prescribed,
                tau: &q_applied,
                gravity,
            };
            match tree::rolled(&mut g, &nodes, &inputs) {
                Some(r) => {
                    let qdd = r.qdd.clone();
                    rolled = Some(r);
                    qdd
                }
                None => tree::articulated_body(&mut g, &nodes, &inputs),
            }
        }
    } else {
        Vec::new()
    };

    // Reduction: driven -> s(t), relaxed -> 0.
    let ts = g.as_sym(t).expect("symbol");
    let mut reduce: HashMap<Sym, Expr> = HashMap::new();
    for c in &coords {
        let (z, zd, zdd, zddd) = match &c.kind {
            CoordKind::Free => continue,
            CoordKind::Driven(law) => {
                let d1 = g.diff(*law, ts);
                let d2 = g.diff(d1, ts);
                let d3 = g.diff(d2, ts);
                (*law, d1, d2, d3)
            }
            CoordKind::Relaxed => (zero, zero, zero, zero),
            CoordKind::Dependent([h, hd, hdd]) => (*h, *hd, *hdd, zero),
        };
        for (s, v) in [(c.z, z), (c.zd, zd), (c.zdd, zdd), (c.zddd, zddd)] {
            reduce.insert(g.as_sym(s).expect("symbol"), v);
        }
    }
    let free_idx: Vec<usize> = coords
        .iter()
        .enumerate()
        .filter(|(_, c)| matches!(c.kind, CoordKind::Free))
        .map(|(i, _)| i)
        .collect();
    let n = free_idx.len();
    // Reduce everything in one pass over the shared graph (one rebuild, not one per entry).
    let mut full_rows = Vec::with_capacity(n * n + n + 1 + phi_full.len());
    for &i in &free_idx {
        full_rows.extend(free_idx.iter().map(|&j| m_full[i][j]));
    }
    for &i in &free_idx {
        // Move the driven coordinates' known accelerations to the right side.
        let mut fi = f_full[i];
        for (j, c) in coords.iter().enumerate() {
            if let CoordKind::Driven(_) = c.kind {
                let mz = g.mul(m_full[i][j], c.zdd);
                fi = g.sub(fi, mz);
            }
        }
        full_rows.push(fi);
    }
    full_rows.push(energy_full);
    full_rows.extend(&phi_full);
    let n_rows = full_rows.len();
    if recursive {
        // Every free coordinate is a joint's (a pure tree): the recursion gives each one.
        full_rows.extend(free_idx.iter().map(|&i| qdd_recursive[i].unwrap_or(zero)));
    }
    // A rolled chain's expressions around its loops (the carried values' starts) are in
    // full coordinates too.
    let run_inits: Vec<Expr> = rolled
        .iter()
        .flat_map(|r| r.loops.iter())
        .flat_map(|l| l.carried.iter().map(|c| c.1))
        .collect();
    let n_rows_recursive = full_rows.len();
    full_rows.extend(&run_inits);
    // A long tree's mass matrix as `M qdd` (free coordinates' accelerations; driven ones at
    // rest), formed column by column at run time: O(n) code instead of O(n d) entries.
    let lazy_mass = m_by_recursion && !ast.jacobian && n >= LAZY_MASS_FROM;
    let n_rows_inits = full_rows.len();
    if lazy_mass {
        let accel: Vec<Expr> = coords
            .iter()
            .map(|c| match c.kind {
                CoordKind::Free => c.zdd,
                _ => zero,
            })
            .collect();
        let rows = spatial::mass_times(&mut g, &steps, &accel);
        full_rows.extend(free_idx.iter().map(|&i| rows[i]));
    }
    let mut reduced = g.substitute_all(&full_rows, &reduce);
    let mass_times = lazy_mass.then(|| reduced.split_off(n_rows_inits));
    let reduced_inits = reduced.split_off(n_rows_recursive);
    let recursive_qdd = recursive.then(|| reduced.split_off(n_rows));
    let rolled = match rolled {
        Some(mut r) => {
            let mut inits = reduced_inits.into_iter();
            for l in &mut r.loops {
                for c in &mut l.carried {
                    c.1 = inits.next().expect("one reduced start per carried value");
                }
            }
            for (e, per_link) in r.placeholders() {
                roles.insert(g.as_sym(e).expect("symbol"), Role::RunLocal { per_link });
            }
            let first = free_idx.iter().position(|&i| i == r.first_coord);
            let consecutive = first.is_some_and(|f| {
                (0..r.len).all(|k| free_idx.get(f + k) == Some(&(r.first_coord + k)))
            });
            match (first, consecutive) {
                (Some(f), true) => Some((r, f)),
                _ => unreachable!("a rolled run's joints are free, consecutive coordinates"),
            }
        }
        None => None,
    };
    let mass: Vec<Vec<Expr>> = reduced[..n * n]
        .chunks(n.max(1))
        .take(n)
        .map(<[Expr]>::to_vec)
        .collect();
    let mut forces: Vec<Expr> = reduced[n * n..n * n + n].to_vec();
    let energy = reduced[n * n + n];
    let phi: Vec<Expr> = reduced[n * n + n + 1..].to_vec();

    // Constraints in free coordinates.
    let qsyms: Vec<Sym> = free_idx.iter().map(|&i| zsyms[i]).collect();
    let phi_q: Vec<Vec<Expr>> = phi
        .iter()
        .map(|p| qsyms.iter().map(|s| g.diff(*p, *s)).collect())
        .collect();
    let phi_t: Vec<Expr> = phi.iter().map(|p| g.diff(*p, ts)).collect();
    let qd: Vec<Expr> = free_idx.iter().map(|&i| coords[i].zd).collect();
    let qdd: Vec<Expr> = free_idx.iter().map(|&i| coords[i].zdd).collect();
    let mut gamma = Vec::new();
    for (k, row) in phi_q.iter().enumerate() {
        let phidot0 = g.dot(row, &qd);
        let phidot = g.add(phidot0, phi_t[k]);
        let mut terms: Vec<Expr> = qsyms
            .iter()
            .zip(&qd)
            .map(|(s, v)| {
                let d = g.diff(phidot, *s);
                g.mul(d, *v)
            })
            .collect();
        terms.push(g.diff(phidot, ts));
        let s = g.sum(terms);
        gamma.push(g.neg(s));
    }
    let m_con = phi.len();
    let lambdas: Vec<Expr> = (0..m_con)
        .map(|k| {
            let s = g.symbol(&format!("lambda:{k}"));
            roles.insert(g.as_sym(s).expect("symbol"), Role::Lambda(k));
            s
        })
        .collect();

    // Checks that need the equations.
    if m_con > n {
        for tokens in &phi_tokens[n..] {
            errors.over(tokens, format!("more constraints ({m_con}) than free coordinates ({n}): this one over-determines the mechanism"));
        }
    }
    for (k, how) in closure::constant_dependence(&mut g, &phi, &qsyms) {
        if m_con > n && k >= n {
            continue; // already an over-determining constraint
        }
        let why = match how {
            closure::Dependence::NoCoordinate => "the coordinate terms of this constraint cancel: it relates only parameters and `t`, so it cannot hold the mechanism".to_string(),
            closure::Dependence::Redundant => "this constraint repeats earlier ones (a combination of them with constant coefficients): the constraint Jacobian would be singular everywhere; remove it".to_string(),
            closure::Dependence::Contradictory(v) => format!("this constraint contradicts earlier ones: its coordinate part is a constant combination of theirs but its constant part differs by {v}"),
            closure::Dependence::Dependent => "this constraint's coordinate part is a constant combination of earlier constraints': it is redundant or contradicts them (depending on the parameters), and the constraint Jacobian would be singular everywhere".to_string(),
        };
        errors.over(phi_tokens[k], why);
    }
    for (k, p) in phi.iter().enumerate() {
        if !qsyms.iter().any(|s| g.depends_on(*p, *s)) {
            errors.over(phi_tokens[k], "this constraint involves no coordinate: it relates only parameters and `t`, so it cannot hold the mechanism");
        }
    }
    for (a, &i) in free_idx.iter().enumerate() {
        let in_constraint = phi.iter().any(|p| g.depends_on(*p, qsyms[a]));
        if g.is_zero(mass[a][a]) && !in_constraint {
            errors.at(
                coords[i].name.span(),
                format!("coordinate `{}` moves no mass and no constraint fixes it: the mass matrix would be singular", coords[i].name),
            );
        }
    }

    // Outputs and events, with reactions on request.
    let mut outputs = Vec::new();
    let mut events = Vec::new();
    let mut frictions = Vec::new();
    {
        let mut kin = Kin {
            coords: &coords,
            bodies: &bodies,
            t,
            dim,
            reactions: &mut reactions,
        };
        for o in &ast.outputs {
            let mut lw = Lowerer {
                g: &mut g,
                names: &names,
                struct_name: &struct_name,
                model: Some(&mut kin),
                errors: &mut errors,
            };
            if let Some(e) = lw.scalar(&o.expr, Context::Output) {
                outputs.push(OutputEq {
                    name: o.name.clone(),
                    expr: e,
                });
            }
        }
        for ev in &ast.events {
            let mut lw = Lowerer {
                g: &mut g,
                names: &names,
                struct_name: &struct_name,
                model: Some(&mut kin),
                errors: &mut errors,
            };
            if let Some(e) = lw.scalar(&ev.expr, Context::Output) {
                events.push(EventEq {
                    name: ev.name.clone(),
                    expr: e,
                    direction: ev.direction,
                    terminal: ev.terminal,
                });
            }
        }
        for f in &ast.frictions {
            let Some(a) = free_idx.iter().position(|&i| coords[i].name == f.along) else {
                errors.at(
                    f.along.span(),
                    format!(
                        "friction acts along a free coordinate; `{}` is not one",
                        f.along
                    ),
                );
                continue;
            };
            let mut lw = Lowerer {
                g: &mut g,
                names: &names,
                struct_name: &struct_name,
                model: Some(&mut kin),
                errors: &mut errors,
            };
            let mu = lw.scalar(&f.mu, Context::Constant);
            let mu_static = match &f.mu_static {
                Some(e) => lw.scalar(e, Context::Constant),
                None => mu,
            };
            let normal = lw.scalar(&f.normal, Context::Output);
            if frictions.iter().any(|e: &FrictionEq| e.coord == a) {
                errors.at(
                    f.along.span(),
                    format!("a second `friction` along `{}`: one contact per coordinate (its stuck rows would coincide)", f.along),
                );
                continue;
            }
            if let (Some(mu), Some(mu_static), Some(normal)) = (mu, mu_static, normal) {
                crate::friction::check_coefficients(&g, mu, mu_static, f, &mut errors);
                let what = format!("friction coefficient along `{}`", f.along);
                checks.push(check(format!("the {what}"), mu, false));
                checks.push(check(format!("the static {what}"), mu_static, false));
                frictions.push(FrictionEq {
                    coord: a,
                    mu,
                    mu_static,
                    normal,
                    span: f.span,
                });
            }
        }
    }
    // r_u = (M zdd - f + Phi_z^T lambda)_u, then reduced.
    let mut reaction_map: HashMap<Sym, Expr> = HashMap::new();
    for (u, placeholder) in &reactions {
        let zdd: Vec<Expr> = coords.iter().map(|c| c.zdd).collect();
        let ma = g.dot(&m_full[*u], &zdd);
        let mut r = g.sub(ma, f_full[*u]);
        for (k, p) in phi_full.iter().enumerate() {
            let d = g.diff(*p, zsyms[*u]);
            let dl = g.mul(d, lambdas[k]);
            r = g.add(r, dl);
        }
        reaction_map.insert(g.as_sym(*placeholder).expect("symbol"), r);
    }
    let finish = |g: &mut Graph, e: Expr| {
        let e = g.substitute(e, &reaction_map);
        g.substitute(e, &reduce)
    };
    for o in &mut outputs {
        o.expr = finish(&mut g, o.expr);
    }
    for e in &mut events {
        e.expr = finish(&mut g, e.expr);
    }
    // A third derivative of a free coordinate would need d(qdd)/dt of the solved dynamics:
    // refused rather than silently zero.
    let jerks: Vec<Sym> = free_idx
        .iter()
        .map(|&i| g.as_sym(coords[i].zddd).expect("symbol"))
        .collect();
    let named = outputs
        .iter()
        .map(|o| (&o.name, o.expr))
        .chain(events.iter().map(|e| (&e.name, e.expr)));
    for (name, e) in named {
        if jerks.iter().any(|j| g.depends_on(e, *j)) {
            errors.at(
                name.span(),
                format!("`{name}` needs the third time derivative of a free coordinate (`der` of an acceleration), which is not available"),
            );
        }
    }
    // Coulomb friction while sliding: Q_s = -mu |N| sign(qd_s). The normal force must not
    // depend on the accelerations it helps determine (checked), so the solve stays linear.
    let frictionless = (!frictions.is_empty()).then(|| forces.clone());
    for (k, f) in frictions.iter_mut().enumerate() {
        f.normal = finish(&mut g, f.normal);
        if let Some(normal) = crate::friction::explicit_normal(&mut g, &roles, f.normal) {
            f.normal = normal;
        } else {
            errors.at(
                f.span,
                "this normal force depends on the accelerations (the friction would make the equations implicit): not supported",
            );
            continue;
        }
        let abs_n = g.call(Func::Abs, f.normal);
        let sign = g.symbol(&format!("friction_direction:{k}"));
        roles.insert(g.as_sym(sign).expect("symbol"), Role::FrictionDirection(k));
        let mn = g.mul(f.mu, abs_n);
        let q = g.mul(mn, sign);
        forces[f.coord] = g.sub(forces[f.coord], q);
    }
    // One free coordinate without constraints: `qdd = f / m` with the factors the two share
    // cancelled and the parameters' quotient apart (`-m g l sin(theta) / (m l^2)` is
    // `(-g / l) sin(theta)`), as one writes it by hand; generated code checks `m` first.
    let single_qdd = (n == 1 && phi.is_empty() && recursive_qdd.is_none() && frictions.is_empty())
        .then(|| {
            let parameters_only =
                |g: &Graph, e: Expr| !uses_roles(g, &roles, e, |r| !matches!(r, Role::Param(_)));
            g.quotient_cancelled(forces[0], mass[0][0], parameters_only)
        });

    // Residual Jacobians for implicit methods.
    let jacobian = ast.jacobian.then(|| {
        let qdsyms: Vec<Sym> = qd.iter().map(|e| g.as_sym(*e).expect("symbol")).collect();
        let mut r = Vec::new();
        for a in 0..n {
            let ma = g.dot(&mass[a], &qdd);
            let mut ra = g.sub(ma, forces[a]);
            for k in 0..m_con {
                let pl = g.mul(phi_q[k][a], lambdas[k]);
                ra = g.add(ra, pl);
            }
            r.push(ra);
        }
        let c: Vec<Expr> = (0..m_con)
            .map(|k| {
                let pa = g.dot(&phi_q[k], &qdd);
                g.sub(pa, gamma[k])
            })
            .collect();
        let jac = |g: &mut Graph, rows: &[Expr], by: &[Sym]| -> Vec<Vec<Expr>> {
            rows.iter()
                .map(|e| by.iter().map(|s| g.diff(*e, *s)).collect())
                .collect()
        };
        ResidualJacobian {
            r_q: jac(&mut g, &r, &qsyms),
            r_qd: jac(&mut g, &r, &qdsyms),
            c_q: jac(&mut g, &c, &qsyms),
            c_qd: jac(&mut g, &c, &qdsyms),
        }
    });

    // Initial conditions.
    let mut init_q = vec![zero; n];
    let mut init_qd = vec![zero; n];
    for i in &ast.inits {
        // A dependent coordinate's initial state follows from the closure.
        let dependent = |c: &Coord| matches!(c.kind, CoordKind::Dependent(_));
        if coords.iter().any(|c| c.name == i.coord && dependent(c)) {
            continue;
        }
        let Some(a) = free_idx.iter().position(|&j| coords[j].name == i.coord) else {
            errors.at(
                i.coord.span(),
                format!("`{}` is not a free coordinate", i.coord),
            );
            continue;
        };
        if let Some(v) = (Lowerer {
            g: &mut g,
            names: &names,
            struct_name: &struct_name,
            model: None,
            errors: &mut errors,
        })
        .scalar(&i.value, Context::Constant)
        {
            if i.velocity {
                init_qd[a] = v
            } else {
                init_q[a] = v
            }
        }
    }
    // Folding constants can produce inf or NaN (`1.0 / 0.0`, `ln(-1.0)`, a derivative of
    // `sqrt` at a point where its argument vanishes): refuse them here, not at run time.
    {
        let mut roots: Vec<Expr> = mass
            .iter()
            .flatten()
            .chain(&forces)
            .chain(&phi)
            .chain(&phi_t)
            .chain(&gamma)
            .copied()
            .collect();
        roots.extend(phi_q.iter().flatten());
        roots.extend(
            outputs
                .iter()
                .map(|o| o.expr)
                .chain(events.iter().map(|e| e.expr)),
        );
        roots.extend(init_q.iter().chain(&init_qd));
        roots.push(energy);
        if let Some(j) = &jacobian {
            roots.extend(
                j.r_q
                    .iter()
                    .chain(&j.r_qd)
                    .chain(&j.c_q)
                    .chain(&j.c_qd)
                    .flatten(),
            );
        }
        if roots.iter().any(|e| g.has_nonfinite_constant(*e)) {
            errors.at(
                ast.ident.span(),
                "the model's equations contain a non-finite constant (a division by zero, the log or square root of a negative number, or the derivative of `sqrt` where its argument is zero)",
            );
        }
    }
    check_default_configuration(ast, &mut g, &phi, &phi_tokens, &init_q, &roles, &mut errors);
    errors.finish()?;

    let one = g.one();
    Ok(Equations {
        zero,
        one,
        free: free_idx.iter().map(|&i| coords[i].name.clone()).collect(),
        g,
        roles,
        mass,
        forces,
        energy,
        phi,
        phi_q,
        phi_t,
        gamma,
        jacobian,
        outputs,
        events,
        frictions,
        frictionless,
        recursive_qdd,
        mass_times,
        single_qdd,
        rolled,
        init_q,
        init_qd,
        closure_domain,
        checks,
    })
}

impl Equations {
    /// The constant 0 of this model's graph (already interned: every graph has it).
    pub fn g_zero(&self) -> Expr {
        self.zero
    }
    /// The constant 1 of this model's graph.
    pub fn g_one(&self) -> Expr {
        self.one
    }
}

/// The constraint equations of a model with their spans, as `minimal_coordinates` edits
/// them.
struct LoopParts<'a, 'b> {
    phi: &'a mut Vec<Expr>,
    spans: &'a mut Vec<Span>,
    tokens: &'a mut Vec<&'b proc_macro2::TokenStream>,
}

/// Minimal coordinates for a closed loop (see closure.rs): where the closure has a closed
/// form, each dependent coordinate becomes that form in the kinematics (bodies, points, the
/// coordinate's own name), its constraints are dropped and the rest of the derivation sees
/// an unconstrained model. Returns the run-time domain conditions, `None` when the model
/// keeps the augmented form (asked for, reactions or friction that need the multipliers,
/// no independent coordinate left, or no closed form).
#[allow(clippy::too_many_arguments)]
fn minimal_coordinates(
    ast: &Mechanism,
    g: &mut Graph,
    coords: &mut [Coord],
    roles: &mut HashMap<Sym, Role>,
    names: &mut Names,
    bodies: &mut [BodyKin],
    loops: LoopParts<'_, '_>,
    t: Expr,
    errors: &mut Errors,
) -> Option<Vec<closure::Domain>> {
    if loops.phi.is_empty() || ast.loop_form == parse::LoopForm::Augmented {
        return None;
    }
    let env = default_values(ast, g, coords, names);
    let free: Vec<closure::Unknown> = coords
        .iter()
        .enumerate()
        .filter(|(_, c)| matches!(c.kind, CoordKind::Free))
        .map(|(i, c)| closure::Unknown {
            index: i,
            sym: g.as_sym(c.z).expect("symbol"),
            name: c.name.to_string(),
            default: env.get(&g.as_sym(c.z).expect("symbol")).copied(),
        })
        .collect();
    let asks_reactions = ast.outputs.iter().any(|o| names_reaction(&o.expr))
        || ast.events.iter().any(|e| names_reaction(&e.expr));
    let why_not = if !ast.frictions.is_empty() {
        Some("friction keeps the augmented form (its normal force may need the multipliers)")
    } else if !ast.relaxed.is_empty() || asks_reactions {
        Some("reactions (`relaxed`, `reaction(..)`) need the multipliers of the augmented form")
    } else if free.len() <= loops.phi.len() {
        Some("no independent coordinate would remain (the constraints fix every free coordinate)")
    } else {
        None
    };
    let solution = match why_not {
        Some(_) => None,
        None => closure::solve(g, loops.phi, &free, &env),
    };
    let Some(solution) = solution else {
        if ast.loop_form == parse::LoopForm::Minimal {
            let why = why_not.unwrap_or("no closed form for the closure: the derive solves a constraint linear in one coordinate with a constant coefficient, an angle inside only `sin`/`cos` of itself, or a planar loop of two angles");
            errors.at(
                ast.loop_form_span,
                format!("`minimal` coordinates are not possible here: {why}"),
            );
        }
        return None;
    };
    check_closure_defaults(g, &loops, &env, ast, errors);
    // z -> h (sin z, cos z by the form's own), z' -> dh/dt, z'' -> d2h/dt2.
    let mut map: HashMap<Sym, Expr> = HashMap::new();
    let mut forms = Vec::new();
    let mut eliminations = Vec::new();
    {
        let mut none = Vec::new();
        let kin = Kin {
            coords,
            bodies,
            t,
            dim: ast.dim,
            reactions: &mut none,
        };
        for &(i, form) in &solution.solved {
            let h = form.value;
            eliminations.push((g.as_sym(coords[i].z).expect("symbol"), form));
            let hd = kin.tder(g, h);
            let hdd = kin.tder(g, hd);
            let c = &coords[i];
            for (s, v) in [(c.zd, hd), (c.zdd, hdd)] {
                map.insert(g.as_sym(s).expect("symbol"), v);
            }
            forms.push((i, [h, hd, hdd]));
        }
    }
    let mut dependent_names = Vec::new();
    for (i, form) in forms {
        coords[i].kind = CoordKind::Dependent(form);
        dependent_names.push((coords[i].name.to_string(), form[0]));
    }
    let mut memos: Vec<HashMap<Expr, Expr>> = vec![HashMap::new(); eliminations.len()];
    let mut close = |g: &mut Graph, e: Expr| {
        let mut e = g.substitute(e, &map);
        for ((x, form), memo) in eliminations.iter().zip(memos.iter_mut()) {
            e = closure::eliminate(g, e, *x, *form, memo);
        }
        e
    };
    for b in bodies.iter_mut() {
        let BodyKin {
            r,
            angle,
            rot,
            origin,
            frame_angle,
            frame_rot,
            frame_omega,
            ..
        } = b;
        let kinematics = r
            .iter_mut()
            .chain(angle.iter_mut())
            .chain(rot.iter_mut().flatten().flatten())
            .chain(origin.iter_mut())
            .chain(frame_angle.iter_mut())
            .chain(frame_rot.iter_mut().flatten().flatten())
            .chain(frame_omega.iter_mut().flatten());
        for e in kinematics {
            *e = close(g, *e);
        }
    }
    for binding in names.values_mut() {
        if let Binding::Value(v) = binding {
            *v = match v {
                Value::Scalar(e) => Value::Scalar(close(g, *e)),
                Value::Vector(v) => Value::Vector(v.iter().map(|&e| close(g, e)).collect()),
                Value::Matrix(m) => Value::Matrix(m.map(|row| row.map(|e| close(g, e)))),
            };
        }
    }
    for (name, h) in dependent_names {
        names.insert(name, Binding::Value(Value::Scalar(h)));
    }
    // The state is the independent coordinates, in the order of `coords`.
    let mut next = 0;
    for c in coords.iter() {
        let [z, zd, zdd] = [c.z, c.zd, c.zdd].map(|e| g.as_sym(e).expect("symbol"));
        match c.kind {
            CoordKind::Free => {
                roles.insert(z, Role::Q(next));
                roles.insert(zd, Role::Qd(next));
                roles.insert(zdd, Role::Qdd(next));
                next += 1;
            }
            CoordKind::Dependent(_) => {
                for s in [z, zd, zdd] {
                    roles.remove(&s);
                }
            }
            _ => {}
        }
    }
    loops.phi.clear();
    loops.spans.clear();
    loops.tokens.clear();
    Some(solution.domain)
}

/// Whether an output or event expression names `reaction`.
fn names_reaction(e: &syn::Expr) -> bool {
    fn walk(ts: proc_macro2::TokenStream) -> bool {
        ts.into_iter().any(|tt| match tt {
            proc_macro2::TokenTree::Ident(i) => i == "reaction",
            proc_macro2::TokenTree::Group(gr) => walk(gr.stream()),
            _ => false,
        })
    }
    walk(quote::ToTokens::to_token_stream(e))
}

/// Values of the default configuration: parameter `#[default]`s, `init` positions (with
/// those defaults) and driven coordinates at `t = 0`; a parameter without a default leaves
/// only the constant `init` positions.
fn default_values(
    ast: &Mechanism,
    g: &mut Graph,
    coords: &[Coord],
    names: &Names,
) -> HashMap<Sym, f64> {
    let mut env: HashMap<Sym, f64> = HashMap::new();
    let mut scratch = Errors::default();
    let no_names = HashMap::new();
    for p in &ast.params {
        let Some(d) = &p.default else { continue };
        let e = Lowerer {
            g,
            names: &no_names,
            struct_name: "",
            model: None,
            errors: &mut scratch,
        }
        .scalar(d, Context::Constant);
        if let Some(v) = e.and_then(|e| g.as_const(e)) {
            let s = g.symbol(&p.name.to_string());
            env.insert(g.as_sym(s).expect("symbol"), v);
        }
    }
    let time = g.symbol("t");
    if let Some(s) = g.as_sym(time) {
        env.insert(s, 0.0);
    }
    let mut values = Vec::new();
    for c in coords {
        let value = match &c.kind {
            CoordKind::Driven(law) => Some(*law),
            _ => ast
                .inits
                .iter()
                .find(|i| !i.velocity && i.coord == c.name)
                .and_then(|i| {
                    Lowerer {
                        g,
                        names,
                        struct_name: "",
                        model: None,
                        errors: &mut scratch,
                    }
                    .scalar(&i.value, Context::Constant)
                }),
        };
        if let Some(e) = value {
            let v = g.eval(e, &|s| env.get(&s).copied().unwrap_or(f64::NAN));
            if v.is_finite() {
                values.push((g.as_sym(c.z).expect("symbol"), v));
            }
        }
    }
    env.extend(values);
    env
}

/// The closure's equations at the default configuration, when it is complete (as
/// `check_default_configuration` does for the augmented form).
fn check_closure_defaults(
    g: &Graph,
    loops: &LoopParts<'_, '_>,
    env: &HashMap<Sym, f64>,
    ast: &Mechanism,
    errors: &mut Errors,
) {
    let positioned = |c: &Ident| ast.inits.iter().any(|i| !i.velocity && i.coord == *c);
    if ast.params.iter().any(|p| p.default.is_none()) || !ast.coords.iter().all(positioned) {
        return;
    }
    for (k, p) in loops.phi.iter().enumerate() {
        let r = g.eval(*p, &|s| env.get(&s).copied().unwrap_or(f64::NAN));
        if r.is_finite() && r.abs() > 1e-9 {
            errors.over(
                loops.tokens[k],
                format!("the default configuration (parameter defaults and `init` positions at t = 0) violates this constraint: residual {r:.3e}"),
            );
        }
    }
}

fn g_half(g: &mut Graph) -> Expr {
    g.constant(0.5)
}

/// A tree body's parent (`None`: the ground) among the bodies declared before it, or a
/// spanned error.
fn tree_parent(
    tb: &parse::TreeBody,
    declared: &HashMap<String, usize>,
    errors: &mut Errors,
) -> Result<Option<usize>, ()> {
    let Some(p) = &tb.parent else {
        return Ok(None);
    };
    match declared.get(&p.to_string()) {
        Some(&i) => Ok(Some(i)),
        None => {
            errors.at(p.span(), format!("unknown parent `{p}`: a tree body's parent is `ground` or a `body` declared before it"));
            Err(())
        }
    }
}

/// A joint freed by `reaction`: its origin moves by the relaxed coordinates along the
/// ground's axes (zero in the motion; their multipliers are the joint's force).
fn free_joint(g: &mut Graph, origin: &mut [Expr], tb: &parse::TreeBody, coords: &[Coord]) {
    for (o, r) in origin.iter_mut().zip(tb.reaction.iter().flatten()) {
        if let Some(c) = coords.iter().find(|c| c.name == *r) {
            *o = g.add(*o, c.z);
        }
    }
}

/// A tree body's `at` or `com`: a constant vector of `len` entries, zero when not given.
fn tree_vector(lw: &mut Lowerer<'_>, e: &Option<syn::Expr>, len: usize) -> Option<Vec<Expr>> {
    match e {
        Some(e) => lw.vector(e, Context::Constant, len),
        None => Some(vec![lw.g.zero(); len]),
    }
}

/// A tree body's mass, with a spanned error when it is a constant that is not positive.
/// A check of an element's constant (stiffness, damping, friction): eager.
fn check(what: String, expr: Expr, positive: bool) -> ParamCheck {
    ParamCheck {
        what,
        expr,
        positive,
        eager: true,
    }
}

/// Every body's mass (> 0) and diagonal inertias (>= 0: a zero one of a free body makes the
/// mass matrix singular, which the solve reports; a tree body's zero inertia is a point
/// mass), named by the body.
fn body_checks(names: &Names, bodies: &[BodyKin]) -> Vec<ParamCheck> {
    let mut by_index: Vec<(usize, &String)> = names
        .iter()
        .filter_map(|(n, b)| match b {
            Binding::Body(i) => Some((*i, n)),
            _ => None,
        })
        .collect();
    by_index.sort();
    let mut out = Vec::new();
    for (i, name) in by_index {
        let b = &bodies[i];
        out.push(ParamCheck {
            eager: false,
            ..check(format!("the mass of `{name}`"), b.mass, true)
        });
        if let Some(inertia) = &b.inertia {
            let axes = if b.rot.is_some() { 3 } else { 1 };
            for (k, row) in inertia.iter().enumerate().take(axes) {
                let what = if axes == 1 {
                    format!("the inertia of `{name}`")
                } else {
                    format!("the inertia of `{name}` about its axis {k}")
                };
                out.push(ParamCheck {
                    eager: false,
                    ..check(what, row[k], false)
                });
            }
        }
    }
    out
}

fn tree_mass(lw: &mut Lowerer<'_>, tb: &parse::TreeBody) -> Option<Expr> {
    let e = tb.mass.as_ref()?;
    let m = lw.scalar(e, Context::Constant)?;
    if lw.g.as_const(m).is_some_and(|v| v <= 0.0) {
        lw.errors
            .over(e, format!("body `{}` has no positive mass", tb.name));
    }
    Some(m)
}

/// Lagrange's form of the forces of a scleronomic system (kinetic energy `zd^T M zd / 2`):
/// `f_i = Q_i - sum_{j<=k} C_ijk zd_j zd_k` with the Christoffel sums
/// `C_ijk = dM_ij/dz_k + dM_ik/dz_j - dM_jk/dz_i` (`j < k`) and `C_ijj = dM_ij/dz_j -
/// dM_jj/dz_i / 2`. It differentiates the simplified mass matrix, so a velocity-product term
/// whose sum vanishes is never formed (a pendulum link's own `u'^2`); Kane's `J . (J' qd)`
/// forms such terms and cancels them only when they meet in one sum.
fn lagrange_forces(
    g: &mut Graph,
    m: &[Vec<Expr>],
    applied: &[Expr],
    z: &[Sym],
    coords: &[Coord],
) -> Vec<Expr> {
    let n = z.len();
    let dm: Vec<Vec<Vec<Expr>>> = m
        .iter()
        .map(|row| {
            row.iter()
                .map(|&e| z.iter().map(|&s| g.diff(e, s)).collect())
                .collect()
        })
        .collect();
    (0..n)
        .map(|i| {
            let mut velocity_terms = Vec::new();
            for j in 0..n {
                for k in j..n {
                    let terms = if j == k {
                        vec![(1.0, dm[i][j][j]), (-0.5, dm[j][j][i])]
                    } else {
                        vec![(1.0, dm[i][j][k]), (1.0, dm[i][k][j]), (-1.0, dm[j][k][i])]
                    };
                    let c = signed_sum(g, &terms);
                    if g.is_zero(c) {
                        continue;
                    }
                    let v = g.mul(coords[j].zd, coords[k].zd);
                    velocity_terms.push(g.mul(c, v));
                }
            }
            let c = g.sum(velocity_terms);
            g.sub(applied[i], c)
        })
        .collect()
}

/// `sum k e` with the coefficients of one node added up first, so `x + y - x` is `y`.
fn signed_sum(g: &mut Graph, terms: &[(f64, Expr)]) -> Expr {
    let mut merged: Vec<(f64, Expr)> = Vec::new();
    for &(k, e) in terms.iter().filter(|(_, e)| !g.is_zero(*e)) {
        match merged.iter_mut().find(|(_, m)| *m == e) {
            Some(slot) => slot.0 += k,
            None => merged.push((k, e)),
        }
    }
    let parts: Vec<Expr> = merged
        .into_iter()
        .filter(|(k, _)| *k != 0.0)
        .map(|(k, e)| {
            let k = g.constant(k);
            g.mul(k, e)
        })
        .collect();
    g.sum(parts)
}

/// `[d/dt e]` without its `zdd` terms: the acceleration-like part that does not depend on
/// the unknown accelerations (`a0`, `alpha0`).
fn drop_qdd(g: &mut Graph, kin: &Kin<'_>, v: Expr) -> Expr {
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

/// When every parameter has a default and the initial positions are given, the default
/// configuration must satisfy the constraints: checked here, at compile time.
fn check_default_configuration(
    ast: &Mechanism,
    g: &mut Graph,
    phi: &[Expr],
    spans: &[&proc_macro2::TokenStream],
    init_q: &[Expr],
    roles: &HashMap<Sym, Role>,
    errors: &mut Errors,
) {
    let positioned = |c: &Ident| ast.inits.iter().any(|i| !i.velocity && i.coord == *c);
    if phi.is_empty()
        || ast.params.iter().any(|p| p.default.is_none())
        || !ast.coords.iter().all(positioned)
    {
        return;
    }
    let mut values: HashMap<Sym, f64> = HashMap::new();
    let no_names = HashMap::new();
    let mut scratch = Errors::default();
    for p in &ast.params {
        let e = Lowerer {
            g,
            names: &no_names,
            struct_name: "",
            model: None,
            errors: &mut scratch,
        }
        .scalar(p.default.as_ref().expect("checked"), Context::Constant);
        match e.and_then(|e| g.as_const(e)) {
            Some(v) => {
                let s = g.symbol(&p.name.to_string());
                values.insert(g.as_sym(s).expect("symbol"), v);
            }
            None => return,
        }
    }
    let env_params = values.clone();
    for (a, e) in init_q.iter().enumerate() {
        let v = g.eval(*e, &|s| env_params.get(&s).copied().unwrap_or(f64::NAN));
        if let Some((s, _)) = roles.iter().find(|(_, r)| **r == Role::Q(a)) {
            values.insert(*s, v);
        }
    }
    for (k, p) in phi.iter().enumerate() {
        let r = g.eval(*p, &|s| {
            if g_is_time(roles, s) {
                0.0
            } else {
                values.get(&s).copied().unwrap_or(f64::NAN)
            }
        });
        if r.is_finite() && r.abs() > 1e-9 {
            errors.over(
                spans[k],
                format!("the default configuration (parameter defaults and `init` positions at t = 0) violates this constraint: residual {r:.3e}"),
            );
        }
    }
}

fn g_is_time(roles: &HashMap<Sym, Role>, s: Sym) -> bool {
    roles.get(&s) == Some(&Role::Time)
}

/// Whether `e` uses a symbol whose role satisfies `pred`.
pub fn uses_roles(
    g: &Graph,
    roles: &HashMap<Sym, Role>,
    e: Expr,
    pred: impl Fn(&Role) -> bool,
) -> bool {
    g.free_symbols(e)
        .iter()
        .any(|s| roles.get(s).is_some_and(&pred))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value for every symbol, the same for one name in every graph.
    fn value_of(g: &Graph, s: Sym) -> f64 {
        let h = g
            .sym_name(s)
            .bytes()
            .fold(7u64, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b)));
        0.3 + (h % 1000) as f64 / 1000.0
    }

    /// Kane's and Lagrange's forces of `input`, evaluated at one state: two derivations of
    /// the same equations, so they must agree to rounding.
    fn forms_agree(input: syn::DeriveInput) {
        let ast = parse::Mechanism::from_syn(&input).expect("parses");
        let kane = derive_with(&ast, InertialForm::Kane).expect("derives");
        let lagrange = derive_with(&ast, InertialForm::Lagrange).expect("derives");
        assert_eq!(kane.forces.len(), lagrange.forces.len());
        for (&k, &l) in kane.forces.iter().zip(&lagrange.forces) {
            let fk = kane.g.eval(k, &|s| value_of(&kane.g, s));
            let fl = lagrange.g.eval(l, &|s| value_of(&lagrange.g, s));
            assert!(fk.is_finite() && fl.is_finite());
            assert!(
                (fk - fl).abs() <= 1e-12 * fk.abs().max(1.0),
                "{}: Kane {fk}, Lagrange {fl}",
                input.ident
            );
        }
    }

    #[test]
    fn kane_and_lagrange_give_the_same_forces() {
        forms_agree(syn::parse_quote! {
            #[gravity(0.0, -g)]
            #[coords(a, b)]
            #[particle(p1, mass = m1, at = [l1 * sin(a), -l1 * cos(a)])]
            #[particle(p2, mass = m2, at = [l1 * sin(a) + l2 * sin(b), -l1 * cos(a) - l2 * cos(b)])]
            struct DoublePendulum { m1: f64, m2: f64, l1: f64, l2: f64, g: f64 }
        });
        forms_agree(syn::parse_quote! {
            #[gravity(0.0, -g)]
            #[coords(theta, beta, x)]
            #[constraint(x == l * cos(beta) + r * cos(theta))]
            #[constraint(l * sin(beta) == r * sin(theta))]
            #[rigid(crank, mass = m_c, inertia = m_c * r * r / 12.0, at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
            #[rigid(rod, mass = m_r, inertia = m_r * l * l / 12.0,
                    at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
                    angle = -beta)]
            #[particle(piston, mass = m_p, at = [x, 0.0])]
            struct SliderCrank { r: f64, l: f64, m_c: f64, m_r: f64, m_p: f64, g: f64 }
        });
        // A heavy top: spatial rotation, gyroscopic terms.
        forms_agree(syn::parse_quote! {
            #[mechanism(spatial)]
            #[gravity(0.0, 0.0, -g)]
            #[coords(psi, theta, phi)]
            #[rigid3(top, mass = m, inertia = diag(a, a, c),
                     at = rot_z(psi) * rot_y(theta) * [0.0, 0.0, h],
                     rotation = rot_z(psi) * rot_y(theta) * rot_z(phi))]
            struct Top { m: f64, a: f64, c: f64, h: f64, g: f64 }
        });
        // Elastic pendulum with a damper, a driven cart carrying it, and a torque.
        forms_agree(syn::parse_quote! {
            #[gravity(0.0, -g)]
            #[coords(r, u)]
            #[drive(x = a * sin(w * t))]
            #[particle(cart, mass = m0, at = [x, 0.0])]
            #[rigid(bob, mass = m, inertia = j, at = [x + r * sin(u), -r * cos(u)], angle = u)]
            #[spring(s, from = cart, to = bob, k = k, length = l0)]
            #[damper(d, from = cart, to = bob, c = c)]
            #[torque(tq, on = bob, value = -c * der(u))]
            struct Elastic { m0: f64, m: f64, j: f64, k: f64, l0: f64, c: f64, a: f64, w: f64, g: f64 }
        });
    }
}
