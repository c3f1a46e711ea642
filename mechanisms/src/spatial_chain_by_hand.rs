//! A spatial chain of `B` identical bodies on universal joints written by hand with
//! Featherstone's articulated-body algorithm: the O(B) reference the generated spatial trees
//! are timed against (the `scaling` report, `--family spatial`) and checked against
//! (`tests/spatial_chain_by_hand.rs`). The spatial twin of [`crate::chain_by_hand`].
//!
//! # The chain
//! `B` uniform bars of length `l`, mass `m`, centroidal inertia `diag(i, i, j)` in the bar's
//! axes, each hanging along its own `-z` axis from a universal joint `rot_x(a_k) rot_y(b_k)`
//! at the lower end of the bar above (the first at the ground's origin); gravity `(0, 0, -g)`.
//! The state is `[a_1, b_1, .., a_B, b_B; rates]`, the coordinates in the order the derive
//! gives them for [`spatial_chain_source`].
//!
//! # The algorithm (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, Sect. 7.3)
//! 6D spatial vectors in body coordinates: a motion `(w, v)` (`v` the velocity of the frame
//! origin) and a force `(n, f)` (moment about the origin). Each joint is two revolute steps,
//! about `x` into a massless frame at the joint and about `y` into the bar's frame, so that
//! each step has the motion subspace `S = e_x` or `e_y` and one scalar `D = S^T I^A S`. Per
//! step: `v = X v_parent + S qd`, `c = v x S qd`, `p = v x* I v`; inward
//! `U = I^A S`, `D = U_axis`, `u = tau - p^A_axis`, the parent receives
//! `X^T (I^A - U U^T / D) X` and `X^T (p^A + I^a c + U u / D)`; outward
//! `a = X a_parent + c`, `qdd = (u - U . a) / D`, `a += S qdd`. Gravity is the ground's
//! fictitious upward acceleration `(0, 0, g)`. Everything lives in fixed-size arrays on the
//! stack: no allocation.

use mbd::{Error, OdeSystem, Result, Vector};

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

/// A spatial motion or force.
#[derive(Clone, Copy, Default)]
struct Sv {
    a: V3,
    l: V3,
}

/// A symmetric spatial inertia `[[a, b], [b^T, m]]`.
#[derive(Clone, Copy, Default)]
struct Si {
    a: M3,
    b: M3,
    m: M3,
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn mv(m: &M3, v: V3) -> V3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

fn mtv(m: &M3, v: V3) -> V3 {
    std::array::from_fn(|k| m[0][k] * v[0] + m[1][k] * v[1] + m[2][k] * v[2])
}

fn skew(c: V3) -> M3 {
    [[0.0, -c[2], c[1]], [c[2], 0.0, -c[0]], [-c[1], c[0], 0.0]]
}

fn mm(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|k| (0..3).map(|j| a[i][j] * b[j][k]).sum()))
}

fn si_mul(i: &Si, v: Sv) -> Sv {
    Sv {
        a: add(mv(&i.a, v.a), mv(&i.b, v.l)),
        l: add(mtv(&i.b, v.a), mv(&i.m, v.l)),
    }
}

/// One step: a rotation by `(c, s)` about `axis` (0: x, 1: y) after a shift by `r`
/// (`r = (0, 0, r_z)`).
#[derive(Clone, Copy, Default)]
struct Joint {
    axis: usize,
    c: f64,
    s: f64,
    rz: f64,
}

impl Joint {
    /// `R v` (child axes to parent axes) for `R = rot_axis(q)`.
    fn up(&self, v: V3) -> V3 {
        let (c, s) = (self.c, self.s);
        if self.axis == 0 {
            [v[0], c * v[1] - s * v[2], s * v[1] + c * v[2]]
        } else {
            [c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]]
        }
    }

    /// `R^T v` (parent axes to child axes).
    fn down(&self, v: V3) -> V3 {
        let (c, s) = (self.c, self.s);
        if self.axis == 0 {
            [v[0], c * v[1] + s * v[2], -s * v[1] + c * v[2]]
        } else {
            [c * v[0] - s * v[2], v[1], s * v[0] + c * v[2]]
        }
    }

    /// `X m`: `(E w, E (v - r x w))`.
    fn motion(&self, m: Sv) -> Sv {
        let rw = cross([0.0, 0.0, self.rz], m.a);
        let v = [m.l[0] - rw[0], m.l[1] - rw[1], m.l[2] - rw[2]];
        Sv {
            a: self.down(m.a),
            l: self.down(v),
        }
    }

    /// `X^T f`: `(R n + r x R f, R f)`.
    fn force(&self, f: Sv) -> Sv {
        let fl = self.up(f.l);
        Sv {
            a: add(self.up(f.a), cross([0.0, 0.0, self.rz], fl)),
            l: fl,
        }
    }

    /// `R M R^T`.
    fn rotate(&self, m: &M3) -> M3 {
        let cols: [V3; 3] = std::array::from_fn(|k| self.up([m[0][k], m[1][k], m[2][k]]));
        // cols[k] = R m e_k; rows of (R m) R^T: R applied to each row of R m.
        let rm: M3 = std::array::from_fn(|i| [cols[0][i], cols[1][i], cols[2][i]]);
        std::array::from_fn(|i| self.up(rm[i]))
    }

    /// `X^T I X`: rotate the blocks, then shift by `r`.
    fn inertia(&self, i: &Si) -> Si {
        let (a, b, m) = (self.rotate(&i.a), self.rotate(&i.b), self.rotate(&i.m));
        if self.rz == 0.0 {
            return Si { a, b, m };
        }
        let rx = skew([0.0, 0.0, self.rz]);
        let rxm = mm(&rx, &m);
        let bt: M3 = std::array::from_fn(|r| std::array::from_fn(|k| b[k][r]));
        let s = mm(&rx, &bt);
        let rmr = mm(&rxm, &rx);
        Si {
            a: std::array::from_fn(|r| {
                std::array::from_fn(|k| a[r][k] + s[r][k] + s[k][r] - rmr[r][k])
            }),
            b: std::array::from_fn(|r| std::array::from_fn(|k| b[r][k] + rxm[r][k])),
            m,
        }
    }
}

/// The `B`-body universal-joint chain of the module docs, evaluated by the articulated-body
/// algorithm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpatialChainByHand<const B: usize> {
    pub m: f64,
    pub l: f64,
    /// Centroidal moments of inertia about the bar's `x`, `y` axes (`i`) and its `z` axis (`j`).
    pub i: f64,
    pub j: f64,
    pub g: f64,
}

impl<const B: usize> SpatialChainByHand<B> {
    pub fn new(m: f64, l: f64, i: f64, j: f64, g: f64) -> Self {
        SpatialChainByHand { m, l, i, j, g }
    }

    fn check(&self) -> Result<()> {
        let ok = |x: f64| x > 0.0 && x.is_finite();
        if !(ok(self.m) && ok(self.l) && ok(self.i) && ok(self.j) && self.g.is_finite()) {
            return Err(Error::InvalidInput {
                what: "SpatialChainByHand",
                detail: format!(
                    "needs m, l, i, j > 0 finite and g finite, got m = {}, l = {}, i = {}, j = {}, g = {}",
                    self.m, self.l, self.i, self.j, self.g
                ),
            });
        }
        Ok(())
    }

    /// The bar's spatial inertia about its joint, in its frame (mass centre at `(0, 0, -l/2)`).
    fn bar(&self) -> Si {
        let (m, h) = (self.m, -0.5 * self.l);
        let mh2 = m * h * h;
        let mc = skew([0.0, 0.0, m * h]);
        Si {
            a: [
                [self.i + mh2, 0.0, 0.0],
                [0.0, self.i + mh2, 0.0],
                [0.0, 0.0, self.j],
            ],
            b: mc,
            m: [[m, 0.0, 0.0], [0.0, m, 0.0], [0.0, 0.0, m]],
        }
    }

    /// The articulated-body algorithm over the `2 B` steps; `q`, `qd`, `qdd` have `2 B`
    /// entries.
    fn aba(&self, q: &[f64], qd: &[f64], qdd: &mut [f64]) {
        let bar = self.bar();
        // Per body: its two steps (x into the massless frame, y into the bar).
        let mut x = [[Joint::default(); 2]; B];
        let mut c = [[Sv::default(); 2]; B];
        let mut ia = [[Si::default(); 2]; B];
        let mut pa = [[Sv::default(); 2]; B];
        let mut u_vec = [[Sv::default(); 2]; B];
        let mut u = [[0.0; 2]; B];
        let mut dinv = [[0.0; 2]; B];
        // 1. Outward.
        let mut v = Sv::default();
        for k in 0..B {
            for st in 0..2 {
                let (s, co) = q[2 * k + st].sin_cos();
                let rz = if k > 0 && st == 0 { -self.l } else { 0.0 };
                let jt = Joint {
                    axis: st,
                    c: co,
                    s,
                    rz,
                };
                x[k][st] = jt;
                v = jt.motion(v);
                let rate = qd[2 * k + st];
                v.a[st] += rate;
                // c = v x (S qd): S qd = rate e_axis (angular).
                let mut e = [0.0; 3];
                e[st] = rate;
                c[k][st] = Sv {
                    a: cross(v.a, e),
                    l: cross(v.l, e),
                };
                if st == 1 {
                    let h = si_mul(&bar, v);
                    pa[k][1] = Sv {
                        a: add(cross(v.a, h.a), cross(v.l, h.l)),
                        l: cross(v.a, h.l),
                    };
                    ia[k][1] = bar;
                }
            }
        }
        // 2. Inward.
        for k in (0..B).rev() {
            for st in (0..2).rev() {
                let (i_a, p_a) = (ia[k][st], pa[k][st]);
                let mut e = Sv::default();
                e.a[st] = 1.0;
                let uv = si_mul(&i_a, e);
                let d = 1.0 / uv.a[st];
                let uu = -p_a.a[st];
                u_vec[k][st] = uv;
                u[k][st] = uu;
                dinv[k][st] = d;
                if k == 0 && st == 0 {
                    break;
                }
                let mut i_art = i_a;
                for r in 0..3 {
                    for q in 0..3 {
                        i_art.a[r][q] -= uv.a[r] * uv.a[q] * d;
                        i_art.b[r][q] -= uv.a[r] * uv.l[q] * d;
                        i_art.m[r][q] -= uv.l[r] * uv.l[q] * d;
                    }
                }
                let ic = si_mul(&i_art, c[k][st]);
                let ud = uu * d;
                let p_art = Sv {
                    a: std::array::from_fn(|r| p_a.a[r] + ic.a[r] + uv.a[r] * ud),
                    l: std::array::from_fn(|r| p_a.l[r] + ic.l[r] + uv.l[r] * ud),
                };
                let jt = x[k][st];
                let (i_up, p_up) = (jt.inertia(&i_art), jt.force(p_art));
                let (pk, ps) = if st == 1 { (k, 0) } else { (k - 1, 1) };
                let target = &mut ia[pk][ps];
                for r in 0..3 {
                    for q in 0..3 {
                        target.a[r][q] += i_up.a[r][q];
                        target.b[r][q] += i_up.b[r][q];
                        target.m[r][q] += i_up.m[r][q];
                    }
                }
                let tp = &mut pa[pk][ps];
                tp.a = add(tp.a, p_up.a);
                tp.l = add(tp.l, p_up.l);
            }
        }
        // 3. Outward.
        let mut a = Sv {
            a: [0.0; 3],
            l: [0.0, 0.0, self.g],
        };
        for k in 0..B {
            for st in 0..2 {
                let am = x[k][st].motion(a);
                a = Sv {
                    a: add(am.a, c[k][st].a),
                    l: add(am.l, c[k][st].l),
                };
                let uv = u_vec[k][st];
                let acc = (u[k][st] - dot(uv.a, a.a) - dot(uv.l, a.l)) * dinv[k][st];
                qdd[2 * k + st] = acc;
                a.a[st] += acc;
            }
        }
    }

    /// The joint accelerations at `(q, qd)` (`q = [a_1, b_1, ..]`, `2 B` entries each).
    pub fn acceleration(&self, q: &[f64], qd: &[f64]) -> Result<Vec<f64>> {
        self.check()?;
        if q.len() != 2 * B || qd.len() != 2 * B {
            return Err(Error::InvalidInput {
                what: "SpatialChainByHand",
                detail: format!("needs {} coordinates and rates", 2 * B),
            });
        }
        let mut qdd = vec![0.0; 2 * B];
        self.aba(q, qd, &mut qdd);
        Ok(qdd)
    }
}

impl<const B: usize, const D: usize> OdeSystem<D> for SpatialChainByHand<B> {
    /// `y = [q; qd]`, `y' = [qd; qdd]`.
    fn rhs(&self, _t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        const {
            assert!(
                D == 4 * B,
                "the state of a B-body universal chain has 4 B entries"
            )
        };
        self.check()?;
        let mut out = Vector::<D>::zeros();
        let (q, qd) = y.as_slice().split_at(2 * B);
        let (vel, acc) = out.as_mut_slice().split_at_mut(2 * B);
        vel.copy_from_slice(qd);
        self.aba(q, qd, acc);
        Ok(out)
    }
}

/// The same chain in the joint-tree language: the source of a `#[derive(Mechanism)]` struct
/// `name` with fields `m`, `l`, `i`, `j`, `g` and bodies `u1..uB` on joints
/// `universal(a1, b1) ..`. The `scaling` report writes it into its throw-away crates;
/// `form` is `""` or a `#[mechanism]` option such as `"mass_matrix"`.
pub fn spatial_chain_source(name: &str, bodies: usize, form: &str) -> String {
    let option = if form.is_empty() {
        String::new()
    } else {
        format!(", {form}")
    };
    let mut src = format!(
        "#[derive(Debug, Clone, Mechanism)]\n#[mechanism(spatial{option})]\n#[gravity(0.0, 0.0, -g)]\n"
    );
    for k in 1..=bodies {
        let (parent, at) = if k == 1 {
            (String::new(), String::new())
        } else {
            (
                format!("parent = u{}, ", k - 1),
                "at = [0.0, 0.0, -l], ".to_string(),
            )
        };
        src += &format!(
            "#[body(u{k}, {parent}joint = universal(a{k}, b{k}), {at}com = [0.0, 0.0, -l / 2.0], \
             mass = m, inertia = diag(i, i, j))]\n"
        );
    }
    src += &format!(
        "pub struct {name} {{ pub m: f64, pub l: f64, pub i: f64, pub j: f64, pub g: f64 }}\n"
    );
    src
}
