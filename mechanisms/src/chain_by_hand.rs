//! A planar chain of `N` identical links written by hand with Featherstone's articulated-body
//! algorithm: the O(N) reference the generated chain models are timed against (the
//! `scaling` report) and checked against (`tests/chain_by_hand.rs`).
//!
//! # The chain
//! `N` uniform links of length `l`, mass `m`, centroidal inertia `m l^2 / 12`, joined by
//! revolute joints, the first pinned to the ground at the origin; gravity `(0, -g)`. The
//! coordinates `q_1..q_N` are *relative* joint angles: link `k`'s absolute angle is
//! `theta_k = q_1 + ... + q_k` and its direction `(sin theta_k, -cos theta_k)` (the chain hangs
//! straight down at `q = 0`). Joint `k` sits at the distal end of link `k - 1` (joint 1 at the
//! origin), link `k`'s mass centre at `joint_k + (l / 2)(sin theta_k, -cos theta_k)`.
//!
//! # The algorithm (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, Sect. 7.3, with
//! the planar vectors of Sect. 2.16)
//! Planar spatial vectors have three components: a motion `[omega; v_x, v_y]` (`v` the
//! velocity of the body point at the frame's origin) and a force `[n; f_x, f_y]` (`n` the
//! moment about that origin). Link `k`'s frame sits at joint `k`, rotated by `theta_k`, so
//! the link lies along its local `-y` axis with its mass centre at `(0, -l/2)`, and its
//! spatial inertia about the joint is the constant
//! `I = [[m l^2/3, m l/2, 0], [m l/2, m, 0], [0, 0, m]]`. The joint's motion subspace is
//! `S = [1, 0, 0]`. From the parent's frame (origin `l` further down the parent's `-y` axis,
//! or the ground's origin for link 1) to link `k`'s,
//! `X_k = [[1, 0, 0], [c l_p, c, s], [-s l_p, -s, c]]`, `c = cos q_k`, `s = sin q_k`,
//! `l_p = l` (`0` for link 1). Gravity enters as the ground's fictitious acceleration
//! `a_0 = [0; 0, g]`.
//!
//! 1. Outward: `v_k = X_k v_{k-1} + S qd_k`, `c_k = v_k x S qd_k`, `p_k = v_k x* I v_k`.
//! 2. Inward: `U = I^A S`, `D = S^T U`, `u = -S^T p^A`; the parent receives
//!    `X^T (I^A - U U^T / D) X` and `X^T (p^A + I^a c + U u / D)`.
//! 3. Outward: `a_k = X_k a_{k-1} + c_k`, `qdd_k = (u - U^T a_k) / D`, `a_k += S qdd_k`.
//!
//! Hand optimisation: with `S = [1, 0, 0]` the articulated inertia passed to the parent,
//! `I^a = I^A - U U^T / D`, has a zero first row and column, and the bias force passed on has
//! a zero first component (`u = -p^A_0`), so the transforms act on a 2x2 block and a
//! 2-vector: `X^T I^a X` is the rotated block `K' = E^T K E` (`E` the 2x2 rotation in `X`)
//! bordered by `l K'_{0.}`, and nothing is ever stored as a 3x3 matrix. No allocation:
//! everything lives in `[f64; N]` arrays on the stack. Per link: one `sin_cos` and about
//! 70 floating-point operations.

use mbd::{Error, OdeSystem, Result, Vector};

/// The `N`-link chain of the module docs, evaluated by the articulated-body algorithm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainByHand<const N: usize> {
    /// Mass of each link.
    pub m: f64,
    /// Length of each link.
    pub l: f64,
    /// Gravitational acceleration (along `-y`).
    pub g: f64,
}

impl<const N: usize> ChainByHand<N> {
    /// The chain with links of mass `m` and length `l` under gravity `g`.
    pub fn new(m: f64, l: f64, g: f64) -> Self {
        ChainByHand { m, l, g }
    }

    /// The joint accelerations `qdd` at `(q, qd)`. Refuses a link without positive finite
    /// mass and length (its articulated inertia would be singular).
    pub fn acceleration(&self, q: &Vector<N>, qd: &Vector<N>) -> Result<Vector<N>> {
        self.check()?;
        let mut qdd = Vector::<N>::zeros();
        self.aba(q.as_slice(), qd.as_slice(), qdd.as_mut_slice());
        Ok(qdd)
    }

    fn check(&self) -> Result<()> {
        let ok = |x: f64| x > 0.0 && x.is_finite();
        if !(ok(self.m) && ok(self.l) && self.g.is_finite()) {
            return Err(Error::InvalidInput {
                what: "ChainByHand",
                detail: format!(
                    "needs m > 0, l > 0 finite and g finite, got m = {}, l = {}, g = {}",
                    self.m, self.l, self.g
                ),
            });
        }
        Ok(())
    }

    /// The articulated-body algorithm; `q`, `qd`, `qdd` have `N` entries.
    #[inline]
    fn aba(&self, q: &[f64], qd: &[f64], qdd: &mut [f64]) {
        let (m, l, g) = (self.m, self.l, self.g);
        // The link's spatial inertia about its joint, in its frame.
        let (i00, i01, i11) = (m * l * l / 3.0, 0.5 * m * l, m);

        // Per link: the joint's rotation, the velocity-product acceleration c = (0, c1, c2),
        // then the articulated inertia I^A (symmetric: a00 a01 a02 / a11 a12 / a22) and bias p^A.
        let mut sn = [0.0; N];
        let mut cs = [0.0; N];
        let mut c1 = [0.0; N];
        let mut c2 = [0.0; N];
        let mut a00 = [0.0; N];
        let mut a01 = [0.0; N];
        let mut a02 = [0.0; N];
        let mut a11 = [0.0; N];
        let mut a12 = [0.0; N];
        let mut a22 = [0.0; N];
        let mut p0 = [0.0; N];
        let mut p1 = [0.0; N];
        let mut p2 = [0.0; N];

        // 1. Outward: velocities, velocity products, rigid-body inertias and bias forces.
        let (mut w, mut vx, mut vy) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..N {
            let (s, c) = q[k].sin_cos();
            sn[k] = s;
            cs[k] = c;
            // v_k = X_k v_{k-1} + S qd_k: the parent's joint velocity moved l down its link.
            let lp = if k == 0 { 0.0 } else { l };
            let (x, y) = (vx + w * lp, vy);
            vx = c * x + s * y;
            vy = -s * x + c * y;
            w += qd[k];
            // c_k = v_k x [qd_k; 0, 0].
            c1[k] = vy * qd[k];
            c2[k] = -vx * qd[k];
            // p_k = v_k x* (I v_k), with I v = (h0, h1, h2).
            let h1 = i01 * w + i11 * vx;
            let h2 = i11 * vy;
            p0[k] = -vy * h1 + vx * h2;
            p1[k] = -w * h2;
            p2[k] = w * h1;
            a00[k] = i00;
            a01[k] = i01;
            a11[k] = i11;
            a22[k] = i11;
        }

        // 2. Inward: articulated inertias and bias forces, handed to the parent.
        let mut dinv = [0.0; N];
        let mut uu = [0.0; N];
        for k in (0..N).rev() {
            let d = 1.0 / a00[k];
            let u = -p0[k];
            dinv[k] = d;
            uu[k] = u;
            if k == 0 {
                break;
            }
            // I^a = I^A - U U^T / D: only the 2x2 block K survives.
            let (u1, u2) = (a01[k], a02[k]);
            let k11 = a11[k] - u1 * u1 * d;
            let k12 = a12[k] - u1 * u2 * d;
            let k22 = a22[k] - u2 * u2 * d;
            // p^a = p^A + I^a c + U u / D: its first component is p0 + u = 0.
            let ud = u * d;
            let q1 = p1[k] + k11 * c1[k] + k12 * c2[k] + u1 * ud;
            let q2 = p2[k] + k12 * c1[k] + k22 * c2[k] + u2 * ud;
            // To the parent: K' = E^T K E with E = [[c, s], [-s, c]]; P' = E^T P.
            let (s, c) = (sn[k], cs[k]);
            let (e11, e12) = (c * k11 - s * k12, c * k12 - s * k22); // (E^T K) row 1
            let (e21, e22) = (s * k11 + c * k12, s * k12 + c * k22); // (E^T K) row 2
            let kk11 = e11 * c - e12 * s;
            let kk12 = e11 * s + e12 * c;
            let kk22 = e21 * s + e22 * c;
            let pp1 = c * q1 - s * q2;
            let pp2 = s * q1 + c * q2;
            // X^T I^a X = [[l^2 K'11, l K'11, l K'12], [., K'11, K'12], [., ., K'22]].
            let j = k - 1;
            a00[j] += l * l * kk11;
            a01[j] += l * kk11;
            a02[j] += l * kk12;
            a11[j] += kk11;
            a12[j] += kk12;
            a22[j] += kk22;
            // X^T p^a = [l P'_1; P'_1, P'_2].
            p0[j] += l * pp1;
            p1[j] += pp1;
            p2[j] += pp2;
        }

        // 3. Outward: accelerations, from the ground's fictitious upward acceleration g.
        let (mut aw, mut ax, mut ay) = (0.0f64, 0.0f64, g);
        for k in 0..N {
            let (s, c) = (sn[k], cs[k]);
            let lp = if k == 0 { 0.0 } else { l };
            let (x, y) = (ax + aw * lp, ay);
            ax = c * x + s * y + c1[k];
            ay = -s * x + c * y + c2[k];
            let acc = (uu[k] - a00[k] * aw - a01[k] * ax - a02[k] * ay) * dinv[k];
            qdd[k] = acc;
            aw += acc;
        }
    }

    /// Kinetic plus gravitational potential energy, from the kinematics of the module docs
    /// (mass-centre positions and velocities in the ground frame), independently of the
    /// algorithm: conserved along exact solutions.
    pub fn energy(&self, q: &Vector<N>, qd: &Vector<N>) -> f64 {
        let (m, l, g) = (self.m, self.l, self.g);
        let (mut th, mut thd) = (0.0, 0.0);
        let (mut jy, mut jvx, mut jvy) = (0.0, 0.0, 0.0); // joint k's height and velocity
        let mut e = 0.0;
        for k in 0..N {
            th += q[k];
            thd += qd[k];
            let (s, c) = f64::sin_cos(th);
            // Centre: joint + (l/2)(s, -c); its velocity adds (l/2) thd (c, s).
            let (vx, vy) = (jvx + 0.5 * l * thd * c, jvy + 0.5 * l * thd * s);
            let y = jy - 0.5 * l * c;
            e += 0.5 * m * (vx * vx + vy * vy) + 0.5 * (m * l * l / 12.0) * thd * thd + m * g * y;
            jy -= l * c;
            jvx += l * thd * c;
            jvy += l * thd * s;
        }
        e
    }
}

impl<const N: usize, const D: usize> OdeSystem<D> for ChainByHand<N> {
    /// `y = [q; qd]`, `y' = [qd; qdd]`.
    fn rhs(&self, _t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        const { assert!(D == 2 * N, "the state of an N-link chain has 2 N entries") };
        self.check()?;
        let mut out = Vector::<D>::zeros();
        let (q, qd) = y.as_slice().split_at(N);
        let (vel, acc) = out.as_mut_slice().split_at_mut(N);
        vel.copy_from_slice(qd);
        self.aba(q, qd, acc);
        Ok(out)
    }
}

/// The same chain in today's explicit-expression language: the source of a
/// `#[derive(Mechanism)]` struct `name` with fields `m`, `l`, `g`, coordinates `q1..qN`, and
/// each link a `#[rigid]` with its mass-centre position and absolute angle written out.
/// The `scaling` report writes it into its throw-away crates.
pub fn explicit_source(name: &str, n: usize) -> String {
    let mut src = String::from("#[derive(Debug, Clone, Mechanism)]\n#[gravity(0.0, -g)]\n");
    let coords: Vec<String> = (1..=n).map(|k| format!("q{k}")).collect();
    src += &format!("#[coords({})]\n", coords.join(", "));
    for k in 1..=n {
        let theta = |j: usize| coords[..j].join(" + ");
        // x = l (sin th_1 + ... + sin th_{k-1}) + l/2 sin th_k, y likewise with -cos.
        let mut x: Vec<String> = (1..k).map(|j| format!("l * sin({})", theta(j))).collect();
        let mut y: Vec<String> = (1..k).map(|j| format!("l * cos({})", theta(j))).collect();
        x.push(format!("l / 2.0 * sin({})", theta(k)));
        y.push(format!("l / 2.0 * cos({})", theta(k)));
        src += &format!(
            "#[rigid(link{k}, mass = m, inertia = m * l * l / 12.0, at = [{}, -({})], angle = {})]\n",
            x.join(" + "),
            y.join(" + "),
            theta(k)
        );
    }
    src += &format!("pub struct {name} {{ pub m: f64, pub l: f64, pub g: f64 }}\n");
    src
}

/// The same chain in the joint-tree language (`#[chain]`).
pub fn chain_source(name: &str, n: usize) -> String {
    format!(
        "#[derive(Debug, Clone, Mechanism)]\n#[gravity(0.0, -g)]\n\
         #[chain(link, n = {n}, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]\n\
         pub struct {name} {{ pub m: f64, pub l: f64, pub g: f64 }}\n"
    )
}
