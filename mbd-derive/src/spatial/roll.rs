//! A spatial tree's tail run of identical links, rolled: the articulated-body recursion
//! generated once for one link, as three loops over the links, instead of unrolled (the
//! spatial twin of `tree::rolled`). A link is a group of `per` consecutive steps (a
//! universal joint's two, a spherical joint's three): the code of one group, whatever the
//! length of the run, so a long chain's build no longer grows with its length.

use super::{
    Articulated, Inputs, Joint, Node, Outward, Si, Step, Sv, Transform, Unrolled, accelerate,
    inertia_at_origin, inward, outward, sv_add,
};
use crate::sym::{Expr, Func, Graph, Node as SymNode};
use crate::tree::{Loop, Rolled};

/// The fewest identical links rolled into loops. Measured with the `scaling` report
/// (bars on universal joints, generated against hand-written in one process): 8 bars (a
/// run of 7) run at 0.27 of the hand-written twin rolled against 0.36 unrolled, 32 bars at
/// 0.28 against 0.39, and build in 6.5 s instead of 28 s (docs/ARCHITECTURE.md).
pub const ROLL_FROM: usize = 6;

/// The steps a link may have (a spherical joint's three).
const MAX_PER_LINK: usize = 3;

/// Whether two nodes are the same step of identical links: the same joint axis, offset,
/// mass centre, mass and inertia (hash-consed, so equal expressions are equal nodes).
fn same(a: &Node, b: &Node) -> bool {
    let axis = |n: &Node| match n.step {
        Step::Revolute { axis, .. } => Some(axis),
        _ => None,
    };
    axis(a).is_some()
        && axis(a) == axis(b)
        && a.at == b.at
        && a.com == b.com
        && a.mass == b.mass
        && a.inertia == b.inertia
}

/// A run's step: a free revolute step turned by its coordinate itself, with no applied
/// generalised force (`tau` would differ per link). Its coordinate, or `None`.
fn free_coord(g: &Graph, n: &Node, inp: &Inputs<'_>) -> Option<usize> {
    let Step::Revolute { coord, .. } = n.step else {
        return None;
    };
    let turned = n
        .turn
        .is_some_and(|(_, angle)| matches!(g.node(angle), SymNode::Sym(_)));
    (turned && inp.prescribed[coord].is_none() && g.is_zero(inp.tau[coord])).then_some(coord)
}

/// How many links of `per` steps end the tree, each identical to the last, each on the one
/// before, their coordinates consecutive.
fn links_of(g: &Graph, nodes: &[Node], inp: &Inputs<'_>, per: usize) -> usize {
    let n = nodes.len();
    let Some(last) = nodes.last().and_then(|l| free_coord(g, l, inp)) else {
        return 0;
    };
    let mut links = 0;
    while (links + 1) * per <= n {
        let start = n - (links + 1) * per;
        let step_ok = |k: usize| {
            let i = start + k;
            let inner = k == 0 || nodes[i].parent == Some(i - 1);
            let coord = (last + i + 1).checked_sub(n);
            inner && same(&nodes[i], &nodes[n - per + k]) && free_coord(g, &nodes[i], inp) == coord
        };
        // The next link hangs on this one's last step.
        let next = start + per;
        let chained = links == 0 || nodes[next].parent == Some(next - 1);
        if !(chained && (0..per).all(step_ok)) {
            break;
        }
        links += 1;
    }
    // The run's first link must hang on something: the rest of the tree is not empty.
    while links > 0 && nodes[n - links * per].parent.is_none() {
        links -= 1;
    }
    links
}

/// The tail run as (first node, steps per link, links), the longest over the link sizes,
/// when it has at least [`ROLL_FROM`] links.
fn tail_run(g: &Graph, nodes: &[Node], inp: &Inputs<'_>) -> Option<(usize, usize, usize)> {
    (1..=MAX_PER_LINK)
        .map(|per| (per, links_of(g, nodes, inp, per)))
        .filter(|&(_, links)| links >= ROLL_FROM)
        .max_by_key(|&(per, links)| (per * links, usize::MAX - per))
        .map(|(per, links)| (nodes.len() - per * links, per, links))
}

/// A value kept per link for a later loop: its placeholder (a constant needs none).
fn keep(g: &mut Graph, name: &str, value: Expr, into: &mut Vec<(Expr, Expr)>) -> Expr {
    if g.as_const(value).is_some() {
        return value;
    }
    let s = g.symbol(&format!("__mbd_run_{name}"));
    into.push((s, value));
    s
}

fn keep_sv(g: &mut Graph, name: &str, v: Sv, into: &mut Vec<(Expr, Expr)>) -> Sv {
    Sv {
        a: [0, 1, 2].map(|i| keep(g, &format!("{name}a{i}"), v.a[i], into)),
        l: [0, 1, 2].map(|i| keep(g, &format!("{name}l{i}"), v.l[i], into)),
    }
}

fn placeholder_sv(g: &mut Graph, name: &str) -> Sv {
    Sv {
        a: [0, 1, 2].map(|i| g.symbol(&format!("__mbd_run_{name}a{i}"))),
        l: [0, 1, 2].map(|i| g.symbol(&format!("__mbd_run_{name}l{i}"))),
    }
}

/// `(placeholder, start, next)` for the six components of a carried spatial vector.
fn carry_sv(held: Sv, start: Sv, next: Sv) -> Vec<(Expr, Expr, Expr)> {
    (0..3)
        .map(|i| (held.a[i], start.a[i], next.a[i]))
        .chain((0..3).map(|i| (held.l[i], start.l[i], next.l[i])))
        .collect()
}

/// The upper triangle of a 3x3 matrix, row by row.
const UPPER: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// A symmetric inertia's 21 independent entries (`a`, `m` upper triangles, all of `b`) as
/// placeholders, and the inertia they stand for.
fn placeholder_si(g: &mut Graph) -> (Vec<Expr>, Si) {
    let mut held = Vec::with_capacity(21);
    let sym = |g: &mut Graph, name: &str, held: &mut Vec<Expr>| {
        let mut m = [[g.zero(); 3]; 3];
        for (r, k) in UPPER {
            m[r][k] = g.symbol(&format!("__mbd_run_k{name}{r}{k}"));
            m[k][r] = m[r][k];
            held.push(m[r][k]);
        }
        m
    };
    let a = sym(g, "a", &mut held);
    let m = sym(g, "m", &mut held);
    let b = std::array::from_fn(|r| {
        std::array::from_fn(|k| {
            let s = g.symbol(&format!("__mbd_run_kb{r}{k}"));
            held.push(s);
            s
        })
    });
    (held, Si { a, b, m })
}

/// `i`'s entries in [`placeholder_si`]'s order.
fn si_entries(i: &Si) -> Vec<Expr> {
    let mut out = Vec::with_capacity(21);
    for m in [&i.a, &i.m] {
        out.extend(UPPER.iter().map(|&(r, k)| m[r][k]));
    }
    out.extend(i.b.iter().flatten().copied());
    out
}

/// The rotation about `axis` by the angle whose cosine and sine are `c`, `s`.
fn rotation_cs(g: &mut Graph, axis: usize, c: Expr, s: Expr) -> [[Expr; 3]; 3] {
    let ns = g.neg(s);
    let (o, z) = (g.one(), g.zero());
    match axis {
        0 => [[o, z, z], [z, c, ns], [z, s, c]],
        1 => [[c, z, s], [z, o, z], [ns, z, c]],
        _ => [[c, ns, z], [s, c, z], [z, z, o]],
    }
}

/// One link's steps as the loops see them: a template node (its turn by a placeholder
/// angle), the transform from the stored cosine and sine, the stored `c` and `p`.
struct LinkStep {
    node: Node,
    x: Transform,
    o: Outward,
}

/// The recursion of [`super::articulated_body`] with its tail run rolled into loops, when
/// the tree has one (see [`tail_run`]).
pub fn rolled(g: &mut Graph, nodes: &[Node], inp: &Inputs<'_>) -> Option<Rolled> {
    let (start, per, len) = tail_run(g, nodes, inp)?;
    let parent = nodes[start].parent?;
    let first_coord = free_coord(g, &nodes[start], inp)?;
    let coords: Vec<(Expr, Expr)> = (0..per)
        .map(|k| {
            let q = g.symbol(&format!("__mbd_run_q{k}"));
            (q, g.symbol(&format!("__mbd_run_qd{k}")))
        })
        .collect();
    let mut velocity = inp.velocity.to_vec();
    for (k, c) in coords.iter().enumerate() {
        velocity[first_coord + k] = c.1;
    }
    let zero = g.zero();
    let rest_nodes = &nodes[..start];
    let rest = Unrolled::new(g, rest_nodes, inp);

    // Loop 1: velocities; keeps each step's cosine, sine, c and p.
    let v_in = placeholder_sv(g, "v");
    let mut stored1 = Vec::new();
    let mut steps: Vec<LinkStep> = Vec::with_capacity(per);
    let mut v = v_in;
    for k in 0..per {
        let src = &nodes[start + k];
        let (axis, _) = src.turn?;
        let node = Node {
            parent: Some(0),
            step: src.step,
            turn: Some((axis, coords[k].0)),
            at: src.at,
            com: src.com,
            mass: src.mass,
            inertia: src.inertia,
        };
        let x = Transform::new(g, &node);
        let o = outward(g, &node, &x, Some(v), &velocity);
        v = o.v;
        let (c, s) = (
            g.call(Func::Cos, coords[k].0),
            g.call(Func::Sin, coords[k].0),
        );
        let (c, s) = (
            keep(g, &format!("cos{k}"), c, &mut stored1),
            keep(g, &format!("sin{k}"), s, &mut stored1),
        );
        let rot = Some(rotation_cs(g, axis, c, s));
        let o = Outward {
            c: keep_sv(g, &format!("c{k}"), o.c, &mut stored1),
            p: keep_sv(g, &format!("p{k}"), o.p, &mut stored1),
            ..o
        };
        steps.push(LinkStep {
            x: Transform { rot, r: node.at },
            node,
            o,
        });
    }
    let loop1 = Loop {
        reverse: false,
        carried: carry_sv(v_in, rest.out[parent].v, v),
        stored: stored1,
        qdd: Vec::new(),
    };

    // Loop 2, tips to root: articulated inertias, the child's hand-on carried (zero below
    // the tip); keeps each step's U, u and 1 / D.
    let (k_held, k_in) = placeholder_si(g);
    let f_in = placeholder_sv(g, "f");
    let mut stored2 = Vec::new();
    let mut arts: Vec<Option<Articulated>> = vec![None; per];
    let mut hand_on = (k_in, f_in);
    for k in (0..per).rev() {
        let st = &steps[k];
        let own = inertia_at_origin(g, st.node.mass, st.node.com, &st.node.inertia);
        let mut i_a = own;
        let mut p_a = st.o.p;
        super::add_hand_on(g, (&mut i_a, &mut p_a), hand_on);
        let joint = Joint::Free { tau: zero };
        let (up, art) = inward(g, &st.x, &st.o, &st.node.step, &joint, (i_a, p_a));
        let Some(Articulated::Step { u_vec, u, inv_d }) = art else {
            return None;
        };
        arts[k] = Some(Articulated::Step {
            u_vec: keep_sv(g, &format!("uv{k}"), u_vec, &mut stored2),
            u: keep(g, &format!("u{k}"), u, &mut stored2),
            inv_d: keep(g, &format!("inv_d{k}"), inv_d, &mut stored2),
        });
        hand_on = up;
    }
    let (i_up, p_up) = hand_on;
    let mut carried2: Vec<(Expr, Expr, Expr)> = k_held
        .iter()
        .zip(si_entries(&i_up))
        .map(|(&h, next)| (h, zero, next))
        .collect();
    let zero_sv = Sv {
        a: [zero; 3],
        l: [zero; 3],
    };
    carried2.extend(carry_sv(f_in, zero_sv, p_up));
    let loop2 = Loop {
        reverse: true,
        carried: carried2,
        stored: stored2,
        qdd: Vec::new(),
    };

    // The rest of the tree, passes 2 and 3, with the run's hand-on (the values carried out
    // of loop 2).
    let (a, qdd) = rest.finish(g, rest_nodes, inp, Some((parent, (k_in, f_in))));

    // Loop 3: accelerations.
    let a_in = placeholder_sv(g, "acc");
    let mut acc = a_in;
    let mut local_qdd = vec![None; inp.velocity.len()];
    for (k, st) in steps.iter().enumerate() {
        let ap = st.x.motion(g, acc);
        let a_prime = sv_add(g, ap, st.o.c);
        let joint = Joint::Free { tau: zero };
        let inputs = (a_prime, &velocity[..]);
        acc = accelerate(g, &st.node, &st.o, &joint, arts[k], inputs, &mut local_qdd);
    }
    let run_qdd: Option<Vec<Expr>> = (0..per).map(|k| local_qdd[first_coord + k]).collect();
    let loop3 = Loop {
        reverse: false,
        carried: carry_sv(a_in, a[parent], acc),
        stored: Vec::new(),
        qdd: run_qdd?,
    };
    Some(Rolled {
        first_coord,
        len,
        per,
        coords,
        loops: [loop1, loop2, loop3],
        qdd,
    })
}
