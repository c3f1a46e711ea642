//! Friction contacts of the model (the modes are crate::friction's and the core's): each
//! `friction` lowered to a coefficient pair and a normal force along a free coordinate, then
//! Coulomb's sliding force `-mu |N| sign(qd_s)` added to the reduced forces.

use super::Ast;
use super::checks::check;
use super::kinematics::Kin;
use super::outputs::Finisher;
use super::scope::Scope;
use super::{Coord, FrictionEq, ParamCheck, Role};
use crate::lower::Context;
use crate::sym::{Expr, Func};

pub(super) fn lower(
    ast: &Ast,
    scope: &mut Scope,
    kin: &mut Kin<'_>,
    (coords, free_idx): (&[Coord], &[usize]),
    checks: &mut Vec<ParamCheck>,
) -> Vec<FrictionEq> {
    let mut frictions: Vec<FrictionEq> = Vec::new();
    for f in &ast.frictions {
        let Some(a) = free_idx.iter().position(|&i| coords[i].name == f.along) else {
            scope.errors.at(
                f.along.span(),
                format!(
                    "friction acts along a free coordinate; `{}` is not one",
                    f.along
                ),
            );
            continue;
        };
        let mut lw = scope.lowerer(Some(kin));
        let mu = lw.scalar(&f.mu, Context::Constant);
        let mu_static = match &f.mu_static {
            Some(e) => lw.scalar(e, Context::Constant),
            None => mu,
        };
        let normal = lw.scalar(&f.normal, Context::Output);
        if frictions.iter().any(|e| e.coord == a) {
            scope.errors.at(
                f.along.span(),
                format!("a second `friction` along `{}`: one contact per coordinate (its stuck rows would coincide)", f.along),
            );
            continue;
        }
        if let (Some(mu), Some(mu_static), Some(normal)) = (mu, mu_static, normal) {
            crate::friction::check_coefficients(&scope.g, mu, mu_static, f, &mut scope.errors);
            let what = format!("friction coefficient along `{}`", f.along);
            checks.push(check(format!("the {what}"), mu, false));
            checks.push(check(format!("the static {what}"), mu_static, false));
            frictions.push(FrictionEq {
                coord: a,
                mu,
                mu_static,
                normal,
                span: f.span,
                implicit: None,
            });
        }
    }
    frictions
}

/// Coulomb friction while sliding: `Q_s = -mu |N| sign(qd_s)`. A normal force that depends
/// on the accelerations it helps determine is implicit: it stays out of the forces and is
/// solved with them by the core (`crate::friction::implicit_normal`; refused with a
/// generated `jacobian`). Returns the forces without friction (for the stick test) when
/// there is friction.
pub(super) fn apply(
    scope: &mut Scope,
    finisher: &Finisher<'_>,
    (frictions, jacobian): (&mut [FrictionEq], bool),
    forces: &mut [Expr],
) -> Option<Vec<Expr>> {
    let frictionless = (!frictions.is_empty()).then(|| forces.to_vec());
    for (k, f) in frictions.iter_mut().enumerate() {
        f.normal = finisher.finish(&mut scope.g, f.normal);
        if let Some(normal) = crate::friction::explicit_normal(&mut scope.g, &scope.roles, f.normal)
        {
            f.normal = normal;
        } else {
            f.implicit = crate::friction::implicit_normal(
                &mut scope.g,
                &scope.roles,
                f,
                jacobian,
                &mut scope.errors,
            );
            continue;
        }
        let g = &mut scope.g;
        let abs_n = g.call(Func::Abs, f.normal);
        let sign = g.symbol(&format!("friction_direction:{k}"));
        scope.role(sign, Role::FrictionDirection(k));
        let g = &mut scope.g;
        let mn = g.mul(f.mu, abs_n);
        let q = g.mul(mn, sign);
        forces[f.coord] = g.sub(forces[f.coord], q);
    }
    frictionless
}
