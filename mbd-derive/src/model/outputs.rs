//! Outputs and events: lowered with body queries answered in full coordinates, then
//! reduced, with the reactions they ask for, `r_u = (M zdd - f + Phi_z^T lambda)_u`, put in.

use super::Ast;
use super::kinematics::Kin;
use super::scope::Scope;
use super::{Coord, CoordKind, EventEq, OutputEq};
use crate::lower::{Context, Value};
use crate::sym::{Expr, Graph, Sym};
use std::collections::{HashMap, HashSet};

/// Outputs and events in full coordinates, with reaction placeholders.
pub(super) fn lower(
    ast: &Ast,
    scope: &mut Scope,
    kin: &mut Kin<'_>,
) -> (Vec<OutputEq>, Vec<EventEq>) {
    let mut outputs = Vec::new();
    let mut events = Vec::new();
    for o in &ast.outputs {
        match scope.lowerer(Some(kin)).lower(&o.expr, Context::Output) {
            Some(Value::Scalar(e)) => outputs.push(OutputEq {
                name: o.name.clone(),
                expr: e,
            }),
            Some(Value::Vector(v)) => outputs.extend(components(&o.name, &v)),
            Some(Value::Matrix(_)) => scope.errors.at(
                o.expr.span(),
                "an output is a scalar or a vector, not a matrix: multiply it by a vector or take a component",
            ),
            None => {}
        }
    }
    // Parsing reports two declared outputs of one name; here a component meets a name.
    let mut seen = HashSet::new();
    for o in &outputs {
        let name = o.name.to_string();
        let declared_twice = ast.outputs.iter().filter(|d| d.name == o.name).count() > 1;
        if !seen.insert(name.clone()) && !declared_twice {
            scope.errors.at(
                o.name.span(),
                format!("output `{name}` is declared twice (a vector output `p` gives `p_x`, `p_y`, `p_z`): rename one"),
            );
        }
    }
    for ev in &ast.events {
        if let Some(e) = scope.lowerer(Some(kin)).scalar(&ev.expr, Context::Output) {
            if constant(ast, scope, e) {
                scope.errors.at(
                    ev.name.span(),
                    format!("event `{}` depends only on parameters: it never crosses zero during a run (name a coordinate, a rate or `t`)", ev.name),
                );
            }
            events.push(EventEq {
                name: ev.name.clone(),
                expr: e,
                direction: ev.direction,
                terminal: ev.terminal,
            });
        }
    }
    (outputs, events)
}

/// Whether `e` names nothing but the model's parameters (no coordinate, rate, body query,
/// reaction or `t`): a constant during any run.
fn constant(ast: &Ast, scope: &mut Scope, e: Expr) -> bool {
    let params: Vec<Expr> = (ast.params.iter())
        .map(|p| scope.g.symbol(&p.name.to_string()))
        .collect();
    let g = &scope.g;
    let params: Vec<_> = params.iter().filter_map(|p| g.as_sym(*p)).collect();
    g.free_symbols(e).iter().all(|s| params.contains(s))
}

/// A vector output `p` as its components `p_x`, `p_y` (, `p_z`), in the ground frame.
fn components(name: &syn::Ident, v: &[Expr]) -> Vec<OutputEq> {
    ["x", "y", "z"]
        .iter()
        .zip(v)
        .map(|(axis, e)| OutputEq {
            name: syn::Ident::new(&format!("{name}_{axis}"), name.span()),
            expr: *e,
        })
        .collect()
}

/// Takes an expression of full coordinates and reaction placeholders to the free
/// coordinates.
pub(super) struct Finisher<'a> {
    reactions: HashMap<Sym, Expr>,
    reduce: &'a HashMap<Sym, Expr>,
}

impl Finisher<'_> {
    pub fn finish(&self, g: &mut Graph, e: Expr) -> Expr {
        let e = g.substitute(e, &self.reactions);
        g.substitute(e, self.reduce)
    }
}

/// The equations in full coordinates that reactions are read from: `M`, `f` (before any
/// projection on minimal coordinates), the constraints and their multipliers.
pub(super) struct FullRows<'a> {
    pub m: &'a [Vec<Expr>],
    pub f: &'a [Expr],
    pub phi: &'a [Expr],
    pub lambdas: &'a [Expr],
}

/// The reactions asked for (`(coordinate, placeholder)`), as rows of the full equations.
pub(super) fn reactions<'a>(
    g: &mut Graph,
    coords: &[Coord],
    asked: &[(usize, Expr)],
    full: &FullRows<'_>,
    reduce: &'a HashMap<Sym, Expr>,
) -> Finisher<'a> {
    let mut map: HashMap<Sym, Expr> = HashMap::new();
    let zdd: Vec<Expr> = coords.iter().map(|c| c.zdd).collect();
    let row = |g: &mut Graph, i: usize| {
        let ma = g.dot(&full.m[i], &zdd);
        g.sub(ma, full.f[i])
    };
    // The dependent coordinates' rates `zd_d` and rows `(M zdd - f)_d` (minimal form only),
    // formed once for all the reactions asked.
    let dependent: Vec<(Expr, Expr)> = (coords.iter().enumerate())
        .filter(|_| !asked.is_empty())
        .filter_map(|(d, c)| match c.kind {
            CoordKind::Dependent([_, v, _]) => Some((v, d)),
            _ => None,
        })
        .map(|(v, d)| (v, row(g, d)))
        .collect();
    for (u, placeholder) in asked {
        let mut r = row(g, *u);
        let zu = g.as_sym(coords[*u].z).expect("symbol");
        for (k, p) in full.phi.iter().enumerate() {
            let d = g.diff(*p, zu);
            let dl = g.mul(d, full.lambdas[k]);
            r = g.add(r, dl);
        }
        // In minimal coordinates the closure's forces on `u` are those of the dependent
        // rows carried along the tangent: `Phi_u^T lambda = T_du^T (M zdd - f)_d` with
        // `T_du = d zd_d / d zd_u` (docs/ARCHITECTURE.md, Reactions in minimal coordinates).
        let zdu = g.as_sym(coords[*u].zd).expect("symbol");
        for &(v, row_d) in &dependent {
            let t_du = g.diff(v, zdu);
            let carried = g.mul(t_du, row_d);
            r = g.add(r, carried);
        }
        map.insert(g.as_sym(*placeholder).expect("symbol"), r);
    }
    Finisher {
        reactions: map,
        reduce,
    }
}

/// Outputs and events in the free coordinates. A third derivative of a free coordinate
/// would need `d(qdd)/dt` of the solved dynamics: refused rather than silently zero.
pub(super) fn finish(
    scope: &mut Scope,
    finisher: &Finisher<'_>,
    (outputs, events): (&mut [OutputEq], &mut [EventEq]),
    coords: &[Coord],
    free_idx: &[usize],
) {
    let g = &mut scope.g;
    for o in outputs.iter_mut() {
        o.expr = finisher.finish(g, o.expr);
    }
    for e in events.iter_mut() {
        e.expr = finisher.finish(g, e.expr);
    }
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
            scope.errors.at(
                name.span(),
                format!("`{name}` needs the third time derivative of a free coordinate (`der` of an acceleration), which is not available"),
            );
        }
    }
}
