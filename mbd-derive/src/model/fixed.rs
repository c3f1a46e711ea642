//! Body-fixed points, `#[point(tip, on = arm, at = [0.0, -l])]`: `at` is in the body's
//! frame, from its origin (a tree body's joint, a free body's `at`), so a spring, damper or
//! force on any body (a joint-tree body deep in its chain too) is written where it sits
//! on the body, not through the chain of rotations. Declared once the kinematics are
//! complete, as ordinary named points.

use super::Ast;
use super::kinematics::Kinematics;
use super::scope::Scope;
use crate::lower::{Binding, Context, Model};
use crate::sym::Expr;

/// Declare every `#[point(.., on = body, ..)]` at its place in ground coordinates.
pub(super) fn declare(ast: &Ast, scope: &mut Scope, kinematics: &Kinematics) {
    let len = scope.dim.len();
    for p in &ast.points {
        let Some(on) = &p.on else { continue };
        let body = match scope.names.get(&on.to_string()) {
            Some(Binding::Body(b)) => *b,
            _ => {
                let why =
                    format!("`on` names the body the point is fixed to; `{on}` is not a body");
                scope.errors.at(on.span(), why);
                continue;
            }
        };
        let Some(offset) = scope.lowerer(None).vector(&p.at, Context::Kinematics, len) else {
            continue;
        };
        let mut reactions: Vec<(usize, Expr)> = Vec::new();
        let mut kin = kinematics.kin(scope.t, scope.dim, &mut reactions);
        match kin.body(&mut scope.g, "position", body, Some(offset)) {
            Ok(v) => scope.declare(&p.name, Binding::Value(v)),
            Err(why) => scope.errors.at(on.span(), why),
        }
    }
}
