//! Outputs and events: lowered with body queries answered in full coordinates, then
//! reduced, with the reactions they ask for, `r_u = (M zdd - f + Phi_z^T lambda)_u`, put in.

use super::inertial::Inertial;
use super::kinematics::Kin;
use super::scope::Scope;
use super::{Coord, EventEq, OutputEq};
use crate::lower::Context;
use crate::parse::Mechanism;
use crate::sym::{Expr, Graph, Sym};
use std::collections::HashMap;

/// Outputs and events in full coordinates, with reaction placeholders.
pub(super) fn lower(
    ast: &Mechanism,
    scope: &mut Scope,
    kin: &mut Kin<'_>,
) -> (Vec<OutputEq>, Vec<EventEq>) {
    let mut outputs = Vec::new();
    let mut events = Vec::new();
    for o in &ast.outputs {
        if let Some(e) = scope.lowerer(Some(kin)).scalar(&o.expr, Context::Output) {
            outputs.push(OutputEq {
                name: o.name.clone(),
                expr: e,
            });
        }
    }
    for ev in &ast.events {
        if let Some(e) = scope.lowerer(Some(kin)).scalar(&ev.expr, Context::Output) {
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

/// The reactions asked for (`(coordinate, placeholder)`), as rows of the full equations.
pub(super) fn reactions<'a>(
    g: &mut Graph,
    coords: &[Coord],
    asked: &[(usize, Expr)],
    (inertial, phi_full, lambdas): (&Inertial, &[Expr], &[Expr]),
    reduce: &'a HashMap<Sym, Expr>,
) -> Finisher<'a> {
    let mut map: HashMap<Sym, Expr> = HashMap::new();
    for (u, placeholder) in asked {
        let zdd: Vec<Expr> = coords.iter().map(|c| c.zdd).collect();
        let ma = g.dot(&inertial.m_full[*u], &zdd);
        let mut r = g.sub(ma, inertial.f_full[*u]);
        let zu = g.as_sym(coords[*u].z).expect("symbol");
        for (k, p) in phi_full.iter().enumerate() {
            let d = g.diff(*p, zu);
            let dl = g.mul(d, lambdas[k]);
            r = g.add(r, dl);
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
