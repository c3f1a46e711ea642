//! The inertial forms in full coordinates: `M`, `f` and the energy by the recursions of a
//! pure joint tree (composite rigid bodies and Newton-Euler, spatial.rs), else by Kane's
//! projections, with Lagrange's form of the same forces taken where it is shorter; and a
//! tree's accelerations by the articulated-body recursion (tree.rs, spatial.rs).

use super::Ast;
use super::kinematics::{BodyKin, Kin, Kinematics, drop_qdd};
use super::loads::Forces;
use super::scope::Scope;
use super::{
    Coord, CoordKind, InertialForm, LAGRANGE_MAX_COORDINATES, LAZY_MASS_FROM, RECURSIVE_FROM_BODIES,
};
use crate::lower;
use crate::parse::{self, Dim};
use crate::sym::{Expr, Graph, Sym, schedule};
use crate::{spatial, tree};

/// The equations of motion in full coordinates, before reduction.
pub(super) struct Inertial {
    pub m_full: Vec<Vec<Expr>>,
    pub f_full: Vec<Expr>,
    pub energy_full: Expr,
    /// The accelerations come from the articulated-body recursion.
    pub recursive: bool,
    /// `M` is formed at run time from `M qdd` (a long pure tree without the exact
    /// Jacobian): `m_full` then holds the joints' own diagonal blocks only, zero elsewhere.
    pub lazy_mass: bool,
    pub qdd_recursive: Vec<Option<Expr>>,
    pub rolled: Option<tree::Rolled>,
    /// The spatial recursion's steps (a planar tree's, converted).
    pub steps: Vec<spatial::Node>,
    /// `M zdd - f` by recursive Newton-Euler (`zdd` every coordinate's acceleration symbol),
    /// where `M` and `f` come from the recursions.
    pub inverse_full: Option<Vec<Expr>>,
}

/// What the choice of evaluation needs to know about the constraints.
pub(super) struct Closed {
    pub constrained: bool,
    pub minimal: bool,
}

pub(super) fn inertial(
    ast: &Ast,
    scope: &mut Scope,
    kinematics: &mut Kinematics,
    forces: &Forces,
    closed: Closed,
    form: InertialForm,
) -> Inertial {
    let recursive = evaluation(ast, scope, kinematics, closed);
    let g = &mut scope.g;
    let zero = g.zero();
    let nz = kinematics.coords.len();
    // A pure joint tree's M, f and kinetic energy by recursion (composite rigid bodies,
    // Newton-Euler: O(n^2) and O(n) terms), when every coordinate is a joint's; Kane's
    // projections otherwise (O(n^3) for a chain).
    let velocity: Vec<Expr> = kinematics.coords.iter().map(|c| c.zd).collect();
    let prescribed: Vec<Option<Expr>> = kinematics
        .coords
        .iter()
        .map(|c| (!matches!(c.kind, CoordKind::Free)).then_some(c.zdd))
        .collect();
    let steps = match scope.dim {
        Dim::Planar => spatial::from_planar(g, &kinematics.planar.nodes),
        Dim::Spatial => std::mem::take(&mut kinematics.spatial.steps),
    };
    let inputs = spatial::Inputs {
        velocity: &velocity,
        prescribed: &prescribed,
        tau: &forces.q_applied,
        gravity: match &forces.gravity {
            Some(v) => std::array::from_fn(|i| v.get(i).copied().unwrap_or(zero)),
            None => [zero; 3],
        },
    };
    let m_by_recursion = recursive && spatial::covers(&steps, nz);
    let free = prescribed.iter().filter(|p| p.is_none()).count();
    let lazy_mass = m_by_recursion && !ast.jacobian && free >= LAZY_MASS_FROM;
    let by_recursion =
        m_by_recursion.then(|| spatial::mass_and_forces(g, &steps, &inputs, !lazy_mass));
    let inverse_full = (m_by_recursion && ast.inverse_dynamics).then(|| {
        let accel: Vec<Expr> = kinematics.coords.iter().map(|c| c.zdd).collect();
        spatial::inverse_dynamics(g, &steps, &inputs, &accel)
    });
    let mut reactions = Vec::new();
    let kin = kinematics.kin(scope.t, scope.dim, &mut reactions);
    let (m_full, f_full, kinetic) = match by_recursion {
        Some(rec) => (rec.mass, rec.forces, rec.twice_kinetic),
        None => {
            let q_full = forces.with_gravity(g, kinematics);
            let (mut m_full, f_full, kinetic) = kane(g, &kin, q_full.clone());
            symmetrize(&mut m_full);
            let f_full = choose_form(g, &kin, &m_full, f_full, &q_full, form);
            (m_full, f_full, kinetic)
        }
    };
    let half = g.constant(0.5);
    let kinetic = g.mul(half, kinetic);
    let potential_all = g.add(forces.potential, forces.gravity_energy);
    let energy_full = g.add(kinetic, potential_all);
    let (qdd_recursive, rolled) = if recursive {
        accelerations(g, scope.dim, &kinematics.planar.nodes, &steps, &inputs)
    } else {
        (Vec::new(), None)
    };
    Inertial {
        m_full,
        f_full,
        energy_full,
        recursive,
        lazy_mass,
        qdd_recursive,
        rolled,
        steps,
        inverse_full,
    }
}

/// Whether the articulated-body recursion evaluates the accelerations: for a pure joint
/// tree when it pays or is asked for (asked for elsewhere: a spanned error).
fn evaluation(ast: &Ast, scope: &mut Scope, kin: &Kinematics, closed: Closed) -> bool {
    let (nodes, steps) = (&kin.planar.nodes, &kin.spatial.steps);
    let tree = !(nodes.is_empty() && steps.is_empty());
    let eligible = tree
        && ast.bodies.is_empty()
        && !closed.constrained
        && !closed.minimal
        && ast.frictions.is_empty();
    match ast.evaluation {
        parse::Evaluation::MassMatrix => false,
        parse::Evaluation::Recursive if !eligible => {
            scope.errors.at(ast.evaluation_span, "`recursive` evaluation needs a joint tree (`body`, `chain`) without constraints, friction or free-standing `particle`/`rigid` bodies");
            false
        }
        parse::Evaluation::Recursive => true,
        // A free joint's six coordinates pay from one body on (one free body's rhs: 61 ns
        // by the recursion, 174 ns by the mass matrix; `hunt_big` bench).
        parse::Evaluation::Auto => {
            let free = (ast.tree.iter()).any(|tb| matches!(tb.joint, parse::Joint::Free(..)));
            eligible && (free || nodes.len() + kin.spatial.frames.len() >= RECURSIVE_FROM_BODIES)
        }
    }
}

/// Kane's projection: `M_jk = sum m J_j . J_k + Jw_j^T I Jw_k`,
/// `f_j = Q_j - sum J_j . m a0 - Jw_j^T (I alpha0 + w x I w)`; the upper triangle of `M`,
/// `f`, and twice the kinetic energy.
fn kane(g: &mut Graph, kin: &Kin<'_>, q_full: Vec<Expr>) -> (Vec<Vec<Expr>>, Vec<Expr>, Expr) {
    let zero = g.zero();
    let nz = kin.coords.len();
    let zdsyms: Vec<Sym> = kin
        .coords
        .iter()
        .map(|c| g.as_sym(c.zd).expect("symbol"))
        .collect();
    let mut m_full = vec![vec![zero; nz]; nz];
    let mut f_full = q_full;
    let mut kinetic = zero;
    for b in kin.bodies {
        let v: Vec<Expr> = b.r.iter().map(|x| kin.tder(g, *x)).collect();
        let jac: Vec<Vec<Expr>> = zdsyms
            .iter()
            .map(|s| v.iter().map(|x| g.diff(*x, *s)).collect())
            .collect();
        let a0: Vec<Expr> = v.iter().map(|x| drop_qdd(g, kin, *x)).collect();
        let vv = g.dot(&v, &v);
        let mv = g.mul(b.mass, vv);
        kinetic = g.add(kinetic, mv);
        for j in 0..nz {
            if jac[j].iter().all(|x| g.is_zero(*x)) {
                continue;
            }
            for k in j..nz {
                let d = g.dot(&jac[j], &jac[k]);
                let md = g.mul(b.mass, d);
                m_full[j][k] = g.add(m_full[j][k], md);
            }
            let d = g.dot(&jac[j], &a0);
            let md = g.mul(b.mass, d);
            f_full[j] = g.sub(f_full[j], md);
        }
        kane_rotation(g, kin, b, &zdsyms, (&mut m_full, &mut f_full, &mut kinetic));
    }
    (m_full, f_full, kinetic)
}

/// A body's rotational part of Kane's form: planar scalar, or spatial body-frame vector.
fn kane_rotation(
    g: &mut Graph,
    kin: &Kin<'_>,
    b: &BodyKin,
    zdsyms: &[Sym],
    (m_full, f_full, kinetic): (&mut [Vec<Expr>], &mut [Expr], &mut Expr),
) {
    let nz = zdsyms.len();
    let (w, inertia): (Vec<Expr>, [[Expr; 3]; 3]) = match (b.angle, b.rot, b.inertia) {
        (Some(phi), _, Some(i)) => {
            let z = g.zero();
            let w = kin.tder(g, phi);
            (vec![w], [[i[0][0], z, z], [z, z, z], [z, z, z]])
        }
        (None, Some(_), Some(i)) => (kin.omega_body(g, b), i),
        _ => return,
    };
    let nw = w.len();
    let iw: Vec<Expr> = (0..nw).map(|r| g.dot(&inertia[r][..nw], &w)).collect();
    let wiw = g.dot(&w, &iw);
    *kinetic = g.add(*kinetic, wiw);
    let jw: Vec<Vec<Expr>> = zdsyms
        .iter()
        .map(|s| w.iter().map(|x| g.diff(*x, *s)).collect())
        .collect();
    let alpha0: Vec<Expr> = w.iter().map(|x| drop_qdd(g, kin, *x)).collect();
    let mut inertial: Vec<Expr> = (0..nw).map(|r| g.dot(&inertia[r][..nw], &alpha0)).collect();
    if nw == 3 {
        let gyro = lower::cross(g, &w, &iw);
        for r in 0..3 {
            inertial[r] = g.add(inertial[r], gyro[r]);
        }
    }
    for j in 0..nz {
        if jw[j].iter().all(|x| g.is_zero(*x)) {
            continue;
        }
        let ij: Vec<Expr> = (0..nw).map(|r| g.dot(&inertia[r][..nw], &jw[j])).collect();
        for k in j..nz {
            let d = g.dot(&ij, &jw[k]);
            m_full[j][k] = g.add(m_full[j][k], d);
        }
        let d = g.dot(&jw[j], &inertial);
        f_full[j] = g.sub(f_full[j], d);
    }
}

/// Symmetric: fill the lower triangle from the upper one.
fn symmetrize(m_full: &mut [Vec<Expr>]) {
    for j in 1..m_full.len() {
        let (upper, lower) = m_full.split_at_mut(j);
        for (k, row) in upper.iter().enumerate() {
            lower[0][k] = row[j];
        }
    }
}

/// Lagrange's form of the same forces, taken instead of Kane's when it is shorter.
fn choose_form(
    g: &mut Graph,
    kin: &Kin<'_>,
    m_full: &[Vec<Expr>],
    kane: Vec<Expr>,
    applied_full: &[Expr],
    form: InertialForm,
) -> Vec<Expr> {
    let time = g.as_sym(kin.t).expect("symbol");
    let scleronomic = kin.bodies.iter().all(|b| {
        let rot = b.rot.iter().flatten().flatten();
        b.r.iter()
            .chain(&b.angle)
            .chain(rot)
            .all(|&e| !g.depends_on(e, time))
    });
    let zsyms: Vec<Sym> = kin
        .coords
        .iter()
        .map(|c| g.as_sym(c.z).expect("symbol"))
        .collect();
    let nz = zsyms.len();
    match form {
        InertialForm::Shorter if scleronomic && nz <= LAGRANGE_MAX_COORDINATES => {
            let lagrange = lagrange_forces(g, m_full, applied_full, &zsyms, kin.coords);
            let cost = |g: &Graph, f: &[Expr]| {
                let roots: Vec<Expr> = m_full.iter().flatten().chain(f).copied().collect();
                schedule(g, &roots).len()
            };
            if cost(g, &lagrange) < cost(g, &kane) {
                return lagrange;
            }
            kane
        }
        #[cfg(test)]
        InertialForm::Lagrange => {
            assert!(scleronomic, "Lagrange's form needs time-free kinematics");
            lagrange_forces(g, m_full, applied_full, &zsyms, kin.coords)
        }
        _ => kane,
    }
}

/// The accelerations of a pure joint tree by the articulated-body recursion; a planar run of
/// identical links rolled into loops when it has one.
fn accelerations(
    g: &mut Graph,
    dim: Dim,
    nodes: &[tree::Node],
    steps: &[spatial::Node],
    inputs: &spatial::Inputs<'_>,
) -> (Vec<Option<Expr>>, Option<tree::Rolled>) {
    if dim == Dim::Spatial {
        return match spatial::rolled(g, steps, inputs) {
            Some(r) => (r.qdd.clone(), Some(r)),
            None => (spatial::articulated_body(g, steps, inputs), None),
        };
    }
    let inputs = tree::Inputs {
        velocity: inputs.velocity,
        prescribed: inputs.prescribed,
        tau: inputs.tau,
        gravity: [inputs.gravity[0], inputs.gravity[1]],
    };
    match tree::rolled(g, nodes, &inputs) {
        Some(r) => (r.qdd.clone(), Some(r)),
        None => (tree::articulated_body(g, nodes, &inputs), None),
    }
}
/// Lagrange's form of the forces of a scleronomic system (kinetic energy `zd^T M zd / 2`):
/// `f_i = Q_i - sum_{j<=k} C_ijk zd_j zd_k` with the Christoffel sums
/// `C_ijk = dM_ij/dz_k + dM_ik/dz_j - dM_jk/dz_i` (`j < k`) and `C_ijj = dM_ij/dz_j -
/// dM_jj/dz_i / 2`. It differentiates the simplified mass matrix, so a velocity-product term
/// whose sum vanishes is never formed (a pendulum link's own `u'^2`); Kane's `J . (J' qd)`
/// forms such terms and cancels them only when they meet in one sum.
fn lagrange_forces(
    g: &mut Graph,
    m: &[Vec<Expr>],
    applied: &[Expr],
    z: &[Sym],
    coords: &[Coord],
) -> Vec<Expr> {
    let n = z.len();
    let dm: Vec<Vec<Vec<Expr>>> = m
        .iter()
        .map(|row| {
            row.iter()
                .map(|&e| z.iter().map(|&s| g.diff(e, s)).collect())
                .collect()
        })
        .collect();
    (0..n)
        .map(|i| {
            let mut velocity_terms = Vec::new();
            for j in 0..n {
                for k in j..n {
                    let terms = if j == k {
                        vec![(1.0, dm[i][j][j]), (-0.5, dm[j][j][i])]
                    } else {
                        vec![(1.0, dm[i][j][k]), (1.0, dm[i][k][j]), (-1.0, dm[j][k][i])]
                    };
                    let c = signed_sum(g, &terms);
                    if g.is_zero(c) {
                        continue;
                    }
                    let v = g.mul(coords[j].zd, coords[k].zd);
                    velocity_terms.push(g.mul(c, v));
                }
            }
            let c = g.sum(velocity_terms);
            g.sub(applied[i], c)
        })
        .collect()
}

/// `sum k e` with the coefficients of one node added up first, so `x + y - x` is `y`.
fn signed_sum(g: &mut Graph, terms: &[(f64, Expr)]) -> Expr {
    let mut merged: Vec<(f64, Expr)> = Vec::new();
    for &(k, e) in terms.iter().filter(|(_, e)| !g.is_zero(*e)) {
        match merged.iter_mut().find(|(_, m)| *m == e) {
            Some(slot) => slot.0 += k,
            None => merged.push((k, e)),
        }
    }
    let parts: Vec<Expr> = merged
        .into_iter()
        .filter(|(k, _)| *k != 0.0)
        .map(|(k, e)| {
            let k = g.constant(k);
            g.mul(k, e)
        })
        .collect();
    g.sum(parts)
}
