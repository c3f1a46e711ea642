//! The symbolic expression engine of the derive: a hash-consed expression DAG with
//! simplifying constructors, exact differentiation, substitution, evaluation and a
//! code-generation schedule.
//!
//! Plain Rust on purpose (no `syn`, `quote` or `proc_macro2`): it is unit- and
//! property-tested on its own, and could move to its own crate unchanged.
//!
//! - `expr.rs`: the arena, interning, symbols, free-symbol and non-smooth summaries;
//! - `simplify.rs`: the simplifying constructors (`add`, `mul`, …) and their rewrite rules;
//! - `diff.rs`: memoised differentiation; `subs.rs`: substitution; `eval.rs`: evaluation;
//! - `schedule.rs`: topological order and use counts for code generation.
#![allow(
    dead_code,
    unused_imports,
    reason = "the engine's API is consumed by the model and codegen stages, which use different parts of it"
)]

mod diff;
mod eval;
mod expr;
mod schedule;
mod simplify;
mod subs;

#[cfg(test)]
mod tests;

pub use expr::{Const, Expr, Func, Graph, Node, Sym};
pub use schedule::{schedule, use_counts};
