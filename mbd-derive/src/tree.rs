//! Joint trees: the articulated-body recursion that gives a planar tree's accelerations in
//! O(n) straight-line code.
//!
//! Featherstone's articulated-body algorithm (RBDA, ch. 7) in body coordinates, with planar
//! spatial vectors: a motion `(w, vx, vy)` (angular rate, velocity of the frame origin) and a
//! force `(n, fx, fy)` (moment about the frame origin, resultant), both in the body's frame.
//! Each body's inertia is then a constant of the parameters, and a joint's transform is one
//! rotation by its relative angle and one shift by its offset: the operations a careful
//! hand-written implementation does, unrolled over the tree at compile time, and ordered for
//! the latency of the inward pass's dependency chain (see [`inward`]).

use crate::sym::{Expr, Func, Graph};

/// A joint as the recursion sees it: the index of its coordinate among the full ones.
pub enum JointKin {
    Revolute {
        coord: usize,
    },
    /// `axis`: the unit direction in the parent's frame.
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
    /// The body frame's origin in the parent's frame (the prismatic travel included).
    pub at: [Expr; 2],
    /// The body frame's angle relative to the parent's.
    pub relative: Expr,
    /// The mass centre in the body's frame.
    pub com: [Expr; 2],
    /// The frame in the ground's coordinates (for loop closures).
    pub origin: [Expr; 2],
    pub angle: Expr,
    pub mass: Expr,
    /// Centroidal inertia; zero for a point mass.
    pub inertia: Expr,
}

/// `R(angle) v`.
pub fn rotate(g: &mut Graph, angle: Expr, v: [Expr; 2]) -> [Expr; 2] {
    let (c, s) = (g.call(Func::Cos, angle), g.call(Func::Sin, angle));
    rotate_cs(g, c, s, v)
}

fn rotate_cs(g: &mut Graph, c: Expr, s: Expr, v: [Expr; 2]) -> [Expr; 2] {
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

/// Spatial inertia about the frame origin of mass `m` at `c` with centroidal inertia `i`.
fn inertia_at_origin(g: &mut Graph, m: Expr, c: [Expr; 2], i: Expr) -> M3 {
    let r2 = g.dot(&c, &c);
    let mr2 = g.mul(m, r2);
    let (mcx, mcy) = (g.mul(m, c[0]), g.mul(m, c[1]));
    let nmcy = g.neg(mcy);
    let z = g.zero();
    [[g.add(i, mr2), nmcy, mcx], [nmcy, m, z], [mcx, z, m]]
}

/// A joint's parent-to-child transform: rotation by the relative angle (`cos`, `sin`) and the
/// child origin `r` in the parent's frame.
struct Transform {
    c: Expr,
    s: Expr,
    r: [Expr; 2],
}

impl Transform {
    fn new(g: &mut Graph, node: &Node) -> Self {
        Transform {
            c: g.call(Func::Cos, node.relative),
            s: g.call(Func::Sin, node.relative),
            r: node.at,
        }
    }

    /// `R^T v` (parent axes to child axes).
    fn to_child(&self, g: &mut Graph, v: [Expr; 2]) -> [Expr; 2] {
        let s = g.neg(self.s);
        rotate_cs(g, self.c, s, v)
    }

    /// `R v` (child axes to parent axes).
    fn to_parent(&self, g: &mut Graph, v: [Expr; 2]) -> [Expr; 2] {
        rotate_cs(g, self.c, self.s, v)
    }

    /// `w x r` for the planar rate `w`: `w (-r_y, r_x)`.
    fn arm(&self, g: &mut Graph, w: Expr) -> [Expr; 2] {
        let (a, b) = (g.mul(w, self.r[1]), g.mul(w, self.r[0]));
        [g.neg(a), b]
    }

    /// `X v + extra`: a motion vector of the parent frame seen in the child frame, plus one
    /// of the child's. Summed as `R^T v_lin + (extra_lin + w R^T (-r_y, r_x))`, the parent's
    /// angular rate `w` (the last value of the parent's step in pass 3) entering through one
    /// product and two sums, and the linear part through one rotation and one sum (as
    /// `R^T (v_lin + w x r)` it waited for a product, three sums and a rotation).
    fn motion_plus(&self, g: &mut Graph, v: V3, extra: V3) -> V3 {
        let rot = self.to_child(g, [v[1], v[2]]);
        let one = g.one();
        let arm = self.arm(g, one);
        let rho = self.to_child(g, arm);
        let lin = [0, 1].map(|i| {
            let w_term = g.mul(v[0], rho[i]);
            let late = g.add(extra[1 + i], w_term);
            g.add(rot[i], late)
        });
        [g.add(v[0], extra[0]), lin[0], lin[1]]
    }

    /// A motion vector of the parent frame seen in the child frame.
    fn motion(&self, g: &mut Graph, v: V3) -> V3 {
        let arm = self.arm(g, v[0]);
        let at_child = [g.add(v[1], arm[0]), g.add(v[2], arm[1])];
        let lin = self.to_child(g, at_child);
        [v[0], lin[0], lin[1]]
    }

    /// A force of the child frame seen in the parent frame (`X^T f`).
    fn force(&self, g: &mut Graph, f: V3) -> V3 {
        let lin = self.to_parent(g, [f[1], f[2]]);
        let (a, b) = (g.mul(self.r[0], lin[1]), g.mul(self.r[1], lin[0]));
        let moment = g.sub(a, b);
        [g.add(f[0], moment), lin[0], lin[1]]
    }

    /// An articulated inertia of the child frame seen in the parent frame (`X^T I X`):
    /// rotate the linear blocks, then shift the reference point by `r`.
    fn inertia(&self, g: &mut Graph, i: &M3) -> M3 {
        let b = self.to_parent(g, [i[1][0], i[2][0]]);
        let c0 = self.to_parent(g, [i[1][1], i[2][1]]);
        let c1 = self.to_parent(g, [i[1][2], i[2][2]]);
        // R C R^T: rotate the columns (above), then the rows; symmetric, so of the second
        // row only its diagonal entry is computed.
        let r0 = self.to_parent(g, [c0[0], c1[0]]);
        let r11 = {
            let (a, b) = (g.mul(self.s, c0[1]), g.mul(self.c, c1[1]));
            g.add(a, b)
        };
        let cr = [[r0[0], r0[1]], [r0[1], r11]];
        let rho = [g.neg(self.r[1]), self.r[0]];
        let w = [
            {
                let d = g.dot(&cr[0], &rho);
                g.add(b[0], d)
            },
            {
                let d = g.dot(&cr[1], &rho);
                g.add(b[1], d)
            },
        ];
        // a = i00 + 2 b.rho + rho^T C' rho, the last with the parameter-only products
        // rho_r rho_k (off the dependency chain through C').
        let brho = g.dot(&b, &rho);
        let two_brho = g.add(brho, brho);
        let mut a = g.add(i[0][0], two_brho);
        for r in 0..2 {
            for k in 0..2 {
                let rr = g.mul(rho[r], rho[k]);
                let term = g.mul(cr[r][k], rr);
                a = g.add(a, term);
            }
        }
        [
            [a, w[0], w[1]],
            [w[0], cr[0][0], cr[0][1]],
            [w[1], cr[1][0], cr[1][1]],
        ]
    }
}

/// The motion subspace of a joint in the child's frame.
fn subspace(g: &mut Graph, node: &Node, x: &Transform) -> Option<V3> {
    match &node.joint {
        JointKin::Revolute { .. } => Some([g.one(), g.zero(), g.zero()]),
        JointKin::Prismatic { axis, .. } => {
            let a = x.to_child(g, *axis);
            Some([g.zero(), a[0], a[1]])
        }
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

/// How a joint's coordinate enters one body's step.
#[derive(Clone, Copy)]
enum JointInput {
    /// Free: its generalised force other than gravity and inertia.
    Free { tau: Expr },
    /// Driven: its known acceleration.
    Driven { qdd: Expr },
    /// A fixed joint.
    Locked,
}

impl JointInput {
    fn of(node: &Node, inp: &Inputs<'_>) -> Self {
        match node.joint.coord() {
            Some(j) => match inp.prescribed[j] {
                None => JointInput::Free { tau: inp.tau[j] },
                Some(qdd) => JointInput::Driven { qdd },
            },
            None => JointInput::Locked,
        }
    }
}

/// Pass 1 of one body: velocity `v`, velocity-product acceleration `c`, bias force `p` and
/// rigid spatial inertia, from the parent's velocity (`None`: the ground) and the joint rate.
struct Outward {
    s: Option<V3>,
    v: V3,
    c: V3,
    p: V3,
    inertia: M3,
}

fn outward(
    g: &mut Graph,
    node: &Node,
    x: &Transform,
    parent: Option<V3>,
    rate: Option<Expr>,
) -> Outward {
    let z3 = [g.zero(); 3];
    let s = subspace(g, node, x);
    let vp = match parent {
        Some(v) => x.motion(g, v),
        None => z3,
    };
    let (v, c) = match (s, rate) {
        (Some(si), Some(rate)) => {
            let vj = scale3(g, si, rate);
            let v = add3(g, vp, vj);
            (v, cross_motion(g, v, vj))
        }
        _ => (vp, z3),
    };
    let inertia = inertia_at_origin(g, node.mass, node.com, node.inertia);
    let iv = mat_vec(g, &inertia, v);
    let p = cross_force(g, v, iv);
    Outward {
        s,
        v,
        c,
        p,
        inertia,
    }
}

/// What pass 3 needs of a free joint, in the parent's frame: `w = X^T U / D`
/// (`U = I^A S`) and `ed = e / D`, `e = u - U . c` (`u = tau - S . p^A`), so that
/// `qdd = ed - w . a_parent` waits on the parent's acceleration for one product and one
/// sum per component (the division and the scaling done in pass 2, off pass 3's chain).
#[derive(Clone, Copy)]
struct Articulated {
    w: V3,
    ed: Expr,
}

/// Pass 2 of one body: from its articulated inertia and bias force `(i_a, p_a)` (its own
/// plus its children's), what it hands its parent, in the parent's frame.
///
/// The handed-on `I^a = I^A - U U^T / D` and `p^a = p^A + I^a c + U u / D` are each kept as
/// a part without `1 / D` and a rank-one part with it, transformed to the parent apart, and
/// joined last: the pass is one long dependency chain through the divisions, and this way
/// each link adds one division, one multiplication and two additions to it (transforming
/// after the division adds two rotations and a shift).
fn inward(
    g: &mut Graph,
    node: &Node,
    x: &Transform,
    s: Option<V3>,
    joint: JointInput,
    (i_a, p_a): (M3, V3),
    c: V3,
) -> ((M3, V3), Option<Articulated>) {
    let Some(si) = s else {
        return ((x.inertia(g, &i_a), x.force(g, p_a)), None);
    };
    match joint {
        JointInput::Free { tau } => {
            let u = mat_vec(g, &i_a, si);
            let d = g.dot(&si, &u);
            let sp = g.dot(&si, &p_a);
            let u_force = g.sub(tau, sp);
            let one = g.one();
            let inv_d = g.div(one, d);
            let (mut i_rest, mut u_rest) = (i_a, u);
            let revolute = matches!(node.joint, JointKin::Revolute { .. });
            if revolute {
                // S = e0: row and column 0 of I^a vanish exactly (they would leave rounding
                // noise, and work, in the symbolic form); U's first entry goes with them.
                let z = g.zero();
                i_rest[0] = [z; 3];
                for row in &mut i_rest {
                    row[0] = z;
                }
                u_rest[0] = z;
            }
            let uc = g.dot(&u_rest, &c);
            let e = g.sub(u_force, uc);
            let ic = mat_vec(g, &i_rest, c);
            let mut p_rest = add3(g, p_a, ic);
            if revolute {
                // The joint transmits no moment but its own effort: p^a_0 = tau.
                p_rest[0] = tau;
            }
            // In the parent's frame: X^T I^a X = X^T I X - (X^T U)(X^T U)^T / D and
            // X^T p^a = X^T p + (X^T U) (e / D).
            let mut i_up = x.inertia(g, &i_rest);
            let v = x.force(g, u_rest);
            for r in 0..3 {
                for k in r..3 {
                    let vv = g.mul(v[r], v[k]);
                    let vvd = g.mul(vv, inv_d);
                    i_up[r][k] = g.sub(i_up[r][k], vvd);
                    i_up[k][r] = i_up[r][k];
                }
            }
            let ed = g.mul(e, inv_d);
            let p_base = x.force(g, p_rest);
            let v_ed = scale3(g, v, ed);
            let p_up = add3(g, p_base, v_ed);
            // Pass 3 uses the whole U (its first entry is D for a revolute joint); `e` is the
            // same with it, `c`'s angular entry being zero.
            let xu = x.force(g, u);
            let art = Articulated {
                w: scale3(g, xu, inv_d),
                ed,
            };
            ((i_up, p_up), Some(art))
        }
        JointInput::Driven { qdd } => {
            let sq = scale3(g, si, qdd);
            let acc = add3(g, c, sq);
            let ic = mat_vec(g, &i_a, acc);
            let p = add3(g, p_a, ic);
            ((x.inertia(g, &i_a), x.force(g, p)), None)
        }
        JointInput::Locked => ((x.inertia(g, &i_a), x.force(g, p_a)), None),
    }
}

/// Pass 3 of one body: its acceleration from its parent's (in the parent's frame), and
/// its free joint's acceleration.
fn accelerate(
    g: &mut Graph,
    x: &Transform,
    s: Option<V3>,
    joint: JointInput,
    parent: V3,
    c: V3,
    art: Option<Articulated>,
) -> (V3, Option<Expr>) {
    let a_prime = x.motion_plus(g, parent, c);
    let Some(si) = s else {
        return (a_prime, None);
    };
    let (acc, free) = match (joint, art) {
        (JointInput::Free { .. }, Some(art)) => {
            // U . a' = (X^T U) . a_parent + U . c; the parent's angular acceleration, the
            // last value of its step, is taken last.
            let mut acc = art.ed;
            for i in [1, 2, 0] {
                let term = g.mul(art.w[i], parent[i]);
                acc = g.sub(acc, term);
            }
            (acc, true)
        }
        (JointInput::Driven { qdd }, _) => (qdd, false),
        _ => return (a_prime, None),
    };
    let sq = scale3(g, si, acc);
    (add3(g, a_prime, sq), free.then_some(acc))
}

/// Adds a child's inertia and bias force, seen in the parent's frame, to the parent's.
fn hand_on(g: &mut Graph, (ia, pa): (&mut M3, &mut V3), (i_up, p_up): (M3, V3)) {
    for r in 0..3 {
        for k in r..3 {
            ia[r][k] = g.add(ia[r][k], i_up[r][k]);
            ia[k][r] = ia[r][k];
        }
    }
    *pa = add3(g, *pa, p_up);
}

/// The ground's fictitious acceleration that stands for gravity.
fn base_acceleration(g: &mut Graph, gravity: [Expr; 2]) -> V3 {
    let (gx, gy) = (g.neg(gravity[0]), g.neg(gravity[1]));
    [g.zero(), gx, gy]
}

/// The three passes of the recursion unrolled over a tree (all of it, or the part around a
/// rolled run), one body at a time.
struct Unrolled<'n> {
    nodes: &'n [Node],
    xs: Vec<Transform>,
    joints: Vec<JointInput>,
    out: Vec<Outward>,
}

impl<'n> Unrolled<'n> {
    /// Pass 1, root to tips: velocities, velocity products, bias forces, rigid inertias.
    fn new(g: &mut Graph, nodes: &'n [Node], inp: &Inputs<'_>) -> Self {
        let xs: Vec<Transform> = nodes.iter().map(|node| Transform::new(g, node)).collect();
        let joints: Vec<JointInput> = nodes.iter().map(|n| JointInput::of(n, inp)).collect();
        let mut out: Vec<Outward> = Vec::with_capacity(nodes.len());
        for (node, x) in nodes.iter().zip(&xs) {
            let parent = node.parent.map(|p| out[p].v);
            let rate = node.joint.coord().map(|j| inp.velocity[j]);
            let o = outward(g, node, x, parent, rate);
            out.push(o);
        }
        Unrolled {
            nodes,
            xs,
            joints,
            out,
        }
    }

    /// Passes 2 (tips to root, with `extra` handed on to one body by a part of the tree
    /// not in `nodes`) and 3 (root to tips, gravity as an upward acceleration of the
    /// ground): every body's acceleration and the free joints' accelerations, indexed like
    /// the full coordinates.
    fn finish(
        &self,
        g: &mut Graph,
        inp: &Inputs<'_>,
        extra: Option<(usize, (M3, V3))>,
    ) -> (Vec<V3>, Vec<Option<Expr>>) {
        let (nodes, xs, out) = (self.nodes, &self.xs, &self.out);
        let mut ia: Vec<M3> = out.iter().map(|o| o.inertia).collect();
        let mut pa: Vec<V3> = out.iter().map(|o| o.p).collect();
        if let Some((i, up)) = extra {
            hand_on(g, (&mut ia[i], &mut pa[i]), up);
        }
        let mut arts: Vec<Option<Articulated>> = vec![None; nodes.len()];
        for i in (0..nodes.len()).rev() {
            let (up, art) = inward(
                g,
                &nodes[i],
                &xs[i],
                out[i].s,
                self.joints[i],
                (ia[i], pa[i]),
                out[i].c,
            );
            arts[i] = art;
            if let Some(p) = nodes[i].parent {
                hand_on(g, (&mut ia[p], &mut pa[p]), up);
            }
        }
        let base = base_acceleration(g, inp.gravity);
        let mut a: Vec<V3> = Vec::with_capacity(nodes.len());
        let mut qdd = vec![None; inp.velocity.len()];
        for (i, node) in nodes.iter().enumerate() {
            let parent = node.parent.map_or(base, |p| a[p]);
            let (ai, acc) = accelerate(
                g,
                &xs[i],
                out[i].s,
                self.joints[i],
                parent,
                out[i].c,
                arts[i],
            );
            if let (Some(acc), Some(j)) = (acc, node.joint.coord()) {
                qdd[j] = Some(acc);
            }
            a.push(ai);
        }
        (a, qdd)
    }
}

/// The accelerations of the free joint coordinates: `Some(qdd)` at each free coordinate a
/// joint moves, by the three passes of the articulated-body algorithm.
pub fn articulated_body(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Vec<Option<Expr>> {
    Unrolled::new(g, nodes, inp).finish(g, inp, None).1
}

/// The shortest run of identical links that is rolled into loops. Measured with the
/// `scaling` report (generated against hand-written, one process, a chain's first link is
/// not part of its run): an 8-link chain runs at 0.83-0.87 unrolled and 0.78 rolled, a
/// 12-link one at 1.13 unrolled and 0.85 rolled; 6 links (unrolled either way) 0.73-0.94.
pub const ROLL_FROM: usize = 6;

/// One loop over the links of a run (see [`Rolled`]).
pub struct Loop {
    /// Tips to root (the inward pass).
    pub reverse: bool,
    /// Loop-carried values: placeholder symbol, value before the first link (an expression
    /// of the rest of the tree, evaluated just before the loop), value handed to the next.
    pub carried: Vec<(Expr, Expr, Expr)>,
    /// Per-link values kept for the later loops: placeholder symbol (read at the link's
    /// index), value.
    pub stored: Vec<(Expr, Expr)>,
    /// The link's joint accelerations, one per coordinate of a link (the last loop).
    pub qdd: Vec<Expr>,
}

/// The articulated-body recursion with a run of identical links (the tail of a `chain`)
/// generated once, as three loops over the links, instead of unrolled: the code of one
/// link, whatever the length of the run. Placeholder symbols stand for the link's
/// coordinate and rate (`q`, `qd`), for loop-carried values and for stored ones; the rest of
/// the tree stays unrolled around the loops.
pub struct Rolled {
    /// Full-coordinate index of the run's first joint; the run's joints are consecutive.
    pub first_coord: usize,
    /// Links in the run, coordinates per link (a spatial link's steps: `spatial/roll.rs`).
    pub len: usize,
    pub per: usize,
    /// Placeholders of a link's coordinates and rates, in order.
    pub coords: Vec<(Expr, Expr)>,
    /// Outward velocities, inward articulated inertias, outward accelerations.
    pub loops: [Loop; 3],
    /// The accelerations of the other free coordinates (`None` at the run's), evaluated
    /// after the inward loop.
    pub qdd: Vec<Option<Expr>>,
}

impl Rolled {
    /// Every placeholder symbol, and whether it is read per link (a stored array).
    pub fn placeholders(&self) -> Vec<(Expr, bool)> {
        let mut all: Vec<(Expr, bool)> = (self.coords.iter())
            .flat_map(|&(q, qd)| [(q, false), (qd, false)])
            .collect();
        for l in &self.loops {
            all.extend(l.carried.iter().map(|c| (c.0, false)));
            all.extend(l.stored.iter().map(|s| (s.0, true)));
        }
        all
    }
}

/// The tail of `nodes` that is a run of at least [`ROLL_FROM`] identical links: each a
/// free revolute joint on the one before, with the same offset, mass centre, mass and
/// inertia, no applied generalised force and consecutive coordinates. `None` without one.
fn tail_run(g: &Graph, nodes: &[Node], inp: &Inputs<'_>) -> Option<usize> {
    let last = nodes.last()?;
    let same = |n: &Node| {
        n.at == last.at && n.com == last.com && n.mass == last.mass && n.inertia == last.inertia
    };
    let coord = |n: &Node| match n.joint {
        JointKin::Revolute { coord }
            if inp.prescribed[coord].is_none() && g.is_zero(inp.tau[coord]) =>
        {
            matches!(g.node(n.relative), crate::sym::Node::Sym(_)).then_some(coord)
        }
        _ => None,
    };
    let mut start = nodes.len() - 1;
    coord(last)?;
    while start > 0 {
        let n = &nodes[start];
        let prev = &nodes[start - 1];
        let chained = n.parent == Some(start - 1)
            && same(prev)
            && prev.parent.is_some()
            && matches!((coord(prev), coord(n)), (Some(a), Some(b)) if a + 1 == b);
        if !chained {
            break;
        }
        start -= 1;
    }
    (nodes.len() - start >= ROLL_FROM && nodes[start].parent.is_some()).then_some(start)
}

/// The recursion of [`articulated_body`] with its tail run rolled into loops, when the tree
/// has one (see [`tail_run`]).
pub fn rolled(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Option<Rolled> {
    let start = tail_run(g, nodes, inp)?;
    let len = nodes.len() - start;
    let head = &nodes[start];
    let parent = head.parent?;
    let JointKin::Revolute { coord: first_coord } = head.joint else {
        return None;
    };
    let mut ph = |name: &str| g.symbol(&format!("__mbd_run_{name}"));
    let (q, qd) = (ph("q"), ph("qd"));
    let v_in = [ph("vw"), ph("vx"), ph("vy")];
    let k_names = ["k00", "k01", "k02", "k11", "k12", "k22"];
    let k_in: Vec<Expr> = k_names.iter().map(|n| ph(n)).collect();
    let f_in = [ph("f0"), ph("f1"), ph("f2")];
    let a_in = [ph("aw"), ph("ax"), ph("ay")];
    // One link, its angle the placeholder `q` (each pass is given its parent directly).
    let link = Node {
        parent: Some(0),
        joint: JointKin::Revolute { coord: first_coord },
        at: head.at,
        relative: q,
        com: head.com,
        origin: head.origin,
        angle: head.angle,
        mass: head.mass,
        inertia: head.inertia,
    };
    let zero = g.zero();
    let tau = JointInput::Free { tau: zero };

    // Loop 1: velocities; keeps the rotation, c and p per link.
    let x = Transform::new(g, &link);
    let o = outward(g, &link, &x, Some(v_in), Some(qd));
    let mut stored1 = Vec::new();
    let keep = |g: &mut Graph, name: &str, value: Expr, into: &mut Vec<(Expr, Expr)>| {
        if g.as_const(value).is_some() {
            return value;
        }
        let s = g.symbol(&format!("__mbd_run_{name}"));
        into.push((s, value));
        s
    };
    let cs = keep(g, "cos", x.c, &mut stored1);
    let sn = keep(g, "sin", x.s, &mut stored1);
    let c_k = [0, 1, 2].map(|i| keep(g, &format!("c{i}"), o.c[i], &mut stored1));
    let p_k = [0, 1, 2].map(|i| keep(g, &format!("p{i}"), o.p[i], &mut stored1));

    // The rest of the tree, pass 1: the velocity of the run's parent.
    let rest = Unrolled::new(g, &nodes[..start], inp);
    let loop1 = Loop {
        reverse: false,
        carried: (0..3)
            .map(|i| (v_in[i], rest.out[parent].v[i], o.v[i]))
            .collect(),
        stored: stored1,
        qdd: Vec::new(),
    };

    // Loop 2, tips to root: the articulated inertia from the link's own and the child's
    // hand-on (carried; zero below the tip).
    let xt = Transform {
        c: cs,
        s: sn,
        r: head.at,
    };
    let own = inertia_at_origin(g, head.mass, head.com, head.inertia);
    let k_full = [
        [k_in[0], k_in[1], k_in[2]],
        [k_in[1], k_in[3], k_in[4]],
        [k_in[2], k_in[4], k_in[5]],
    ];
    let mut i_a = own;
    for r in 0..3 {
        for c in 0..3 {
            i_a[r][c] = g.add(own[r][c], k_full[r][c]);
        }
    }
    let p_a = add3(g, p_k, f_in);
    let s_link = subspace(g, &link, &xt);
    let ((i_up, p_up), art) = inward(g, &link, &xt, s_link, tau, (i_a, p_a), c_k);
    let art = art?;
    let mut stored2 = Vec::new();
    let w = [0, 1, 2].map(|i| keep(g, &format!("w{i}"), art.w[i], &mut stored2));
    let ed = keep(g, "ed", art.ed, &mut stored2);
    let up_entries = [
        i_up[0][0], i_up[0][1], i_up[0][2], i_up[1][1], i_up[1][2], i_up[2][2],
    ];
    let mut carried2: Vec<(Expr, Expr, Expr)> =
        (0..6).map(|i| (k_in[i], zero, up_entries[i])).collect();
    carried2.extend((0..3).map(|i| (f_in[i], zero, p_up[i])));
    let loop2 = Loop {
        reverse: true,
        carried: carried2,
        stored: stored2,
        qdd: Vec::new(),
    };

    // The rest of the tree, passes 2 and 3, with the run's hand-on (the values carried out
    // of loop 2).
    let (a, qdd) = rest.finish(g, inp, Some((parent, (k_full, f_in))));

    // Loop 3: accelerations.
    let art = Articulated { w, ed };
    let (a_link, acc) = accelerate(g, &xt, s_link, tau, a_in, c_k, Some(art));
    let loop3 = Loop {
        reverse: false,
        carried: (0..3).map(|i| (a_in[i], a[parent][i], a_link[i])).collect(),
        stored: Vec::new(),
        qdd: acc.into_iter().collect(),
    };
    Some(Rolled {
        first_coord,
        len,
        per: 1,
        coords: vec![(q, qd)],
        loops: [loop1, loop2, loop3],
        qdd,
    })
}
