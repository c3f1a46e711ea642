//! Stage 2: the parsed (and checked) model -> its `syn`-free description, lowered once, up front.
//!
//! Every expression of every attribute (and of the drawn shapes) becomes a [`Term`]: the
//! expression language's own tree (numbers, names, named constants, `+ - * /`, calls,
//! vectors, indexing), with the spans its errors need and nothing of `syn`. Everything the
//! syntax alone can refuse is refused here, for the whole model at once, each error at its
//! span: literals that are not finite numbers, unknown functions and wrong arities, `^`
//! and `==`, paths that are not constants, indices that are not integers, unsupported
//! expressions. What a name means, and what a body query answers, is the mechanics' part:
//! `lower::Lowerer` evaluates terms over the model's names into symbolic values.

use crate::geometry::Shape;
use crate::lower::{FUNCTIONS, path_constant};
use crate::parse::{
    Body, Closure, Constraint, Damper, End, Errors, Event, Friction, Init, Joint, Load, Mechanism,
    Named, Param, Point, Spring, TreeBody,
};
use proc_macro2::{Punct, Spacing, Span, TokenStream};
use syn::spanned::Spanned;
use syn::{Ident, LitInt};

/// One lowered expression: its kind and its extent (first and last token), so that an
/// error can point at a part or span the whole, as it would on the source.
#[derive(Clone, Debug)]
pub struct Term {
    pub kind: Kind,
    pub first: Span,
    pub last: Span,
}

#[derive(Clone, Debug)]
pub enum Kind {
    /// A finite number.
    Number(f64),
    /// A bare name: a parameter, coordinate, point, body, `t` or a named constant.
    Name(Ident),
    /// A constant by path (`std::f64::consts::PI`), with its source text.
    Constant(f64, String),
    /// Parentheses, an invisible group or a cast (`x as f64`): the value of the inside.
    Wrap(Box<Term>),
    Neg(Box<Term>),
    Binary(Op, Box<Term>, Box<Term>),
    Array(Vec<Term>),
    Index(Box<Term>, usize),
    /// A call of a known function with its arity checked (`f(x)` or `x.f()`).
    Call(Ident, Vec<Term>),
    /// Refused, its error already reported.
    Invalid,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Op {
    Add,
    Sub,
    Mul,
    Div,
}

impl Term {
    /// The same term, extending to `last`.
    fn until(self, last: Span) -> Term {
        Term { last, ..self }
    }

    /// The value of a constant scalar term, with `env` for names (the parameters'
    /// defaults); `None` when it is not one (as `check::fold` on the source).
    pub fn fold(&self, env: &std::collections::HashMap<String, f64>) -> Option<f64> {
        match &self.kind {
            Kind::Number(v) | Kind::Constant(v, _) => Some(*v),
            Kind::Name(id) => {
                let name = id.to_string();
                env.get(&name)
                    .copied()
                    .or_else(|| crate::lower::named_constant(&name))
            }
            Kind::Wrap(x) => x.fold(env),
            Kind::Neg(x) => x.fold(env).map(|v| -v),
            Kind::Binary(op, l, r) => {
                let (x, y) = (l.fold(env)?, r.fold(env)?);
                match op {
                    Op::Add => Some(x + y),
                    Op::Sub => Some(x - y),
                    Op::Mul => Some(x * y),
                    Op::Div => Some(x / y),
                }
            }
            Kind::Call(name, args) => {
                let args: Option<Vec<f64>> = args.iter().map(|a| a.fold(env)).collect();
                crate::check::apply(&name.to_string(), &args?)
            }
            Kind::Array(_) | Kind::Index(..) | Kind::Invalid => None,
        }
    }

    /// Where the term is (its first token, as `syn` spans an expression on stable).
    pub fn span(&self) -> Span {
        self.first.join(self.last).unwrap_or(self.first)
    }
}

/// The term's extent as two tokens, so that `Errors::over` spans it from first to last.
impl quote::ToTokens for Term {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        for span in [self.first, self.last] {
            let mut p = Punct::new('#', Spacing::Alone);
            p.set_span(span);
            tokens.extend([proc_macro2::TokenTree::Punct(p)]);
        }
    }
}

/// The whole model, lowered: the parsed structure with every expression a [`Term`], and
/// the shapes `#[mechanism(geometry)]` draws.
pub struct Lowered {
    pub ast: Mechanism<Term>,
    pub shapes: Vec<Shape<Term>>,
}

/// Lowers every expression of `ast`, collecting every error.
pub fn lower(ast: &Mechanism, errors: &mut Errors) -> Lowered {
    // A default is refused as a whole when it is not a number (`Scope::parameters`): what
    // its syntax refuses is not reported apart.
    let params = ast
        .params
        .iter()
        .map(|p| Param {
            name: p.name.clone(),
            default: p
                .default
                .as_ref()
                .map(|e| term(e, &mut Errors::default(), None)),
        })
        .collect();
    let known = Known::of(ast);
    let mut l = |e: &syn::Expr| term(e, errors, Some(&known));
    let lowered = Mechanism {
        ident: ast.ident.clone(),
        params,
        dim: ast.dim,
        dim_span: ast.dim_span,
        gravity: ast.gravity.as_ref().map(&mut l),
        coords: ast.coords.clone(),
        drives: ast.drives.iter().map(|d| named(d, &mut l)).collect(),
        relaxed: ast.relaxed.clone(),
        constraints: ast
            .constraints
            .iter()
            .map(|c| Constraint {
                tokens: c.tokens.clone(),
                lhs: l(&c.lhs),
                rhs: l(&c.rhs),
            })
            .collect(),
        bodies: ast.bodies.iter().map(|b| body(b, &mut l)).collect(),
        tree: ast.tree.iter().map(|b| tree_body(b, &mut l)).collect(),
        closures: ast.closures.iter().map(|c| closure(c, &mut l)).collect(),
        points: ast
            .points
            .iter()
            .map(|p| Point {
                name: p.name.clone(),
                at: l(&p.at),
                on: p.on.clone(),
            })
            .collect(),
        springs: ast
            .springs
            .iter()
            .map(|s| Spring {
                name: s.name.clone(),
                from: end(&s.from, &mut l),
                to: end(&s.to, &mut l),
                k: l(&s.k),
                length: s.length.as_ref().map(&mut l),
            })
            .collect(),
        dampers: ast
            .dampers
            .iter()
            .map(|d| Damper {
                name: d.name.clone(),
                from: end(&d.from, &mut l),
                to: end(&d.to, &mut l),
                c: l(&d.c),
            })
            .collect(),
        loads: ast.loads.iter().map(|x| load(x, &mut l)).collect(),
        potentials: ast.potentials.iter().map(&mut l).collect(),
        frictions: ast
            .frictions
            .iter()
            .map(|f| Friction {
                along: f.along.clone(),
                mu: l(&f.mu),
                mu_static: f.mu_static.as_ref().map(&mut l),
                normal: l(&f.normal),
                span: f.span,
            })
            .collect(),
        outputs: ast.outputs.iter().map(|o| named(o, &mut l)).collect(),
        inputs: ast.inputs.clone(),
        events: ast
            .events
            .iter()
            .map(|e| Event {
                name: e.name.clone(),
                expr: l(&e.expr),
                direction: e.direction,
                terminal: e.terminal,
            })
            .collect(),
        inits: ast
            .inits
            .iter()
            .map(|i| Init {
                coord: i.coord.clone(),
                velocity: i.velocity,
                value: l(&i.value),
            })
            .collect(),
        jacobian: ast.jacobian,
        geometry: ast.geometry,
        inverse_dynamics: ast.inverse_dynamics,
        evaluation: ast.evaluation,
        evaluation_span: ast.evaluation_span,
        loop_form: ast.loop_form,
        loop_form_span: ast.loop_form_span,
    };
    let shapes = crate::geometry::shapes(ast)
        .into_iter()
        .map(|s| Shape {
            kind: s.kind,
            name: s.name,
            points: s.points.iter().map(&mut l).collect(),
        })
        .collect();
    Lowered {
        ast: lowered,
        shapes,
    }
}

fn named(n: &Named, l: &mut impl FnMut(&syn::Expr) -> Term) -> Named<Term> {
    Named {
        name: n.name.clone(),
        expr: l(&n.expr),
    }
}

fn end(e: &End, l: &mut impl FnMut(&syn::Expr) -> Term) -> End<Term> {
    match e {
        End::Named(id) => End::Named(id.clone()),
        End::At(e) => End::At(l(e)),
    }
}

fn load(x: &Load, l: &mut impl FnMut(&syn::Expr) -> Term) -> Load<Term> {
    match x {
        Load::Force { at, value } => Load::Force {
            at: l(at),
            value: l(value),
        },
        Load::Torque { body, value } => Load::Torque {
            body: body.clone(),
            value: l(value),
        },
        Load::Generalized { coord, value } => Load::Generalized {
            coord: coord.clone(),
            value: l(value),
        },
    }
}

fn body(b: &Body, l: &mut impl FnMut(&syn::Expr) -> Term) -> Body<Term> {
    Body {
        name: b.name.clone(),
        kind: b.kind,
        mass: b.mass.as_ref().map(&mut *l),
        inertia: b.inertia.as_ref().map(&mut *l),
        at: b.at.as_ref().map(&mut *l),
        orientation: b.orientation.as_ref().map(&mut *l),
    }
}

fn tree_body(b: &TreeBody, l: &mut impl FnMut(&syn::Expr) -> Term) -> TreeBody<Term> {
    let joint = match &b.joint {
        Joint::Revolute { coord, axis } => Joint::Revolute {
            coord: coord.clone(),
            axis: axis.clone(),
        },
        Joint::Prismatic { coord, axis } => Joint::Prismatic {
            coord: coord.clone(),
            axis: l(axis),
        },
        Joint::Universal(a, b) => Joint::Universal(a.clone(), b.clone()),
        Joint::Spherical(a, b, c) => Joint::Spherical(a.clone(), b.clone(), c.clone()),
        Joint::Ball(a, b, c) => Joint::Ball(a.clone(), b.clone(), c.clone()),
        Joint::Free(at, r) => Joint::Free(at.clone(), r.clone()),
        Joint::Fixed => Joint::Fixed,
    };
    TreeBody {
        name: b.name.clone(),
        parent: b.parent.clone(),
        joint,
        joint_span: b.joint_span,
        at: b.at.as_ref().map(&mut *l),
        angle: b.angle.as_ref().map(&mut *l),
        com: b.com.as_ref().map(&mut *l),
        reaction: b.reaction.clone(),
        mass: b.mass.as_ref().map(&mut *l),
        inertia: b.inertia.as_ref().map(&mut *l),
    }
}

fn closure(c: &Closure, l: &mut impl FnMut(&syn::Expr) -> Term) -> Closure<Term> {
    Closure {
        a: c.a.clone(),
        at_a: c.at_a.as_ref().map(&mut *l),
        b: c.b.clone(),
        at_b: c.at_b.as_ref().map(&mut *l),
        joint: c.joint,
        axis_a: c.axis_a.as_ref().map(&mut *l),
        axis_b: c.axis_b.as_ref().map(&mut *l),
        normal_a: c.normal_a.as_ref().map(&mut *l),
        normal_b: c.normal_b.as_ref().map(&mut *l),
        tokens: c.tokens.clone(),
    }
}

/// The names the model declares anywhere (parameters, coordinates free, driven and
/// relaxed, points, bodies) and `t`: a bare name outside them is refused at once. (Whether
/// a known name may stand where it does is the mechanics': a point used before its
/// declaration, a coordinate in a constant.) Each unknown name is reported once, where it
/// first appears.
pub struct Known {
    names: std::collections::HashSet<String>,
    struct_name: String,
    reported: std::cell::RefCell<std::collections::HashSet<String>>,
}

impl Known {
    fn of(ast: &Mechanism) -> Known {
        let names = (ast.params.iter().map(|p| &p.name))
            .chain(&ast.coords)
            .chain(ast.drives.iter().map(|d| &d.name))
            .chain(&ast.relaxed)
            .chain(ast.points.iter().map(|p| &p.name))
            .chain(ast.bodies.iter().map(|b| &b.name))
            .chain(ast.tree.iter().map(|b| &b.name))
            .map(|id| id.to_string())
            .chain(["t".to_string()])
            .collect();
        Known {
            names,
            struct_name: ast.ident.to_string(),
            reported: Default::default(),
        }
    }

    fn knows(&self, id: &Ident) -> bool {
        let name = id.to_string();
        self.names.contains(&name) || crate::lower::named_constant(&name).is_some()
    }
}

/// Lowers one expression, reporting what its syntax alone refuses, and (with `known`)
/// the names the model does not have.
pub fn term(e: &syn::Expr, errors: &mut Errors, known: Option<&Known>) -> Term {
    crate::guard::recurse(|| term_here(e, errors, known))
}

fn term_here(e: &syn::Expr, errors: &mut Errors, known: Option<&Known>) -> Term {
    use syn::Expr as E;
    let one = |kind, span: Span| Term {
        kind,
        first: span,
        last: span,
    };
    match e {
        E::Lit(lit) => one(number(&lit.lit, errors), lit.lit.span()),
        E::Paren(p) => one(
            Kind::Wrap(Box::new(term(&p.expr, errors, known))),
            p.paren_token.span.join(),
        ),
        E::Group(g) => one(
            Kind::Wrap(Box::new(term(&g.expr, errors, known))),
            g.group_token.span,
        ),
        E::Cast(c) => {
            let inner = term(&c.expr, errors, known);
            let last = quote::ToTokens::to_token_stream(&c.ty)
                .into_iter()
                .last()
                .map_or(c.as_token.span, |t| t.span());
            let first = inner.first;
            Term {
                kind: Kind::Wrap(Box::new(inner)),
                first,
                last,
            }
        }
        E::Path(p) => path(p, errors, known),
        E::Unary(u) => {
            let inner = term(&u.expr, errors, known);
            let last = inner.last;
            let first = u.op.span();
            let kind = match u.op {
                syn::UnOp::Neg(_) => Kind::Neg(Box::new(inner)),
                syn::UnOp::Deref(_) => {
                    let msg = "only unary `-` is supported; `**` is not a power in Rust: use `x.powi(2)` or `powf(x, y)`";
                    errors.at(u.span(), msg);
                    Kind::Invalid
                }
                _ => {
                    errors.at(u.span(), "only unary `-` is supported");
                    Kind::Invalid
                }
            };
            Term { kind, first, last }
        }
        E::Binary(b) => {
            let (l, r) = (term(&b.left, errors, known), term(&b.right, errors, known));
            let last = r.last;
            let op = match b.op {
                syn::BinOp::Add(_) => Some(Op::Add),
                syn::BinOp::Sub(_) => Some(Op::Sub),
                syn::BinOp::Mul(_) => Some(Op::Mul),
                syn::BinOp::Div(_) => Some(Op::Div),
                syn::BinOp::BitXor(_) => {
                    let msg = "`^` is not a power in Rust: use `x.powi(2)` or `powf(x, y)`";
                    errors.at(b.op.span(), msg);
                    None
                }
                syn::BinOp::Eq(_) => {
                    errors.at(b.op.span(), "`==` belongs only in `constraint(...)`");
                    None
                }
                other => {
                    let op = quote::ToTokens::to_token_stream(&other).to_string();
                    let msg = format!(
                        "`{op}` is not an operator of the language: it has `+`, `-`, `*`, `/` (and `==` in a constraint)"
                    );
                    errors.at(b.op.span(), msg);
                    None
                }
            };
            let first = l.first;
            let kind = op.map_or(Kind::Invalid, |op| {
                Kind::Binary(op, Box::new(l), Box::new(r))
            });
            Term { kind, first, last }
        }
        E::Array(a) => {
            let items = a.elems.iter().map(|x| term(x, errors, known)).collect();
            one(Kind::Array(items), a.bracket_token.span.join())
        }
        E::Index(i) => {
            let inner = term(&i.expr, errors, known);
            let first = inner.first;
            let k = match &*i.index {
                E::Lit(syn::ExprLit {
                    lit: syn::Lit::Int(k),
                    ..
                }) => index(k, errors),
                other => {
                    errors.at(other.span(), "index with a constant integer");
                    None
                }
            };
            let kind = k.map_or(Kind::Invalid, |k| Kind::Index(Box::new(inner), k));
            let last = i.bracket_token.span.join();
            Term { kind, first, last }
        }
        E::Call(c) => {
            let E::Path(p) = &*c.func else {
                errors.at(c.func.span(), "expected a function name");
                return one(Kind::Invalid, c.span());
            };
            let Some(name) = p.path.get_ident() else {
                let last = p.path.segments.last().map(|s| s.ident.to_string());
                let msg = match last {
                    Some(f) if FUNCTIONS.iter().any(|(n, _)| *n == f) => {
                        format!("write the function without a path: `{f}(..)`")
                    }
                    _ => "expected a function name".to_string(),
                };
                errors.at(p.span(), msg);
                return one(Kind::Invalid, c.span());
            };
            let args = arguments(name, c.args.iter(), errors, known);
            let kind = call(name, args, || c.span(), errors);
            one(kind, name.span()).until(c.paren_token.span.join())
        }
        E::MethodCall(m) => {
            let args = std::iter::once(&*m.receiver).chain(&m.args);
            let args = arguments(&m.method, args, errors, known);
            let first = args[0].first;
            let kind = call(&m.method, args, || m.span(), errors);
            one(kind, first).until(m.paren_token.span.join())
        }
        E::Field(f) => {
            let msg =
                "a vector has no fields: take a component by index, `v[0]`, `v[1]` (, `v[2]`)";
            errors.at(f.span(), msg);
            one(Kind::Invalid, f.span())
        }
        other => {
            let msg = "unsupported expression: use numbers, names, `+ - * /`, calls, `[..]`";
            errors.at(other.span(), msg);
            one(Kind::Invalid, other.span())
        }
    }
}

/// A literal as a finite number.
fn number(lit: &syn::Lit, errors: &mut Errors) -> Kind {
    let v = match lit {
        syn::Lit::Float(f) => f.base10_parse::<f64>(),
        syn::Lit::Int(i) => i.base10_parse::<f64>(),
        _ => {
            errors.at(lit.span(), "expected a number");
            return Kind::Invalid;
        }
    };
    match v {
        Ok(v) if v.is_finite() => Kind::Number(v),
        Ok(_) => {
            let msg = "this number is too large for an `f64` (it would be infinite)";
            errors.at(lit.span(), msg);
            Kind::Invalid
        }
        Err(err) => {
            errors.push(err);
            Kind::Invalid
        }
    }
}

fn index(k: &LitInt, errors: &mut Errors) -> Option<usize> {
    k.base10_parse::<usize>()
        .map_err(|_| errors.at(k.span(), "index with a constant integer"))
        .ok()
}

/// A bare name, or a constant by path; any other path is refused.
fn path(p: &syn::ExprPath, errors: &mut Errors, known: Option<&Known>) -> Term {
    if let Some(id) = p.path.get_ident() {
        let span = id.span();
        let kind = match known {
            Some(k) if !k.knows(id) => {
                let name = id.to_string();
                if k.reported.borrow_mut().insert(name.clone()) {
                    let declared = k.names.iter().map(String::as_str);
                    errors.at(
                        span,
                        crate::lower::unknown_name(&name, &k.struct_name, declared),
                    );
                }
                Kind::Invalid
            }
            _ => Kind::Name(id.clone()),
        };
        return Term {
            kind,
            first: span,
            last: span,
        };
    }
    // Rare (a constant by path, or a mistake): its tokens are worth making.
    let tokens = quote::ToTokens::to_token_stream(p);
    let mut spans = tokens.clone().into_iter().map(|t| t.span());
    let first = spans.next().unwrap_or_else(Span::call_site);
    let last = spans.last().unwrap_or(first);
    let kind = if let Some(v) = path_constant(&p.path) {
        Kind::Constant(v, tokens.to_string())
    } else {
        let last_name = p
            .path
            .segments
            .last()
            .map(|s| s.ident.to_string())
            .unwrap_or_default();
        let bad = [
            "NAN",
            "INFINITY",
            "NEG_INFINITY",
            "MAX",
            "MIN",
            "EPSILON",
            "MIN_POSITIVE",
        ];
        let why = if bad.contains(&last_name.as_str()) {
            format!("`{last_name}` is not a value a model can mean: use a finite number")
        } else {
            format!(
                "expected a parameter, coordinate or constant name; the constants are `{}` (also as `std::f64::consts::..`)",
                crate::lower::CONSTANTS
                    .iter()
                    .map(|c| c.0)
                    .collect::<Vec<_>>()
                    .join("`, `")
            )
        };
        errors.over(p, why);
        Kind::Invalid
    };
    Term { kind, first, last }
}

/// A call's arguments; the body or coordinate a body query or `reaction` names is the
/// mechanics' to judge (it says what is not a body), so it is not checked as a name here.
fn arguments<'e>(
    name: &Ident,
    args: impl Iterator<Item = &'e syn::Expr>,
    errors: &mut Errors,
    known: Option<&Known>,
) -> Vec<Term> {
    let fname = name.to_string();
    let query = crate::lower::BODY_QUERIES.contains(&fname.as_str()) || fname == "reaction";
    args.enumerate()
        .map(|(i, a)| term(a, errors, if query && i == 0 { None } else { known }))
        .collect()
}

/// The message for a function the language does not have, with what to write instead
/// where a common name from other languages or tools has a spelling here, else the known
/// function one typo away, else the list of functions.
fn unknown_function(fname: &str) -> String {
    let instead = match fname {
        "log" => Some("`ln(x)` (natural logarithm)"),
        "log10" => Some("`ln(x) / LN_10`"),
        "log2" => Some("`ln(x) / LN_2`"),
        "pow" => Some("`powi(x, n)` (integer n) or `powf(x, y)`"),
        "sqr" | "square" => Some("`powi(x, 2)`"),
        "cbrt" => Some("`powf(x, 1.0 / 3.0)`"),
        "arctan" | "atan2f" => Some("`atan(x)` or `atan2(y, x)`"),
        "fabs" => Some("`abs(x)`"),
        "omega" | "angular_vel" | "angvel" | "ang_vel" => Some("`angular_velocity(body)`"),
        "alpha" | "angular_acc" | "angacc" => Some("`angular_acceleration(body)`"),
        "speed" => Some("`norm(velocity(body))`"),
        "vel" => Some("`velocity(body)`"),
        "pos" | "location" => Some("`position(body)`"),
        "acc" | "accel" => Some("`acceleration(body)`"),
        "theta" | "orientation" => Some("`angle(body)`"),
        "d" | "dt" | "diff" | "derivative" | "ddt" => Some("`der(x)` (the time derivative)"),
        "force" | "constraint_force" => Some("`reaction(u)` of a relaxed or driven coordinate `u`"),
        "energy" | "kinetic_energy" | "potential_energy" => Some(
            "it out, e.g. `0.5 * m * dot(velocity(b), velocity(b))`; the model's total is `energy(t, q, qd)` at run time",
        ),
        _ => None,
    };
    let known = || FUNCTIONS.iter().map(|(n, _)| *n);
    if let Some(hint) = instead {
        format!("unknown function `{fname}`: write {hint}")
    } else if let Some(near) = crate::lower::closest(fname, known()).or_else(|| {
        known()
            .filter(|k| k.len() >= 3)
            .find(|k| fname.starts_with(k))
    }) {
        format!("unknown function `{fname}`: did you mean `{near}`?")
    } else {
        let all: Vec<&str> = known().collect();
        format!(
            "unknown function `{fname}`: the functions are {}",
            all.join(", ")
        )
    }
}

/// A call of a known function with the right number of arguments (`span`: the call's,
/// for the arity's error).
fn call(name: &Ident, args: Vec<Term>, span: impl Fn() -> Span, errors: &mut Errors) -> Kind {
    let fname = name.to_string();
    let Some(&(_, arity)) = FUNCTIONS.iter().find(|(n, _)| *n == fname) else {
        errors.at(name.span(), unknown_function(&fname));
        return Kind::Invalid;
    };
    let arity_ok = args.len() == arity
        || (crate::lower::BODY_QUERIES.contains(&fname.as_str()) && args.len() == 2);
    if !arity_ok {
        let msg = format!("`{fname}` takes {arity} argument(s), found {}", args.len());
        errors.at(span(), msg);
        return Kind::Invalid;
    }
    Kind::Call(name.clone(), args)
}
