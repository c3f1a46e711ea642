//! Joint trees (`body`, `chain`): each body's frame is its parent's, moved by the joint.
//! Planar trees become `tree::Node`s, spatial ones frames composed with rotation matrices
//! and one-degree-of-freedom `spatial::Node` steps for the recursions.

use super::Ast;
use super::Coord;
use super::kinematics::{BodyKin, Frame, PlanarTree, SpatialTree};
use super::scope::Scope;
use crate::lower::{self, Binding, Context, Lowerer, Value};
use crate::lowered::Term;
use crate::parse::{self, Dim, Errors};
use crate::sym::{Expr, Graph};
use crate::{spatial, tree};
use std::collections::HashMap;

/// The constant inputs of a planar tree body: joint position, mass centre, angle offset,
/// mass, inertia and a prismatic joint's axis.
type PlanarInputs = ([Expr; 2], [Expr; 2], Expr, Expr, Expr, Option<[Expr; 2]>);

pub(super) fn planar(
    ast: &Ast,
    scope: &mut Scope,
    coords: &[Coord],
    bodies: &mut Vec<BodyKin>,
) -> PlanarTree {
    let mut tree = PlanarTree::default();
    let dim = scope.dim;
    for tb in ast.tree.iter().filter(|_| dim == Dim::Planar) {
        match &tb.joint {
            parse::Joint::Revolute { axis: Some(a), .. } => {
                scope.errors.at(a.span(), "a planar revolute joint turns about the plane's normal: write `revolute(q)` without an axis");
                continue;
            }
            parse::Joint::Universal(..)
            | parse::Joint::Spherical(..)
            | parse::Joint::Ball(..)
            | parse::Joint::Free(..) => {
                scope.errors.at(tb.joint_span, "a `universal`, `spherical`, `ball` or `free` joint needs a spatial mechanism: `#[mechanism(spatial)]`");
                continue;
            }
            _ => {}
        }
        let Ok(parent) = tree_parent(tb, &tree.node_of, &mut scope.errors) else {
            continue;
        };
        let Some((at, com, offset, mass, inertia, axis)) =
            planar_inputs(&mut scope.lowerer(None), tb)
        else {
            continue;
        };
        let coord = tb
            .joint
            .coords()
            .first()
            .map(|c| coords.iter().position(|k| k.name == **c));
        let g = &mut scope.g;
        let (p_origin, p_angle) = match parent {
            Some(p) => (tree.nodes[p].origin, tree.nodes[p].angle),
            None => ([g.zero(), g.zero()], g.zero()),
        };
        let mut local = at;
        let mut relative = offset;
        let joint = match (&tb.joint, coord.flatten(), axis) {
            (parse::Joint::Revolute { .. }, Some(j), _) => {
                relative = g.add(relative, coords[j].z);
                tree::JointKin::Revolute { coord: j }
            }
            (parse::Joint::Prismatic { .. }, Some(j), Some(axis)) => {
                tree.axes.push((tb.name.to_string(), axis.to_vec()));
                for (l, a) in local.iter_mut().zip(axis) {
                    let d = g.mul(a, coords[j].z);
                    *l = g.add(*l, d);
                }
                tree::JointKin::Prismatic { coord: j, axis }
            }
            _ => tree::JointKin::Fixed,
        };
        let angle = g.add(p_angle, relative);
        let moved = tree::rotate(g, p_angle, local);
        let mut origin = [g.add(p_origin[0], moved[0]), g.add(p_origin[1], moved[1])];
        free_joint(g, &mut origin, tb, coords);
        let arm = tree::rotate(g, angle, com);
        let com_world = [g.add(origin[0], arm[0]), g.add(origin[1], arm[1])];
        let z = g.zero();
        let rigid = !g.is_zero(inertia);
        bodies.push(BodyKin {
            mass,
            inertia: rigid.then_some([[inertia, z, z], [z, z, z], [z, z, z]]),
            r: com_world.to_vec(),
            angle: rigid.then_some(angle),
            rot: None,
            origin: origin.to_vec(),
            frame_angle: Some(angle),
            frame_rot: None,
            frame_omega: None,
        });
        scope.declare(&tb.name, Binding::Body(bodies.len() - 1));
        tree.node_of.insert(tb.name.to_string(), tree.nodes.len());
        tree.nodes.push(tree::Node {
            parent,
            joint,
            at: local,
            relative,
            com,
            origin,
            angle,
            mass,
            inertia,
        });
    }
    tree
}

fn planar_inputs(lw: &mut Lowerer<'_>, tb: &parse::TreeBody<Term>) -> Option<PlanarInputs> {
    let vec2 = |lw: &mut Lowerer<'_>, e: &Option<Term>| tree_vector(lw, e, 2).map(|v| [v[0], v[1]]);
    let (at, com) = (vec2(lw, &tb.at), vec2(lw, &tb.com));
    let offset = match &tb.angle {
        Some(e) => lw.scalar(e, Context::Constant),
        None => Some(lw.g.zero()),
    };
    let mass = tree_mass(lw, tb);
    let inertia = match &tb.inertia {
        Some(e) => lw.scalar(e, Context::Constant),
        None => Some(lw.g.zero()),
    };
    let axis = match &tb.joint {
        parse::Joint::Prismatic { axis, .. } => lw
            .vector(axis, Context::Constant, 2)
            .map(|v| Some([v[0], v[1]])),
        _ => Some(None),
    };
    Some((at?, com?, offset?, mass?, inertia?, axis?))
}

/// The constant inputs of a spatial tree body: joint position, mass centre, mass, inertia
/// (`None`: a point mass) and a prismatic joint's axis (empty for other joints).
struct SpatialInputs {
    at: Vec<Expr>,
    com: Vec<Expr>,
    mass: Expr,
    inertia: Option<[[Expr; 3]; 3]>,
    axis: Vec<Expr>,
}

pub(super) fn spatial(
    ast: &Ast,
    scope: &mut Scope,
    coords: &[Coord],
    bodies: &mut Vec<BodyKin>,
) -> SpatialTree {
    let mut tree = SpatialTree::default();
    // The spatial recursion's frame of each body (its joint's last step).
    let mut step_of_frame: Vec<usize> = Vec::new();
    let dim = scope.dim;
    for tb in ast.tree.iter().filter(|_| dim == Dim::Spatial) {
        if let Some(e) = &tb.angle {
            scope.errors.over(
                e,
                "`angle` is planar: a spatial tree body's orientation comes from its joints",
            );
        }
        let Ok(parent) = tree_parent(tb, &tree.frame_of, &mut scope.errors) else {
            continue;
        };
        let z: Vec<(Expr, Expr)> = tb
            .joint
            .coords()
            .iter()
            .filter_map(|c| coords.iter().find(|k| k.name == **c).map(|k| (k.z, k.zd)))
            .collect();
        if !ball_coordinates_free(tb, coords, &mut scope.errors)
            || !turns_something(ast, tb, &mut scope.errors)
        {
            continue;
        }
        let Some(mut input) = spatial_inputs(&mut scope.lowerer(None), tb) else {
            continue;
        };
        let (o, zero) = (scope.g.one(), scope.g.zero());
        let identity = [[o, zero, zero], [zero, o, zero], [zero, zero, o]];
        let Some(turns) = joint_turns(scope, tb, &z, &mut input) else {
            continue;
        };
        if matches!(tb.joint, parse::Joint::Prismatic { .. }) {
            tree.axes.push((tb.name.to_string(), input.axis.clone()));
        }
        let g = &mut scope.g;
        let parent_frame = parent.map(|p| tree.frames[p]);
        let frame = compose(g, identity, parent_frame, &turns, &input.at, (tb, coords));
        let r: Vec<Expr> = (0..3)
            .map(|i| {
                let arm = g.dot(&frame.rot[i], &input.com);
                g.add(frame.origin[i], arm)
            })
            .collect();
        bodies.push(BodyKin {
            mass: input.mass,
            rot: input.inertia.is_some().then_some(frame.rot),
            inertia: input.inertia,
            r,
            angle: None,
            origin: frame.origin.to_vec(),
            frame_angle: None,
            frame_rot: Some(frame.rot),
            frame_omega: Some(frame.omega),
        });
        scope.declare(&tb.name, Binding::Body(bodies.len() - 1));
        let coord_of: Vec<usize> = tb
            .joint
            .coords()
            .iter()
            .filter_map(|c| coords.iter().position(|k| k.name == **c))
            .collect();
        let step_parent = parent.map(|p| step_of_frame[p]);
        push_steps(
            &mut scope.g,
            &mut tree.steps,
            step_parent,
            (tb, &turns),
            &coord_of,
            &input,
        );
        step_of_frame.push(tree.steps.len() - 1);
        tree.frame_of.insert(tb.name.to_string(), tree.frames.len());
        tree.frames.push(frame);
    }
    tree
}

fn spatial_inputs(lw: &mut Lowerer<'_>, tb: &parse::TreeBody<Term>) -> Option<SpatialInputs> {
    let (at, com) = (tree_vector(lw, &tb.at, 3), tree_vector(lw, &tb.com, 3));
    let mass = tree_mass(lw, tb);
    let inertia = match &tb.inertia {
        Some(e) => match lw.lower(e, Context::Constant) {
            Some(Value::Matrix(m)) => Some(Some(m)),
            Some(_) => {
                lw.errors
                    .over(e, "a spatial inertia is `diag(a, b, c)` or a 3x3 matrix");
                None
            }
            None => None,
        },
        None => Some(None),
    };
    let axis = match &tb.joint {
        parse::Joint::Prismatic { axis, .. } => lw.vector(axis, Context::Constant, 3),
        _ => Some(Vec::new()),
    };
    Some(SpatialInputs {
        at: at?,
        com: com?,
        mass: mass?,
        inertia: inertia?,
        axis: axis?,
    })
}

/// A joint's rotation: elementary rotations `R_1(q_1) R_2(q_2) ..` (axis 0/1/2 for x/y/z,
/// angle, rate), or a ball joint's modified Rodrigues parameters and their rates.
enum Turns {
    Elementary(Vec<(usize, Expr, Expr)>),
    Ball {
        sigma: [Expr; 3],
        rate: [Expr; 3],
    },
    /// A free joint: the joint origin moved by `travel` in the parent's axes, then a ball.
    Free {
        travel: [Expr; 3],
        sigma: [Expr; 3],
        rate: [Expr; 3],
    },
}

/// The joint's rotation; a prismatic joint moves `at` along its axis instead. `None`: a
/// spanned error.
fn joint_turns(
    scope: &mut Scope,
    tb: &parse::TreeBody<Term>,
    z: &[(Expr, Expr)],
    input: &mut SpatialInputs,
) -> Option<Turns> {
    if let (parse::Joint::Ball(..), &[a, b, c]) = (&tb.joint, z) {
        let (sigma, rate) = ([a.0, b.0, c.0], [a.1, b.1, c.1]);
        return Some(Turns::Ball { sigma, rate });
    }
    if let (parse::Joint::Free(..), &[x, y, w, a, b, c]) = (&tb.joint, z) {
        let (sigma, rate) = ([a.0, b.0, c.0], [a.1, b.1, c.1]);
        let travel = [x.0, y.0, w.0];
        return Some(Turns::Free {
            travel,
            sigma,
            rate,
        });
    }
    Some(Turns::Elementary(match (&tb.joint, z) {
        (parse::Joint::Revolute { axis: None, .. }, _) => {
            scope.errors.at(
                tb.joint_span,
                "a spatial revolute joint names its axis: `revolute(q, x | y | z)` (`chain` is planar)",
            );
            return None;
        }
        (parse::Joint::Revolute { axis: Some(a), .. }, &[q]) => {
            let axis = ["x", "y", "z"]
                .iter()
                .position(|n| a == n)
                .expect("parse admits x, y, z");
            vec![(axis, q.0, q.1)]
        }
        (parse::Joint::Universal(..), &[a, b]) => vec![(0, a.0, a.1), (1, b.0, b.1)],
        (parse::Joint::Spherical(..), &[a, b, c]) => {
            vec![(2, a.0, a.1), (1, b.0, b.1), (0, c.0, c.1)]
        }
        (parse::Joint::Prismatic { .. }, &[s]) => {
            let g = &mut scope.g;
            for (l, a) in input.at.iter_mut().zip(&input.axis) {
                let d = g.mul(*a, s.0);
                *l = g.add(*l, d);
            }
            Vec::new()
        }
        _ => Vec::new(),
    }))
}

/// A body's frame from its parent's (`None`: the ground) and its joint's turns.
fn compose(
    g: &mut Graph,
    identity: [[Expr; 3]; 3],
    parent: Option<Frame>,
    turns: &Turns,
    at: &[Expr],
    (tb, coords): (&parse::TreeBody<Term>, &[Coord]),
) -> Frame {
    let zero = identity[0][1];
    let (relative, omega_joint) = match turns {
        Turns::Elementary(turns) => elementary(g, identity, turns),
        &Turns::Ball { sigma, rate } | &Turns::Free { sigma, rate, .. } => (
            crate::ball::rotation(g, sigma),
            crate::ball::omega(g, sigma, rate),
        ),
    };
    let at: Vec<Expr> = match turns {
        Turns::Free { travel, .. } => (at.iter().zip(travel))
            .map(|(&a, &d)| g.add(a, d))
            .collect(),
        _ => at.to_vec(),
    };
    let parent = parent.unwrap_or(Frame {
        origin: [zero; 3],
        rot: identity,
        omega: [zero; 3],
    });
    // omega = R_joint^T omega_parent + omega_joint, in the body's frame: O(1) per body
    // over its parent's, where vee(R^T R') would differentiate the whole product.
    let omega: [Expr; 3] = std::array::from_fn(|k| {
        let col = [relative[0][k], relative[1][k], relative[2][k]];
        let carried = g.dot(&col, &parent.omega);
        g.add(carried, omega_joint[k])
    });
    let rot = lower::matmul(g, &parent.rot, &relative);
    let mut origin: [Expr; 3] = std::array::from_fn(|i| {
        let moved = g.dot(&parent.rot[i], &at);
        g.add(parent.origin[i], moved)
    });
    free_joint(g, &mut origin, tb, coords);
    Frame { origin, rot, omega }
}

/// `R_joint` of elementary rotations, and the joint's angular velocity in the child's frame,
/// `sum_i (R_{i+1} .. R_k)^T e_i q_i'` (built from the last rotation back).
fn elementary(
    g: &mut Graph,
    identity: [[Expr; 3]; 3],
    turns: &[(usize, Expr, Expr)],
) -> ([[Expr; 3]; 3], [Expr; 3]) {
    let mut relative = identity;
    let mut omega_joint = [identity[0][1]; 3];
    for &(e, angle, rate) in turns.iter().rev() {
        for (k, w) in omega_joint.iter_mut().enumerate() {
            // (P^T e)_k = P[e][k] for P = R_{i+1} .. R_k.
            let term = g.mul(relative[e][k], rate);
            *w = g.add(*w, term);
        }
        let r = lower::rotation(g, ["rot_x", "rot_y", "rot_z"][e], angle);
        relative = lower::matmul(g, &r, &relative);
    }
    (relative, omega_joint)
}

/// A step of the spatial recursion, its turn and its shift from the previous frame.
type StepAt = (spatial::Step, Option<(usize, Expr)>, [Expr; 3]);

/// The joint as one-degree-of-freedom steps of the spatial recursion; the body's mass and
/// inertia ride on the last.
fn push_steps(
    g: &mut Graph,
    steps: &mut Vec<spatial::Node>,
    mut step_parent: Option<usize>,
    (tb, turns): (&parse::TreeBody<Term>, &Turns),
    coord_of: &[usize],
    input: &SpatialInputs,
) {
    let zero = g.zero();
    let (com, axis) = (&input.com, &input.axis);
    let at: [Expr; 3] = std::array::from_fn(|i| input.at[i]);
    let joint_steps: Vec<StepAt> = match (turns, coord_of) {
        _ if matches!(tb.joint, parse::Joint::Prismatic { .. }) && axis.len() == 3 => {
            let axis = [axis[0], axis[1], axis[2]];
            match coord_of {
                &[coord] => vec![(spatial::Step::Prismatic { coord, axis }, None, at)],
                _ => vec![(spatial::Step::Fixed, None, at)],
            }
        }
        (&Turns::Ball { sigma, .. }, &[c0, c1, c2]) => {
            let coords = [c0, c1, c2];
            vec![(spatial::Step::Ball { coords, sigma }, None, at)]
        }
        (Turns::Free { travel, sigma, .. }, &[x, y, w, c0, c1, c2]) => {
            let ball = spatial::Step::Ball {
                coords: [c0, c1, c2],
                sigma: *sigma,
            };
            free_steps(g, at, (*travel, [x, y, w]), ball)
        }
        (Turns::Elementary(turns), _) if turns.len() == coord_of.len() && !turns.is_empty() => {
            turns
                .iter()
                .zip(coord_of)
                .enumerate()
                .map(|(k, (&(axis, angle, _), &coord))| {
                    let shift = if k == 0 { at } else { [zero; 3] };
                    (
                        spatial::Step::Revolute { coord, axis },
                        Some((axis, angle)),
                        shift,
                    )
                })
                .collect()
        }
        _ => vec![(spatial::Step::Fixed, None, at)],
    };
    let last = joint_steps.len() - 1;
    for (k, (step, turn, shift)) in joint_steps.into_iter().enumerate() {
        let body = k == last;
        steps.push(spatial::Node {
            parent: step_parent,
            step,
            turn,
            at: shift,
            com: if body {
                std::array::from_fn(|i| com[i])
            } else {
                [zero; 3]
            },
            mass: if body { input.mass } else { zero },
            inertia: match input.inertia {
                Some(i) if body => i,
                _ => [[zero; 3]; 3],
            },
        });
        step_parent = Some(steps.len() - 1);
    }
}

/// A free joint as steps: prismatic along the parent's `x`, `y`, `z` (massless frames, each
/// shifted by its own travel only, so that each transform depends on its own coordinate),
/// then the ball at the moved origin: the articulated-body recursion takes a floating base
/// with three scalar divisions and one 3x3 inverse, with nothing singular.
fn free_steps(
    g: &mut Graph,
    at: [Expr; 3],
    (travel, coords): ([Expr; 3], [usize; 3]),
    ball: spatial::Step,
) -> Vec<StepAt> {
    let (zero, one) = (g.zero(), g.one());
    let mut out: Vec<StepAt> = (0..3)
        .map(|k| {
            let (mut axis, mut shift) = ([zero; 3], if k == 0 { at } else { [zero; 3] });
            axis[k] = one;
            shift[k] = g.add(shift[k], travel[k]);
            let step = spatial::Step::Prismatic {
                coord: coords[k],
                axis,
            };
            (step, None, shift)
        })
        .collect();
    out.push((ball, None, [zero; 3]));
    out
}

/// A ball joint's coordinates (or a free joint's rotation's) move together (their rates
/// are one angular velocity): none of them may be driven. `false` after a spanned error.
fn ball_coordinates_free(
    tb: &parse::TreeBody<Term>,
    coords: &[Coord],
    errors: &mut Errors,
) -> bool {
    let Some(ball) = tb.joint.ball_coords() else {
        return true;
    };
    let what = match tb.joint {
        parse::Joint::Free(..) => "the rotation of a free joint",
        _ => "a ball joint",
    };
    let driven = ball.into_iter().find(|c| {
        coords
            .iter()
            .any(|k| k.name == **c && !matches!(k.kind, super::CoordKind::Free))
    });
    match driven {
        Some(c) => {
            errors.at(c.span(), format!("`{c}` is a coordinate of {what}, which cannot be driven: its three coordinates describe one rotation (drive a `spherical` joint's angles instead)"));
            false
        }
        None => true,
    }
}

/// A point mass alone on a ball or free joint has no inertia about the line through the
/// joint origin and its mass centre: its rotation about it is undetermined at every state.
/// `false` after a spanned error.
fn turns_something(ast: &Ast, tb: &parse::TreeBody<Term>, errors: &mut Errors) -> bool {
    let carries = ast.tree.iter().any(|b| b.parent.as_ref() == Some(&tb.name));
    if tb.joint.ball_coords().is_none() || tb.inertia.is_some() || carries {
        return true;
    }
    errors.at(tb.name.span(), format!("`{}` is a point mass on a three-axis rotation: nothing resists its turning about the line through the joint and its mass centre, so its rotation is undetermined; give it an `inertia`", tb.name));
    false
}

/// A tree body's parent (`None`: the ground) among the bodies declared before it, or a
/// spanned error.
fn tree_parent(
    tb: &parse::TreeBody<Term>,
    declared: &HashMap<String, usize>,
    errors: &mut Errors,
) -> Result<Option<usize>, ()> {
    let Some(p) = &tb.parent else {
        return Ok(None);
    };
    match declared.get(&p.to_string()) {
        Some(&i) => Ok(Some(i)),
        None => {
            errors.at(p.span(), format!("unknown parent `{p}`: a tree body's parent is `ground` or a `body` declared before it"));
            Err(())
        }
    }
}

/// A joint freed by `reaction`: its origin moves by the relaxed coordinates along the
/// ground's axes (zero in the motion; their multipliers are the joint's force).
fn free_joint(g: &mut Graph, origin: &mut [Expr], tb: &parse::TreeBody<Term>, coords: &[Coord]) {
    for (o, r) in origin.iter_mut().zip(tb.reaction.iter().flatten()) {
        if let Some(c) = coords.iter().find(|c| c.name == *r) {
            *o = g.add(*o, c.z);
        }
    }
}

/// A tree body's `at` or `com`: a constant vector of `len` entries, zero when not given.
fn tree_vector(lw: &mut Lowerer<'_>, e: &Option<Term>, len: usize) -> Option<Vec<Expr>> {
    match e {
        Some(e) => lw.vector(e, Context::Constant, len),
        None => Some(vec![lw.g.zero(); len]),
    }
}

/// A tree body's mass, with a spanned error when it is a constant that is not positive.
fn tree_mass(lw: &mut Lowerer<'_>, tb: &parse::TreeBody<Term>) -> Option<Expr> {
    let e = tb.mass.as_ref()?;
    let m = lw.scalar(e, Context::Constant)?;
    if lw.g.as_const(m).is_some_and(|v| v <= 0.0) {
        lw.errors
            .over(e, format!("body `{}` has no positive mass", tb.name));
    }
    Some(m)
}
