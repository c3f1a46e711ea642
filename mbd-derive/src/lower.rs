//! Lowered user expressions ([`Term`]s, `lowered.rs`) -> symbolic values over the model's
//! names, with spanned errors: what a name means, whether a function or body query may
//! stand where it is, what the operands' shapes allow.
//!
//! The expression language is a small, smooth subset of Rust: numbers, names (parameters,
//! coordinates, `t`, `PI`), `+ - * /`, unary minus, calls of the functions in [`FUNCTIONS`]
//! in either style (`sin(x)` or `x.sin()`), vector literals `[a, b]`, indexing `v[0]`, and in
//! outputs the body queries (`velocity(rod)`, `reaction(ux)`, `der(x)`, ...).

use crate::lowered::{Kind, Op, Term};
use crate::parse::Errors;
use crate::sym::{Expr, Func, Graph};
use std::collections::HashMap;

/// A lowered value: a scalar, a vector (positions, velocities) or a 3x3 matrix (rotations).
#[derive(Clone, Debug)]
pub enum Value {
    Scalar(Expr),
    Vector(Vec<Expr>),
    Matrix([[Expr; 3]; 3]),
}

/// Where an expression stands decides what it may name.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Context {
    /// Drive laws and parameter-only values (mass, inertia, stiffness): `t` and parameters.
    Constant,
    /// Kinematics (positions, angles, constraints): coordinates too; only smooth functions.
    Kinematics,
    /// Forces: coordinates, `der(...)` of them.
    Force,
    /// Outputs and events: everything, including body queries and reactions.
    Output,
}

/// What a name stands for.
#[derive(Clone, Debug)]
pub enum Binding {
    Value(Value),
    /// A coordinate (its position symbol), free, driven or relaxed.
    Coord(Expr),
    /// A body, by index; only meaningful as the argument of a body query.
    Body(usize),
}

/// Functions the language knows, with their arity (for messages and checks).
pub const FUNCTIONS: &[(&str, usize)] = &[
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("asin", 1),
    ("acos", 1),
    ("atan", 1),
    ("sinh", 1),
    ("cosh", 1),
    ("tanh", 1),
    ("exp", 1),
    ("ln", 1),
    ("sqrt", 1),
    ("abs", 1),
    ("signum", 1),
    ("atan2", 2),
    ("hypot", 2),
    ("powi", 2),
    ("powf", 2),
    ("min", 2),
    ("max", 2),
    ("norm", 1),
    ("dot", 2),
    ("cross", 2),
    ("der", 1),
    ("rot_x", 1),
    ("rot_y", 1),
    ("rot_z", 1),
    ("diag", 3),
    ("reaction", 1),
    ("position", 1),
    ("velocity", 1),
    ("acceleration", 1),
    ("angle", 1),
    ("angular_velocity", 1),
    ("angular_acceleration", 1),
];

/// The named constants (those of `std::f64::consts`): written bare (`PI`) or by path
/// (`std::f64::consts::FRAC_PI_2`, `f64::consts::TAU`).
pub const CONSTANTS: &[(&str, f64)] = {
    use std::f64::consts as c;
    &[
        ("PI", c::PI),
        ("E", c::E),
        ("TAU", c::TAU),
        ("FRAC_PI_2", c::FRAC_PI_2),
        ("FRAC_PI_3", c::FRAC_PI_3),
        ("FRAC_PI_4", c::FRAC_PI_4),
        ("FRAC_PI_6", c::FRAC_PI_6),
        ("FRAC_PI_8", c::FRAC_PI_8),
        ("FRAC_1_PI", c::FRAC_1_PI),
        ("FRAC_2_PI", c::FRAC_2_PI),
        ("FRAC_2_SQRT_PI", c::FRAC_2_SQRT_PI),
        ("SQRT_2", c::SQRT_2),
        ("FRAC_1_SQRT_2", c::FRAC_1_SQRT_2),
        ("LN_2", c::LN_2),
        ("LN_10", c::LN_10),
        ("LOG2_E", c::LOG2_E),
        ("LOG10_E", c::LOG10_E),
        ("LOG2_10", c::LOG2_10),
        ("LOG10_2", c::LOG10_2),
    ]
};

/// A named constant by its bare name (`PI`).
pub fn named_constant(name: &str) -> Option<f64> {
    CONSTANTS.iter().find(|c| c.0 == name).map(|c| c.1)
}

/// A constant by path: `std::f64::consts::PI`, `core::f64::consts::PI`, `f64::consts::PI`,
/// `consts::PI`.
pub fn path_constant(path: &syn::Path) -> Option<f64> {
    let segs: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
    let (last, prefix) = segs.split_last()?;
    let ok = matches!(
        prefix
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>()
            .as_slice(),
        ["std" | "core", "f64", "consts"] | ["f64", "consts"] | ["consts"]
    );
    if ok { named_constant(last) } else { None }
}

/// The message for a name that is none of the model's, with a hint where a newcomer's
/// habit has a spelling here (`pi`, `x_dot`, `time`) or a declared name is one typo away.
pub fn unknown_name<'a>(
    name: &str,
    struct_name: &str,
    declared: impl IntoIterator<Item = &'a str>,
) -> String {
    let declared: Vec<&str> = declared.into_iter().collect();
    let upper = name.to_uppercase();
    let hint = if named_constant(&upper).is_some() {
        format!(": did you mean the constant `{upper}`?")
    } else if let Some(base) = name.strip_suffix("_dot").filter(|b| !b.is_empty()) {
        format!(": a coordinate's rate is written `der({base})`")
    } else if name == "time" {
        ": time is `t`".to_string()
    } else if let Some(rate) = crate::hints::rate(name, &declared) {
        format!(": if it is meant as a rate, write `{rate}`")
    } else if let Some(near) = closest(name, declared) {
        format!(": did you mean `{near}`?")
    } else {
        String::new()
    };
    format!(
        "unknown name `{name}`: not a parameter (field) of `{struct_name}`, a coordinate, a point or a body{hint}"
    )
}

/// The candidate one or two edits from `name` (one for names of up to four letters), if
/// exactly one is nearest: a typo's likely intent.
pub fn closest<'a>(name: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let limit = if name.chars().count() <= 4 { 1 } else { 2 };
    let near: Vec<(usize, &str)> = candidates
        .into_iter()
        .map(|c| (edits(name, c), c))
        .filter(|&(d, _)| d > 0 && d <= limit)
        .collect();
    let least = near.iter().map(|&(d, _)| d).min()?;
    let mut best = near.iter().filter(|&&(d, _)| d == least).map(|&(_, c)| c);
    let first = best.next()?;
    best.all(|c| c == first).then_some(first)
}

/// Levenshtein distance (insert, delete, substitute, and a swap of two neighbours).
fn edits(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let sub = d[i - 1][j - 1] + usize::from(a[i - 1] != b[j - 1]);
            d[i][j] = sub.min(d[i - 1][j] + 1).min(d[i][j - 1] + 1);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d[i][j] = d[i][j].min(d[i - 2][j - 2] + 1);
            }
        }
    }
    d[a.len()][b.len()]
}

/// Whether body query or `reaction` `fname` may stand in `ctx`: positions and angles are
/// kinematics (forces' points, spring and damper ends), velocities are forces' too;
/// accelerations and reactions would make the forces depend on the solution.
fn query_allowed(fname: &str, ctx: Context) -> bool {
    match ctx {
        Context::Output => true,
        Context::Force => !matches!(fname, "acceleration" | "angular_acceleration" | "reaction"),
        Context::Kinematics => {
            !BODY_QUERIES.contains(&fname) && fname != "reaction"
                || matches!(fname, "position" | "angle")
        }
        Context::Constant => !BODY_QUERIES.contains(&fname) && fname != "reaction",
    }
}

/// Where a refused body query can be written instead.
fn query_hint(fname: &str) -> &'static str {
    match fname {
        "position" | "angle" => " (and in forces, spring and damper ends and `force`'s `at`)",
        "velocity" | "angular_velocity" => " (and in force values)",
        _ => "",
    }
}

/// Body queries answered by [`Model::body`].
pub const BODY_QUERIES: &[&str] = &[
    "position",
    "velocity",
    "acceleration",
    "angle",
    "angular_velocity",
    "angular_acceleration",
];

/// Answers the questions an expression may ask about the model: time derivatives,
/// body kinematics, reactions. Implemented by the mechanics stage.
pub trait Model {
    /// Total time derivative `de/dt` (positions -> velocities -> accelerations).
    fn der(&mut self, g: &mut Graph, v: &Value) -> Value;
    /// A body query (`velocity(rod)`, `position(rod, [0.1, 0.0])`, ...), or why the body
    /// cannot answer it.
    fn body(
        &mut self,
        g: &mut Graph,
        query: &str,
        body: usize,
        offset: Option<Vec<Expr>>,
    ) -> Result<Value, String>;
    /// The symbol standing for the reaction along relaxed or driven coordinate `coord`.
    fn reaction(&mut self, g: &mut Graph, coord: Expr) -> Option<Expr>;
}

pub struct Lowerer<'a> {
    pub g: &'a mut Graph,
    pub names: &'a HashMap<String, Binding>,
    pub struct_name: &'a str,
    pub model: Option<&'a mut dyn Model>,
    pub errors: &'a mut Errors,
}

type Res = Result<Value, ()>;

impl Lowerer<'_> {
    /// Lower `e`, reporting errors (and returning `None`) on anything outside `ctx`.
    pub fn lower(&mut self, e: &Term, ctx: Context) -> Option<Value> {
        self.expr(e, ctx).ok()
    }

    /// Lower a scalar.
    pub fn scalar(&mut self, e: &Term, ctx: Context) -> Option<Expr> {
        match self.expr(e, ctx).ok()? {
            Value::Scalar(s) => Some(s),
            Value::Vector(v) => {
                let hint = format!(
                    "expected a scalar expression, found a vector of {} components: take one (`v[0]`), `norm(v)` or `dot(v, w)`",
                    v.len()
                );
                self.errors.at(e.span(), hint);
                None
            }
            Value::Matrix(_) => {
                let hint = "expected a scalar expression, found a 3x3 matrix: multiply it by a vector and take a component (`(m * v)[0]`)";
                self.errors.at(e.span(), hint);
                None
            }
        }
    }

    /// Lower a vector of `len` components (`len = 0`: any length).
    pub fn vector(&mut self, e: &Term, ctx: Context, len: usize) -> Option<Vec<Expr>> {
        match self.expr(e, ctx).ok()? {
            Value::Vector(v) if len == 0 || v.len() == len => Some(v),
            Value::Vector(v) => {
                let dims = if len == 2 {
                    "planar (2 components)"
                } else {
                    "spatial (3 components)"
                };
                // Spatial by a third gravity component is the surprise worth naming.
                let why = if len == 3 {
                    ": the mechanism is spatial (`gravity` of 3 components, or `#[mechanism(spatial)]`)"
                } else {
                    ": the mechanism is planar (by `#[mechanism(planar)]`, or by default: spatial needs `#[mechanism(spatial)]` or `gravity` of 3 components)"
                };
                let n = v.len();
                let s = if n == 1 { "" } else { "s" };
                self.errors.at(
                    e.span(),
                    format!("expected a {dims} vector, found {n} component{s}{why}"),
                );
                None
            }
            _ => {
                self.errors.at(
                    e.span(),
                    format!("expected a vector `[..]` of {len} components"),
                );
                None
            }
        }
    }

    fn fail<T>(&mut self, span: proc_macro2::Span, msg: impl std::fmt::Display) -> Result<T, ()> {
        self.errors.at(span, msg);
        Err(())
    }

    /// One level of the recursion over `e`, on a stack that grows as it deepens (a sum of
    /// thousands of terms nests once per term).
    fn expr(&mut self, e: &Term, ctx: Context) -> Res {
        crate::guard::recurse(|| self.expr_here(e, ctx))
    }

    fn expr_here(&mut self, e: &Term, ctx: Context) -> Res {
        match &e.kind {
            Kind::Number(v) => Ok(Value::Scalar(self.g.constant(*v))),
            Kind::Constant(v, _) => Ok(Value::Scalar(self.g.constant(*v))),
            Kind::Wrap(inner) => self.expr(inner, ctx),
            Kind::Name(id) => self.path(id, ctx),
            Kind::Neg(inner) => {
                let v = self.expr(inner, ctx)?;
                Ok(self.map(v, |g, x| g.neg(x)))
            }
            Kind::Binary(op, l, r) => {
                let l = self.expr(l, ctx)?;
                let r = self.expr(r, ctx)?;
                let v = self.binary(e, *op, l, r)?;
                self.finite_constant(e, v)
            }
            Kind::Array(elems) => {
                let mut items = Vec::new();
                let mut rows = Vec::new();
                for el in elems {
                    match self.expr(el, ctx)? {
                        Value::Scalar(s) => items.push(s),
                        Value::Vector(v) if v.len() == 3 => rows.push(v),
                        _ => return self.fail(el.span(), "vector components must be scalars"),
                    }
                }
                match (items.is_empty(), rows.len()) {
                    (false, 0) => Ok(Value::Vector(items)),
                    (true, 3) => Ok(Value::Matrix([
                        [rows[0][0], rows[0][1], rows[0][2]],
                        [rows[1][0], rows[1][1], rows[1][2]],
                        [rows[2][0], rows[2][1], rows[2][2]],
                    ])),
                    _ => self.fail(
                        e.span(),
                        "expected `[x, y]`, `[x, y, z]` or a 3x3 matrix `[[..], [..], [..]]`",
                    ),
                }
            }
            Kind::Index(inner, k) => match self.expr(inner, ctx)? {
                Value::Vector(v) if *k < v.len() => Ok(Value::Scalar(v[*k])),
                _ => self.fail(e.span(), "index out of range, or not a vector"),
            },
            Kind::Call(name, args) => self.call(name, args, ctx, e.span()),
            Kind::Invalid => Err(()),
        }
    }

    fn path(&mut self, id: &syn::Ident, ctx: Context) -> Res {
        let name = id.to_string();
        if name == "t" {
            let t = self.g.symbol("t");
            return Ok(Value::Scalar(t));
        }
        match self.names.get(&name) {
            Some(Binding::Value(v)) => Ok(v.clone()),
            Some(Binding::Coord(c)) => {
                if ctx == Context::Constant {
                    self.fail(
                        id.span(),
                        format!(
                            "`{name}` is a coordinate: not allowed here (only `t` and parameters)"
                        ),
                    )
                } else {
                    Ok(Value::Scalar(*c))
                }
            }
            Some(Binding::Body(_)) => self.fail(
                id.span(),
                format!("`{name}` is a body: use `position({name})`, `velocity({name})`, ..."),
            ),
            None => match named_constant(&name) {
                Some(v) => Ok(Value::Scalar(self.g.constant(v))),
                None => {
                    let declared = self.names.keys().map(String::as_str);
                    self.fail(id.span(), unknown_name(&name, self.struct_name, declared))
                }
            },
        }
    }

    /// A constant that folded to NaN or infinity (`0.0 / 0.0`, `1.0 / (2.0 - 2.0)`) is a
    /// mistake: refused here rather than emitted into the code.
    fn finite_constant(&mut self, e: &Term, v: Value) -> Res {
        let bad = match &v {
            Value::Scalar(s) => self.g.as_const(*s).filter(|x| !x.is_finite()),
            _ => None,
        };
        match bad {
            Some(x) => {
                let msg = format!(
                    "this constant expression is {x}, not a finite number (a division by zero?)"
                );
                self.errors.over(e, msg);
                Err(())
            }
            None => Ok(v),
        }
    }

    fn map(&mut self, v: Value, f: impl Fn(&mut Graph, Expr) -> Expr) -> Value {
        match v {
            Value::Scalar(s) => Value::Scalar(f(self.g, s)),
            Value::Vector(v) => Value::Vector(v.into_iter().map(|x| f(self.g, x)).collect()),
            Value::Matrix(m) => Value::Matrix(m.map(|row| row.map(|x| f(self.g, x)))),
        }
    }

    fn binary(&mut self, b: &Term, op: Op, l: Value, r: Value) -> Res {
        use Op as B;
        let g = &mut *self.g;
        match (op, l, r) {
            (B::Add, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(g.add(x, y))),
            (B::Sub, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(g.sub(x, y))),
            (B::Mul, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(g.mul(x, y))),
            (B::Div, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(g.div(x, y))),
            (B::Add, Value::Vector(x), Value::Vector(y)) if x.len() == y.len() => Ok(
                Value::Vector(x.iter().zip(&y).map(|(a, b)| g.add(*a, *b)).collect()),
            ),
            (B::Sub, Value::Vector(x), Value::Vector(y)) if x.len() == y.len() => Ok(
                Value::Vector(x.iter().zip(&y).map(|(a, b)| g.sub(*a, *b)).collect()),
            ),
            (B::Mul, Value::Scalar(s), Value::Vector(v))
            | (B::Mul, Value::Vector(v), Value::Scalar(s)) => {
                Ok(Value::Vector(v.iter().map(|x| g.mul(s, *x)).collect()))
            }
            (B::Div, Value::Vector(v), Value::Scalar(s)) => {
                Ok(Value::Vector(v.iter().map(|x| g.div(*x, s)).collect()))
            }
            (B::Mul, Value::Matrix(a), Value::Matrix(c)) => Ok(Value::Matrix(matmul(g, &a, &c))),
            (B::Mul, Value::Matrix(a), Value::Vector(v)) if v.len() == 3 => {
                Ok(Value::Vector((0..3).map(|i| g.dot(&a[i], &v)).collect()))
            }
            _ => self.fail(
                b.span(),
                "operands do not match (scalar, vector or matrix of the wrong size)",
            ),
        }
    }

    /// A call of a known function with the right arguments' count (checked by lowering):
    /// whether it may stand in `ctx`, then its value.
    fn call(
        &mut self,
        name: &syn::Ident,
        args: &[Term],
        ctx: Context,
        span: proc_macro2::Span,
    ) -> Res {
        let fname = name.to_string();
        if !query_allowed(&fname, ctx) {
            return self.fail(
                name.span(),
                format!(
                    "`{fname}(..)` is only available in outputs and events{}",
                    query_hint(&fname)
                ),
            );
        }
        if ctx == Context::Kinematics && matches!(fname.as_str(), "abs" | "signum" | "min" | "max")
        {
            return self.fail(
                name.span(),
                format!("`{fname}` is not smooth: kinematics must be differentiable twice (no abs, signum, min, max)"),
            );
        }
        if fname == "der" {
            if ctx == Context::Kinematics {
                return self.fail(
                    name.span(),
                    "`der(..)` is not allowed in kinematics or constants",
                );
            }
            if ctx == Context::Constant {
                return self.fail(
                    name.span(),
                    "`der(..)` is not allowed in a constant (a coefficient, mass, stiffness, \
                     length or initial value): a velocity-dependent load is a force \
                     (`damper`, `generalized_force`, or in a friction's `normal`)",
                );
            }
            let v = self.expr(&args[0], ctx)?;
            let Some(model) = self.model.as_deref_mut() else {
                return self.fail(name.span(), "`der(..)` is not available here");
            };
            return Ok(model.der(self.g, &v));
        }
        if BODY_QUERIES.contains(&fname.as_str()) {
            return self.body_query(name, args, ctx);
        }
        if fname == "reaction" {
            return self.reaction(name, args);
        }
        let vals = args
            .iter()
            .map(|a| self.expr(a, ctx))
            .collect::<Result<Vec<_>, _>>()?;
        self.function(&fname, args, &vals, span)
    }

    /// `position(b)`, `velocity(b, [..])`, ..: answered by the model.
    fn body_query(&mut self, name: &syn::Ident, args: &[Term], ctx: Context) -> Res {
        let fname = name.to_string();
        let body = match &args[0].kind {
            Kind::Name(id) if let Some(Binding::Body(b)) = self.names.get(&id.to_string()) => *b,
            Kind::Name(_) | Kind::Constant(..) => {
                let text = match &args[0].kind {
                    Kind::Constant(_, text) => text.clone(),
                    Kind::Name(id) => id.to_string(),
                    _ => unreachable!("matched above"),
                };
                let mut msg = format!("`{fname}` takes a body name; `{text}` is not a body");
                if let Some(Binding::Value(Value::Vector(_))) = self.names.get(&text) {
                    msg += &format!(
                        ": `{text}` is a point, a vector already (write `{text}`); for a point fixed to a body, ask the body: `{fname}(body, [offset])`"
                    );
                }
                return self.fail(args[0].span(), msg);
            }
            Kind::Invalid => return Err(()),
            _ => return self.fail(args[0].span(), format!("`{fname}` takes a body name")),
        };
        let offset = match args.get(1) {
            Some(e) => match self.expr(e, ctx)? {
                Value::Vector(v) => Some(v),
                _ => return self.fail(e.span(), "the offset is a body-fixed vector `[..]`"),
            },
            None => None,
        };
        let Some(model) = self.model.as_deref_mut() else {
            return self.fail(name.span(), format!("`{fname}` is not available here"));
        };
        match model.body(self.g, &fname, body, offset) {
            Ok(v) => Ok(v),
            Err(why) => self.fail(name.span(), why),
        }
    }

    /// `reaction(u)`: the reaction along a relaxed or driven coordinate.
    fn reaction(&mut self, name: &syn::Ident, args: &[Term]) -> Res {
        let coord = match &args[0].kind {
            Kind::Name(id) if let Some(Binding::Coord(c)) = self.names.get(&id.to_string()) => *c,
            Kind::Name(_) | Kind::Constant(..) => {
                let msg = "`reaction` takes a relaxed or driven coordinate";
                return self.fail(args[0].span(), msg);
            }
            Kind::Invalid => return Err(()),
            _ => return self.fail(args[0].span(), "`reaction` takes a coordinate name"),
        };
        let Some(model) = self.model.as_deref_mut() else {
            return self.fail(name.span(), "`reaction` is not available here");
        };
        match model.reaction(self.g, coord) {
            Some(r) => Ok(Value::Scalar(r)),
            None => self.fail(
                args[0].span(),
                "`reaction` needs a `relaxed` or driven coordinate",
            ),
        }
    }

    /// The mathematical functions, on lowered arguments.
    fn function(
        &mut self,
        fname: &str,
        args: &[Term],
        vals: &[Value],
        span: proc_macro2::Span,
    ) -> Res {
        let g = &mut *self.g;
        let scalar = |v: &Value| match v {
            Value::Scalar(s) => Some(*s),
            _ => None,
        };
        let vector = |v: &Value| match v {
            Value::Vector(s) => Some(s.clone()),
            _ => None,
        };
        if let Some(f) = Func::from_name(fname)
            && let Some(x) = scalar(&vals[0])
        {
            return Ok(Value::Scalar(g.call(f, x)));
        }
        let two = (vals.first().and_then(scalar), vals.get(1).and_then(scalar));
        let out = match (fname, two) {
            ("atan2", (Some(y), Some(x))) => Value::Scalar(g.atan2(y, x)),
            ("hypot", (Some(x), Some(y))) => {
                let (x2, y2) = (g.powi(x, 2), g.powi(y, 2));
                let s = g.add(x2, y2);
                Value::Scalar(g.call(Func::Sqrt, s))
            }
            ("powf", (Some(x), Some(y))) => Value::Scalar(g.powf(x, y)),
            ("min", (Some(x), Some(y))) => Value::Scalar(g.min(x, y)),
            ("max", (Some(x), Some(y))) => Value::Scalar(g.max(x, y)),
            ("powi", (Some(x), Some(n))) => match g.as_const(n) {
                Some(k) if k.fract() == 0.0 && k.abs() < 64.0 => Value::Scalar(g.powi(x, k as i32)),
                _ => {
                    return self.fail(
                        args[1].span(),
                        "`powi` takes a constant integer exponent: for any other use `powf(x, y)`",
                    );
                }
            },
            ("rot_x" | "rot_y" | "rot_z", (Some(a), _)) => Value::Matrix(rotation(g, fname, a)),
            ("diag", _) => match (scalar(&vals[0]), scalar(&vals[1]), scalar(&vals[2])) {
                (Some(a), Some(b), Some(c)) => {
                    let z = g.zero();
                    Value::Matrix([[a, z, z], [z, b, z], [z, z, c]])
                }
                _ => return self.fail(span, "`diag` takes three scalars"),
            },
            ("norm", _) => match vector(&vals[0]) {
                Some(v) => {
                    let s = g.dot(&v, &v);
                    Value::Scalar(g.call(Func::Sqrt, s))
                }
                None => return self.fail(args[0].span(), "`norm` takes a vector"),
            },
            ("dot", _) => match (vector(&vals[0]), vector(&vals[1])) {
                (Some(a), Some(b)) if a.len() == b.len() => Value::Scalar(g.dot(&a, &b)),
                _ => return self.fail(span, "`dot` takes two vectors of one length"),
            },
            ("cross", _) => match (vector(&vals[0]), vector(&vals[1])) {
                (Some(a), Some(b)) if a.len() == 3 && b.len() == 3 => {
                    Value::Vector(cross(g, &a, &b).to_vec())
                }
                (Some(a), Some(b)) if a.len() == 2 && b.len() == 2 => {
                    let (p, q) = (g.mul(a[0], b[1]), g.mul(a[1], b[0]));
                    Value::Scalar(g.sub(p, q))
                }
                _ => return self.fail(span, "`cross` takes two vectors of one length"),
            },
            _ => return self.fail(span, format!("wrong argument kinds for `{fname}`")),
        };
        Ok(out)
    }
}

/// Elementary rotation matrices (world from body), right-handed.
pub fn rotation(g: &mut Graph, axis: &str, a: Expr) -> [[Expr; 3]; 3] {
    let (c, s) = (g.call(Func::Cos, a), g.call(Func::Sin, a));
    let ns = g.neg(s);
    let (o, z) = (g.one(), g.zero());
    match axis {
        "rot_x" => [[o, z, z], [z, c, ns], [z, s, c]],
        "rot_y" => [[c, z, s], [z, o, z], [ns, z, c]],
        _ => [[c, ns, z], [s, c, z], [z, z, o]],
    }
}

pub fn matmul(g: &mut Graph, a: &[[Expr; 3]; 3], b: &[[Expr; 3]; 3]) -> [[Expr; 3]; 3] {
    let mut out = [[g.zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let col = [b[0][j], b[1][j], b[2][j]];
            out[i][j] = g.dot(&a[i], &col);
        }
    }
    out
}

pub fn cross(g: &mut Graph, a: &[Expr], b: &[Expr]) -> [Expr; 3] {
    let mut c = [g.zero(); 3];
    for (i, ci) in c.iter_mut().enumerate() {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let (p, q) = (g.mul(a[j], b[k]), g.mul(a[k], b[j]));
        *ci = g.sub(p, q);
    }
    c
}

#[cfg(test)]
mod tests {
    use super::closest;

    #[test]
    fn a_typo_names_the_one_nearest_declared_name() {
        let names = ["length", "mass", "m", "theta", "th"];
        assert_eq!(closest("lenght", names), Some("length")); // a swap
        assert_eq!(closest("mas", names), Some("mass")); // a letter short
        assert_eq!(closest("thetta", names), Some("theta"));
        // Two at the same distance: no guess. Too far: no guess.
        assert_eq!(closest("ab", ["aa", "bb"]), None);
        assert_eq!(closest("velocity", names), None);
        // Short names allow one edit only.
        assert_eq!(closest("mxxs", names), None); // two edits from `mass`
    }
}
