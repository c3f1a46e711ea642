//! Applied forces as generalised forces in full coordinates: springs and potentials by
//! `-dV/dz`, dampers by `-dD/dz'` (Rayleigh), forces and torques by virtual work, gravity
//! last (its potential enters only the energy). `lower` meets the user's expressions once;
//! `generalized` works on what it returns, without `syn`.

use super::Ast;
use super::ParamCheck;
use super::checks::check;
use super::kinematics::{Kin, Kinematics};
use super::scope::Scope;
use crate::lower::{Binding, Context, Value};
use crate::lowered::Term;
use crate::parse::{End, Load};
use crate::sym::{Expr, Func, Graph, Sym};
use quote::ToTokens;

/// The loads of a model, lowered.
pub(super) struct Loads {
    gravity: Option<Vec<Expr>>,
    springs: Vec<Spring>,
    potentials: Vec<Expr>,
    dampers: Vec<Damper>,
    applied: Vec<Applied>,
}

/// A spring of stiffness `k` and length `l0` between two points.
struct Spring {
    name: String,
    ends: (Vec<Expr>, Vec<Expr>),
    k: Expr,
    l0: Expr,
}

/// A damper of coefficient `c` between two points.
struct Damper {
    name: String,
    ends: (Vec<Expr>, Vec<Expr>),
    c: Expr,
}

enum Applied {
    Force {
        at: Vec<Expr>,
        force: Vec<Expr>,
    },
    /// Planar: the body's angle and the torque; spatial: the body and the torque vector.
    PlanarTorque {
        angle: Expr,
        tau: Expr,
    },
    SpatialTorque {
        body: usize,
        tau: Vec<Expr>,
    },
    Generalized {
        coord: usize,
        value: Expr,
    },
}

/// The generalised forces other than gravity, gravity, and the potential energy.
pub(super) struct Forces {
    /// Applied forces other than gravity: the joint efforts of the recursive evaluation.
    pub q_applied: Vec<Expr>,
    pub gravity: Option<Vec<Expr>>,
    /// Springs' and potentials' energy.
    pub potential: Expr,
    pub gravity_energy: Expr,
}

/// The symbols forces are projected on.
struct Axes {
    z: Vec<Sym>,
    zd: Vec<Sym>,
}

impl Axes {
    /// Virtual work `F . dr/dz_j` of `force` at `at`.
    fn add_force_at(&self, g: &mut Graph, q: &mut [Expr], at: &[Expr], force: &[Expr]) {
        for (j, zs) in self.z.iter().enumerate() {
            let col: Vec<Expr> = at.iter().map(|x| g.diff(*x, *zs)).collect();
            let w = g.dot(force, &col);
            q[j] = g.add(q[j], w);
        }
    }
}

/// Gravity, springs, potentials, dampers and loads, with spanned errors for what has no
/// meaning (unknown names, a torque on a particle).
pub(super) fn lower(
    ast: &Ast,
    scope: &mut Scope,
    kinematics: &Kinematics,
    reactions: &mut Vec<(usize, Expr)>,
) -> Loads {
    let len = scope.dim.len();
    let gravity = match &ast.gravity {
        Some(e) => scope.lowerer(None).vector(e, Context::Constant, len),
        None => None,
    };
    let mut springs = Vec::new();
    for s in &ast.springs {
        let (a, b) = (
            end_position(scope, kinematics, &s.from),
            end_position(scope, kinematics, &s.to),
        );
        let mut lw = scope.lowerer(None);
        let k = lw.scalar(&s.k, Context::Constant);
        let l0 = match &s.length {
            Some(e) => lw.scalar(e, Context::Constant),
            None => Some(lw.g.zero()),
        };
        if let (Some(a), Some(b), Some(k), Some(l0)) = (a, b, k, l0) {
            let (name, ends) = (s.name.to_string(), (a, b));
            springs.push(Spring { name, ends, k, l0 });
        }
    }
    let potentials: Vec<Expr> = ast
        .potentials
        .iter()
        .filter_map(|p| {
            let mut none = Vec::new();
            let mut kin = kinematics.kin(scope.t, scope.dim, &mut none);
            scope.lowerer(Some(&mut kin)).scalar(p, Context::Kinematics)
        })
        .collect();
    let mut dampers = Vec::new();
    for d in &ast.dampers {
        let (a, b) = (
            end_position(scope, kinematics, &d.from),
            end_position(scope, kinematics, &d.to),
        );
        let c = scope.lowerer(None).scalar(&d.c, Context::Constant);
        if let (Some(a), Some(b), Some(c)) = (a, b, c) {
            let (name, ends) = (d.name.to_string(), (a, b));
            dampers.push(Damper { name, ends, c });
        }
    }
    let mut kin = kinematics.kin(scope.t, scope.dim, reactions);
    let applied: Vec<Applied> = ast
        .loads
        .iter()
        .filter_map(|load| lower_load(load, scope, &mut kin))
        .collect();
    still(
        ast,
        scope,
        kinematics,
        (&springs, &dampers),
        (&potentials, &applied),
    );
    Loads {
        gravity,
        springs,
        potentials,
        dampers,
        applied,
    }
}

/// Loads that act on nothing are errors, not silent no-ops: a spring or damper whose ends
/// both stay put, a force at a point or a torque on a body that moves with no coordinate
/// and not with `t` (its virtual work is zero: a mistyped end or body; one moved by a drive
/// loads the drive), a potential of no coordinate. Each lowered list holds the attributes
/// that lowered, in order; one that failed has its error.
fn still(
    ast: &Ast,
    scope: &mut Scope,
    kinematics: &Kinematics,
    (springs, dampers): (&[Spring], &[Damper]),
    (potentials, applied): (&[Expr], &[Applied]),
) {
    let q = kinematics.z_syms(&scope.g);
    let mut z = q.clone();
    z.extend(scope.g.as_sym(scope.t));
    let g = &scope.g;
    let moves = |v: &[Expr]| v.iter().any(|e| z.iter().any(|s| g.depends_on(*e, *s)));
    let mut out: Vec<(proc_macro2::TokenStream, String)> = Vec::new();
    for s in springs {
        if !moves(&s.ends.0) && !moves(&s.ends.1) {
            let at = ast
                .springs
                .iter()
                .find(|a| a.name == s.name)
                .map(|a| a.name.to_token_stream());
            out.extend(at.map(|at| (at, format!("spring `{}` joins two points that move with no coordinate: it acts on nothing (name a body, or a point on one)", s.name))));
        }
    }
    for d in dampers {
        if !moves(&d.ends.0) && !moves(&d.ends.1) {
            let at = ast
                .dampers
                .iter()
                .find(|a| a.name == d.name)
                .map(|a| a.name.to_token_stream());
            out.extend(at.map(|at| (at, format!("damper `{}` joins two points that move with no coordinate: it acts on nothing (name a body, or a point on one)", d.name))));
        }
    }
    if potentials.len() == ast.potentials.len() {
        for (p, term) in potentials.iter().zip(&ast.potentials) {
            if !q.iter().any(|s| g.depends_on(*p, *s)) {
                out.push((
                    term.to_token_stream(),
                    "this potential depends on no coordinate: it exerts no force".into(),
                ));
            }
        }
    }
    if applied.len() == ast.loads.len() {
        for (a, load) in applied.iter().zip(&ast.loads) {
            let msg = match (a, load) {
                (Applied::Force { at, .. }, Load::Force { at: term, .. }) if !moves(at) => (
                    term.to_token_stream(),
                    "this force acts at a point that moves with no coordinate: it does no work (apply it at a body: `position(b)` or `position(b, [..])`)".to_string(),
                ),
                (Applied::PlanarTorque { angle, .. }, Load::Torque { body, .. }) if !moves(&[*angle]) => (
                    body.to_token_stream(),
                    format!("`{body}` turns with no coordinate: a torque on it does no work"),
                ),
                _ => continue,
            };
            out.push(msg);
        }
    }
    for (tokens, msg) in out {
        scope.errors.over(tokens, msg);
    }
}

/// A spring's or damper's end: a named point or body, or a position.
fn end_position(scope: &mut Scope, kinematics: &Kinematics, end: &End<Term>) -> Option<Vec<Expr>> {
    match end {
        End::Named(id) => match scope.names.get(&id.to_string()) {
            Some(Binding::Value(Value::Vector(v))) => Some(v.clone()),
            Some(Binding::Body(b)) => Some(kinematics.bodies[*b].r.clone()),
            _ => {
                let hint = if id == "ground" {
                    ": the ground is no point; give a fixed end as a position `[x, y]` or a `#[point(name, at = [..])]`"
                } else {
                    ""
                };
                scope
                    .errors
                    .at(id.span(), format!("unknown point or body `{id}`{hint}"));
                None
            }
        },
        End::At(e) => {
            // `position(b, [..])` may name a body-fixed point here.
            let (len, mut none) = (scope.dim.len(), Vec::new());
            let mut kin = kinematics.kin(scope.t, scope.dim, &mut none);
            scope
                .lowerer(Some(&mut kin))
                .vector(e, Context::Kinematics, len)
        }
    }
}

/// A force at a point, a torque on a body, or a generalised force along a coordinate.
fn lower_load(load: &Load<Term>, scope: &mut Scope, kin: &mut Kin<'_>) -> Option<Applied> {
    let len = scope.dim.len();
    match load {
        Load::Force { at, value } => {
            let mut lw = scope.lowerer(Some(kin));
            let at = lw.vector(at, Context::Kinematics, len);
            let force = lw.vector(value, Context::Force, len);
            Some(Applied::Force {
                at: at?,
                force: force?,
            })
        }
        Load::Torque { body, value } => {
            let Some(Binding::Body(bi)) = scope.names.get(&body.to_string()) else {
                scope
                    .errors
                    .at(body.span(), format!("unknown body `{body}`"));
                return None;
            };
            let bi = *bi;
            let b = &kin.bodies[bi];
            match (b.angle, b.rot) {
                (Some(angle), _) => {
                    let tau = scope.lowerer(Some(kin)).scalar(value, Context::Force)?;
                    Some(Applied::PlanarTorque { angle, tau })
                }
                (None, Some(_)) => {
                    let tau = scope.lowerer(Some(kin)).vector(value, Context::Force, 3)?;
                    Some(Applied::SpatialTorque { body: bi, tau })
                }
                _ => {
                    scope.errors.at(
                        body.span(),
                        format!(
                            "`{body}` is a point mass (a `particle`, or a `body` without \
                             `inertia`): a torque needs a rigid body; give it an `inertia` \
                             (a free body: `rigid`), or, on a joint-tree body, apply the \
                             torque along its joint's angle `q`: \
                             `#[generalized_force(name, along = q, value = ..)]`"
                        ),
                    );
                    None
                }
            }
        }
        Load::Generalized { coord, value } => {
            let Some(j) = kin.coords.iter().position(|c| c.name == *coord) else {
                scope
                    .errors
                    .at(coord.span(), format!("unknown coordinate `{coord}`"));
                return None;
            };
            let value = scope.lowerer(Some(kin)).scalar(value, Context::Force)?;
            Some(Applied::Generalized { coord: j, value })
        }
    }
}

pub(super) fn generalized(
    scope: &mut Scope,
    kinematics: &Kinematics,
    loads: Loads,
    checks: &mut Vec<ParamCheck>,
) -> Forces {
    let zero = scope.g.zero();
    let nz = kinematics.coords.len();
    let mut reactions = Vec::new();
    let kin = kinematics.kin(scope.t, scope.dim, &mut reactions);
    let axes = Axes {
        z: kinematics.z_syms(&scope.g),
        zd: kinematics.zd_syms(&scope.g),
    };
    let g = &mut scope.g;
    let mut q_full = vec![zero; nz];
    let potential = springs_and_potentials(g, &loads, checks);
    for (j, zs) in axes.z.iter().enumerate() {
        let dv = g.diff(potential, *zs);
        q_full[j] = g.sub(q_full[j], dv);
    }
    dampers(g, &kin, &loads.dampers, &axes, &mut q_full, checks);
    for load in &loads.applied {
        apply_load(g, load, &kin, &axes, &mut q_full);
    }
    let mut gravity_energy = zero;
    if let Some(grav) = &loads.gravity {
        for b in &kinematics.bodies {
            let w: Vec<Expr> = grav.iter().map(|gc| g.mul(b.mass, *gc)).collect();
            let h = g.dot(&w, &b.r);
            gravity_energy = g.sub(gravity_energy, h);
        }
    }
    Forces {
        q_applied: q_full,
        gravity: loads.gravity,
        potential,
        gravity_energy,
    }
}

impl Forces {
    /// All applied forces, gravity's by virtual work added: a derivative of every body's
    /// position by every coordinate (O(bodies x depth) terms in a chain), so only Kane's
    /// projection asks; a pure tree's recursions take gravity as the ground's acceleration
    /// (computed for every tree, this was most of a 64-link spatial chain's expansion).
    pub fn with_gravity(&self, g: &mut Graph, kinematics: &Kinematics) -> Vec<Expr> {
        let mut q_full = self.q_applied.clone();
        if let Some(grav) = &self.gravity {
            let axes = Axes {
                z: kinematics.z_syms(g),
                zd: Vec::new(),
            };
            for b in &kinematics.bodies {
                let w: Vec<Expr> = grav.iter().map(|gc| g.mul(b.mass, *gc)).collect();
                axes.add_force_at(g, &mut q_full, &b.r, &w);
            }
        }
        q_full
    }
}

fn length(g: &mut Graph, a: &[Expr], b: &[Expr]) -> Expr {
    let s = squared_length(g, a, b);
    g.call(Func::Sqrt, s)
}

fn squared_length(g: &mut Graph, a: &[Expr], b: &[Expr]) -> Expr {
    let d: Vec<Expr> = a.iter().zip(b).map(|(x, y)| g.sub(*y, *x)).collect();
    g.dot(&d, &d)
}

/// `V = sum k (l - l0)^2 / 2` over the springs plus the user's potentials.
fn springs_and_potentials(g: &mut Graph, loads: &Loads, checks: &mut Vec<ParamCheck>) -> Expr {
    let mut potential = g.zero();
    for s in &loads.springs {
        let (name, (a, b), k, l0) = (&s.name, &s.ends, s.k, s.l0);
        checks.push(check(format!("the stiffness of spring `{name}`"), k, false));
        checks.push(check(format!("the length of spring `{name}`"), l0, false));
        // A spring of rest length zero is `k d.d / 2`: through `l = sqrt(d.d)` its force
        // would be 0/0 where the ends meet, though it is zero there.
        let s2 = if g.is_zero(l0) {
            squared_length(g, a, b)
        } else {
            let l = length(g, a, b);
            let stretch = g.sub(l, l0);
            g.powi(stretch, 2)
        };
        let half = g.constant(0.5);
        let half_k = g.mul(half, k);
        let v = g.mul(half_k, s2);
        potential = g.add(potential, v);
    }
    for &v in &loads.potentials {
        potential = g.add(potential, v);
    }
    potential
}

/// Rayleigh dissipation `D = c l'^2 / 2`: `Q_j -= dD/dz'_j = c l' dl'/dz'_j`.
fn dampers(
    g: &mut Graph,
    kin: &Kin<'_>,
    dampers: &[Damper],
    axes: &Axes,
    q_full: &mut [Expr],
    checks: &mut Vec<ParamCheck>,
) {
    for d in dampers {
        let ((a, b), c) = (&d.ends, d.c);
        checks.push(check(format!("the damping of `{}`", d.name), c, false));
        let l = length(g, a, b);
        let ldot = kin.tder(g, l);
        let cl = g.mul(c, ldot);
        for (j, zds) in axes.zd.iter().enumerate() {
            let dl = g.diff(ldot, *zds);
            let w = g.mul(cl, dl);
            q_full[j] = g.sub(q_full[j], w);
        }
    }
}

fn apply_load(g: &mut Graph, load: &Applied, kin: &Kin<'_>, axes: &Axes, q_full: &mut [Expr]) {
    match load {
        Applied::Force { at, force } => axes.add_force_at(g, q_full, at, force),
        Applied::PlanarTorque { angle, tau } => {
            for (j, zs) in axes.z.iter().enumerate() {
                let d = g.diff(*angle, *zs);
                let w = g.mul(*tau, d);
                q_full[j] = g.add(q_full[j], w);
            }
        }
        Applied::SpatialTorque { body, tau } => {
            // World torque . d(w_world)/dzd_j.
            let b = &kin.bodies[*body];
            let rot = b.rot.expect("a spatial body");
            let w_b = kin.omega_body(g, b);
            let w: Vec<Expr> = (0..3).map(|i| g.dot(&rot[i], &w_b)).collect();
            for (j, zds) in axes.zd.iter().enumerate() {
                let col: Vec<Expr> = w.iter().map(|x| g.diff(*x, *zds)).collect();
                let p = g.dot(tau, &col);
                q_full[j] = g.add(q_full[j], p);
            }
        }
        Applied::Generalized { coord, value } => {
            // Along a dependent coordinate too: the projection takes it to the free ones.
            q_full[*coord] = g.add(q_full[*coord], *value);
        }
    }
}
