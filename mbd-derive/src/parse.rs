//! Stage 1: `syn` attributes -> a plain AST of the mechanism.
//!
//! Every attribute's arguments are read as a comma-separated list of Rust expressions:
//! a bare name (`rod`, `falling`), a keyed value (`mass = m`), or an equation
//! (`x == l * cos(beta)`). Values stay `syn::Expr`, so every later error can point at
//! the user's own tokens.

use proc_macro2::Span;
use quote::format_ident;
use syn::punctuated::Punctuated;
use syn::spanned::Spanned;
use syn::{Attribute, Data, DeriveInput, Expr, Fields, Ident, Token};

/// Whether bodies move in a plane (x, y; one angle) or in space (x, y, z; a rotation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dim {
    Planar,
    Spatial,
}

impl Dim {
    pub fn len(self) -> usize {
        match self {
            Dim::Planar => 2,
            Dim::Spatial => 3,
        }
    }
}

pub struct Param<E = Expr> {
    pub name: Ident,
    pub default: Option<E>,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum BodyKind {
    Particle,
    Rigid,
    Rigid3,
}

pub struct Body<E = Expr> {
    pub name: Ident,
    pub kind: BodyKind,
    pub mass: Option<E>,
    pub inertia: Option<E>,
    pub at: Option<E>,
    /// Planar rigid body: its angle. Spatial: its rotation (world from body).
    pub orientation: Option<E>,
}

/// A named point: fixed (`at` holds constants) or moving (an expression of the coordinates).
pub struct Point<E = Expr> {
    pub name: Ident,
    pub at: E,
    /// `on = body`: `at` is in that body's frame, from its origin (a body-fixed point).
    pub on: Option<Ident>,
}

/// Two ends of a spring or a damper: a point name, a body name (its mass centre), or a position.
pub enum End<E = Expr> {
    Named(Ident),
    At(E),
}

pub struct Spring<E = Expr> {
    pub name: Ident,
    pub from: End<E>,
    pub to: End<E>,
    pub k: E,
    pub length: Option<E>,
}

pub struct Damper<E = Expr> {
    pub name: Ident,
    pub from: End<E>,
    pub to: End<E>,
    pub c: E,
}

/// A force applied at a point, or a torque on a body, or a generalised force on a coordinate.
pub enum Load<E = Expr> {
    Force { at: E, value: E },
    Torque { body: Ident, value: E },
    Generalized { coord: Ident, value: E },
}

pub struct Friction<E = Expr> {
    pub along: Ident,
    pub mu: E,
    /// Static coefficient for the stick test (default: `mu`).
    pub mu_static: Option<E>,
    pub normal: E,
    pub span: Span,
}

pub struct Named<E = Expr> {
    pub name: Ident,
    pub expr: E,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Direction {
    Rising,
    Falling,
    Either,
}

pub struct Event<E = Expr> {
    pub name: Ident,
    pub expr: E,
    pub direction: Direction,
    pub terminal: bool,
}

/// An initial value: `theta = 0.5` (position) or `der(theta) = 1.0` (velocity).
pub struct Init<E = Expr> {
    pub coord: Ident,
    pub velocity: bool,
    pub value: E,
}

pub struct Constraint<E = Expr> {
    pub tokens: proc_macro2::TokenStream,
    pub lhs: E,
    pub rhs: E,
}

/// What moves a tree body relative to its parent; each joint brings its own coordinates.
pub enum Joint<E = Expr> {
    /// Rotation about the joint origin by `coord`: planar (`axis: None`, the body's angle is
    /// the parent's plus `coord`), or spatial about the parent's `x`, `y` or `z` axis.
    Revolute { coord: Ident, axis: Option<Ident> },
    /// Translation along `axis` (in the parent's frame) by `coord`.
    Prismatic { coord: Ident, axis: E },
    /// Spatial: `rot_x(a) rot_y(b)` (a Cardan joint, crossed axes `x` then `y`).
    Universal(Ident, Ident),
    /// Spatial: `rot_z(a) rot_y(b) rot_x(c)` (yaw, pitch, roll; singular at `b = ±π/2`).
    Spherical(Ident, Ident, Ident),
    /// Spatial: a spherical joint in modified Rodrigues parameters `sigma = tan(phi/4) n`
    /// (rotation by `phi` about the unit `n`; no singularity short of `phi = 2π`, and the
    /// integrators switch to the shadow set past `phi = π`: `ball.rs`).
    Ball(Ident, Ident, Ident),
    /// Spatial, six degrees of freedom (a floating base): the joint origin moves by
    /// `(x, y, z)` in the parent's axes, and the body turns about it as on a `ball` joint
    /// (the same chart and switch): `free(x, y, z, s1, s2, s3)`.
    Free([Ident; 3], [Ident; 3]),
    /// Welded to the parent.
    Fixed,
}

impl<E> Joint<E> {
    /// The joint's coordinates, in order.
    pub fn coords(&self) -> Vec<&Ident> {
        match self {
            Joint::Revolute { coord, .. } | Joint::Prismatic { coord, .. } => vec![coord],
            Joint::Universal(a, b) => vec![a, b],
            Joint::Spherical(a, b, c) | Joint::Ball(a, b, c) => vec![a, b, c],
            Joint::Free(at, [a, b, c]) => vec![&at[0], &at[1], &at[2], a, b, c],
            Joint::Fixed => Vec::new(),
        }
    }

    /// The modified Rodrigues parameters of a `ball` joint or of a `free` joint's rotation:
    /// coordinates that switch to the shadow set together.
    pub fn ball_coords(&self) -> Option<[&Ident; 3]> {
        match self {
            Joint::Ball(a, b, c) | Joint::Free(_, [a, b, c]) => Some([a, b, c]),
            _ => None,
        }
    }
}

/// A body of the joint tree: its frame is its parent's frame moved by its joint. `at` (the
/// joint origin, in the parent's frame), `angle` (a fixed offset, planar) and `com` (the mass
/// centre, in the body's frame) default to zero.
pub struct TreeBody<E = Expr> {
    pub name: Ident,
    /// `None`: the ground.
    pub parent: Option<Ident>,
    pub joint: Joint<E>,
    pub joint_span: Span,
    pub at: Option<E>,
    pub angle: Option<E>,
    pub com: Option<E>,
    /// Relaxed coordinates `name_rx`, `name_ry` (and `name_rz` in space) that free the joint
    /// origin along the ground's axes, so that `reaction(name_rx)`, ... are the joint's force
    /// on the body.
    pub reaction: Option<Vec<Ident>>,
    pub mass: Option<E>,
    pub inertia: Option<E>,
}

/// A joint that closes a loop of the tree: point `at_a` of body `a` (its frame) stays on
/// point `at_b` of body `b` (`None`: the ground), or on its line along `axis_b` (prismatic).
/// Planar: a revolute joint, two equations. Spatial: `joint` picks the kind (close.rs).
pub struct Closure<E = Expr> {
    pub a: Option<Ident>,
    pub at_a: Option<E>,
    pub b: Option<Ident>,
    pub at_b: Option<E>,
    /// `joint = ..` and its span (`None`: spherical in space, revolute in a plane).
    pub joint: Option<(CloseJoint, Span)>,
    /// Body-fixed directions, each in its body's frame: the joint axis and, for a prismatic
    /// joint, a direction normal to it.
    pub axis_a: Option<E>,
    pub axis_b: Option<E>,
    pub normal_a: Option<E>,
    pub normal_b: Option<E>,
    pub tokens: proc_macro2::TokenStream,
}

/// The kind of a loop-closing joint (`#[close(.., joint = revolute)]`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum CloseJoint {
    Spherical,
    Revolute,
    Universal,
    Prismatic,
}

/// How the accelerations of a joint tree are evaluated.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Evaluation {
    /// The macro chooses (recursive for larger trees).
    Auto,
    /// The articulated-body recursion, O(n) in the bodies.
    Recursive,
    /// The mass matrix and a dense L D L^T solve.
    MassMatrix,
}

/// Which form a closed loop's equations take (`#[mechanism(augmented | minimal)]`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum LoopForm {
    /// Minimal coordinates where the closure has a closed form, else augmented.
    Auto,
    /// Every coordinate, the constraints and their multipliers.
    Augmented,
    /// Minimal coordinates, or a compile error saying why not.
    Minimal,
}

pub struct Mechanism<E = Expr> {
    pub ident: Ident,
    pub params: Vec<Param<E>>,
    pub dim: Dim,
    pub dim_span: Span,
    pub gravity: Option<E>,
    pub coords: Vec<Ident>,
    pub drives: Vec<Named<E>>,
    pub relaxed: Vec<Ident>,
    pub constraints: Vec<Constraint<E>>,
    pub bodies: Vec<Body<E>>,
    pub tree: Vec<TreeBody<E>>,
    pub closures: Vec<Closure<E>>,
    pub points: Vec<Point<E>>,
    pub springs: Vec<Spring<E>>,
    pub dampers: Vec<Damper<E>>,
    pub loads: Vec<Load<E>>,
    pub potentials: Vec<E>,
    pub frictions: Vec<Friction<E>>,
    pub outputs: Vec<Named<E>>,
    /// Parameters that are inputs (`#[input(u, ..)]`, see linear.rs).
    pub inputs: Vec<Ident>,
    pub events: Vec<Event<E>>,
    pub inits: Vec<Init<E>>,
    /// Generate exact Jacobians `d qdd / dq`, `d qdd / dqd` for implicit methods.
    pub jacobian: bool,
    /// Generate `Drawable` (`#[mechanism(geometry)]`, see `geometry.rs`).
    pub geometry: bool,
    /// Generate a joint tree's `inverse_dynamics` by Newton-Euler
    /// (`#[mechanism(inverse_dynamics)]`); otherwise the trait's `M qdd - f` serves.
    pub inverse_dynamics: bool,
    pub evaluation: Evaluation,
    pub evaluation_span: Span,
    pub loop_form: LoopForm,
    pub loop_form_span: Span,
}

/// Collects errors so a model reports all its mistakes at once (serde's `Ctxt`).
#[derive(Default)]
pub struct Errors(Option<syn::Error>);

impl Errors {
    pub fn push(&mut self, err: syn::Error) {
        match &mut self.0 {
            Some(e) => e.combine(err),
            None => self.0 = Some(err),
        }
    }
    pub fn at(&mut self, span: Span, msg: impl std::fmt::Display) {
        self.push(syn::Error::new(span, msg));
    }
    pub fn is_empty(&self) -> bool {
        self.0.is_none()
    }
    /// An error over the whole of `tokens` (first to last token, also on stable).
    pub fn over(&mut self, tokens: impl quote::ToTokens, msg: impl std::fmt::Display) {
        self.push(syn::Error::new_spanned(tokens, msg));
    }
    pub fn finish(self) -> syn::Result<()> {
        self.0.map_or(Ok(()), Err)
    }
}

/// One argument of an attribute list.
enum Arg {
    Flag(Ident),
    Keyed(Ident, Expr),
    Other(Expr),
}

fn args(attr: &Attribute) -> syn::Result<Vec<Arg>> {
    let list = attr.parse_args_with(Punctuated::<Expr, Token![,]>::parse_terminated)?;
    Ok(list.into_iter().map(classify).collect())
}

fn classify(e: Expr) -> Arg {
    match e {
        Expr::Path(p) if p.qself.is_none() && p.path.get_ident().is_some() => {
            Arg::Flag(p.path.get_ident().cloned().expect("checked"))
        }
        Expr::Assign(a) => match &*a.left {
            Expr::Path(p) if p.path.get_ident().is_some() => {
                Arg::Keyed(p.path.get_ident().cloned().expect("checked"), *a.right)
            }
            _ => Arg::Other(Expr::Assign(a)),
        },
        other => Arg::Other(other),
    }
}

/// The keyed arguments of a named item, e.g. `rigid(rod, mass = m, at = [..])`.
struct Item {
    name: Ident,
    keys: Vec<(Ident, Expr)>,
    flags: Vec<Ident>,
    /// Keys an unknown key's hint already stands for: not reported missing again.
    hinted: Vec<String>,
}

impl Item {
    fn read(
        attr: &Attribute,
        errors: &mut Errors,
        allowed: &[&str],
        flags: &[&str],
    ) -> Option<Item> {
        let args = match args(attr) {
            Ok(a) => a,
            Err(e) => {
                errors.push(e);
                return None;
            }
        };
        let mut it = args.into_iter();
        let name = match it.next() {
            Some(Arg::Flag(name)) => name,
            first => {
                let span = match &first {
                    Some(Arg::Keyed(k, _)) => k.span(),
                    Some(Arg::Other(e)) => e.span(),
                    _ => attr.path().span(),
                };
                errors.at(
                    span,
                    format!(
                        "`{}` needs a name first, e.g. `{}(name, ...)`",
                        attr_name(attr),
                        attr_name(attr)
                    ),
                );
                return None;
            }
        };
        let mut item = Item {
            name,
            keys: Vec::new(),
            flags: Vec::new(),
            hinted: Vec::new(),
        };
        for arg in it {
            match arg {
                Arg::Keyed(k, v) if allowed.contains(&k.to_string().as_str()) => {
                    if item.keys.iter().any(|(k2, _)| *k2 == k) {
                        errors.at(k.span(), format!("duplicate key `{k}`"));
                    }
                    item.keys.push((k, v));
                }
                Arg::Keyed(k, _) => {
                    let name = attr_name(attr);
                    let (hint, meant) = crate::hints::unknown_key(&name, &k.to_string(), allowed);
                    item.hinted.extend(meant);
                    let keys = allowed.join("`, `");
                    let message = if hint.is_empty() {
                        format!("unknown key `{k}` in `{name}`, expected one of `{keys}`")
                    } else {
                        format!("unknown key `{k}` in `{name}`{hint} (its keys: `{keys}`)")
                    };
                    errors.at(k.span(), message)
                }
                Arg::Flag(f) if flags.contains(&f.to_string().as_str()) => item.flags.push(f),
                Arg::Flag(f) => errors.at(
                    f.span(),
                    format!("unexpected `{f}` in `{}`", attr_name(attr)),
                ),
                Arg::Other(e) => errors.at(
                    e.span(),
                    format!("expected `key = value` in `{}`", attr_name(attr)),
                ),
            }
        }
        Some(item)
    }
    fn take(&mut self, key: &str) -> Option<Expr> {
        let i = self.keys.iter().position(|(k, _)| k == key)?;
        Some(self.keys.remove(i).1)
    }
    fn require(&mut self, key: &str, errors: &mut Errors, what: &str) -> Option<Expr> {
        let v = self.take(key);
        if v.is_none() && !self.hinted.iter().any(|h| h == key) {
            errors.at(
                self.name.span(),
                format!("{what} `{}` has no `{key}`", self.name),
            );
        }
        v
    }
}

fn attr_name(attr: &Attribute) -> String {
    attr.path()
        .get_ident()
        .map(|i| i.to_string())
        .unwrap_or_default()
}

fn end(e: Expr) -> End {
    match classify(e) {
        Arg::Flag(name) => End::Named(name),
        Arg::Keyed(k, v) => End::At(syn::parse_quote!(#k = #v)),
        Arg::Other(e) => End::At(e),
    }
}

/// `name = expr` pairs, as in `drive(theta = omega * t)` and `output(v = speed(ball))`.
fn named_list(attr: &Attribute, errors: &mut Errors) -> Vec<Named> {
    let mut out = Vec::new();
    match args(attr) {
        Ok(args) => {
            for arg in args {
                match arg {
                    Arg::Keyed(name, expr) => out.push(Named { name, expr }),
                    Arg::Flag(f) => errors.at(f.span(), format!("expected `{f} = <expression>`")),
                    Arg::Other(e) => errors.at(e.span(), "expected `name = <expression>`"),
                }
            }
        }
        Err(e) => errors.push(e),
    }
    out
}

/// Loads named twice (`force`, `torque` and `generalized_force` share one namespace): each
/// would be applied, so the second is refused, its message naming the first.
fn duplicate_loads(attrs: &[Attribute], errors: &mut Errors) {
    let mut seen: Vec<(Ident, String)> = Vec::new();
    for attr in attrs {
        let kind = attr_name(attr);
        if !matches!(kind.as_str(), "force" | "torque" | "generalized_force") {
            continue;
        }
        let Ok(list) = args(attr) else { continue };
        let Some(Arg::Flag(name)) = list.into_iter().next() else {
            continue;
        };
        if let Some((_, first)) = seen.iter().find(|(n, _)| *n == name) {
            errors.at(
                name.span(),
                format!("duplicate load `{name}`: a `{first}` named `{name}` is given above; give each load its own name"),
            );
        } else {
            seen.push((name, kind));
        }
    }
}

fn ident_list(attr: &Attribute, errors: &mut Errors) -> Vec<Ident> {
    match attr.parse_args_with(Punctuated::<Ident, Token![,]>::parse_terminated) {
        Ok(list) => list.into_iter().collect(),
        Err(e) => {
            errors.push(e);
            Vec::new()
        }
    }
}

impl Mechanism {
    #[cfg(test)]
    pub fn from_syn(input: &DeriveInput) -> syn::Result<Mechanism> {
        Self::read(input).map_err(|(e, _)| e)
    }

    /// [`Self::from_syn`], keeping what was read when there are errors (for the skeleton a
    /// failed derive still emits), unless the input is not a struct of parameters at all.
    pub fn read(input: &DeriveInput) -> Result<Mechanism, (syn::Error, Option<Box<Mechanism>>)> {
        let mut errors = Errors::default();
        let params = params(input, &mut errors).map_err(|e| (e, None))?;
        let mut m = Mechanism::empty(input.ident.clone(), params);
        let mut dim_given = false;
        for attr in &input.attrs {
            m.attribute(attr, &mut dim_given, &mut errors);
        }
        m.joint_coordinates(&mut errors);
        m.duplicates(&mut errors);
        duplicate_loads(&input.attrs, &mut errors);
        let names = m.bodies.iter().map(|b| &b.name);
        if let Some(over) = names.chain(m.tree.iter().map(|b| &b.name)).nth(MAX_BODIES) {
            errors.at(over.span(), too_many_bodies());
        }
        match errors.finish() {
            Ok(()) => Ok(m),
            Err(e) => Err((e, Some(Box::new(m)))),
        }
    }

    fn empty(ident: Ident, params: Vec<Param>) -> Mechanism {
        Mechanism {
            ident,
            params,
            dim: Dim::Planar,
            dim_span: Span::call_site(),
            gravity: None,
            coords: Vec::new(),
            drives: Vec::new(),
            relaxed: Vec::new(),
            constraints: Vec::new(),
            bodies: Vec::new(),
            tree: Vec::new(),
            closures: Vec::new(),
            points: Vec::new(),
            springs: Vec::new(),
            dampers: Vec::new(),
            loads: Vec::new(),
            potentials: Vec::new(),
            frictions: Vec::new(),
            outputs: Vec::new(),
            inputs: Vec::new(),
            events: Vec::new(),
            inits: Vec::new(),
            jacobian: false,
            geometry: false,
            inverse_dynamics: false,
            evaluation: Evaluation::Auto,
            evaluation_span: Span::call_site(),
            loop_form: LoopForm::Auto,
            loop_form_span: Span::call_site(),
        }
    }

    /// One attribute of the struct, by its name; attributes of other macros are left alone.
    fn attribute(&mut self, attr: &Attribute, dim_given: &mut bool, errors: &mut Errors) {
        let m = self;
        let name = attr_name(attr);
        let errors = &mut *errors;
        match name.as_str() {
            "mechanism" => m.options(attr, dim_given, errors),
            "gravity" => m.gravity(attr, *dim_given, errors),
            "coords" => m.coords.extend(ident_list(attr, errors)),
            "relaxed" => m.relaxed.extend(ident_list(attr, errors)),
            "drive" => m.drives.extend(named_list(attr, errors)),
            "output" => m.outputs.extend(named_list(attr, errors)),
            "input" => m.inputs.extend(ident_list(attr, errors)),
            "constraint" => match attr.parse_args::<Expr>() {
                Ok(Expr::Binary(b)) if matches!(b.op, syn::BinOp::Eq(_)) => {
                    m.constraints.push(Constraint {
                        tokens: quote::ToTokens::to_token_stream(&b),
                        lhs: *b.left,
                        rhs: *b.right,
                    })
                }
                Ok(Expr::Assign(a)) => errors.over(
                    a.eq_token,
                    "a constraint is an equation: `lhs == rhs`, with `==` (`=` assigns)",
                ),
                Ok(e) => errors.over(&e, "a constraint is an equation: `lhs == rhs`"),
                Err(e) => errors.push(e),
            },
            "particle" | "rigid" | "rigid3" => m.free_body(attr, &name, *dim_given, errors),
            "body" => m.tree_body(attr, errors),
            "close" => m.closure(attr, errors),
            "chain" => {
                let keys = &["n", "joint", "length", "mass", "inertia", "parent", "at"];
                if let Some(item) = Item::read(attr, errors, keys, &[]) {
                    chain(item, &mut m.tree, errors);
                }
            }
            "point" => {
                if let Some(mut item) = Item::read(attr, errors, &["at", "on"], &[])
                    && let Some(at) = item.require("at", errors, "point")
                {
                    let on = item.take("on").and_then(|e| match classify(e) {
                        Arg::Flag(body) => Some(body),
                        _ => {
                            let why = "`on` names the body the point is fixed to";
                            errors.at(item.name.span(), why);
                            None
                        }
                    });
                    m.points.push(Point {
                        name: item.name,
                        at,
                        on,
                    });
                }
            }
            "spring" => m.spring(attr, errors),
            "damper" => m.damper(attr, errors),
            "force" | "torque" | "generalized_force" => m.load(attr, &name, errors),
            "potential" => match attr.parse_args::<Expr>() {
                Ok(e) => m.potentials.push(e),
                Err(e) => errors.push(e),
            },
            "friction" => match args(attr) {
                Ok(list) => m.frictions.extend(friction(attr, list, errors)),
                Err(e) => errors.push(e),
            },
            "event" => match args(attr) {
                Ok(list) => m.events.extend(event(attr, list, errors)),
                Err(e) => errors.push(e),
            },
            "init" => m.init(attr, errors),
            _ => {}
        }
    }

    /// `#[mechanism(planar | spatial, jacobian, geometry, inverse_dynamics, recursive | mass_matrix, augmented | minimal)]`.
    fn options(&mut self, attr: &Attribute, dim_given: &mut bool, errors: &mut Errors) {
        for arg in args(attr).unwrap_or_else(|e| {
            errors.push(e);
            Vec::new()
        }) {
            match arg {
                    Arg::Flag(f) if f == "planar" || f == "spatial" => {
                        self.dim = if f == "planar" { Dim::Planar } else { Dim::Spatial };
                        self.dim_span = f.span();
                        *dim_given = true;
                    }
                    Arg::Flag(f) if f == "jacobian" => self.jacobian = true,
                    Arg::Flag(f) if f == "geometry" => self.geometry = true,
                    Arg::Flag(f) if f == "inverse_dynamics" => self.inverse_dynamics = true,
                    Arg::Flag(f) if f == "recursive" || f == "mass_matrix" => {
                        self.evaluation = if f == "recursive" { Evaluation::Recursive } else { Evaluation::MassMatrix };
                        self.evaluation_span = f.span();
                    }
                    Arg::Flag(f) if f == "augmented" || f == "minimal" => {
                        self.loop_form = if f == "augmented" { LoopForm::Augmented } else { LoopForm::Minimal };
                        self.loop_form_span = f.span();
                    }
                    Arg::Flag(f) => errors.at(
                        f.span(),
                        format!("unknown mechanism option `{f}`, expected one of `planar`, `spatial`, `jacobian`, `geometry`, `inverse_dynamics`, `recursive`, `mass_matrix`, `augmented`, `minimal`"),
                    ),
                    Arg::Keyed(k, _) => errors.at(k.span(), format!("unknown mechanism option `{k}`")),
                    Arg::Other(e) => errors.at(e.span(), "expected a mechanism option"),
                }
        }
    }

    /// `#[gravity(..)]`: also the dimension, when `mechanism` did not give it.
    fn gravity(&mut self, attr: &Attribute, dim_given: bool, errors: &mut Errors) {
        // The span of `(..)`: one group, so it covers all arguments on stable.
        let args_span = match &attr.meta {
            syn::Meta::List(l) => l.delimiter.span().join(),
            _ => attr.path().span(),
        };
        let list = attr.parse_args_with(Punctuated::<Expr, Token![,]>::parse_terminated);
        match list {
            Ok(list) => {
                let items: Vec<Expr> = list.into_iter().collect();
                if !matches!(items.len(), 2 | 3) {
                    let n = items.len();
                    errors.at(
                        args_span,
                        format!(
                            "`gravity` has {n} component{}: it is the acceleration of free \
                             fall as a vector, `#[gravity(0.0, -g)]` in a plane (`y` up), \
                             `#[gravity(0.0, 0.0, -g)]` in space (`z` up)",
                            if n == 1 { "" } else { "s" }
                        ),
                    );
                    return;
                }
                if !dim_given {
                    self.dim = if items.len() == 3 {
                        Dim::Spatial
                    } else {
                        Dim::Planar
                    };
                    self.dim_span = args_span;
                }
                self.gravity = Some(syn::parse_quote_spanned!(args_span=> [#(#items),*]));
            }
            Err(e) => errors.push(e),
        }
    }

    /// `#[particle(..)]`, `#[rigid(..)]`, `#[rigid3(..)]`.
    fn free_body(&mut self, attr: &Attribute, name: &str, dim_given: bool, errors: &mut Errors) {
        let (kind, keys): (BodyKind, &[&str]) = match name {
            "particle" => (BodyKind::Particle, &["mass", "at"]),
            "rigid" => (BodyKind::Rigid, &["mass", "inertia", "at", "angle"]),
            _ => (BodyKind::Rigid3, &["mass", "inertia", "at", "rotation"]),
        };
        if let Some(mut item) = Item::read(attr, errors, keys, &[]) {
            if kind == BodyKind::Rigid3 && !dim_given {
                self.dim = Dim::Spatial;
                self.dim_span = item.name.span();
            }
            let orientation = match kind {
                BodyKind::Particle => None,
                BodyKind::Rigid => item.take("angle"),
                BodyKind::Rigid3 => item.take("rotation"),
            };
            self.bodies.push(Body {
                mass: item.require("mass", errors, "body"),
                inertia: item.take("inertia"),
                at: item.require("at", errors, "body"),
                orientation,
                kind,
                name: item.name,
            });
        }
    }

    /// `#[body(..)]`: a joint-tree body; `reaction` frees its joint.
    fn tree_body(&mut self, attr: &Attribute, errors: &mut Errors) {
        let keys = &["parent", "joint", "at", "angle", "com", "mass", "inertia"];
        if let Some(mut item) = Item::read(attr, errors, keys, &["reaction"]) {
            // `_rz` joins in a spatial mechanism, once the dimension is known.
            let reaction = (!item.flags.is_empty()).then(|| {
                let n = &item.name;
                let rx = format_ident!("{}_rx", n, span = n.span());
                let ry = format_ident!("{}_ry", n, span = n.span());
                self.relaxed.extend([rx.clone(), ry.clone()]);
                vec![rx, ry]
            });
            let joint_expr = item.require("joint", errors, "body");
            let joint_span = joint_expr.as_ref().map_or(item.name.span(), Spanned::span);
            let joint = joint_expr.and_then(|j| joint(j, errors));
            if let (Some(Joint::Free(..)), Some(flag)) = (&joint, item.flags.first()) {
                errors.at(flag.span(), "a free joint transmits no force: its origin already moves freely, so `reaction` would have nothing to report");
                return;
            }
            let parent = item.take("parent").and_then(|p| parent(p, errors));
            if let Some(joint) = joint {
                self.tree.push(TreeBody {
                    parent,
                    joint,
                    joint_span,
                    at: item.take("at"),
                    angle: item.take("angle"),
                    com: item.take("com"),
                    reaction,
                    mass: item.require("mass", errors, "body"),
                    inertia: item.take("inertia"),
                    name: item.name,
                });
            }
        }
    }

    /// `#[close(..)]`: a loop-closing joint.
    fn closure(&mut self, attr: &Attribute, errors: &mut Errors) {
        let keys = &[
            "a", "at_a", "b", "at_b", "joint", "axis_a", "axis_b", "normal_a", "normal_b",
        ];
        if let Some(mut item) = Item::read(attr, errors, keys, &[]) {
            let a = item.require("a", errors, "closure");
            let b = item.require("b", errors, "closure");
            let joint = item.take("joint").and_then(|j| close_joint(j, errors));
            if let (Some(a), Some(b)) = (a, b) {
                self.closures.push(Closure {
                    a: parent(a, errors),
                    at_a: item.take("at_a"),
                    b: parent(b, errors),
                    at_b: item.take("at_b"),
                    joint,
                    axis_a: item.take("axis_a"),
                    axis_b: item.take("axis_b"),
                    normal_a: item.take("normal_a"),
                    normal_b: item.take("normal_b"),
                    tokens: quote::ToTokens::to_token_stream(attr),
                });
            }
        }
    }

    fn spring(&mut self, attr: &Attribute, errors: &mut Errors) {
        if let Some(mut item) = Item::read(attr, errors, &["from", "to", "k", "length"], &[]) {
            let (from, to, k) = (
                item.require("from", errors, "spring"),
                item.require("to", errors, "spring"),
                item.require("k", errors, "spring"),
            );
            if let (Some(from), Some(to), Some(k)) = (from, to, k) {
                let length = item.take("length");
                self.springs.push(Spring {
                    name: item.name,
                    from: end(from),
                    to: end(to),
                    k,
                    length,
                });
            }
        }
    }

    fn damper(&mut self, attr: &Attribute, errors: &mut Errors) {
        if let Some(mut item) = Item::read(attr, errors, &["from", "to", "c"], &[]) {
            let (from, to, c) = (
                item.require("from", errors, "damper"),
                item.require("to", errors, "damper"),
                item.require("c", errors, "damper"),
            );
            if let (Some(from), Some(to), Some(c)) = (from, to, c) {
                self.dampers.push(Damper {
                    name: item.name,
                    from: end(from),
                    to: end(to),
                    c,
                });
            }
        }
    }

    /// `#[force(..)]`, `#[torque(..)]`, `#[generalized_force(..)]`.
    fn load(&mut self, attr: &Attribute, name: &str, errors: &mut Errors) {
        let key = match name {
            "force" => "at",
            "torque" => "on",
            _ => "along",
        };
        if let Some(mut item) = Item::read(attr, errors, &[key, "value"], &[]) {
            let target = item.require(key, errors, name);
            let value = item.require("value", errors, name);
            if let (Some(target), Some(value)) = (target, value) {
                match (name, classify(target)) {
                    ("force", Arg::Flag(id)) => self.loads.push(Load::Force {
                        at: syn::parse_quote!(#id),
                        value,
                    }),
                    ("force", Arg::Other(at)) => self.loads.push(Load::Force { at, value }),
                    ("torque", Arg::Flag(body)) => self.loads.push(Load::Torque { body, value }),
                    (_, Arg::Flag(coord)) if name == "generalized_force" => {
                        self.loads.push(Load::Generalized { coord, value })
                    }
                    (_, _) => errors.at(
                        item.name.span(),
                        format!("`{key}` of `{name}` must be a name"),
                    ),
                }
            }
        }
    }

    fn init(&mut self, attr: &Attribute, errors: &mut Errors) {
        match attr.parse_args_with(Punctuated::<Expr, Token![,]>::parse_terminated) {
            Ok(list) => {
                for e in list {
                    match init(e) {
                        Ok(i) => self.inits.push(i),
                        Err(e) => errors.push(e),
                    }
                }
            }
            Err(e) => errors.push(e),
        }
    }

    /// Each joint brings its coordinate: free, unless a `drive` gives its law; a freed
    /// spatial joint its `_rz` reaction too.
    fn joint_coordinates(&mut self, errors: &mut Errors) {
        let m = self;
        if m.dim == Dim::Spatial {
            for b in &mut m.tree {
                if let Some(reaction) = &mut b.reaction {
                    let n = &b.name;
                    let rz = format_ident!("{}_rz", n, span = n.span());
                    m.relaxed.push(rz.clone());
                    reaction.push(rz);
                }
            }
        }
        // Each joint brings its coordinate: free, unless a `drive` gives its law.
        let mut moved = std::collections::HashSet::new();
        for b in &m.tree {
            let coords = b.joint.coords();
            for (k, c) in coords.iter().copied().enumerate() {
                if coords[..k].contains(&c) {
                    let why = "each of the joint's degrees of freedom needs its own coordinate";
                    errors.at(
                        c.span(),
                        format!("coordinate `{c}` is named twice in this joint: {why}"),
                    );
                } else if !moved.insert(c.to_string()) {
                    errors.at(
                        c.span(),
                        format!("coordinate `{c}` is already moved by another joint"),
                    );
                } else if !m.coords.contains(c) && !m.drives.iter().any(|d| d.name == *c) {
                    m.coords.push(c.clone());
                }
            }
        }
    }

    /// Outputs, events and initial values named twice.
    fn duplicates(&self, errors: &mut Errors) {
        let m = self;
        let mut seen = std::collections::HashSet::new();
        for name in m.outputs.iter().map(|o| &o.name) {
            if !seen.insert(name.to_string()) {
                errors.at(name.span(), format!("duplicate output `{name}`"));
            }
        }
        let mut seen = std::collections::HashSet::new();
        for name in m.events.iter().map(|e| &e.name) {
            if !seen.insert(name.to_string()) {
                errors.at(name.span(), format!("duplicate event `{name}`"));
            }
        }
        let mut seen = std::collections::HashSet::new();
        for i in &m.inits {
            if !seen.insert((i.coord.to_string(), i.velocity)) {
                let what = if i.velocity { "velocity" } else { "position" };
                errors.at(
                    i.coord.span(),
                    format!("initial {what} of `{}` given twice", i.coord),
                );
            }
        }
    }
}

/// `revolute(q)` (planar), `revolute(q, x | y | z)` (spatial), `prismatic(s, axis)`,
/// `universal(a, b)`, `spherical(a, b, c)`, `ball(a, b, c)`, `free(x, y, z, s1, s2, s3)` or
/// `fixed`. Which joints suit the mechanism's
/// dimension is checked with the mechanics.
fn joint(e: Expr, errors: &mut Errors) -> Option<Joint> {
    const EXPECTED: &str = "expected a joint: `revolute(coordinate)` (planar), \
        `revolute(coordinate, x | y | z)` (spatial), `prismatic(coordinate, axis)`, \
        `universal(a, b)`, `spherical(a, b, c)`, `ball(a, b, c)`, \
        `free(x, y, z, s1, s2, s3)` (spatial, six degrees of freedom) or `fixed`";
    match &e {
        Expr::Path(p) if p.path.is_ident("fixed") => Some(Joint::Fixed),
        Expr::Call(c) => {
            let kind = match &*c.func {
                Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                _ => None,
            };
            let args: Vec<&Expr> = c.args.iter().collect();
            let name = |i: usize| match args.get(i).map(|a| classify((**a).clone())) {
                Some(Arg::Flag(id)) => Some(id),
                _ => None,
            };
            let elementary = |id: Ident| {
                ["x", "y", "z"]
                    .contains(&id.to_string().as_str())
                    .then_some(id)
            };
            match (kind.as_deref(), name(0), args.len()) {
                (Some("revolute"), Some(q), 1) => Some(Joint::Revolute {
                    coord: q,
                    axis: None,
                }),
                (Some("revolute"), Some(q), 2) if name(1).and_then(elementary).is_some() => {
                    Some(Joint::Revolute {
                        coord: q,
                        axis: name(1),
                    })
                }
                (Some("prismatic"), Some(s), 2) => Some(Joint::Prismatic {
                    coord: s,
                    axis: args[1].clone(),
                }),
                (Some("universal"), Some(a), 2) if name(1).is_some() => {
                    Some(Joint::Universal(a, name(1)?))
                }
                (Some("spherical"), Some(a), 3) if name(1).is_some() && name(2).is_some() => {
                    Some(Joint::Spherical(a, name(1)?, name(2)?))
                }
                (Some("ball"), Some(a), 3) if name(1).is_some() && name(2).is_some() => {
                    Some(Joint::Ball(a, name(1)?, name(2)?))
                }
                (Some("free"), Some(x), 6) if (1..6).all(|i| name(i).is_some()) => {
                    let n = |i: usize| name(i).expect("checked above");
                    Some(Joint::Free([x, n(1), n(2)], [n(3), n(4), n(5)]))
                }
                (Some("free"), ..) => {
                    errors.over(&e, "a free joint names its six coordinates: `free(x, y, z, s1, s2, s3)` (the joint origin's travel in the parent's axes, then a ball's rotation)");
                    None
                }
                _ => {
                    errors.over(&e, EXPECTED);
                    None
                }
            }
        }
        _ => {
            errors.over(&e, EXPECTED);
            None
        }
    }
}

/// A loop-closing joint's kind: `spherical`, `revolute`, `universal` or `prismatic`.
fn close_joint(e: Expr, errors: &mut Errors) -> Option<(CloseJoint, Span)> {
    let span = e.span();
    let kind = match classify(e) {
        Arg::Flag(id) => match id.to_string().as_str() {
            "spherical" => Some(CloseJoint::Spherical),
            "revolute" => Some(CloseJoint::Revolute),
            "universal" => Some(CloseJoint::Universal),
            "prismatic" => Some(CloseJoint::Prismatic),
            _ => None,
        },
        _ => None,
    };
    if kind.is_none() {
        errors.at(
            span,
            "a closing joint is `spherical`, `revolute`, `universal` or `prismatic` (its axes go in `axis_a`, `axis_b`, and for `prismatic` `normal_a`, `normal_b`)",
        );
    }
    kind.map(|k| (k, span))
}

/// A parent body's name, or `ground`.
fn parent(e: Expr, errors: &mut Errors) -> Option<Ident> {
    match classify(e) {
        Arg::Flag(id) if id == "ground" => None,
        Arg::Flag(id) => Some(id),
        Arg::Keyed(k, _) => {
            errors.at(k.span(), "`parent` names a body or `ground`");
            None
        }
        Arg::Other(e) => {
            errors.over(&e, "`parent` names a body or `ground`");
            None
        }
    }
}

/// `chain(link, n = 3, joint = revolute, length = l, mass = m, inertia = i)`: `n` identical
/// links `link_1 ..= link_n` hanging from `at` on `parent` (the ground's origin by default),
/// each turned by its relative angle `link_q1 ..` (zero: straight down, along the parent's
/// `-y`), mass centre at mid-length.
/// The most bodies (free, tree and chain links together) a model may have: the symbolic
/// stage's memory grows faster than the bodies (a 512-link chain builds in about a
/// minute; 1024 links ran out of 6 GB), so past this the derive stops with a spanned error
/// instead of exhausting the machine.
pub const MAX_BODIES: usize = 512;

fn too_many_bodies() -> String {
    format!(
        "a model has at most {MAX_BODIES} bodies (the derive's size limit: the symbolic stage's memory grows faster than the bodies)"
    )
}

fn chain(mut item: Item, tree: &mut Vec<TreeBody>, errors: &mut Errors) {
    let name = item.name.clone();
    let n = match item.require("n", errors, "chain") {
        Some(Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Int(i),
            ..
        })) => match i.base10_parse::<usize>() {
            Ok(n) if (1..=MAX_BODIES).contains(&n) => Some(n),
            Ok(n) if n > MAX_BODIES => {
                errors.at(i.span(), too_many_bodies());
                None
            }
            _ => {
                errors.at(i.span(), "a chain has `n >= 1` links");
                None
            }
        },
        Some(other) => {
            errors.over(&other, "`n` is the number of links, an integer literal");
            None
        }
        None => None,
    };
    match item.require("joint", errors, "chain") {
        Some(Expr::Path(p)) if p.path.is_ident("revolute") => {}
        Some(other) => errors.over(&other, "a chain's links are joined by `revolute` joints"),
        None => {}
    }
    let length = item.require("length", errors, "chain");
    let mass = item.require("mass", errors, "chain");
    let inertia = item.take("inertia");
    let mut parent_name = item.take("parent").and_then(|p| parent(p, errors));
    let at = item.take("at");
    let (Some(n), Some(length)) = (n, length) else {
        return;
    };
    let span = name.span();
    for k in 1..=n {
        let body = format_ident!("{}_{}", name, k, span = span);
        let coord = format_ident!("{}_q{}", name, k, span = span);
        tree.push(TreeBody {
            name: body.clone(),
            parent: parent_name.replace(body),
            joint: Joint::Revolute { coord, axis: None },
            joint_span: span,
            at: if k == 1 {
                at.clone()
            } else {
                Some(syn::parse_quote_spanned!(span=> [0.0, -(#length)]))
            },
            angle: None,
            com: Some(syn::parse_quote_spanned!(span=> [0.0, -(#length) / 2.0])),
            reaction: None,
            mass: mass.clone(),
            inertia: inertia.clone(),
        });
    }
}

fn init(e: Expr) -> syn::Result<Init> {
    let span = e.span();
    let Expr::Assign(a) = e else {
        return Err(syn::Error::new(
            span,
            "expected `coordinate = value` or `der(coordinate) = value`",
        ));
    };
    let (coord, velocity) = match &*a.left {
        Expr::Path(p) if p.path.get_ident().is_some() => {
            (p.path.get_ident().cloned().expect("checked"), false)
        }
        Expr::Call(c)
            if matches!(&*c.func, Expr::Path(p) if p.path.is_ident("der")) && c.args.len() == 1 =>
        {
            match &c.args[0] {
                Expr::Path(p) if p.path.get_ident().is_some() => {
                    (p.path.get_ident().cloned().expect("checked"), true)
                }
                other => {
                    return Err(syn::Error::new(
                        other.span(),
                        "`der` takes a coordinate name",
                    ));
                }
            }
        }
        other => {
            return Err(syn::Error::new(
                other.span(),
                "expected `coordinate` or `der(coordinate)`",
            ));
        }
    };
    Ok(Init {
        coord,
        velocity,
        value: *a.right,
    })
}

fn params(input: &DeriveInput, errors: &mut Errors) -> syn::Result<Vec<Param>> {
    let Data::Struct(data) = &input.data else {
        return Err(syn::Error::new(
            input.ident.span(),
            "`Mechanism` is derived for a struct of parameters",
        ));
    };
    if !input.generics.params.is_empty() {
        return Err(syn::Error::new(
            input.generics.span(),
            "a mechanism's parameter struct cannot be generic",
        ));
    }
    let fields = match &data.fields {
        Fields::Named(f) => f.named.iter().collect::<Vec<_>>(),
        Fields::Unit => Vec::new(),
        Fields::Unnamed(f) => {
            return Err(syn::Error::new(
                f.span(),
                "parameters are named fields of type `f64`",
            ));
        }
    };
    let mut out = Vec::new();
    for field in fields {
        let name = field.ident.clone().expect("named field");
        if !matches!(&field.ty, syn::Type::Path(p) if p.path.is_ident("f64")) {
            errors.at(
                field.ty.span(),
                format!("parameter `{name}` must be an `f64`"),
            );
        }
        let mut default = None;
        for attr in &field.attrs {
            if attr.path().is_ident("default") {
                match attr.parse_args::<Expr>() {
                    Ok(e) => default = Some(e),
                    Err(e) => errors.push(e),
                }
            }
        }
        out.push(Param { name, default });
    }
    Ok(out)
}

/// `#[friction(along = s, mu = .., normal = ..)]` (`mu_k`, `mu_s`/`mu_static` optional).
fn friction(attr: &Attribute, list: Vec<Arg>, errors: &mut Errors) -> Option<Friction> {
    let (mut along, mut mu, mut normal, mut mu_static) = (None, None, None, None);
    for arg in list {
        match arg {
            Arg::Keyed(k, v) if k == "along" => match classify(v) {
                Arg::Flag(c) => along = Some(c),
                _ => errors.at(k.span(), "`along` names a coordinate"),
            },
            // `mu` is both coefficients unless `mu_s` is given;
            // `mu_k` names the kinetic one alone.
            Arg::Keyed(k, v) if k == "mu" || k == "mu_k" => {
                if mu.is_some() {
                    errors.at(k.span(), "`friction` takes one of `mu` and `mu_k` (the kinetic coefficient)");
                }
                mu = Some(v)
            }
            Arg::Keyed(k, v) if k == "normal" => normal = Some(v),
            Arg::Keyed(k, v) if k == "mu_s" || k == "mu_static" => {
                if mu_static.is_some() {
                    errors.at(k.span(), "`friction` takes one of `mu_s` and `mu_static` (the static coefficient)");
                }
                mu_static = Some(v)
            }
            Arg::Keyed(k, _) | Arg::Flag(k) => errors.at(
                k.span(),
                format!("unknown key `{k}` in `friction`, expected one of `along`, `mu`, `mu_k`, `mu_s`, `mu_static`, `normal`"),
            ),
            Arg::Other(e) => errors.at(e.span(), "expected `key = value` in `friction`"),
        }
    }
    match (along, mu, normal) {
        (Some(along), Some(mu), Some(normal)) => Some(Friction {
            along,
            mu,
            mu_static,
            normal,
            span: attr.span(),
        }),
        (along, mu, normal) => {
            let keys = [
                ("`along`", along.is_none()),
                ("`mu`", mu.is_none()),
                ("`normal`", normal.is_none()),
            ];
            let missing: Vec<&str> = keys.iter().filter(|k| k.1).map(|k| k.0).collect();
            let msg = format!(
                "`friction` needs `along`, `mu` (or `mu_k`) and `normal`; missing: {}",
                missing.join(", ")
            );
            errors.over(attr, msg);
            None
        }
    }
}

/// `#[event(name = expr, rising | falling, terminal)]`.
fn event(attr: &Attribute, list: Vec<Arg>, errors: &mut Errors) -> Option<Event> {
    let mut it = list.into_iter();
    let Some(Arg::Keyed(name, expr)) = it.next() else {
        errors.over(attr, "an event starts with `name = <expression>`");
        return None;
    };
    let mut ev = Event {
        name,
        expr,
        direction: Direction::Either,
        terminal: false,
    };
    for arg in it {
        match arg {
            Arg::Flag(f) if f == "rising" => ev.direction = Direction::Rising,
            Arg::Flag(f) if f == "falling" => ev.direction = Direction::Falling,
            Arg::Flag(f) if f == "terminal" => ev.terminal = true,
            Arg::Flag(f) | Arg::Keyed(f, _) => errors.at(
                f.span(),
                format!(
                    "unknown event option `{f}`, expected one of `rising`, `falling`, `terminal`"
                ),
            ),
            Arg::Other(e) => errors.at(e.span(), "expected an event option"),
        }
    }
    Some(ev)
}
