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
//! `b = +-pi/2`, where the mass matrix is singular too). A ball joint (`ball.rs`) is one
//! node with three columns instead, taken by the articulated-body pass in its angular
//! velocity with a 3x3 `D`: nothing in it is singular.

use crate::lower;
use crate::sym::{Expr, Graph};

mod roll;
pub use roll::rolled;

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
    /// A ball joint (`ball.rs`): three coordinates, the modified Rodrigues parameters
    /// `sigma` (their position symbols), rotation `R(sigma)`, motion subspace the columns of
    /// `E(sigma)`. The articulated-body recursion takes it as one three-degree-of-freedom
    /// joint in the child's angular velocity (a 3x3 `D`), so nothing in it is singular.
    Ball {
        coords: [usize; 3],
        sigma: V3,
    },
    Fixed,
}

impl Step {
    /// The coordinates the step moves.
    fn coords(&self) -> Vec<usize> {
        match self {
            Step::Revolute { coord, .. } | Step::Prismatic { coord, .. } => vec![*coord],
            Step::Ball { coords, .. } => coords.to_vec(),
            Step::Fixed => Vec::new(),
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
        let rot = match node.step {
            Step::Ball { sigma, .. } => Some(crate::ball::rotation(g, sigma)),
            _ => node
                .turn
                .map(|(axis, angle)| lower::rotation(g, ["rot_x", "rot_y", "rot_z"][axis], angle)),
        };
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

/// The motion subspace of a step in the child's frame: a column per coordinate it moves.
fn subspace(g: &mut Graph, step: &Step, x: &Transform) -> Vec<(usize, Sv)> {
    let z = [g.zero(); 3];
    match step {
        Step::Revolute { axis, coord } => {
            let mut e = z;
            e[*axis] = g.one();
            vec![(*coord, Sv { a: e, l: z })]
        }
        Step::Prismatic { axis, coord } => vec![(
            *coord,
            Sv {
                a: z,
                l: x.to_child(g, *axis),
            },
        )],
        Step::Ball { coords, sigma } => {
            let e = crate::ball::rate_matrix(g, *sigma);
            (0..3)
                .map(|k| {
                    let a = [e[0][k], e[1][k], e[2][k]];
                    (coords[k], Sv { a, l: z })
                })
                .collect()
        }
        Step::Fixed => Vec::new(),
    }
}

/// `S' qd` of a step whose subspace moves with its coordinates (a ball joint's
/// `(E' sigma', 0)`), `None` for the others.
fn subspace_rate(g: &mut Graph, step: &Step, velocity: &[Expr]) -> Option<Sv> {
    let Step::Ball { coords, sigma } = step else {
        return None;
    };
    let rate = coords.map(|j| velocity[j]);
    let z = g.zero();
    Some(Sv {
        a: crate::ball::bias(g, *sigma, rate),
        l: [z; 3],
    })
}

/// `sum_k S_k x_k` over a step's columns.
fn combine_columns(g: &mut Graph, s: &[(usize, Sv)], x: &[Expr]) -> Option<Sv> {
    let mut out: Option<Sv> = None;
    for &(j, col) in s {
        let term = sv_scale(g, col, x[j]);
        out = Some(match out {
            Some(o) => sv_add(g, o, term),
            None => term,
        });
    }
    out
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

/// Pass 1 of one frame (`c = v x v_J`: without `S' qd`, which the articulated-body
/// recursion's ball joint does not have in its own velocity coordinates).
struct Outward {
    s: Vec<(usize, Sv)>,
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
    velocity: &[Expr],
) -> Outward {
    let z = [g.zero(); 3];
    let zero = Sv { a: z, l: z };
    let s = subspace(g, &node.step, x);
    let vp = parent.map_or(zero, |v| x.motion(g, v));
    let (v, c) = match combine_columns(g, &s, velocity) {
        Some(vj) => {
            let v = sv_add(g, vp, vj);
            (v, cross_motion(g, v, vj))
        }
        None => (vp, zero),
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

/// What pass 3 needs of a free step: `U = I^A S`, `u = tau - S . p^A` and `1 / D`; of a
/// ball joint (in its angular velocity `w`, `S = (1, 0)`): `I^A`'s blocks `a` (`= D`) and
/// `b`, `D^-1` and `u = n - p^A_a` (`n` the moment of its generalised forces).
#[derive(Clone, Copy)]
enum Articulated {
    Step { u_vec: Sv, u: Expr, inv_d: Expr },
    Ball { a: M3, b: M3, d_inv: M3, u: V3 },
}

/// The inverse of a symmetric 3x3 matrix: its adjugate over its determinant (one division).
fn inverse_sym(g: &mut Graph, m: &M3) -> M3 {
    let cof = |g: &mut Graph, i: usize, k: usize| {
        let (i1, i2, k1, k2) = ((i + 1) % 3, (i + 2) % 3, (k + 1) % 3, (k + 2) % 3);
        let (p, q) = (g.mul(m[i1][k1], m[i2][k2]), g.mul(m[i1][k2], m[i2][k1]));
        g.sub(p, q)
    };
    let c: M3 = std::array::from_fn(|i| std::array::from_fn(|k| cof(g, i, k)));
    let det = g.dot(&m[0], &c[0]);
    let one = g.one();
    let inv_det = g.div(one, det);
    let mut out = c;
    for r in 0..3 {
        for k in r..3 {
            out[r][k] = g.mul(c[k][r], inv_det);
            out[k][r] = out[r][k];
        }
    }
    out
}

/// Pass 2 of one frame: what it hands its parent, in the parent's frame.
fn inward(
    g: &mut Graph,
    x: &Transform,
    o: &Outward,
    step: &Step,
    joint: &Joint,
    (i_a, p_a): (Si, Sv),
) -> ((Si, Sv), Option<Articulated>) {
    let (ia, pa, art) = match (joint, o.s.first()) {
        (Joint::Free { tau }, Some(&(_, si))) => {
            let (ia, pa, art) = articulate(g, o, step, *tau, (i_a, p_a), si);
            (ia, pa, Some(art))
        }
        (Joint::Ball { moment }, _) => {
            let (ia, pa, art) = articulate_ball(g, o, *moment, (i_a, p_a));
            (ia, pa, Some(art))
        }
        (Joint::Driven { qdd }, _) => {
            let sq = combine_columns(g, &o.s, qdd).expect("a driven step moves");
            let acc = sv_add(g, o.c, sq);
            let ic = si_mul(g, &i_a, acc);
            (i_a, sv_add(g, p_a, ic), None)
        }
        _ => (i_a, p_a, None),
    };
    ((x.inertia(g, &ia), x.force(g, pa)), art)
}

/// A free one-degree-of-freedom step: `I^a = I^A - U U^T / D`, `p^a = p^A + I^a c + U u / D`.
fn articulate(
    g: &mut Graph,
    o: &Outward,
    step: &Step,
    tau: Expr,
    (i_a, p_a): (Si, Sv),
    si: Sv,
) -> (Si, Sv, Articulated) {
    let uv = si_mul(g, &i_a, si);
    let d = sv_dot(g, si, uv);
    let sp = sv_dot(g, si, p_a);
    let u = g.sub(tau, sp);
    let one = g.one();
    let inv_d = g.div(one, d);
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
    let slide = unit_axis(g, step);
    if let Some(k) = slide {
        // S = (0, e_k) (a free joint's travel): I^a S = 0 exactly, the linear column k.
        let z = g.zero();
        for r in 0..3 {
            ia.b[r][k] = z;
            ia.m[r][k] = z;
            ia.m[k][r] = z;
        }
    }
    let ic = si_mul(g, &ia, o.c);
    let uu = sv_scale(g, ud, u);
    let pa = sv_add(g, p_a, ic);
    let mut pa = sv_add(g, pa, uu);
    if let Step::Revolute { axis, .. } = step {
        // The step transmits no moment about its axis but its own effort.
        pa.a[*axis] = tau;
    }
    if let Some(k) = slide {
        // Nor a force along its axis.
        pa.l[k] = tau;
    }
    let art = Articulated::Step {
        u_vec: uv,
        u,
        inv_d,
    };
    (ia, pa, art)
}

/// The axis `k` of a prismatic step along `e_k` (a free joint's travel), whose subspace is
/// then `(0, e_k)`: a prismatic step has no rotation, so its axis is the same in both frames.
fn unit_axis(g: &Graph, step: &Step) -> Option<usize> {
    let Step::Prismatic { axis, .. } = step else {
        return None;
    };
    let v = axis.map(|a| g.as_const(a));
    (0..3).find(|&k| (0..3).all(|i| v[i] == Some(if i == k { 1.0 } else { 0.0 })))
}

/// A free ball joint in its angular velocity (`S = (1, 0)`, `D = a`): `I^a` keeps only
/// `m - b^T D^-1 b` (its `a` and `b` blocks are exactly zero), and `p^a` the moment `n` and
/// the force `p^A_l + (m - b^T D^-1 b) c_l + b^T D^-1 u`.
fn articulate_ball(
    g: &mut Graph,
    o: &Outward,
    moment: V3,
    (i_a, p_a): (Si, Sv),
) -> (Si, Sv, Articulated) {
    let d_inv = inverse_sym(g, &i_a.a);
    let u = sub3(g, moment, p_a.a);
    // b^T D^-1, then the reduced mass block.
    let bt_dinv = lower::matmul(g, &transpose(&i_a.b), &d_inv);
    let reduced = lower::matmul(g, &bt_dinv, &i_a.b);
    let z = g.zero();
    let mut ia = Si {
        a: [[z; 3]; 3],
        b: [[z; 3]; 3],
        m: i_a.m,
    };
    for (r, row) in reduced.iter().enumerate() {
        for (k, &x) in row.iter().enumerate().skip(r) {
            ia.m[r][k] = g.sub(i_a.m[r][k], x);
            ia.m[k][r] = ia.m[r][k];
        }
    }
    let mc = mat_vec(g, &ia.m, o.c.l);
    let bu = mat_vec(g, &bt_dinv, u);
    let fl = add3(g, p_a.l, mc);
    let pa = Sv {
        a: moment,
        l: add3(g, fl, bu),
    };
    let art = Articulated::Ball {
        a: i_a.a,
        b: i_a.b,
        d_inv,
        u,
    };
    (ia, pa, art)
}

/// How a step's coordinates enter the recursion.
enum Joint {
    Free {
        tau: Expr,
    },
    /// A ball joint's three free coordinates, by the moment of their generalised forces.
    Ball {
        moment: V3,
    },
    /// Every coordinate driven: the known accelerations, per full coordinate.
    Driven {
        qdd: Vec<Expr>,
    },
    Locked,
}

impl Joint {
    fn of(g: &mut Graph, step: &Step, inp: &Inputs<'_>) -> Self {
        let coords = step.coords();
        if coords.is_empty() {
            return Joint::Locked;
        }
        // A ball joint with a driven coordinate is refused where it is declared
        // (model/trees.rs), so a ball here is free.
        let ball = matches!(step, Step::Ball { .. });
        if !ball && inp.prescribed[coords[0]].is_some() {
            let zero = g.zero();
            let mut qdd = vec![zero; inp.velocity.len()];
            for &j in &coords {
                qdd[j] = inp.prescribed[j].expect("all prescribed");
            }
            return Joint::Driven { qdd };
        }
        match step {
            Step::Ball { sigma, coords } => {
                let tau = coords.map(|j| inp.tau[j]);
                Joint::Ball {
                    moment: crate::ball::moment(g, *sigma, tau),
                }
            }
            _ => Joint::Free {
                tau: inp.tau[coords[0]],
            },
        }
    }
}

/// Pass 3 of one frame with `a'` (its parent's acceleration carried over, plus `c`): the
/// accelerations of its free coordinates into `qdd`, and its own acceleration.
fn accelerate(
    g: &mut Graph,
    node: &Node,
    o: &Outward,
    joint: &Joint,
    art: Option<Articulated>,
    (a_prime, velocity): (Sv, &[Expr]),
    qdd: &mut [Option<Expr>],
) -> Sv {
    match (joint, art, o.s.first()) {
        (Joint::Free { .. }, Some(Articulated::Step { u_vec, u, inv_d }), Some(&(j, si))) => {
            let ua = sv_dot(g, u_vec, a_prime);
            let num = g.sub(u, ua);
            let acc = g.mul(num, inv_d);
            qdd[j] = Some(acc);
            let sq = sv_scale(g, si, acc);
            sv_add(g, a_prime, sq)
        }
        (Joint::Ball { .. }, Some(Articulated::Ball { a, b, d_inv, u }), _) => {
            // w' = D^-1 (u - U^T a'), U^T a' = a a'_a + b a'_l.
            let (aa, ba) = (mat_vec(g, &a, a_prime.a), mat_vec(g, &b, a_prime.l));
            let ua = add3(g, aa, ba);
            let rest = sub3(g, u, ua);
            let w_dot = mat_vec(g, &d_inv, rest);
            let Step::Ball { coords, sigma } = node.step else {
                unreachable!("a ball's articulation is a ball step's")
            };
            let rate = coords.map(|j| velocity[j]);
            let sdd = crate::ball::sigma_dd(g, sigma, rate, w_dot);
            for (&j, e) in coords.iter().zip(sdd) {
                qdd[j] = Some(e);
            }
            Sv {
                a: add3(g, a_prime.a, w_dot),
                l: a_prime.l,
            }
        }
        (Joint::Driven { qdd: known }, _, _) => {
            let sq = combine_columns(g, &o.s, known).expect("a driven step moves");
            sv_add(g, a_prime, sq)
        }
        _ => a_prime,
    }
}

/// The three passes of the articulated-body algorithm over a tree, unrolled; the rest of a
/// tree whose tail run is rolled (`roll.rs`) uses them with the run's hand-on.
struct Unrolled {
    xs: Vec<Transform>,
    joints: Vec<Joint>,
    out: Vec<Outward>,
}

impl Unrolled {
    /// Pass 1, root to tips.
    fn new(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Self {
        let xs: Vec<Transform> = nodes.iter().map(|n| Transform::new(g, n)).collect();
        let joints: Vec<Joint> = nodes.iter().map(|n| Joint::of(g, &n.step, inp)).collect();
        let mut out: Vec<Outward> = Vec::with_capacity(nodes.len());
        for (node, x) in nodes.iter().zip(&xs) {
            let parent = node.parent.map(|p| out[p].v);
            let o = outward(g, node, x, parent, inp.velocity);
            out.push(o);
        }
        Unrolled { xs, joints, out }
    }

    /// Passes 2 (tips to root, with `hand_on` added at its node: a rolled run's) and 3
    /// (root to tips): every frame's acceleration and the free coordinates' `qdd`.
    fn finish(
        &self,
        g: &mut Graph,
        nodes: &[Node],
        inp: &Inputs<'_>,
        hand_on: Option<(usize, (Si, Sv))>,
    ) -> (Vec<Sv>, Vec<Option<Expr>>) {
        let mut ia: Vec<Si> = self.out.iter().map(|o| o.inertia).collect();
        let mut pa: Vec<Sv> = self.out.iter().map(|o| o.p).collect();
        if let Some((at, up)) = hand_on {
            add_hand_on(g, (&mut ia[at], &mut pa[at]), up);
        }
        let mut arts: Vec<Option<Articulated>> = vec![None; nodes.len()];
        for i in (0..nodes.len()).rev() {
            let (up, art) = inward(
                g,
                &self.xs[i],
                &self.out[i],
                &nodes[i].step,
                &self.joints[i],
                (ia[i], pa[i]),
            );
            arts[i] = art;
            if let Some(p) = nodes[i].parent {
                add_hand_on(g, (&mut ia[p], &mut pa[p]), up);
            }
        }
        // Gravity as an upward acceleration of the ground.
        let base = base_acceleration(g, inp.gravity);
        let mut a: Vec<Sv> = Vec::with_capacity(nodes.len());
        let mut qdd = vec![None; inp.velocity.len()];
        for (i, node) in nodes.iter().enumerate() {
            let parent = node.parent.map_or(base, |p| a[p]);
            let ap = self.xs[i].motion(g, parent);
            let a_prime = sv_add(g, ap, self.out[i].c);
            let inputs = (a_prime, inp.velocity);
            let o = &self.out[i];
            let acc = accelerate(g, node, o, &self.joints[i], arts[i], inputs, &mut qdd);
            a.push(acc);
        }
        (a, qdd)
    }
}

/// `(0, -gravity)`: the ground's acceleration that stands for gravity.
fn base_acceleration(g: &mut Graph, gravity: V3) -> Sv {
    let z = g.zero();
    Sv {
        a: [z; 3],
        l: gravity.map(|x| g.neg(x)),
    }
}

/// A child's articulated inertia and bias force added to its parent's.
fn add_hand_on(g: &mut Graph, (ia, pa): (&mut Si, &mut Sv), (i_up, p_up): (Si, Sv)) {
    for r in 0..3 {
        for k in 0..3 {
            ia.a[r][k] = g.add(ia.a[r][k], i_up.a[r][k]);
            ia.b[r][k] = g.add(ia.b[r][k], i_up.b[r][k]);
            ia.m[r][k] = g.add(ia.m[r][k], i_up.m[r][k]);
        }
    }
    *pa = sv_add(g, *pa, p_up);
}

/// The accelerations of the free joint coordinates: `Some(qdd)` at each free coordinate a
/// step moves, by the three passes of the articulated-body algorithm, unrolled.
pub fn articulated_body(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Vec<Option<Expr>> {
    Unrolled::new(g, nodes, inp).finish(g, nodes, inp, None).1
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

/// `carried`: whether `M` is written out; without, only each joint's own diagonal block
/// (what the singular-mass check reads; `M` is then formed at run time from [`mass_times`]),
/// since carrying every column up to the root is O(n d) terms, quadratic in a chain.
pub fn mass_and_forces(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>, carried: bool) -> Inertial {
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
        let o = outward(g, node, x, parent, inp.velocity);
        let ap = x.motion(g, node.parent.map_or(base, |p| acc[p]));
        let mut a = sv_add(g, ap, o.c);
        if let Some(r) = subspace_rate(g, &node.step, inp.velocity) {
            a = sv_add(g, a, r);
        }
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
        for &(j, s) in &out[i].s {
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
        for (c, &(ji, s)) in out[i].s.iter().enumerate() {
            let mut f = si_mul(g, &composite[i], s);
            // The step's own columns (a ball joint's 3x3 block).
            for &(jk, sk) in &out[i].s[..=c] {
                let m = sv_dot(g, sk, f);
                mass[ji][jk] = m;
                mass[jk][ji] = m;
            }
            let mut k = i;
            while let Some(p) = nodes[k].parent.filter(|_| carried) {
                f = xs[k].force(g, f);
                k = p;
                for &(jk, sk) in &out[k].s {
                    let m = sv_dot(g, sk, f);
                    mass[ji][jk] = m;
                    mass[jk][ji] = m;
                }
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
        for j in n.step.coords() {
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
/// A ball joint's `S' qd` is left out: it is a velocity term, part of `f`.
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
        if let Some(sa) = combine_columns(g, &s, accel) {
            a = sv_add(g, a, sa);
        }
        let inertia = inertia_at_origin(g, node.mass, node.com, &node.inertia);
        force.push(si_mul(g, &inertia, a));
        acc.push(a);
        subspaces.push(s);
    }
    let mut out = vec![zero; accel.len()];
    for i in (0..nodes.len()).rev() {
        for &(j, s) in &subspaces[i] {
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
        let o = outward(g, node, x, parent, inp.velocity);
        let ap = x.motion(g, node.parent.map_or(base, |p| acc[p]));
        let mut a = sv_add(g, ap, o.c);
        if let Some(r) = subspace_rate(g, &node.step, inp.velocity) {
            a = sv_add(g, a, r);
        }
        if let Some(sa) = combine_columns(g, &o.s, accel) {
            a = sv_add(g, a, sa);
        }
        let ia = si_mul(g, &o.inertia, a);
        force.push(sv_add(g, ia, o.p));
        acc.push(a);
        out.push(o);
    }
    let mut efforts: Vec<Expr> = inp.tau.iter().map(|&t| g.neg(t)).collect();
    for i in (0..nodes.len()).rev() {
        for &(j, s) in &out[i].s {
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
