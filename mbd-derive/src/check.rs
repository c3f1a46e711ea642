//! Stage 1b: what the attributes say must be something the mechanics can mean.
//!
//! Run between `parse` and `model`, on the raw attributes (which `parse` reduces, the last of
//! two contradicting flags winning) and on the AST. Three kinds of checks, each a spanned
//! error that says what to write instead:
//! - contradictions and repetitions: two `#[gravity]`, `planar` with `spatial`, `recursive`
//!   with `mass_matrix`, `augmented` with `minimal`, `rising` with `falling`, a flag or a `#[default]` given twice;
//! - names the macro generates (`chain(link, ..)`: `link_1 ..`, `link_q1 ..`;
//!   `body(b, .., reaction)`: `b_rx`, `b_ry`, `b_rz`; the state's `x_dot`) used for something
//!   else;
//! - physical constants folded with the parameters' `#[default]`s: a mass `-m` with
//!   `#[default(1.0)] m` is refused like `-1.0`; masses, inertias, stiffnesses, dampings,
//!   lengths and friction coefficients must have their sign, every default must be finite,
//!   and a mass or an inertia cannot depend on time (Kane's and Lagrange's forms would then
//!   disagree by `dm/dt qd`).
//!
//! A value that does not fold (a parameter without a default) is checked at run time by the
//! generated `check_parameters`.

use crate::lower;
use crate::parse::{BodyKind, Errors, Load, Mechanism};
use proc_macro2::Span;
use std::collections::{HashMap, HashSet};
use syn::punctuated::Punctuated;
use syn::{Attribute, DeriveInput, Expr, Ident, Token};

/// Every check of this module; all errors at once.
pub fn check(input: &DeriveInput, ast: &Mechanism) -> syn::Result<()> {
    let mut errors = Errors::default();
    repetitions(input, &mut errors);
    reserved_names(input, ast, &mut errors);
    let env = defaults(ast, &mut errors);
    constants(ast, &generated(input), &env, &mut errors);
    chain_lengths(input, &env, &mut errors);
    driven_loads(ast, &mut errors);
    for (name, a, b) in ast
        .springs
        .iter()
        .map(|s| (&s.name, &s.from, &s.to))
        .chain(ast.dampers.iter().map(|d| (&d.name, &d.from, &d.to)))
    {
        if same_ends(a, b) {
            errors.at(
                name.span(),
                format!("`{name}` joins an end to itself: give two different points or bodies"),
            );
        }
    }
    errors.finish()
}

fn list(attr: &Attribute) -> Vec<Expr> {
    attr.parse_args_with(Punctuated::<Expr, Token![,]>::parse_terminated)
        .map(|l| l.into_iter().collect())
        .unwrap_or_default()
}

fn flag(e: &Expr) -> Option<&Ident> {
    match e {
        Expr::Path(p) if p.qself.is_none() => p.path.get_ident(),
        _ => None,
    }
}

fn key(e: &Expr) -> Option<(&Ident, &Expr)> {
    match e {
        Expr::Assign(a) => flag(&a.left).map(|k| (k, &*a.right)),
        _ => None,
    }
}

/// Flags and attributes that may appear once, and pairs that contradict each other.
fn repetitions(input: &DeriveInput, errors: &mut Errors) {
    let mut gravity = false;
    let mut seen: HashMap<String, Span> = HashMap::new();
    const EXCLUSIVE: [(&str, &str, &str); 3] = [
        (
            "planar",
            "spatial",
            "a mechanism is either `planar` or `spatial`",
        ),
        (
            "recursive",
            "mass_matrix",
            "a tree is evaluated either `recursive`ly or through its `mass_matrix`",
        ),
        (
            "augmented",
            "minimal",
            "a closed loop is kept either `augmented` or in `minimal` coordinates",
        ),
    ];
    for attr in &input.attrs {
        if attr.path().is_ident("gravity") {
            if gravity {
                errors.over(attr, "`gravity` given twice: a mechanism has one `#[gravity(..)]` (the last would silently win)");
            }
            gravity = true;
        }
        if attr.path().is_ident("mechanism") {
            for f in list(attr).iter().filter_map(flag) {
                let name = f.to_string();
                if seen.insert(name.clone(), f.span()).is_some() {
                    errors.at(f.span(), format!("mechanism option `{f}` given twice"));
                }
                for (a, b, why) in EXCLUSIVE {
                    let other = if name == a {
                        b
                    } else if name == b {
                        a
                    } else {
                        continue;
                    };
                    if seen.contains_key(other) {
                        errors.at(
                            f.span(),
                            format!("`{f}` contradicts `{other}`: {why}; keep one"),
                        );
                    }
                }
            }
        }
        if attr.path().is_ident("event") {
            event_flags(attr, errors);
        }
    }
    for field in fields(input) {
        let mut given = false;
        for attr in field.attrs.iter().filter(|a| a.path().is_ident("default")) {
            if given {
                errors.over(attr, "`default` given twice for one parameter");
            }
            given = true;
        }
    }
}

fn event_flags(attr: &Attribute, errors: &mut Errors) {
    let mut flags: Vec<&Ident> = Vec::new();
    let args = list(attr);
    for f in args.iter().skip(1).filter_map(flag) {
        if flags.contains(&f) {
            errors.at(f.span(), format!("event option `{f}` given twice"));
        }
        let other = if f == "rising" {
            "falling"
        } else if f == "falling" {
            "rising"
        } else {
            ""
        };
        if flags.iter().any(|g| *g == other) {
            errors.at(
                f.span(),
                format!("`{f}` contradicts `{other}`: an event counts crossings in one direction; for both directions give neither"),
            );
        }
        flags.push(f);
    }
}

fn fields(input: &DeriveInput) -> Vec<&syn::Field> {
    match &input.data {
        syn::Data::Struct(s) => s.fields.iter().collect(),
        _ => Vec::new(),
    }
}

/// The names the macro makes up, with what makes them: `chain(link, n = 2, ..)` makes bodies
/// `link_1`, `link_2` and coordinates `link_q1`, `link_q2`; `body(b, .., reaction)` makes
/// relaxed coordinates `b_rx`, `b_ry` (and `b_rz` in space).
fn generated(input: &DeriveInput) -> HashMap<String, String> {
    let mut out = HashMap::new();
    for attr in &input.attrs {
        let args = list(attr);
        let Some(name) = args.first().and_then(flag) else {
            continue;
        };
        if attr.path().is_ident("chain") {
            let n = args.iter().filter_map(key).find(|(k, _)| *k == "n");
            let n = match n.map(|(_, v)| v) {
                Some(Expr::Lit(syn::ExprLit {
                    lit: syn::Lit::Int(i),
                    ..
                })) => i.base10_parse::<usize>().unwrap_or(0).min(10_000),
                _ => 0,
            };
            for k in 1..=n {
                let why = format!("`chain({name}, ..)` names its links");
                out.insert(format!("{name}_{k}"), why.clone());
                out.insert(format!("{name}_q{k}"), format!("{why}' angles"));
            }
        }
        if attr.path().is_ident("body")
            && args
                .iter()
                .skip(1)
                .filter_map(flag)
                .any(|f| f == "reaction")
        {
            for axis in ["rx", "ry", "rz"] {
                out.insert(
                    format!("{name}_{axis}"),
                    format!("`body({name}, .., reaction)` names its joint's free translations"),
                );
            }
        }
    }
    out
}

/// Generated names are reserved: a user's coordinate, body, point, element or parameter of
/// the same name would silently become the generated one (a particle moving with a chain's
/// angle). Reading them (`init`, outputs, `drive`) is their purpose and stays allowed.
fn reserved_names(input: &DeriveInput, ast: &Mechanism, errors: &mut Errors) {
    let reserved = generated(input);
    let mut user: Vec<Ident> = Vec::new();
    for attr in &input.attrs {
        let args = list(attr);
        let path = attr.path();
        if ["coords", "relaxed"].iter().any(|p| path.is_ident(p)) {
            user.extend(args.iter().filter_map(flag).cloned());
        }
        let named = [
            "particle", "rigid", "rigid3", "body", "point", "spring", "damper", "chain",
        ];
        if named.iter().any(|p| path.is_ident(p))
            && let Some(n) = args.first().and_then(flag)
        {
            // A chain's own name is not one of its generated names.
            user.push(n.clone());
            if n == "ground" && !path.is_ident("point") {
                let why = "`ground` is the fixed frame (`parent = ground`, `b = ground`): rename this one";
                errors.at(n.span(), why);
            }
        }
    }
    user.extend(ast.params.iter().map(|p| p.name.clone()));
    for tb in &ast.tree {
        // A joint coordinate the user wrote (a chain's own are generated and expected).
        if !is_chain_body(&reserved, &tb.name) {
            user.extend(tb.joint.coords().into_iter().cloned());
        }
    }
    for id in user {
        if let Some(why) = reserved.get(&id.to_string()) {
            errors.at(
                id.span(),
                format!("`{id}` is a name the macro generates ({why}): rename this one"),
            );
        }
    }
    // The state struct has a field `x` and `x_dot` per coordinate.
    let coords: HashSet<String> = ast.coords.iter().map(|c| c.to_string()).collect();
    for c in &ast.coords {
        if let Some(base) = c.to_string().strip_suffix("_dot")
            && coords.contains(base)
        {
            errors.at(
                c.span(),
                format!("`{c}` is the name of `{base}`'s velocity in the generated state: rename this coordinate"),
            );
        }
    }
}

fn is_chain_body(reserved: &HashMap<String, String>, body: &Ident) -> bool {
    reserved
        .get(&body.to_string())
        .is_some_and(|why| why.starts_with("`chain("))
}

/// Every parameter's default, folded; a default that is not finite is an error.
fn defaults(ast: &Mechanism, errors: &mut Errors) -> HashMap<String, f64> {
    let mut env = HashMap::new();
    for p in &ast.params {
        let Some(d) = &p.default else { continue };
        match fold(d, &HashMap::new()) {
            Some(v) if v.is_finite() => {
                env.insert(p.name.to_string(), v);
            }
            Some(v) => errors.over(
                d,
                format!("the default of `{}` is {v}, not a finite number", p.name),
            ),
            None => {}
        }
    }
    env
}

/// What a constant must be.
#[derive(Clone, Copy)]
enum Sign {
    Positive,
    NonNegative,
}

/// Value `e` of `what` (e.g. "the mass of `bob`"), folded with the defaults: finite and of
/// `sign`; `timeless`: it may not name `t`.
fn constant(
    e: &Expr,
    what: &str,
    sign: Sign,
    timeless: bool,
    env: &HashMap<String, f64>,
    errors: &mut Errors,
) {
    if timeless && names_time(e) {
        errors.over(
            e,
            format!("{what} depends on time `t`: a varying mass or inertia is not a rigid body (the equations would drop `dm/dt` terms); model the change as a force"),
        );
        return;
    }
    let Some(v) = fold(e, env) else { return };
    let with = if mentions_param(e, env) {
        " (with the parameters' defaults)"
    } else {
        ""
    };
    let bad = match sign {
        Sign::Positive => !(v > 0.0 && v.is_finite()),
        Sign::NonNegative => !(v >= 0.0 && v.is_finite()),
    };
    if bad {
        let need = match sign {
            Sign::Positive => "positive and finite",
            Sign::NonNegative => "zero or positive, and finite",
        };
        errors.over(e, format!("{what} is {}{with}: it must be {need}", show(v)));
    }
}

/// A number for a message: a few significant figures.
fn show(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-3..1e6).contains(&v.abs()) {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s.is_empty() || s == "-" {
            "0".into()
        } else {
            s.into()
        }
    } else {
        format!("{v:.4e}")
    }
}

fn constants(
    ast: &Mechanism,
    reserved: &HashMap<String, String>,
    env: &HashMap<String, f64>,
    errors: &mut Errors,
) {
    use Sign::*;
    for b in &ast.bodies {
        let name = &b.name;
        if let Some(m) = &b.mass {
            constant(
                m,
                &format!("the mass of `{name}`"),
                Positive,
                true,
                env,
                errors,
            );
        }
        match (b.kind, &b.inertia) {
            (BodyKind::Rigid, Some(i)) => constant(
                i,
                &format!("the inertia of `{name}`"),
                Positive,
                true,
                env,
                errors,
            ),
            (BodyKind::Rigid3, Some(i)) => tensor(i, name, true, env, errors),
            _ => {}
        }
    }
    for tb in &ast.tree {
        let name = &tb.name;
        // A chain's links share its values: checked (and reported) once, on the first.
        if is_chain_body(reserved, name) && !name.to_string().ends_with("_1") {
            continue;
        }
        if let Some(m) = &tb.mass {
            constant(
                m,
                &format!("the mass of `{name}`"),
                Positive,
                true,
                env,
                errors,
            );
        }
        match &tb.inertia {
            Some(i @ (Expr::Call(_) | Expr::Array(_))) => tensor(i, name, false, env, errors),
            Some(i) => constant(
                i,
                &format!("the inertia of `{name}`"),
                NonNegative,
                true,
                env,
                errors,
            ),
            None => {}
        }
    }
    for s in &ast.springs {
        constant(
            &s.k,
            &format!("the stiffness of spring `{}`", s.name),
            NonNegative,
            false,
            env,
            errors,
        );
        if let Some(l) = &s.length {
            constant(
                l,
                &format!("the length of spring `{}`", s.name),
                NonNegative,
                false,
                env,
                errors,
            );
        }
    }
    for d in &ast.dampers {
        constant(
            &d.c,
            &format!("the damping of `{}`", d.name),
            NonNegative,
            false,
            env,
            errors,
        );
    }
    for f in &ast.frictions {
        let what = format!("the friction coefficient along `{}`", f.along);
        constant(&f.mu, &what, NonNegative, false, env, errors);
        if let Some(s) = &f.mu_static {
            constant(
                s,
                &format!("the static {}", &what[4..]),
                NonNegative,
                false,
                env,
                errors,
            );
        }
    }
}

/// A chain's `length`: positive, as the meaning of its angles needs (zero hangs straight
/// down; a negative length would point the links up and put every link at one point when
/// zero). Read from the raw attribute: the chain is already expanded into tree bodies.
fn chain_lengths(input: &DeriveInput, env: &HashMap<String, f64>, errors: &mut Errors) {
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("chain")) {
        let args = list(attr);
        let Some(name) = args.first().and_then(flag) else {
            continue;
        };
        if let Some((_, length)) = args.iter().filter_map(key).find(|(k, _)| *k == "length") {
            let what = format!("the length of chain `{name}`");
            constant(length, &what, Sign::Positive, false, env, errors);
        }
    }
}

/// A spatial inertia `diag(a, b, c)` or `[[..], [..], [..]]`: symmetric, and positive
/// definite (`definite`, a free `rigid3`) or semi-definite (a tree body, where a zero moment
/// is a thin rod about its own axis).
fn tensor(e: &Expr, body: &Ident, definite: bool, env: &HashMap<String, f64>, errors: &mut Errors) {
    if names_time(e) {
        errors.over(
            e,
            format!(
                "the inertia of `{body}` depends on time `t`: a varying inertia is not a rigid body"
            ),
        );
        return;
    }
    let entries: Option<[[f64; 3]; 3]> = match e {
        Expr::Call(c)
            if matches!(&*c.func, Expr::Path(p) if p.path.is_ident("diag"))
                && c.args.len() == 3 =>
        {
            let d: Vec<Option<f64>> = c.args.iter().map(|a| fold(a, env)).collect();
            match (d[0], d[1], d[2]) {
                (Some(a), Some(b), Some(c)) => Some([[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]]),
                _ => None,
            }
        }
        Expr::Array(rows) if rows.elems.len() == 3 => {
            let mut m = [[0.0; 3]; 3];
            let mut ok = true;
            for (i, r) in rows.elems.iter().enumerate() {
                match r {
                    Expr::Array(r) if r.elems.len() == 3 => {
                        for (j, x) in r.elems.iter().enumerate() {
                            match fold(x, env) {
                                Some(v) => m[i][j] = v,
                                None => ok = false,
                            }
                        }
                    }
                    _ => ok = false,
                }
            }
            ok.then_some(m)
        }
        _ => None,
    };
    let Some(m) = entries else { return };
    if m.iter().flatten().any(|v| !v.is_finite()) {
        errors.over(e, format!("the inertia of `{body}` is not finite"));
        return;
    }
    let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let asym = (0..3).any(|i| (0..3).any(|j| (m[i][j] - m[j][i]).abs() > 1e-12 * scale));
    if asym {
        errors.over(
            e,
            format!("the inertia of `{body}` is not symmetric: an inertia tensor is"),
        );
        return;
    }
    // Leading principal minors (Sylvester): all positive for a definite tensor; for a
    // semi-definite one every eigenvalue >= 0, checked by the characteristic polynomial's
    // coefficients (all principal minor sums >= 0).
    let d1 = m[0][0];
    let d2 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let d3 = det3(&m);
    let tol = 1e-12 * scale.max(f64::MIN_POSITIVE);
    let ok = if definite {
        d1 > 0.0 && d2 > 0.0 && d3 > 0.0
    } else {
        let trace = m[0][0] + m[1][1] + m[2][2];
        let minors =
            d2 + (m[0][0] * m[2][2] - m[0][2] * m[2][0]) + (m[1][1] * m[2][2] - m[1][2] * m[2][1]);
        trace >= -tol && minors >= -tol * scale && d3 >= -tol * scale * scale
    };
    if !ok {
        let need = if definite {
            "positive definite (every principal moment > 0)"
        } else {
            "positive semi-definite"
        };
        let with = if mentions_param(e, env) {
            " (with the parameters' defaults)"
        } else {
            ""
        };
        errors.over(e, format!("the inertia of `{body}` is not {need}{with}"));
        return;
    }
    // A mass distribution has `I = tr(S) E - S` with `S = sum m r r^T` positive
    // semi-definite, so `S = tr(I)/2 E - I` must be too: each principal moment is at most the
    // sum of the other two (the triangle inequality).
    let half = (m[0][0] + m[1][1] + m[2][2]) / 2.0;
    let s = [0, 1, 2].map(|i| [0, 1, 2].map(|j| if i == j { half } else { 0.0 } - m[i][j]));
    if !semi_definite(&s, tol) {
        let with = if mentions_param(e, env) {
            " (with the parameters' defaults)"
        } else {
            ""
        };
        errors.over(
            e,
            format!(
                "the principal moments of inertia of `{body}` break the triangle inequality{with}: \
                 no body has them (each must be at most the sum of the other two)"
            ),
        );
    }
}

/// Every eigenvalue of the symmetric `m` at least `-tol` (relative to `m`'s scale): the
/// coefficients of its characteristic polynomial (trace, sum of principal 2x2 minors,
/// determinant) are then all non-negative.
fn semi_definite(m: &[[f64; 3]; 3], tol: f64) -> bool {
    let scale = m
        .iter()
        .flatten()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(tol);
    let trace = m[0][0] + m[1][1] + m[2][2];
    let minors = (m[0][0] * m[1][1] - m[0][1] * m[1][0])
        + (m[0][0] * m[2][2] - m[0][2] * m[2][0])
        + (m[1][1] * m[2][2] - m[1][2] * m[2][1]);
    trace >= -tol && minors >= -tol * scale && det3(m) >= -tol * scale * scale
}

fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// `generalized_force` along a driven or relaxed coordinate: its motion is prescribed, so
/// the force would enter only the coordinate's reaction and be silently dropped.
fn driven_loads(ast: &Mechanism, errors: &mut Errors) {
    for load in &ast.loads {
        let Load::Generalized { coord, .. } = load else {
            continue;
        };
        if ast.drives.iter().any(|d| d.name == *coord) && !ast.coords.contains(coord) {
            errors.at(
                coord.span(),
                format!("`{coord}` is driven: its motion is prescribed, so a force along it moves nothing; the effort the drive needs is `reaction({coord})`"),
            );
        } else if ast.relaxed.contains(coord) {
            errors.at(
                coord.span(),
                format!("`{coord}` is relaxed (held at zero): a force along it moves nothing; its holding force is `reaction({coord})`"),
            );
        }
    }
    let mut driven = HashSet::new();
    for d in &ast.drives {
        if !driven.insert(d.name.to_string()) {
            errors.at(
                d.name.span(),
                format!(
                    "drive of `{}` given twice: a coordinate has one law",
                    d.name
                ),
            );
        }
    }
    for f in &ast.frictions {
        let c = &f.along;
        if ast.drives.iter().any(|d| d.name == *c) || ast.relaxed.contains(c) {
            errors.at(
                c.span(),
                format!(
                    "friction along `{c}`, which is not free: friction acts along a free coordinate"
                ),
            );
        }
        let ball =
            (ast.tree.iter()).find(|tb| tb.joint.ball_coords().is_some_and(|b| b.contains(&c)));
        if let Some(tb) = ball {
            let what = match tb.joint {
                crate::parse::Joint::Free(..) => "of a free joint's rotation",
                _ => "of a ball joint",
            };
            errors.at(
                c.span(),
                format!(
                    "friction along `{c}`, a coordinate {what}: its three coordinates describe one rotation (they jump to the shadow set once a turn), so `{c}'` is no sliding velocity; put the friction on an angle of `revolute` or `spherical` joints"
                ),
            );
        }
    }
}

fn names_time(e: &Expr) -> bool {
    let mut found = false;
    visit_idents(e, &mut |id| found |= id == "t");
    found
}

fn mentions_param(e: &Expr, env: &HashMap<String, f64>) -> bool {
    let mut found = false;
    visit_idents(e, &mut |id| found |= env.contains_key(&id.to_string()));
    found
}

/// Every bare name in value position (not function names).
fn visit_idents(e: &Expr, f: &mut dyn FnMut(&Ident)) {
    match e {
        Expr::Path(p) => {
            if let Some(id) = p.path.get_ident() {
                f(id)
            }
        }
        Expr::Paren(p) => visit_idents(&p.expr, f),
        Expr::Group(p) => visit_idents(&p.expr, f),
        Expr::Unary(u) => visit_idents(&u.expr, f),
        Expr::Binary(b) => {
            visit_idents(&b.left, f);
            visit_idents(&b.right, f);
        }
        Expr::Call(c) => c.args.iter().for_each(|a| visit_idents(a, f)),
        Expr::MethodCall(m) => {
            visit_idents(&m.receiver, f);
            m.args.iter().for_each(|a| visit_idents(a, f));
        }
        Expr::Array(a) => a.elems.iter().for_each(|x| visit_idents(x, f)),
        Expr::Index(i) => visit_idents(&i.expr, f),
        Expr::Cast(c) => visit_idents(&c.expr, f),
        _ => {}
    }
}

/// The value of a constant scalar expression, with `env` for names (the parameters'
/// defaults); `None` when it is not one (it names a coordinate, `t`, a parameter without
/// default, or something the language lowers otherwise).
pub fn fold(e: &Expr, env: &HashMap<String, f64>) -> Option<f64> {
    match e {
        Expr::Lit(l) => match &l.lit {
            syn::Lit::Float(f) => f.base10_parse().ok(),
            syn::Lit::Int(i) => i.base10_parse().ok(),
            _ => None,
        },
        Expr::Paren(p) => fold(&p.expr, env),
        Expr::Group(p) => fold(&p.expr, env),
        Expr::Cast(c) => fold(&c.expr, env),
        Expr::Path(p) => match p.path.get_ident() {
            Some(id) => env
                .get(&id.to_string())
                .copied()
                .or_else(|| lower::named_constant(&id.to_string())),
            None => lower::path_constant(&p.path),
        },
        Expr::Unary(u) if matches!(u.op, syn::UnOp::Neg(_)) => fold(&u.expr, env).map(|v| -v),
        Expr::Binary(b) => {
            let (x, y) = (fold(&b.left, env)?, fold(&b.right, env)?);
            match b.op {
                syn::BinOp::Add(_) => Some(x + y),
                syn::BinOp::Sub(_) => Some(x - y),
                syn::BinOp::Mul(_) => Some(x * y),
                syn::BinOp::Div(_) => Some(x / y),
                _ => None,
            }
        }
        Expr::Call(c) => {
            let Expr::Path(p) = &*c.func else { return None };
            let name = p.path.get_ident()?.to_string();
            let args: Option<Vec<f64>> = c.args.iter().map(|a| fold(a, env)).collect();
            apply(&name, &args?)
        }
        Expr::MethodCall(m) => {
            let mut args = vec![fold(&m.receiver, env)?];
            for a in &m.args {
                args.push(fold(a, env)?);
            }
            apply(&m.method.to_string(), &args)
        }
        _ => None,
    }
}

pub fn apply(name: &str, a: &[f64]) -> Option<f64> {
    Some(match (name, a) {
        ("sin", [x]) => x.sin(),
        ("cos", [x]) => x.cos(),
        ("tan", [x]) => x.tan(),
        ("asin", [x]) => x.asin(),
        ("acos", [x]) => x.acos(),
        ("atan", [x]) => x.atan(),
        ("sinh", [x]) => x.sinh(),
        ("cosh", [x]) => x.cosh(),
        ("tanh", [x]) => x.tanh(),
        ("exp", [x]) => x.exp(),
        ("ln", [x]) => x.ln(),
        ("sqrt", [x]) => x.sqrt(),
        ("abs", [x]) => x.abs(),
        ("signum", [x]) => x.signum(),
        ("atan2", [y, x]) => y.atan2(*x),
        ("hypot", [x, y]) => x.hypot(*y),
        ("powi", [x, n]) => x.powi(*n as i32),
        ("powf", [x, y]) => x.powf(*y),
        ("min", [x, y]) => x.min(*y),
        ("max", [x, y]) => x.max(*y),
        _ => return None,
    })
}

/// Whether a spatial rotation `rot` (lowered) is one: `R^T R = I` and `det R = 1` at two
/// sample values of its symbols (parameters at their `defaults` where given). A product of
/// `rot_x`, `rot_y`, `rot_z` always is; a matrix written out may not be (a scale, a
/// reflection). `None`: it names a parameter without default, so it cannot be judged here.
pub fn is_rotation(
    g: &crate::sym::Graph,
    rot: &[[crate::sym::Expr; 3]; 3],
    defaults: &HashMap<String, f64>,
    params: &HashSet<String>,
) -> Option<bool> {
    let mut symbols = std::collections::BTreeSet::new();
    for x in rot.iter().flatten() {
        symbols.extend(g.free_symbols(*x));
    }
    if symbols.iter().any(|s| {
        let n = g.sym_name(*s);
        params.contains(n) && !defaults.contains_key(n)
    }) {
        return None;
    }
    for sample in [0.37, -1.21] {
        let env = |s: crate::sym::Sym| {
            let n = g.sym_name(s);
            defaults
                .get(n)
                .copied()
                .unwrap_or(sample + 0.1 * n.len() as f64)
        };
        let r: Vec<[f64; 3]> = rot.iter().map(|row| row.map(|x| g.eval(x, &env))).collect();
        let m = [r[0], r[1], r[2]];
        for i in 0..3 {
            for j in 0..3 {
                let dot: f64 = (0..3).map(|k| m[k][i] * m[k][j]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                if !close(dot, want) {
                    return Some(false);
                }
            }
        }
        if !close(det3(&m), 1.0) {
            return Some(false);
        }
    }
    Some(true)
}

/// `a` and `b` agree to 1e-9 (false for NaN).
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9
}

/// A spring or damper between one end and itself has no length to change (and its
/// direction is 0/0).
pub fn same_ends(a: &crate::parse::End, b: &crate::parse::End) -> bool {
    match (a, b) {
        (crate::parse::End::Named(x), crate::parse::End::Named(y)) => x == y,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_with_defaults() {
        let env = HashMap::from([("m".to_string(), 1.0)]);
        let e: Expr = syn::parse_quote!(-m * 2.0 + sqrt(4.0) + PI.sin());
        assert!((fold(&e, &env).unwrap() - 0.0).abs() < 1e-15);
        let e: Expr = syn::parse_quote!(m + l);
        assert_eq!(fold(&e, &env), None);
        assert!(fold(&syn::parse_quote!(0.0 / 0.0), &env).unwrap().is_nan());
    }
}
