//! A closed loop in its independent coordinates (coordinate partitioning, Wehage & Haug,
//! J. Mech. Des. 104, 1982): the state's dependent positions and rates are rebuilt from the
//! independent ones on the constraint manifold before every evaluation, so the right-hand
//! side depends on the independent coordinates alone and is the motion's own, smooth along
//! the assembly branch also where `Phi_q` loses rank (a singular position), where the
//! index-1 accelerations are only a limit.
//!
//! The dependent positions come from Gauss–Newton on `Phi(q, t) = 0` started at a Taylor
//! prediction from the last rebuilt state: the prediction, not the integrator's stage,
//! picks the branch, so a stage near the crossing of two branches stays on the one the
//! motion came along. Rates and accelerations follow from the Householder QR of the
//! dependent columns `Phi_d` (least squares, exact for the consistent equations; redundant
//! rows allowed): `qd_d = -Phi_d^+ (Phi_t + Phi_i qd_i)`, and with `qdd = R z'' + c`,
//! `R = [I; -Phi_d^+ Phi_i]`, `c = [0; Phi_d^+ gamma]`, the reduced equations
//! `R^T M R z'' = R^T (f - M c)`. Near a singular position these solves divide rounding by
//! the vanishing singular value, not the drift of an integrated state: the errors stay at
//! `eps / sigma`. A stage closer to the singular instant than rounding can resolve stops
//! with [`Error::SingularPosition`].

use crate::error::{Error, Result};
use crate::model::{Constrained, OdeSystem, Vector};
use nalgebra::{DMatrix, DVector};
use std::cell::RefCell;

/// A rebuilt consistent state `(t, q, qd, qdd)`.
type Rebuilt<const N: usize> = (f64, Vector<N>, Vector<N>, Vector<N>);

/// `sys` seen through its independent coordinates (module docs); states `y = [q; qd]`.
#[derive(Debug)]
pub struct Partitioned<'a, S, const N: usize, const M: usize> {
    sys: &'a S,
    /// Independent and dependent coordinate indices.
    free: Vec<usize>,
    dependent: Vec<usize>,
    last: RefCell<Option<Rebuilt<N>>>,
}

/// Rows of `R` below this fraction of the largest: the dependent columns lost rank.
const SINGULAR: f64 = 1e-13;
/// Refinement steps of the rates' and accelerations' solves ([`Partitioned::solve_refined`]).
const REFINE: usize = 2;
/// Newton converges linearly (halving) very near a singular position.
const NEWTON_ITERATIONS: usize = 60;

impl<'a, S: Constrained<N, M>, const N: usize, const M: usize> Partitioned<'a, S, N, M> {
    /// Choose `N - rank` independent coordinates at `(t, q)`: those the tangent space
    /// moves most (pivoted Gram–Schmidt on the rows of a null-space basis of `Phi_q`).
    pub fn new(sys: &'a S, t: f64, q: &Vector<N>, rank: usize) -> Result<Self> {
        let p = DMatrix::from_fn(M.max(1), N, |i, j| {
            if i < M { sys.phi_q(t, q)[(i, j)] } else { 0.0 }
        });
        let k = N.saturating_sub(rank);
        let free = if k == 0 {
            Vec::new()
        } else {
            let svd = nalgebra::SVD::new(p.transpose() * &p, true, true);
            let v = svd
                .v_t
                .ok_or(Error::SingularConstraintJacobian {
                    t,
                    detail: String::new(),
                })?
                .transpose();
            // Columns of `v` for the k smallest singular values.
            let mut order: Vec<usize> = (0..N).collect();
            order.sort_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]));
            let basis = DMatrix::from_fn(N, k, |i, j| v[(i, order[j])]);
            pivot_rows(basis)
        };
        let dependent = (0..N).filter(|i| !free.contains(i)).collect();
        Ok(Partitioned {
            sys,
            free,
            dependent,
            last: RefCell::new(None),
        })
    }

    /// Forget the last rebuilt state: the next evaluation starts its Newton iteration at
    /// the state it is given, not at a prediction from elsewhere (a run restarted from an
    /// earlier consistent state, after evaluations on the far side of a singular instant).
    pub fn forget(&self) {
        *self.last.borrow_mut() = None;
    }

    /// The system seen.
    pub fn system(&self) -> &'a S {
        self.sys
    }

    /// The independent coordinates.
    pub fn free(&self) -> &[usize] {
        &self.free
    }

    /// QR of the dependent columns of `Phi_q` at `(t, q)`, or `None` when they lost rank.
    fn factor(&self, t: f64, q: &Vector<N>) -> Option<Factored> {
        let pq = self.sys.phi_q(t, q);
        let d = DMatrix::from_fn(M, self.dependent.len(), |i, j| pq[(i, self.dependent[j])]);
        let i = DMatrix::from_fn(M, self.free.len(), |r, j| pq[(r, self.free[j])]);
        let qr = d.clone().qr();
        let r = qr.r();
        let diag = r.diagonal();
        let big = diag.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let small = diag.iter().fold(f64::INFINITY, |m, v| m.min(v.abs()));
        (small > SINGULAR * big && big.is_finite()).then_some(Factored {
            qr,
            r,
            pd: d,
            pi: i,
            conditioning: small / big,
        })
    }

    /// The least-squares solution of `Phi_d x = b`.
    fn solve(f: &Factored, b: &DVector<f64>) -> Option<DVector<f64>> {
        let mut qtb = b.clone();
        f.qr.q_tr_mul(&mut qtb);
        let n = f.r.nrows();
        f.r.solve_upper_triangular(&qtb.rows(0, n).into_owned())
    }

    /// [`Self::solve`] refined ([`REFINE`] times) against the residual `b - Phi_d x` summed
    /// in twice the working precision ([`crate::solve::dot2`]). Near a singular position
    /// `Phi_d` has condition `1/sigma`, and the plain solve's error `eps / sigma` in the
    /// rates goes into `gamma` and is divided by `sigma` again in the accelerations; the
    /// refined solve is as accurate as the entries of `Phi_d` and `b` themselves. Measured
    /// on exact parallelogram states of the 40-loop assembly: crank 0's acceleration was
    /// 8e-11 off at 0.1 rad from flat and 3e-8 at 6e-3 rad, 1e-12 and 2e-15 refined.
    fn solve_refined(f: &Factored, b: &DVector<f64>) -> Option<DVector<f64>> {
        let mut x = Self::solve(f, b)?;
        for _ in 0..REFINE {
            let r = DVector::from_fn(b.len(), |i, _| {
                let row = f.pd.row(i);
                crate::solve::dot2(
                    std::iter::once((b[i], 1.0))
                        .chain(row.iter().zip(x.iter()).map(|(a, v)| (-a, *v))),
                )
            });
            x += Self::solve(f, &r)?;
        }
        Some(x)
    }

    /// The consistent `(q, qd)` with the independent parts of `y`, and the QR at `q`.
    fn rebuild(
        &self,
        t: f64,
        y: &Vector<N>,
        yd: &Vector<N>,
    ) -> Result<(Vector<N>, Vector<N>, Factored)> {
        let singular = || Error::SingularPosition {
            t,
            detail: format!(
                "the dependent coordinates are not determined by the independent ones {:?} \
                 at q = {:?} (a singular position met to rounding)",
                self.free,
                y.as_slice()
            ),
        };
        let predicted = self.last.borrow().map(|(tc, qc, qdc, qddc)| {
            let s = t - tc;
            qc + qdc * s + qddc * (0.5 * s * s)
        });
        // From the prediction (which keeps the branch), else from the state itself.
        let q = match predicted.map(|p| self.newton(t, p, y)) {
            Some(Ok(q)) => q,
            _ => self.newton(t, *y, y)?,
        };
        let fq = self.factor(t, &q).ok_or_else(singular)?;
        let zd = DVector::from_iterator(self.free.len(), self.free.iter().map(|&i| yd[i]));
        let rhs =
            -(DVector::from_iterator(M, self.sys.phi_t(t, &q).iter().copied()) + &fq.pi * &zd);
        let xd = Self::solve_refined(&fq, &rhs).ok_or_else(singular)?;
        let mut qd = Vector::<N>::zeros();
        for (j, &c) in self.free.iter().enumerate() {
            qd[c] = zd[j];
        }
        for (j, &c) in self.dependent.iter().enumerate() {
            qd[c] = xd[j];
        }
        Ok((q, qd, fq))
    }

    /// Gauss–Newton on the dependent coordinates of `q` (its independent ones set from
    /// `y`), to the rounding floor.
    fn newton(&self, t: f64, mut q: Vector<N>, y: &Vector<N>) -> Result<Vector<N>> {
        let singular = || Error::SingularPosition {
            t,
            detail: format!(
                "the dependent coordinates are not determined by the independent ones {:?} \
                 at q = {:?} (a singular position met to rounding)",
                self.free,
                y.as_slice()
            ),
        };
        for &i in &self.free {
            q[i] = y[i];
        }
        let mut converged = false;
        let mut last = f64::INFINITY;
        for _ in 0..NEWTON_ITERATIONS {
            let fq = self.factor(t, &q).ok_or_else(singular)?;
            let phi = DVector::from_iterator(M, self.sys.phi(t, &q).iter().copied());
            let dx = Self::solve(&fq, &phi).ok_or_else(singular)?;
            if !dx.iter().all(|v| v.is_finite()) {
                return Err(Error::NonFinite { t });
            }
            // Rounding in `Phi`, divided by the smallest singular value: the floor of the
            // updates (near a singular position well above `eps`).
            let floor = 64.0 * f64::EPSILON / fq.conditioning;
            let mut small = true;
            for (j, &c) in self.dependent.iter().enumerate() {
                q[c] -= dx[j];
                small &= dx[j].abs() <= floor * (1.0 + q[c].abs());
            }
            // Converged to the floor, or updates that stop halving below it times 1e3.
            let size = dx.amax();
            if small || (size > 0.5 * last && size <= 1e3 * floor) {
                converged = true;
                break;
            }
            last = size;
        }
        if !converged {
            return Err(Error::SingularPosition {
                t,
                detail: format!(
                    "Newton on the dependent coordinates did not converge at q = {:?}",
                    q.as_slice()
                ),
            });
        }
        Ok(q)
    }

    /// `qdd = R z'' + c` from the reduced equations at a consistent `(q, qd)`.
    fn accelerations(
        &self,
        t: f64,
        q: &Vector<N>,
        qd: &Vector<N>,
        f: &Factored,
    ) -> Result<Vector<N>> {
        let (k, n) = (self.free.len(), self.dependent.len());
        let singular = || Error::SingularConstraintJacobian {
            t,
            detail: String::new(),
        };
        let gamma = DVector::from_iterator(M, self.sys.gamma(t, q, qd).iter().copied());
        let cd = Self::solve_refined(f, &gamma).ok_or_else(singular)?;
        let mut r = DMatrix::<f64>::zeros(N, k);
        for j in 0..k {
            let col = Self::solve_refined(f, &f.pi.column(j).into_owned()).ok_or_else(singular)?;
            r[(self.free[j], j)] = 1.0;
            for (i, &c) in self.dependent.iter().enumerate() {
                r[(c, j)] = -col[i];
            }
        }
        let mut c = DVector::<f64>::zeros(N);
        for i in 0..n {
            c[self.dependent[i]] = cd[i];
        }
        let mass = self.sys.mass_matrix(t, q)?;
        let mass = DMatrix::from_fn(N, N, |i, j| mass[(i, j)]);
        let force = DVector::from_iterator(N, self.sys.forces(t, q, qd)?.iter().copied());
        let mr = r.transpose() * &mass * &r;
        let fr = r.transpose() * (force - &mass * &c);
        let zdd = mr
            .cholesky()
            .ok_or(Error::SingularMassMatrix { t })?
            .solve(&fr);
        let qdd = r * zdd + c;
        let out = Vector::<N>::from_iterator(qdd.iter().copied());
        if out.iter().all(|v| v.is_finite()) {
            Ok(out)
        } else {
            Err(Error::NonFinite { t })
        }
    }
}

/// The QR of `Phi_d` and the independent columns `Phi_i` at a rebuilt state.
struct Factored {
    qr: nalgebra::QR<f64, nalgebra::Dyn, nalgebra::Dyn>,
    r: DMatrix<f64>,
    /// `Phi_d` itself, for the refinement's residuals.
    pd: DMatrix<f64>,
    pi: DMatrix<f64>,
    /// `min |r_jj| / max |r_jj|`: about the reciprocal condition of `Phi_d`.
    conditioning: f64,
}

/// `k` row indices of the `N x k` basis, largest remainder first.
fn pivot_rows(mut basis: DMatrix<f64>) -> Vec<usize> {
    let (n, k) = basis.shape();
    let mut chosen = Vec::with_capacity(k);
    for _ in 0..k {
        let best = (0..n)
            .filter(|i| !chosen.contains(i))
            .max_by(|&a, &b| basis.row(a).norm().total_cmp(&basis.row(b).norm()))
            .expect("k <= N");
        chosen.push(best);
        let e = basis.row(best).transpose().normalize();
        for i in 0..n {
            let c = basis.row(i).dot(&e.transpose());
            let mut row = basis.row_mut(i);
            row -= e.transpose() * c;
        }
    }
    chosen.sort_unstable();
    chosen
}

fn split<const N: usize, const D: usize>(y: &Vector<D>) -> (Vector<N>, Vector<N>) {
    (
        y.fixed_rows::<N>(0).into_owned(),
        y.fixed_rows::<N>(N).into_owned(),
    )
}

impl<S: Constrained<N, M>, const N: usize, const M: usize, const D: usize> OdeSystem<D>
    for Partitioned<'_, S, N, M>
{
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>> {
        const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
        let (q0, qd0) = split::<N, D>(y);
        let (q, qd, f) = self.rebuild(t, &q0, &qd0)?;
        let qdd = self.accelerations(t, &q, &qd, &f)?;
        *self.last.borrow_mut() = Some((t, q, qd, qdd));
        Ok(crate::integrate::stack(&qd, &qdd))
    }

    /// The state rebuilt from its independent coordinates.
    fn project(&self, t: f64, y: &mut Vector<D>) -> Result<()> {
        let (q0, qd0) = split::<N, D>(y);
        let (q, qd, _) = self.rebuild(t, &q0, &qd0)?;
        *y = crate::integrate::stack(&q, &qd);
        Ok(())
    }
}
