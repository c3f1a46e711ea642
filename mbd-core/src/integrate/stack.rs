//! Stack for the implicit methods: their Jacobians, iteration matrices and LU factors are
//! `D x D` arrays on the stack (const generics), about 16 of them live at once in Radau5's
//! step (8 bytes a real entry, 16 a complex one). A 100-link chain (`D = 200`) needed 5 MiB
//! and overflowed a test thread's 2 MiB with `SIGABRT`; a 128-link one would overflow a main
//! thread's 8 MiB. So a run whose matrices may not fit what is left of the stack runs on a
//! stack of its own (`stacker`: allocated when needed, committed page by page as used).

/// Runs `f` with at least room for `matrices` complex `D x D` arrays (16 bytes an entry)
/// and 1 MiB besides left on the stack, on a new stack if the current one has less.
pub(crate) fn with_room<const D: usize, R>(matrices: usize, f: impl FnOnce() -> R) -> R {
    let need = matrices
        .saturating_mul(D * D)
        .saturating_mul(16)
        .saturating_add(1 << 20);
    stacker::maybe_grow(need, need, || call(f))
}

/// Out of line, so that `f`'s frame (its arrays) is not part of the caller's, which would
/// be allocated before the check above could move it.
#[inline(never)]
fn call<R>(f: impl FnOnce() -> R) -> R {
    f()
}
