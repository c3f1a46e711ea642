//! The contract between generated models and the numerics.
//!
//! Sizes are const generics (`Vector<N>` is `SVector<f64, N>`), because stable Rust cannot
//! size an array by an associated constant inside generic code. The derive macro knows
//! every size of a model when it expands, so it writes them out as literals: the number of
//! free coordinates `N`, of constraints `M`, of first-order states `D = 2 N`. Generic code in
//! this crate then checks the relations between them at compile time with inline `const`
//! assertions (`const { assert!(D == 2 * N) }`), and a user never writes a size.

use crate::error::Result;
use nalgebra::{SMatrix, SVector};

/// A column of `N` reals.
pub type Vector<const N: usize> = SVector<f64, N>;
/// An `R x C` matrix of reals.
pub type Matrix<const R: usize, const C: usize> = SMatrix<f64, R, C>;

/// A first-order system `y' = f(t, y)` of fixed dimension `D`: what every integrator advances.
///
/// A generated mechanism implements it with `y = [q; qd]` and `D = 2 N`.
pub trait OdeSystem<const D: usize> {
    /// `f(t, y)`. An error (a singular mass matrix, say) stops the integration with that error.
    fn rhs(&self, t: f64, y: &Vector<D>) -> Result<Vector<D>>;

    /// `df/dy` at `(t, y)`. The default differentiates `rhs` by forward differences;
    /// generated models override it with the exact derivative and set [`Self::EXACT_JACOBIAN`].
    fn jacobian(&self, t: f64, y: &Vector<D>) -> Result<Matrix<D, D>> {
        crate::jacobian::forward_difference(|y| self.rhs(t, y), y)
    }

    /// Whether [`Self::jacobian`] is exact (generated) rather than a finite difference.
    const EXACT_JACOBIAN: bool = false;

    /// Whether the right-hand side switches between modes ([`Hybrid`]; generated models with
    /// Coulomb friction). Such a system without [`Self::hybrid`] whose ordinary solve
    /// collapses at a switch fails with [`crate::Error::ModeSwitch`], naming
    /// [`crate::hybrid::solve`].
    const HYBRID: bool = false;

    /// The system's modes, through which an integrator's ordinary `solve` runs it one mode
    /// at a time ([`crate::hybrid::solve`] with its default settings); `None` (the default)
    /// for a smooth system. Generated models with friction return themselves; a hand-written
    /// [`Hybrid`] system returns `Some(self)` to be solved the same way.
    fn hybrid(&self) -> Option<&dyn crate::hybrid::Modes<D>> {
        None
    }

    /// Bring `y` back onto the system's invariant manifolds after an accepted step.
    /// Closed loops project onto `Phi = 0` and `Phi_q qd + Phi_t = 0`; the default does nothing.
    fn project(&self, _t: f64, _y: &mut Vector<D>) -> Result<()> {
        Ok(())
    }

    /// A closed loop's bridge over its singular positions ([`crate::passage`]), through
    /// which an integrator's ordinary `solve` runs; `None` (the default) for a system
    /// without one. Generated models with constraints return themselves.
    fn passage(&self) -> Option<&dyn crate::passage::Bridge<D>> {
        None
    }

    /// [`Mechanism::chart_margin`] at `y = [q; qd]`; `None` (the default) for systems
    /// without closed-form closures.
    fn chart_margin(&self, _t: f64, _y: &Vector<D>) -> Option<f64> {
        None
    }

    /// [`Mechanism::rotation_charts`], the same indices into `y = [q; qd]`'s upper half.
    fn rotation_charts(&self) -> &[[usize; 3]] {
        &[]
    }
}

/// A mechanism in minimal coordinates: `M(q, t) qdd = f(q, qd, t)`, plus constraints when
/// [`Constrained`] is also implemented.
///
/// `q` holds the free coordinates only: driven coordinates are known functions of time and
/// are substituted into the kinematics by the derive.
pub trait Mechanism<const N: usize> {
    /// Names of the free generalised coordinates, in state order.
    const COORDINATES: [&'static str; N];

    /// The constraint rows of its [`Constrained`] implementation (`0`, the default, for a
    /// model without one). [`Self::mass_matrix`] and [`Self::forces`] leave the constraint
    /// forces out, so code that solves `M qdd = f` or `f = 0` alone refuses a model with
    /// rows rather than drop them (a Cartesian pendulum would fall freely).
    const CONSTRAINTS: usize = 0;

    /// The mass matrix `M(q, t)`: symmetric, positive definite when every coordinate moves mass.
    ///
    /// `mass_matrix`, [`Self::forces`], [`Self::energy`] and [`Self::inverse_dynamics`] fail
    /// where the accelerations do: a closed loop in minimal coordinates outside its closed
    /// forms' domain ([`crate::Error::SingularPosition`], naming the coordinate and the
    /// configuration), a parameter that means no mechanism, a NaN or infinite value. They
    /// never hand out a NaN.
    fn mass_matrix(&self, t: f64, q: &Vector<N>) -> Result<Matrix<N, N>>;

    /// The right-hand side `f(q, qd, t)`: generalised applied forces (gravity, springs,
    /// dampers, loads) minus the velocity-product terms.
    fn forces(&self, t: f64, q: &Vector<N>, qd: &Vector<N>) -> Result<Vector<N>>;

    /// Accelerations `qdd`: `M qdd = f`, or the constrained system for closed loops.
    fn acceleration(&self, t: f64, q: &Vector<N>, qd: &Vector<N>) -> Result<Vector<N>>;

    /// Total mechanical energy: kinetic plus the potential of gravity and springs. Conserved
    /// by a model without dampers, friction, loads or drives; the stress suite watches it.
    fn energy(&self, t: f64, q: &Vector<N>, qd: &Vector<N>) -> Result<f64>;

    /// For a closed loop reduced to minimal coordinates by closed forms: how far `q` lies
    /// inside the closed forms' domain (`min (1 - |u|)` over their `asin`/`acos` arguments
    /// `u`; zero at a limit position, negative outside). Fixed-step integrators watch it to
    /// stop at a limit position their stages stepped over ([`crate::closure::ChartWatch`]).
    /// `None` (the default) for models without closed-form closures.
    fn chart_margin(&self, _t: f64, _q: &Vector<N>) -> Option<f64> {
        None
    }

    /// The coordinates of each ball joint's (and free joint's) rotation parameters, which
    /// switch to their shadow set past a half turn ([`crate::chart`]): what an integrator
    /// that does not call [`OdeSystem::project`] (generalized-alpha) switches itself.
    /// Empty (the default) for a model without them.
    fn rotation_charts(&self) -> &[[usize; 3]] {
        &[]
    }

    /// Inverse dynamics: the generalised forces `M qdd - f` that must act besides the
    /// model's own (gravity, springs, dampers, loads) for the accelerations `qdd` (before
    /// constraint forces, for a model with constraints). The default forms `M` and `f`;
    /// the derive overrides it for a joint tree with recursive Newton-Euler (O(n)).
    fn inverse_dynamics(
        &self,
        t: f64,
        q: &Vector<N>,
        qd: &Vector<N>,
        qdd: &Vector<N>,
    ) -> Result<Vector<N>> {
        Ok(self.mass_matrix(t, q)? * qdd - self.forces(t, q, qd)?)
    }
}

/// [`Error::InvalidInput`](crate::Error::InvalidInput) for a model with constraint rows
/// given to `entry`, which solves `M qdd = f` or `f = 0` without them; `instead` names the
/// entry that keeps them.
pub(crate) fn unconstrained<S: Mechanism<N>, const N: usize>(
    entry: &str,
    instead: &str,
) -> Result<()> {
    if S::CONSTRAINTS == 0 {
        return Ok(());
    }
    Err(crate::Error::InvalidInput {
        what: "model",
        detail: format!(
            "it has {} constraint rows, which `{entry}` would drop (it solves the unconstrained \
             equations): use `{instead}`",
            S::CONSTRAINTS
        ),
    })
}

/// Holonomic constraints `Phi(q, t) = 0` on a [`Mechanism`] (`M` equations).
///
/// Sign convention: `M qdd + Phi_q^T lambda = f`, so `-Phi_q^T lambda` is the generalised
/// constraint force and a driving constraint's multiplier is minus the driving effort.
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not `Constrained` with the constraint rows this call needs",
    label = "needs `Constrained<N, M>`: `M` constraint rows (closures and drives) on `N` coordinates",
    note = "`analysis::kinematics` and `kinematic_sweep` need `M = N` (no free coordinate): a \
            mechanism with free coordinates is integrated, its state assembled with \
            `analysis::assemble`, or driven on each free coordinate (`drive`); a loop closed \
            in minimal coordinates has no constraint rows (`#[mechanism(augmented)]` keeps them)"
)]
pub trait Constrained<const N: usize, const M: usize>: Mechanism<N> {
    /// `Phi(q, t)`.
    fn phi(&self, t: f64, q: &Vector<N>) -> Vector<M>;
    /// `Phi_q = dPhi/dq`.
    fn phi_q(&self, t: f64, q: &Vector<N>) -> Matrix<M, N>;
    /// `Phi_t = dPhi/dt`.
    fn phi_t(&self, t: f64, q: &Vector<N>) -> Vector<M>;
    /// `gamma = -(Phi_q qd)_q qd - 2 Phi_qt qd - Phi_tt`, so that `Phi_q qdd = gamma`.
    fn gamma(&self, t: f64, q: &Vector<N>, qd: &Vector<N>) -> Vector<M>;
    /// `qdd` and `lambda` from `[M Phi_q^T; Phi_q 0] [qdd; lambda] = [f; gamma]`.
    fn acceleration_and_multipliers(
        &self,
        t: f64,
        q: &Vector<N>,
        qd: &Vector<N>,
    ) -> Result<(Vector<N>, Vector<M>)>;
}

/// What the derive generated for a model (read by the validation report): the parts that
/// exist (a model without constraints has no constraint code, and so on) and the number of
/// straight-line statements emitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Generated {
    /// Names of the generated parts: `mass_matrix`, `forces`, `phi`, `jacobian`, `outputs`, ...
    pub parts: &'static [&'static str],
    /// Statements (temporaries and assignments) in the generated functions.
    pub statements: usize,
    /// Constraint equations.
    pub constraints: usize,
}

/// A system with discrete modes: smooth dynamics `y' = f_mode(t, y)` within a mode, and
/// switching functions whose zero crossings end it. [`crate::hybrid::solve`] integrates one
/// mode at a time with any [`crate::integrate::Integrator`], locates the switch on the dense
/// output, asks [`Self::switch`] for the next mode and restarts there, so that no step ever
/// integrates across a discontinuity. Coulomb friction is one such system
/// ([`crate::friction`]); the derive implements this trait for every model with friction.
pub trait Hybrid<const D: usize> {
    /// The discrete state (for friction: slip forward, slip backward or stick, per contact).
    /// (`Send + Sync + 'static` so that a [`crate::integrate::Solution`] can keep it,
    /// erased, in its `switches`.)
    type Mode: Copy + PartialEq + std::fmt::Debug + Send + Sync + 'static;

    /// The number of switching functions (the same in every mode).
    const SWITCHES: usize;

    /// `y' = f(t, y)` in `mode`.
    fn rhs_in(&self, t: f64, y: &Vector<D>, mode: &Self::Mode) -> Result<Vector<D>>;

    /// Switching function `k` of `mode`: positive (or zero at the switch that entered the
    /// mode) while the mode holds; its falling crossing of zero ends the mode. NaN when it
    /// cannot be evaluated.
    fn switching(&self, t: f64, y: &Vector<D>, mode: &Self::Mode, k: usize) -> f64;

    /// The mode at `(t, y)` from the state alone: where a run starts, and what the plain
    /// right-hand side uses.
    fn mode_at(&self, t: f64, y: &Vector<D>) -> Result<Self::Mode>;

    /// The mode after switching function `k` of `mode` crossed zero at `(t, y)`; `y` may be
    /// set onto the switching surface (a sliding velocity that reached zero becomes exactly 0).
    fn switch(&self, t: f64, y: &mut Vector<D>, mode: &Self::Mode, k: usize) -> Result<Self::Mode>;

    /// `Some((i, sign))` where switching function `k` of `mode` is `sign * y[i]` (a sliding
    /// velocity): the driver then rules out a crossing inside a step from the dense
    /// polynomial's coefficients instead of sampling the function. The default: `None`.
    fn switching_state(&self, _mode: &Self::Mode, _k: usize) -> Option<(usize, f64)> {
        None
    }

    /// [`OdeSystem::project`] in `mode`; the default does nothing.
    fn project_in(&self, _t: f64, _y: &mut Vector<D>, _mode: &Self::Mode) -> Result<()> {
        Ok(())
    }

    /// The number of kink functions: functions across whose sign change `rhs_in` is
    /// continuous but not smooth, in every mode (a sliding contact's normal force `N`, in
    /// `mu_k |N|`). The driver locates their sign changes as it does switches and restarts
    /// the integrator there in the same mode, so that no step crosses the kink (a step
    /// across one loses the method's order). The default: none.
    const KINKS: usize = 0;

    /// Kink function `k` of `mode` at `(t, y)`; only its sign changes matter, and a
    /// constant (say `1.0`) where the mode has no kink. NaN when it cannot be evaluated.
    fn kink(&self, _t: f64, _y: &Vector<D>, _mode: &Self::Mode, _k: usize) -> f64 {
        1.0
    }
}

/// Coulomb friction at one contact: sliding forward (`qd_s > 0`), backward, or stuck.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Slip {
    /// Sliding with `qd_s > 0`: friction `-mu_k |N|` along `s`.
    Forward,
    /// Sliding with `qd_s < 0`: friction `+mu_k |N|`.
    Backward,
    /// Stuck: `qdd_s = 0`, the friction force is whatever holds it, up to `mu_s |N|`.
    Stick,
}

/// What the mode logic of Coulomb friction needs at `(t, q, qd)`: the equations of motion
/// without friction, and per contact the normal force and the two coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct Contacts<const N: usize, const M: usize, const F: usize> {
    /// `M(q, t)`.
    pub mass: Matrix<N, N>,
    /// `f(q, qd, t)` without friction.
    pub forces: Vector<N>,
    /// `Phi_q` (no rows without constraints).
    pub phi_q: Matrix<M, N>,
    /// `gamma`, so that `Phi_q qdd = gamma`.
    pub gamma: Vector<M>,
    /// The normal force of each contact (its magnitude counts).
    pub normal: [f64; F],
    /// Kinetic coefficients.
    pub mu_k: [f64; F],
    /// Static coefficients, `mu_s >= mu_k`.
    pub mu_s: [f64; F],
}

/// A mechanism with `F` Coulomb friction contacts, each along one free coordinate
/// (`A = N + M + F`, the size of the solve with every contact stuck). The friction forces
/// are `-mu_k |N| sign(qd_s)` while sliding; at `qd_s = 0` they are reactions found with
/// the accelerations ([`crate::friction`]).
pub trait Frictional<const N: usize, const M: usize, const F: usize, const A: usize>:
    Mechanism<N>
{
    /// The free coordinate each contact slides along, in declaration order.
    const ALONG: [usize; F];
    /// The equations without friction and the contacts' data at `(t, q, qd)`.
    fn contacts(&self, t: f64, q: &Vector<N>, qd: &Vector<N>) -> Contacts<N, M, F>;

    /// Whether some normal force depends on the accelerations and multipliers (a revolute
    /// joint's reaction magnitude): the friction is then implicit, and [`Self::normals`]
    /// gives the normals instead of [`Contacts::normal`].
    const IMPLICIT: bool = false;

    /// Every contact's normal force at `(t, q, qd)` with the accelerations and multipliers
    /// `(qdd, lambda)`, and its gradient by them (zero for a normal that does not depend on
    /// them); `None` where no normal is implicit.
    fn normals(
        &self,
        _t: f64,
        _q: &Vector<N>,
        _qd: &Vector<N>,
        _qdd: &Vector<N>,
        _lambda: &Vector<M>,
    ) -> Option<Normals<N, M, F>> {
        None
    }
}

/// Normal forces as functions of the accelerations and multipliers, at one point
/// ([`Frictional::normals`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Normals<const N: usize, const M: usize, const F: usize> {
    /// The normal force of each contact.
    pub value: [f64; F],
    /// Its derivative by `qdd`.
    pub d_qdd: [Vector<N>; F],
    /// Its derivative by `lambda`.
    pub d_lambda: [Vector<M>; F],
}
