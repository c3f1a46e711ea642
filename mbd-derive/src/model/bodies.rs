//! Free-standing bodies (`particle`, `rigid`, `rigid3`): mass, inertia, position and
//! orientation as the user wrote them, in full coordinates.

use super::Ast;
use super::kinematics::BodyKin;
use super::scope::Scope;
use crate::lower::{Binding, Context, Lowerer, Value};
use crate::lowered::Term;
use crate::parse::{self, BodyKind, Dim};
use crate::sym::Expr;
use std::collections::{HashMap, HashSet};

/// A body's inertia (planar: the scalar in `[0][0]`), planar angle and spatial rotation.
type Rotational = (Option<[[Expr; 3]; 3]>, Option<Expr>, Option<[[Expr; 3]; 3]>);

pub(super) fn free_bodies(ast: &Ast, scope: &mut Scope) -> Vec<BodyKin> {
    // Parameters' defaults by name, for checks at the default values.
    let param_names: HashSet<String> = ast.params.iter().map(|p| p.name.to_string()).collect();
    let defaults: HashMap<String, f64> = ast
        .params
        .iter()
        .filter_map(|p| {
            Some((
                p.name.to_string(),
                p.default.as_ref()?.fold(&HashMap::new())?,
            ))
        })
        .collect();
    let dim = scope.dim;
    let mut bodies: Vec<BodyKin> = Vec::new();
    for b in &ast.bodies {
        let mut lw = scope.lowerer(None);
        let mass = b
            .mass
            .as_ref()
            .and_then(|m| lw.scalar(m, Context::Constant));
        if let Some(m) = mass
            && lw.g.as_const(m).is_some_and(|v| v <= 0.0)
        {
            lw.errors.at(
                b.mass.as_ref().expect("mass").span(),
                format!("body `{}` has no positive mass", b.name),
            );
        }
        let r =
            b.at.as_ref()
                .and_then(|e| lw.vector(e, Context::Kinematics, dim.len()));
        let (inertia, angle, rot) = match b.kind {
            BodyKind::Particle => (None, None, None),
            BodyKind::Rigid => planar_rigid(&mut lw, b, dim),
            BodyKind::Rigid3 => spatial_rigid(&mut lw, b, &defaults, &param_names),
        };
        let idx = bodies.len();
        if let (Some(mass), Some(r)) = (mass, r) {
            bodies.push(BodyKin {
                mass,
                inertia,
                origin: r.clone(),
                r,
                angle,
                rot,
                frame_angle: angle,
                frame_rot: rot,
                frame_omega: None,
            });
            scope.declare(&b.name, Binding::Body(idx));
        }
    }
    bodies
}

fn planar_rigid(lw: &mut Lowerer<'_>, b: &parse::Body<Term>, dim: Dim) -> Rotational {
    let (mut inertia, mut angle) = (None, None);
    if dim == Dim::Spatial {
        lw.errors.at(
            b.name.span(),
            format!(
                "`rigid` body `{}` is planar but the mechanism is spatial: use `rigid3`",
                b.name
            ),
        );
    }
    match &b.inertia {
        Some(e) => {
            if let Some(i) = lw.scalar(e, Context::Constant) {
                if lw.g.as_const(i).is_some_and(|v| v <= 0.0) {
                    lw.errors
                        .over(e, format!("body `{}` has no positive inertia", b.name));
                }
                let z = lw.g.zero();
                inertia = Some([[i, z, z], [z, z, z], [z, z, z]]);
            }
        }
        None => lw.errors.at(
            b.name.span(),
            format!("rigid body `{}` has no `inertia`", b.name),
        ),
    }
    match &b.orientation {
        Some(e) => angle = lw.scalar(e, Context::Kinematics),
        None => lw.errors.at(
            b.name.span(),
            format!("rigid body `{}` has no `angle`", b.name),
        ),
    }
    (inertia, angle, None)
}

fn spatial_rigid(
    lw: &mut Lowerer<'_>,
    b: &parse::Body<Term>,
    defaults: &HashMap<String, f64>,
    param_names: &HashSet<String>,
) -> Rotational {
    let (mut inertia, mut rot) = (None, None);
    match &b.inertia {
        Some(e) => match lw.lower(e, Context::Constant) {
            Some(Value::Matrix(m)) => inertia = Some(m),
            Some(_) => lw.errors.at(
                e.span(),
                "a spatial inertia is `diag(a, b, c)` or a 3x3 matrix",
            ),
            None => {}
        },
        None => lw.errors.at(
            b.name.span(),
            format!("rigid body `{}` has no `inertia`", b.name),
        ),
    }
    match &b.orientation {
        Some(e) => match lw.lower(e, Context::Kinematics) {
            Some(Value::Matrix(m)) => {
                if crate::check::is_rotation(lw.g, &m, defaults, param_names) == Some(false) {
                    lw.errors.over(e, format!("the rotation of `{}` is not a rotation (R^T R = I, det R = 1): build it from `rot_x`, `rot_y`, `rot_z`", b.name));
                }
                rot = Some(m)
            }
            Some(_) => lw.errors.at(
                e.span(),
                "a rotation is a product of `rot_x`, `rot_y`, `rot_z` or a 3x3 matrix",
            ),
            None => {}
        },
        None => lw.errors.at(
            b.name.span(),
            format!("rigid body `{}` has no `rotation`", b.name),
        ),
    }
    (inertia, None, rot)
}
