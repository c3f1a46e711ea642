//! Joint trees: body frames composed joint by joint, and the articulated-body recursion
//! that gives a planar tree's accelerations in O(n) straight-line code.
//!
//! Everything is expressed in the ground frame, with planar spatial vectors referred to the
//! world origin `O`: a motion `(w, vx, vy)` (angular rate, velocity of the body point at
//! `O`) and a force `(n, fx, fy)` (moment about `O`, resultant). This is Featherstone's
//! articulated-body algorithm in absolute coordinates (RBDA, ch. 7): no frame transforms
//! between bodies, and each body's kinematics are the nodes the rest of the model shares.

use crate::sym::{Expr, Graph};

/// A joint as the recursion sees it: the index of its coordinate among the full ones.
pub enum JointKin {
    Revolute {
        coord: usize,
    },
    /// `axis`: the unit direction in the ground frame.
    Prismatic {
        coord: usize,
        axis: [Expr; 2],
    },
    Fixed,
}

impl JointKin {
    fn coord(&self) -> Option<usize> {
        match self {
            JointKin::Revolute { coord } | JointKin::Prismatic { coord, .. } => Some(*coord),
            JointKin::Fixed => None,
        }
    }
}

/// One body of the tree, parents before children.
pub struct Node {
    pub parent: Option<usize>,
    pub joint: JointKin,
    /// The joint origin in the ground frame (the revolute axis).
    pub origin: [Expr; 2],
    pub angle: Expr,
    /// The mass centre in the ground frame.
    pub com: [Expr; 2],
    pub mass: Expr,
    /// Centroidal inertia; zero for a point mass.
    pub inertia: Expr,
}

/// `R(angle) v`.
pub fn rotate(g: &mut Graph, angle: Expr, v: [Expr; 2]) -> [Expr; 2] {
    let (c, s) = (
        g.call(crate::sym::Func::Cos, angle),
        g.call(crate::sym::Func::Sin, angle),
    );
    let (cx, sy, sx, cy) = (
        g.mul(c, v[0]),
        g.mul(s, v[1]),
        g.mul(s, v[0]),
        g.mul(c, v[1]),
    );
    [g.sub(cx, sy), g.add(sx, cy)]
}

type V3 = [Expr; 3];
type M3 = [[Expr; 3]; 3];

fn add3(g: &mut Graph, a: V3, b: V3) -> V3 {
    [g.add(a[0], b[0]), g.add(a[1], b[1]), g.add(a[2], b[2])]
}

fn scale3(g: &mut Graph, a: V3, k: Expr) -> V3 {
    [g.mul(a[0], k), g.mul(a[1], k), g.mul(a[2], k)]
}

fn mat_vec(g: &mut Graph, m: &M3, v: V3) -> V3 {
    [g.dot(&m[0], &v), g.dot(&m[1], &v), g.dot(&m[2], &v)]
}

/// Motion cross product `v x m`.
fn cross_motion(g: &mut Graph, v: V3, m: V3) -> V3 {
    let (a, b) = (g.mul(v[2], m[0]), g.mul(v[0], m[2]));
    let (c, d) = (g.mul(v[0], m[1]), g.mul(v[1], m[0]));
    [g.zero(), g.sub(a, b), g.sub(c, d)]
}

/// Force cross product `v x* f`.
fn cross_force(g: &mut Graph, v: V3, f: V3) -> V3 {
    let (a, b) = (g.mul(v[1], f[2]), g.mul(v[2], f[1]));
    let (c, d) = (g.mul(v[0], f[2]), g.mul(v[0], f[1]));
    [g.sub(a, b), g.neg(c), d]
}

/// Spatial inertia about `O` of mass `m` at `c` with centroidal inertia `i`.
fn inertia_at_origin(g: &mut Graph, m: Expr, c: [Expr; 2], i: Expr) -> M3 {
    let r2 = g.dot(&c, &c);
    let mr2 = g.mul(m, r2);
    let (mcx, mcy) = (g.mul(m, c[0]), g.mul(m, c[1]));
    let nmcy = g.neg(mcy);
    let z = g.zero();
    [[g.add(i, mr2), nmcy, mcx], [nmcy, m, z], [mcx, z, m]]
}

/// The motion subspace of a joint in the ground frame.
fn subspace(g: &mut Graph, node: &Node) -> Option<V3> {
    match &node.joint {
        JointKin::Revolute { .. } => {
            let nx = g.neg(node.origin[0]);
            Some([g.one(), node.origin[1], nx])
        }
        JointKin::Prismatic { axis, .. } => Some([g.zero(), axis[0], axis[1]]),
        JointKin::Fixed => None,
    }
}

/// What the recursion needs of the coordinates, indexed like the full coordinates.
pub struct Inputs<'a> {
    pub velocity: &'a [Expr],
    /// `Some(qdd)` for a driven coordinate (its known acceleration), `None` for a free one.
    pub prescribed: &'a [Option<Expr>],
    /// Generalised forces other than gravity and inertia (springs, dampers, loads).
    pub tau: &'a [Expr],
    pub gravity: [Expr; 2],
}

/// The accelerations of the free joint coordinates: `Some(qdd)` at each free coordinate a
/// joint moves, by the three passes of the articulated-body algorithm.
pub fn articulated_body(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Vec<Option<Expr>> {
    let n = nodes.len();
    let z3 = [g.zero(); 3];
    // Pass 1, root to tips: velocities, velocity-product accelerations, bias forces.
    let mut s = Vec::with_capacity(n);
    let mut v: Vec<V3> = Vec::with_capacity(n);
    let mut c: Vec<V3> = Vec::with_capacity(n);
    let mut ia: Vec<M3> = Vec::with_capacity(n);
    let mut pa: Vec<V3> = Vec::with_capacity(n);
    for node in nodes {
        let si = subspace(g, node);
        let vp = node.parent.map_or(z3, |p| v[p]);
        let (vi, ci) = match (si, node.joint.coord()) {
            (Some(si), Some(j)) => {
                let vj = scale3(g, si, inp.velocity[j]);
                let vi = add3(g, vp, vj);
                (vi, cross_motion(g, vi, vj))
            }
            _ => (vp, z3),
        };
        let inertia = inertia_at_origin(g, node.mass, node.com, node.inertia);
        let iv = mat_vec(g, &inertia, vi);
        pa.push(cross_force(g, vi, iv));
        ia.push(inertia);
        s.push(si);
        v.push(vi);
        c.push(ci);
    }
    // Pass 2, tips to root: articulated inertias and bias forces.
    // Per free joint: `U = I^A S`, `1 / D` and `u = tau - S . p^A`.
    let mut u_vec: Vec<Option<(V3, Expr, Expr)>> = (0..n).map(|_| None).collect();
    for i in (0..n).rev() {
        let node = &nodes[i];
        let (i_a, p_a) = (ia[i], pa[i]);
        let (i_pass, p_pass) = match (s[i], node.joint.coord()) {
            (Some(si), Some(j)) => match inp.prescribed[j] {
                None => {
                    let u = mat_vec(g, &i_a, si);
                    let d = g.dot(&si, &u);
                    let sp = g.dot(&si, &p_a);
                    let u_force = g.sub(inp.tau[j], sp);
                    // One division per joint; the articulated inertia stays symmetric.
                    let one = g.one();
                    let inv_d = g.div(one, d);
                    u_vec[i] = Some((u, inv_d, u_force));
                    let u_scaled = scale3(g, u, inv_d);
                    let mut i_pass = i_a;
                    for r in 0..3 {
                        for k in r..3 {
                            let uu = g.mul(u_scaled[r], u[k]);
                            i_pass[r][k] = g.sub(i_a[r][k], uu);
                            i_pass[k][r] = i_pass[r][k];
                        }
                    }
                    let ic = mat_vec(g, &i_pass, c[i]);
                    let ud = g.mul(u_force, inv_d);
                    let uu = scale3(g, u, ud);
                    let p = add3(g, p_a, ic);
                    (i_pass, add3(g, p, uu))
                }
                Some(qdd) => {
                    let sq = scale3(g, si, qdd);
                    let acc = add3(g, c[i], sq);
                    let ic = mat_vec(g, &i_a, acc);
                    (i_a, add3(g, p_a, ic))
                }
            },
            _ => (i_a, p_a),
        };
        if let Some(p) = node.parent {
            for r in 0..3 {
                for k in r..3 {
                    ia[p][r][k] = g.add(ia[p][r][k], i_pass[r][k]);
                    ia[p][k][r] = ia[p][r][k];
                }
            }
            pa[p] = add3(g, pa[p], p_pass);
        }
    }
    // Pass 3, root to tips: accelerations (gravity as an upward acceleration of the ground).
    let base = {
        let (gx, gy) = (g.neg(inp.gravity[0]), g.neg(inp.gravity[1]));
        [g.zero(), gx, gy]
    };
    let mut a: Vec<V3> = Vec::with_capacity(n);
    let mut qdd = vec![None; inp.velocity.len()];
    for (i, node) in nodes.iter().enumerate() {
        let ap = node.parent.map_or(base, |p| a[p]);
        let a_prime = add3(g, ap, c[i]);
        let ai = match (s[i], node.joint.coord()) {
            (Some(si), Some(j)) => {
                let acc = match (&u_vec[i], inp.prescribed[j]) {
                    (Some((u, inv_d, u_force)), None) => {
                        let ua = g.dot(u, &a_prime);
                        let num = g.sub(*u_force, ua);
                        let acc = g.mul(num, *inv_d);
                        qdd[j] = Some(acc);
                        acc
                    }
                    (_, Some(known)) => known,
                    (None, None) => unreachable!("pass 2 visits every free joint"),
                };
                let sq = scale3(g, si, acc);
                add3(g, a_prime, sq)
            }
            _ => a_prime,
        };
        a.push(ai);
    }
    qdd
}
