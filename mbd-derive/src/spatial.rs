//! Spatial joint trees: the articulated-body recursion that gives their accelerations in O(n)
//! straight-line code, the spatial twin of the planar recursion in `tree.rs`.
//!
//! Featherstone's algorithm (RBDA, ch. 7) in body coordinates with 6D spatial vectors: a
//! motion `(w, v)` (angular rate, velocity of the frame origin) and a force `(n, f)` (moment
//! about the frame origin, resultant), both in the body's frame, so each body's inertia is a
//! constant of the parameters. Every joint is a sequence of one-degree-of-freedom steps: a
//! universal joint `rot_x(a) rot_y(b)` is a revolute joint about `x` to a massless frame and
//! one about `y` to the body, a spherical joint three such steps (`z`, `y`, `x`). Each step is
//! a rotation about a coordinate axis (or none) and a shift, so the transforms are a few
//! products, and each joint costs one division: `D = S . I^A S` is a scalar. A step's joint
//! axis is singular exactly where the joint's coordinates are (a spherical joint at
//! `b = +-pi/2`, where the mass matrix is singular too).

use crate::lower;
use crate::sym::{Expr, Graph};

type V3 = [Expr; 3];
type M3 = [[Expr; 3]; 3];

/// One degree of freedom (or none) between a frame and its parent.
#[derive(Clone, Copy)]
pub enum Step {
    /// A rotation about the frame's axis `axis` (0, 1, 2: x, y, z); the angle is the
    /// node's `turn`.
    Revolute {
        coord: usize,
        axis: usize,
    },
    /// A translation along `axis` (unit, parent frame); the travel is in `at`.
    Prismatic {
        coord: usize,
        axis: V3,
    },
    Fixed,
}

impl Step {
    fn coord(&self) -> Option<usize> {
        match self {
            Step::Revolute { coord, .. } | Step::Prismatic { coord, .. } => Some(*coord),
            Step::Fixed => None,
        }
    }
}

/// One frame of the tree, parents before children: a body, or the massless frame between
/// two steps of a multi-degree-of-freedom joint.
pub struct Node {
    pub parent: Option<usize>,
    pub step: Step,
    /// The frame's rotation relative to the parent's: about axis `.0` by the angle `.1` (a
    /// revolute step's coordinate, plus a planar body's constant offset).
    pub turn: Option<(usize, Expr)>,
    /// The frame's origin in the parent's frame (the prismatic travel included).
    pub at: V3,
    /// The mass centre in the frame.
    pub com: V3,
    pub mass: Expr,
    /// Centroidal inertia in the frame's axes (zero: a point mass or a massless frame).
    pub inertia: M3,
}

/// A planar tree's bodies as spatial frames (rotations about `z`, the plane `z = 0`), for
/// the recursions that only the spatial form has (mass matrix, bias forces).
pub fn from_planar(g: &mut Graph, nodes: &[crate::tree::Node]) -> Vec<Node> {
    let z = g.zero();
    nodes
        .iter()
        .map(|n| Node {
            parent: n.parent,
            step: match &n.joint {
                crate::tree::JointKin::Revolute { coord } => Step::Revolute {
                    coord: *coord,
                    axis: 2,
                },
                crate::tree::JointKin::Prismatic { coord, axis } => Step::Prismatic {
                    coord: *coord,
                    axis: [axis[0], axis[1], z],
                },
                crate::tree::JointKin::Fixed => Step::Fixed,
            },
            turn: (!g.is_zero(n.relative)).then_some((2, n.relative)),
            at: [n.at[0], n.at[1], z],
            com: [n.com[0], n.com[1], z],
            mass: n.mass,
            inertia: [[z, z, z], [z, z, z], [z, z, n.inertia]],
        })
        .collect()
}

/// A spatial motion or force vector: angular (moment) part, linear (force) part.
#[derive(Clone, Copy)]
struct Sv {
    a: V3,
    l: V3,
}

/// A symmetric spatial inertia `[[a, b], [b^T, m]]`.
#[derive(Clone, Copy)]
struct Si {
    a: M3,
    b: M3,
    m: M3,
}

fn add3(g: &mut Graph, a: V3, b: V3) -> V3 {
    [g.add(a[0], b[0]), g.add(a[1], b[1]), g.add(a[2], b[2])]
}

fn sub3(g: &mut Graph, a: V3, b: V3) -> V3 {
    [g.sub(a[0], b[0]), g.sub(a[1], b[1]), g.sub(a[2], b[2])]
}

fn scale3(g: &mut Graph, a: V3, k: Expr) -> V3 {
    [g.mul(a[0], k), g.mul(a[1], k), g.mul(a[2], k)]
}

fn cross(g: &mut Graph, a: V3, b: V3) -> V3 {
    lower::cross(g, &a, &b)
}

fn mat_vec(g: &mut Graph, m: &M3, v: V3) -> V3 {
    [g.dot(&m[0], &v), g.dot(&m[1], &v), g.dot(&m[2], &v)]
}

/// `m^T v`.
fn mat_t_vec(g: &mut Graph, m: &M3, v: V3) -> V3 {
    std::array::from_fn(|k| {
        let col = [m[0][k], m[1][k], m[2][k]];
        g.dot(&col, &v)
    })
}

fn transpose(m: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|k| m[k][i]))
}

fn sv_add(g: &mut Graph, x: Sv, y: Sv) -> Sv {
    Sv {
        a: add3(g, x.a, y.a),
        l: add3(g, x.l, y.l),
    }
}

fn sv_scale(g: &mut Graph, x: Sv, k: Expr) -> Sv {
    Sv {
        a: scale3(g, x.a, k),
        l: scale3(g, x.l, k),
    }
}

fn sv_dot(g: &mut Graph, x: Sv, y: Sv) -> Expr {
    let (p, q) = (g.dot(&x.a, &y.a), g.dot(&x.l, &y.l));
    g.add(p, q)
}

/// `I v`.
fn si_mul(g: &mut Graph, i: &Si, v: Sv) -> Sv {
    let (aw, bv) = (mat_vec(g, &i.a, v.a), mat_vec(g, &i.b, v.l));
    let (btw, mv) = (mat_t_vec(g, &i.b, v.a), mat_vec(g, &i.m, v.l));
    Sv {
        a: add3(g, aw, bv),
        l: add3(g, btw, mv),
    }
}

/// Motion cross product `v x m`.
fn cross_motion(g: &mut Graph, v: Sv, m: Sv) -> Sv {
    let (wm, vm) = (cross(g, v.a, m.l), cross(g, v.l, m.a));
    Sv {
        a: cross(g, v.a, m.a),
        l: add3(g, wm, vm),
    }
}

/// Force cross product `v x* f`.
fn cross_force(g: &mut Graph, v: Sv, f: Sv) -> Sv {
    let (wn, vf) = (cross(g, v.a, f.a), cross(g, v.l, f.l));
    Sv {
        a: add3(g, wn, vf),
        l: cross(g, v.a, f.l),
    }
}

/// `[c]x`, the cross-product matrix.
fn skew(g: &mut Graph, c: V3) -> M3 {
    let z = g.zero();
    let n = c.map(|x| g.neg(x));
    [[z, n[2], c[1]], [c[2], z, n[0]], [n[1], c[0], z]]
}

/// Spatial inertia about the frame origin of mass `m` at `c`, centroidal inertia `ic`:
/// `[[ic + m (|c|^2 1 - c c^T), m [c]x], [-m [c]x, m 1]]`.
fn inertia_at_origin(g: &mut Graph, m: Expr, c: V3, ic: &M3) -> Si {
    let z = g.zero();
    let r2 = g.dot(&c, &c);
    let mc = scale3(g, c, m);
    let a = std::array::from_fn(|i| {
        std::array::from_fn(|k| {
            let outer = g.mul(mc[i], c[k]);
            let shifted = if i == k {
                let mr2 = g.mul(m, r2);
                g.sub(mr2, outer)
            } else {
                g.neg(outer)
            };
            g.add(ic[i][k], shifted)
        })
    });
    Si {
        a,
        b: skew(g, mc),
        m: [[m, z, z], [z, m, z], [z, z, m]],
    }
}

/// A step's parent-to-child transform: the child's rotation relative to the parent (`rot`,
/// child axes to parent axes) and the child origin `r` in the parent's frame.
struct Transform {
    rot: Option<M3>,
    r: V3,
}

impl Transform {
    fn new(g: &mut Graph, node: &Node) -> Self {
        let rot = node
            .turn
            .map(|(axis, angle)| lower::rotation(g, ["rot_x", "rot_y", "rot_z"][axis], angle));
        Transform { rot, r: node.at }
    }

    /// Parent axes to child axes.
    fn to_child(&self, g: &mut Graph, v: V3) -> V3 {
        match &self.rot {
            Some(m) => mat_t_vec(g, m, v),
            None => v,
        }
    }

    /// Child axes to parent axes.
    fn to_parent(&self, g: &mut Graph, v: V3) -> V3 {
        match &self.rot {
            Some(m) => mat_vec(g, m, v),
            None => v,
        }
    }

    /// `R M R^T` (a child-axes matrix in parent axes).
    fn mat_to_parent(&self, g: &mut Graph, m: &M3) -> M3 {
        let Some(rot) = &self.rot else {
            return *m;
        };
        let rm = lower::matmul(g, rot, m);
        lower::matmul(g, &rm, &transpose(rot))
    }

    /// A motion of the parent frame seen in the child frame: `(E w, E (v - r x w))`.
    fn motion(&self, g: &mut Graph, m: Sv) -> Sv {
        let rw = cross(g, self.r, m.a);
        let v = sub3(g, m.l, rw);
        Sv {
            a: self.to_child(g, m.a),
            l: self.to_child(g, v),
        }
    }

    /// A force of the child frame seen in the parent frame (`X^T f`): `(n' + r x f', f')`.
    fn force(&self, g: &mut Graph, f: Sv) -> Sv {
        let (n, fl) = (self.to_parent(g, f.a), self.to_parent(g, f.l));
        let rf = cross(g, self.r, fl);
        Sv {
            a: add3(g, n, rf),
            l: fl,
        }
    }

    /// An inertia of the child frame seen in the parent frame (`X^T I X`): rotate the
    /// blocks, then shift the reference point by `r`: `a - b [r]x + [r]x b^T - [r]x m [r]x`,
    /// `b + [r]x m`, `m`.
    fn inertia(&self, g: &mut Graph, i: &Si) -> Si {
        let (a, b, m) = (
            self.mat_to_parent(g, &i.a),
            self.mat_to_parent(g, &i.b),
            self.mat_to_parent(g, &i.m),
        );
        let rx = skew(g, self.r);
        let rx_m = lower::matmul(g, &rx, &m);
        let b_up: M3 = std::array::from_fn(|r| std::array::from_fn(|k| g.add(b[r][k], rx_m[r][k])));
        // a - b rx + rx b^T - rx m rx = a + S + S^T - rx m rx with S = rx b^T.
        let s = lower::matmul(g, &rx, &transpose(&b));
        let rmr = lower::matmul(g, &rx_m, &rx);
        let mut a_up = a;
        for r in 0..3 {
            for k in r..3 {
                let sym = g.add(s[r][k], s[k][r]);
                let t = g.add(a[r][k], sym);
                a_up[r][k] = g.sub(t, rmr[r][k]);
                a_up[k][r] = a_up[r][k];
            }
        }
        Si {
            a: a_up,
            b: b_up,
            m,
        }
    }
}

/// The motion subspace of a step in the child's frame.
fn subspace(g: &mut Graph, step: &Step, x: &Transform) -> Option<Sv> {
    let z = [g.zero(); 3];
    match step {
        Step::Revolute { axis, .. } => {
            let mut e = z;
            e[*axis] = g.one();
            Some(Sv { a: e, l: z })
        }
        Step::Prismatic { axis, .. } => Some(Sv {
            a: z,
            l: x.to_child(g, *axis),
        }),
        Step::Fixed => None,
    }
}

/// What the recursion needs of the coordinates, indexed like the full coordinates.
pub struct Inputs<'a> {
    pub velocity: &'a [Expr],
    /// `Some(qdd)` for a driven coordinate (its known acceleration), `None` for a free one.
    pub prescribed: &'a [Option<Expr>],
    /// Generalised forces other than gravity and inertia (springs, dampers, loads).
    pub tau: &'a [Expr],
    pub gravity: V3,
}

/// Pass 1 of one frame.
struct Outward {
    s: Option<Sv>,
    v: Sv,
    c: Sv,
    p: Sv,
    inertia: Si,
}

fn outward(
    g: &mut Graph,
    node: &Node,
    x: &Transform,
    parent: Option<Sv>,
    rate: Option<Expr>,
) -> Outward {
    let z = [g.zero(); 3];
    let zero = Sv { a: z, l: z };
    let s = subspace(g, &node.step, x);
    let vp = parent.map_or(zero, |v| x.motion(g, v));
    let (v, c) = match (s, rate) {
        (Some(si), Some(rate)) => {
            let vj = sv_scale(g, si, rate);
            let v = sv_add(g, vp, vj);
            (v, cross_motion(g, v, vj))
        }
        _ => (vp, zero),
    };
    let inertia = inertia_at_origin(g, node.mass, node.com, &node.inertia);
    let iv = si_mul(g, &inertia, v);
    let p = cross_force(g, v, iv);
    Outward {
        s,
        v,
        c,
        p,
        inertia,
    }
}

/// What pass 3 needs of a free step: `U = I^A S`, `u = tau - S . p^A` and `1 / D`.
#[derive(Clone, Copy)]
struct Articulated {
    u_vec: Sv,
    u: Expr,
    inv_d: Expr,
}

/// Pass 2 of one frame: what it hands its parent, in the parent's frame.
fn inward(
    g: &mut Graph,
    x: &Transform,
    o: &Outward,
    step: &Step,
    joint: Joint,
    (i_a, p_a): (Si, Sv),
) -> ((Si, Sv), Option<Articulated>) {
    let Some(si) = o.s else {
        return ((x.inertia(g, &i_a), x.force(g, p_a)), None);
    };
    match joint {
        Joint::Free { tau } => {
            let uv = si_mul(g, &i_a, si);
            let d = sv_dot(g, si, uv);
            let sp = sv_dot(g, si, p_a);
            let u = g.sub(tau, sp);
            let one = g.one();
            let inv_d = g.div(one, d);
            // I^a = I^A - U U^T / D.
            let ud = Sv {
                a: scale3(g, uv.a, inv_d),
                l: scale3(g, uv.l, inv_d),
            };
            let mut ia = i_a;
            for r in 0..3 {
                for k in 0..3 {
                    let (aa, ab, am) = (
                        g.mul(ud.a[r], uv.a[k]),
                        g.mul(ud.a[r], uv.l[k]),
                        g.mul(ud.l[r], uv.l[k]),
                    );
                    ia.a[r][k] = g.sub(i_a.a[r][k], aa);
                    ia.b[r][k] = g.sub(i_a.b[r][k], ab);
                    ia.m[r][k] = g.sub(i_a.m[r][k], am);
                }
            }
            if let Step::Revolute { axis, .. } = step {
                // S = e_axis: I^a S = 0 exactly (the symbolic form would keep rounding
                // noise, and work).
                let z = g.zero();
                for k in 0..3 {
                    ia.a[*axis][k] = z;
                    ia.a[k][*axis] = z;
                    ia.b[*axis][k] = z;
                }
            }
            // p^a = p^A + I^a c + U u / D.
            let ic = si_mul(g, &ia, o.c);
            let uu = sv_scale(g, ud, u);
            let pa = sv_add(g, p_a, ic);
            let mut pa = sv_add(g, pa, uu);
            if let Step::Revolute { axis, .. } = step {
                // The step transmits no moment about its axis but its own effort.
                pa.a[*axis] = tau;
            }
            let art = Articulated {
                u_vec: uv,
                u,
                inv_d,
            };
            ((x.inertia(g, &ia), x.force(g, pa)), Some(art))
        }
        Joint::Driven { qdd } => {
            let sq = sv_scale(g, si, qdd);
            let acc = sv_add(g, o.c, sq);
            let ic = si_mul(g, &i_a, acc);
            let p = sv_add(g, p_a, ic);
            ((x.inertia(g, &i_a), x.force(g, p)), None)
        }
        Joint::Locked => ((x.inertia(g, &i_a), x.force(g, p_a)), None),
    }
}

/// How a step's coordinate enters the recursion.
#[derive(Clone, Copy)]
enum Joint {
    Free { tau: Expr },
    Driven { qdd: Expr },
    Locked,
}

impl Joint {
    fn of(step: &Step, inp: &Inputs<'_>) -> Self {
        match step.coord() {
            Some(j) => match inp.prescribed[j] {
                None => Joint::Free { tau: inp.tau[j] },
                Some(qdd) => Joint::Driven { qdd },
            },
            None => Joint::Locked,
        }
    }
}

/// The accelerations of the free joint coordinates: `Some(qdd)` at each free coordinate a
/// step moves, by the three passes of the articulated-body algorithm, unrolled.
pub fn articulated_body(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Vec<Option<Expr>> {
    let xs: Vec<Transform> = nodes.iter().map(|n| Transform::new(g, n)).collect();
    let joints: Vec<Joint> = nodes.iter().map(|n| Joint::of(&n.step, inp)).collect();
    // Pass 1, root to tips.
    let mut out: Vec<Outward> = Vec::with_capacity(nodes.len());
    for (node, x) in nodes.iter().zip(&xs) {
        let parent = node.parent.map(|p| out[p].v);
        let rate = node.step.coord().map(|j| inp.velocity[j]);
        let o = outward(g, node, x, parent, rate);
        out.push(o);
    }
    // Pass 2, tips to root.
    let mut ia: Vec<Si> = out.iter().map(|o| o.inertia).collect();
    let mut pa: Vec<Sv> = out.iter().map(|o| o.p).collect();
    let mut arts: Vec<Option<Articulated>> = vec![None; nodes.len()];
    for i in (0..nodes.len()).rev() {
        let ((i_up, p_up), art) = inward(
            g,
            &xs[i],
            &out[i],
            &nodes[i].step,
            joints[i],
            (ia[i], pa[i]),
        );
        arts[i] = art;
        if let Some(p) = nodes[i].parent {
            for r in 0..3 {
                for k in 0..3 {
                    ia[p].a[r][k] = g.add(ia[p].a[r][k], i_up.a[r][k]);
                    ia[p].b[r][k] = g.add(ia[p].b[r][k], i_up.b[r][k]);
                    ia[p].m[r][k] = g.add(ia[p].m[r][k], i_up.m[r][k]);
                }
            }
            pa[p] = sv_add(g, pa[p], p_up);
        }
    }
    // Pass 3, root to tips; gravity as an upward acceleration of the ground.
    let z = g.zero();
    let base = Sv {
        a: [z; 3],
        l: inp.gravity.map(|x| g.neg(x)),
    };
    let mut a: Vec<Sv> = Vec::with_capacity(nodes.len());
    let mut qdd = vec![None; inp.velocity.len()];
    for (i, node) in nodes.iter().enumerate() {
        let parent = node.parent.map_or(base, |p| a[p]);
        let ap = xs[i].motion(g, parent);
        let a_prime = sv_add(g, ap, out[i].c);
        let acc = match (out[i].s, joints[i], arts[i]) {
            (Some(si), Joint::Free { .. }, Some(art)) => {
                let ua = sv_dot(g, art.u_vec, a_prime);
                let num = g.sub(art.u, ua);
                let acc = g.mul(num, art.inv_d);
                if let Some(j) = node.step.coord() {
                    qdd[j] = Some(acc);
                }
                Some((si, acc))
            }
            (Some(si), Joint::Driven { qdd }, _) => Some((si, qdd)),
            _ => None,
        };
        a.push(match acc {
            Some((si, acc)) => {
                let sq = sv_scale(g, si, acc);
                sv_add(g, a_prime, sq)
            }
            None => a_prime,
        });
    }
    qdd
}

/// The mass matrix, the forces at zero joint accelerations and the kinetic energy of a
/// tree, over the full coordinates (`nz` of them; every one a step's), by recursion: the
/// composite-rigid-body algorithm for `M` (O(n d) entries for depth `d`, each a force
/// carried up the tree one transform at a time), recursive Newton-Euler at `qdd = 0` for
/// `f = tau - C(q, qd) - G(q)` (O(n)). Kane's projections of the same tree are O(n^3).
pub struct Inertial {
    pub mass: Vec<Vec<Expr>>,
    pub forces: Vec<Expr>,
    /// `2 T = sum v . I v` (the caller halves it with the rest of the kinetic energy).
    pub twice_kinetic: Expr,
}

pub fn mass_and_forces(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Inertial {
    let nz = inp.velocity.len();
    let zero = g.zero();
    let xs: Vec<Transform> = nodes.iter().map(|n| Transform::new(g, n)).collect();
    // Newton-Euler, outward: velocities and accelerations at qdd = 0 (gravity as an upward
    // acceleration of the ground), each frame's own force; kinetic energy.
    let base = Sv {
        a: [zero; 3],
        l: inp.gravity.map(|x| g.neg(x)),
    };
    let mut out: Vec<Outward> = Vec::with_capacity(nodes.len());
    let mut acc: Vec<Sv> = Vec::with_capacity(nodes.len());
    let mut force: Vec<Sv> = Vec::with_capacity(nodes.len());
    let mut twice_kinetic = zero;
    for (node, x) in nodes.iter().zip(&xs) {
        let parent = node.parent.map(|p| out[p].v);
        let rate = node.step.coord().map(|j| inp.velocity[j]);
        let o = outward(g, node, x, parent, rate);
        let ap = x.motion(g, node.parent.map_or(base, |p| acc[p]));
        let a = sv_add(g, ap, o.c);
        let ia = si_mul(g, &o.inertia, a);
        force.push(sv_add(g, ia, o.p));
        let iv = si_mul(g, &o.inertia, o.v);
        let viv = sv_dot(g, o.v, iv);
        twice_kinetic = g.add(twice_kinetic, viv);
        acc.push(a);
        out.push(o);
    }
    // Inward: each step's effort, the forces and composite inertias handed to the parents.
    let mut forces = inp.tau.to_vec();
    let mut composite: Vec<Si> = out.iter().map(|o| o.inertia).collect();
    for i in (0..nodes.len()).rev() {
        if let (Some(s), Some(j)) = (out[i].s, nodes[i].step.coord()) {
            let effort = sv_dot(g, s, force[i]);
            forces[j] = g.sub(forces[j], effort);
        }
        if let Some(p) = nodes[i].parent {
            let up = xs[i].force(g, force[i]);
            force[p] = sv_add(g, force[p], up);
            let i_up = xs[i].inertia(g, &composite[i]);
            let c = &mut composite[p];
            for r in 0..3 {
                for k in 0..3 {
                    c.a[r][k] = g.add(c.a[r][k], i_up.a[r][k]);
                    c.b[r][k] = g.add(c.b[r][k], i_up.b[r][k]);
                    c.m[r][k] = g.add(c.m[r][k], i_up.m[r][k]);
                }
            }
        }
    }
    // Composite rigid bodies: column i of M is the force that moves the subtree at i with a
    // unit rate of its step, projected on every step from i to the root.
    let mut mass = vec![vec![zero; nz]; nz];
    for i in 0..nodes.len() {
        let (Some(s), Some(ji)) = (out[i].s, nodes[i].step.coord()) else {
            continue;
        };
        let mut f = si_mul(g, &composite[i], s);
        mass[ji][ji] = sv_dot(g, s, f);
        let mut k = i;
        while let Some(p) = nodes[k].parent {
            f = xs[k].force(g, f);
            k = p;
            if let (Some(sk), Some(jk)) = (out[k].s, nodes[k].step.coord()) {
                let m = sv_dot(g, sk, f);
                mass[ji][jk] = m;
                mass[jk][ji] = m;
            }
        }
    }
    Inertial {
        mass,
        forces,
        twice_kinetic,
    }
}

/// Whether every coordinate is moved by exactly one step of the tree (what
/// [`mass_and_forces`] needs to give the whole `M` and `f`).
pub fn covers(nodes: &[Node], nz: usize) -> bool {
    let mut seen = vec![false; nz];
    for n in nodes {
        if let Some(j) = n.step.coord() {
            if j >= nz || seen[j] {
                return false;
            }
            seen[j] = true;
        }
    }
    seen.into_iter().all(|s| s)
}

/// `M(q) a` by Newton-Euler at rest without gravity (`a`: per full coordinate, zero for the
/// coordinates that do not move): O(n) code, so that the mass matrix of a long tree can be
/// formed column by column at run time instead of written out entry by entry (O(n d)).
pub fn mass_times(g: &mut Graph, nodes: &[Node], accel: &[Expr]) -> Vec<Expr> {
    let zero = g.zero();
    let z = [zero; 3];
    let xs: Vec<Transform> = nodes.iter().map(|n| Transform::new(g, n)).collect();
    let mut acc: Vec<Sv> = Vec::with_capacity(nodes.len());
    let mut force: Vec<Sv> = Vec::with_capacity(nodes.len());
    let mut subspaces = Vec::with_capacity(nodes.len());
    for (node, x) in nodes.iter().zip(&xs) {
        let s = subspace(g, &node.step, x);
        let parent = node.parent.map_or(Sv { a: z, l: z }, |p| acc[p]);
        let mut a = x.motion(g, parent);
        if let (Some(s), Some(j)) = (s, node.step.coord()) {
            let sa = sv_scale(g, s, accel[j]);
            a = sv_add(g, a, sa);
        }
        let inertia = inertia_at_origin(g, node.mass, node.com, &node.inertia);
        force.push(si_mul(g, &inertia, a));
        acc.push(a);
        subspaces.push(s);
    }
    let mut out = vec![zero; accel.len()];
    for i in (0..nodes.len()).rev() {
        if let (Some(s), Some(j)) = (subspaces[i], nodes[i].step.coord()) {
            out[j] = sv_dot(g, s, force[i]);
        }
        if let Some(p) = nodes[i].parent {
            let up = xs[i].force(g, force[i]);
            force[p] = sv_add(g, force[p], up);
        }
    }
    out
}

/// Inverse dynamics by recursive Newton-Euler: the generalised forces `M a - f` (per full
/// coordinate) that, besides the applied `tau`, give the accelerations `a` (per full
/// coordinate). Outward: each frame's velocity and acceleration with the given `a` (gravity
/// as an upward acceleration of the ground) and its own force `I a + v x* I v`; inward: each
/// step's effort `S . f` less `tau`, the force handed to the parent. O(n) code, shared with
/// the other recursions through the graph.
pub fn inverse_dynamics(
    g: &mut Graph,
    nodes: &[Node],
    inp: &Inputs<'_>,
    accel: &[Expr],
) -> Vec<Expr> {
    let zero = g.zero();
    let xs: Vec<Transform> = nodes.iter().map(|n| Transform::new(g, n)).collect();
    let base = Sv {
        a: [zero; 3],
        l: inp.gravity.map(|x| g.neg(x)),
    };
    let mut out: Vec<Outward> = Vec::with_capacity(nodes.len());
    let mut acc: Vec<Sv> = Vec::with_capacity(nodes.len());
    let mut force: Vec<Sv> = Vec::with_capacity(nodes.len());
    for (node, x) in nodes.iter().zip(&xs) {
        let parent = node.parent.map(|p| out[p].v);
        let rate = node.step.coord().map(|j| inp.velocity[j]);
        let o = outward(g, node, x, parent, rate);
        let ap = x.motion(g, node.parent.map_or(base, |p| acc[p]));
        let mut a = sv_add(g, ap, o.c);
        if let (Some(s), Some(j)) = (o.s, node.step.coord()) {
            let sa = sv_scale(g, s, accel[j]);
            a = sv_add(g, a, sa);
        }
        let ia = si_mul(g, &o.inertia, a);
        force.push(sv_add(g, ia, o.p));
        acc.push(a);
        out.push(o);
    }
    let mut efforts: Vec<Expr> = inp.tau.iter().map(|&t| g.neg(t)).collect();
    for i in (0..nodes.len()).rev() {
        if let (Some(s), Some(j)) = (out[i].s, nodes[i].step.coord()) {
            let effort = sv_dot(g, s, force[i]);
            efforts[j] = g.add(effort, efforts[j]);
        }
        if let Some(p) = nodes[i].parent {
            let up = xs[i].force(g, force[i]);
            force[p] = sv_add(g, force[p], up);
        }
    }
    efforts
}
