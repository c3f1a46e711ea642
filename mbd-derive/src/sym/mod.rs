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
//! - `range.rs`: interval bounds over every value of the symbols;
//! - `regroup.rs`: a residual's constant terms summed before the state's (rounding);
//! - `schedule.rs`: topological order and use counts for code generation;
//! - `hash.rs`: the fast hasher of the internal maps.
//!
//! Node ids are a topological order (operands are always created first), which every
//! pass uses to work bottom-up without recursion. Free symbols and the non-smooth /
//! non-finite flags of each node are computed once, when it is interned, so
//! `depends_on`, `free_symbols`, `nonsmooth_calls` and `has_nonfinite_constant` never
//! walk the graph.
#![allow(
    dead_code,
    unused_imports,
    reason = "the engine's API is consumed by the model and codegen stages, which use different parts of it"
)]

mod diff;
mod eval;
mod expr;
mod hash;
mod range;
mod regroup;
mod schedule;
mod simplify;
mod subs;

#[cfg(test)]
mod tests;

pub use expr::{Const, Expr, Func, Graph, Node, Sym};
pub use schedule::{schedule, use_counts};
