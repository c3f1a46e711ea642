//! Minimal coordinates for a closed loop (the closed forms are closure.rs's, the rates and
//! the projection velocity.rs's): where the closure has a closed form, each dependent
//! coordinate keeps its symbol with its rates by the implicit-function rule, its constraints
//! are dropped, and the equations are projected on the independent coordinates before the
//! closed form replaces it.

use super::Ast;
use super::constraints::Constraints;
use super::kinematics::{Kin, Kinematics};
use super::scope::Scope;
use super::{Coord, CoordKind, Names, Role};
use crate::closure;
use crate::lower::{Context, Lowerer};
use crate::parse::{self, Errors};
use crate::sym::{Expr, Graph, Sym};
use crate::velocity;
use std::collections::HashMap;
use syn::Ident;

/// Returns the run-time domain conditions, `None` when the model keeps the augmented form
/// (asked for, friction whose normal force may need the multipliers, no independent
/// coordinate left, or no closed form).
pub(super) fn minimal_coordinates(
    ast: &Ast,
    scope: &mut Scope,
    kin: &mut Kinematics,
    loops: &mut Constraints<'_>,
) -> Option<velocity::Minimal> {
    if loops.phi.is_empty() || ast.loop_form == parse::LoopForm::Augmented {
        return None;
    }
    let g = &mut scope.g;
    let env = default_values(ast, g, &kin.coords, &scope.names);
    let free: Vec<closure::Unknown> = kin
        .coords
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
    // Reactions (`relaxed`, `reaction(..)`) need no multipliers here: the rows of the
    // relaxed and driven coordinates in minimal coordinates are their reactions
    // (docs/ARCHITECTURE.md, Reactions in minimal coordinates).
    let why_not = if !ast.frictions.is_empty() {
        Some("friction keeps the augmented form (its normal force may need the multipliers)")
    } else if free.len() <= loops.phi.len() {
        Some("no independent coordinate would remain (the constraints fix every free coordinate)")
    } else {
        None
    };
    let solution = match why_not {
        Some(_) => None,
        None => closure::solve(g, &loops.phi, &free, &env),
    };
    // The state is the first-listed coordinates: a closed form that keeps others (the
    // quick-return's slide `s` for its crank `th`) may meet limit positions of its own where
    // the mechanism is regular, so the augmented form serves unless `minimal` is asked for.
    let keeps_first = |sol: &closure::Solution| {
        let dependent = free.len() - loops.phi.len();
        free[dependent..]
            .iter()
            .all(|u| sol.solved.iter().any(|s| s.0 == u.index))
    };
    if let Some(sol) = &solution {
        check_closure_domain(g, loops, sol, &kin.coords, &env, &mut scope.errors);
    }
    let solution =
        solution.filter(|sol| ast.loop_form == parse::LoopForm::Minimal || keeps_first(sol));
    let Some(solution) = solution else {
        if ast.loop_form == parse::LoopForm::Minimal {
            let why = why_not.unwrap_or("no closed form for the closure: the derive solves a constraint linear in one coordinate with a constant coefficient, an angle inside only `sin`/`cos` of itself, or a planar loop of two angles");
            scope.errors.at(
                ast.loop_form_span,
                format!("`minimal` coordinates are not possible here: {why}"),
            );
        }
        return None;
    };
    check_closure_defaults(g, loops, &env, ast, &mut scope.errors);
    crate::branch::check_inits(g, &solution, &kin.coords, &env, ast, &mut scope.errors);
    let forms = keep_symbols(scope, kin, &loops.phi, &solution);
    loops.phi.clear();
    loops.tokens.clear();
    Some(velocity::Minimal {
        domain: solution.domain,
        forms,
    })
}

/// The dependent coordinates stay symbols (velocity.rs): their rates by the implicit-function
/// rule become their kind; their closed forms (returned) replace them after the projection.
/// Then numbers the state anew.
fn keep_symbols(
    scope: &mut Scope,
    kin: &mut Kinematics,
    phi: &[Expr],
    solution: &closure::Solution,
) -> Vec<(Sym, closure::Form)> {
    let g = &mut scope.g;
    let coords = &mut kin.coords;
    let dep: Vec<usize> = solution.solved.iter().map(|s| s.0).collect();
    let [z, zd, zdd] = [|c: &Coord| c.z, |c: &Coord| c.zd, |c: &Coord| c.zdd]
        .map(|f| coords.iter().map(f).collect::<Vec<Expr>>());
    let symbols = velocity::Symbols {
        z: &z,
        zd: &zd,
        zdd: &zdd,
    };
    let rates = {
        let mut none = Vec::new();
        let kin = Kin {
            coords,
            bodies: &kin.bodies,
            t: scope.t,
            dim: scope.dim,
            reactions: &mut none,
        };
        velocity::rates(g, phi, &dep, &solution.pivots, &symbols, &|g, e| {
            kin.tder(g, e)
        })
    };
    let mut forms = Vec::new();
    for (k, &(i, form)) in solution.solved.iter().enumerate() {
        let (v, a) = (rates.velocity[k], rates.acceleration[k]);
        coords[i].kind = CoordKind::Dependent([form.value, v, a]);
        forms.push((g.as_sym(coords[i].z).expect("symbol"), form));
    }
    renumber(g, &mut scope.roles, coords);
    forms
}

/// `M zdd = f` of a model in minimal coordinates projected on its independent coordinates
/// (velocity.rs).
pub(super) fn project(g: &mut Graph, coords: &[Coord], m: &mut [Vec<Expr>], f: &mut [Expr]) {
    let pick = |k: fn(&CoordKind) -> bool| -> Vec<usize> {
        (0..coords.len()).filter(|&i| k(&coords[i].kind)).collect()
    };
    let free = pick(|k| matches!(k, CoordKind::Free));
    let driven = pick(|k| matches!(k, CoordKind::Driven(_)));
    let dependent: Vec<(usize, Expr, Expr)> = coords
        .iter()
        .enumerate()
        .filter_map(|(i, c)| match c.kind {
            CoordKind::Dependent([_, v, a]) => Some((i, v, a)),
            _ => None,
        })
        .collect();
    let [z, zd, zdd] = [|c: &Coord| c.z, |c: &Coord| c.zd, |c: &Coord| c.zdd]
        .map(|f| coords.iter().map(f).collect::<Vec<Expr>>());
    let split = velocity::Split {
        free: &free,
        driven: &driven,
        dependent: &dependent,
    };
    let symbols = velocity::Symbols {
        z: &z,
        zd: &zd,
        zdd: &zdd,
    };
    velocity::project(g, m, f, &split, &symbols);
}

/// The state is the independent coordinates, in the order of `coords`.
fn renumber(g: &Graph, roles: &mut HashMap<Sym, Role>, coords: &[Coord]) {
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
}

/// Values of the default configuration: parameter `#[default]`s, `init` positions (with
/// those defaults) and driven coordinates at `t = 0`; a parameter without a default leaves
/// only the constant `init` positions.
fn default_values(ast: &Ast, g: &mut Graph, coords: &[Coord], names: &Names) -> HashMap<Sym, f64> {
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
            CoordKind::Relaxed => Some(g.zero()),
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

/// The closed form's `asin`/`acos` arguments where they are known at compile time (constants,
/// or the parameter defaults and `init` positions): one outside `[-1, 1]` means the loop
/// cannot close there (`sin(x) == 2.0`, a rod shorter than the crank's reach), refused at
/// the constraints that fix the coordinate rather than left to a run-time error.
fn check_closure_domain(
    g: &Graph,
    loops: &Constraints<'_>,
    solution: &closure::Solution,
    coords: &[Coord],
    env: &HashMap<Sym, f64>,
    errors: &mut Errors,
) {
    for d in &solution.domain {
        let u = g.eval(d.arg, &|s| env.get(&s).copied().unwrap_or(f64::NAN));
        if !(u.is_finite() && u.abs() > 1.0 + 1e-12) {
            continue;
        }
        let solved_by = |c: &usize| coords[*c].name == d.coord.as_str();
        let Some((rows, _)) = solution
            .pivots
            .iter()
            .find(|(_, cs)| cs.iter().any(solved_by))
        else {
            continue;
        };
        let when = if g.eval(d.arg, &|_| f64::NAN).is_finite() {
            "for any values"
        } else {
            "at the default configuration (parameter defaults and `init` positions at t = 0)"
        };
        errors.over(
            loops.tokens[rows[0]],
            format!(
                "the loop cannot close {when}: `{}` would need the sine or cosine {u:.6}, beyond 1",
                d.coord
            ),
        );
    }
}

/// The closure's equations at the default configuration, when it is complete (as
/// `check_default_configuration` does for the augmented form).
fn check_closure_defaults(
    g: &Graph,
    loops: &Constraints<'_>,
    env: &HashMap<Sym, f64>,
    ast: &Ast,
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
