//! The `#[derive(Mechanism)]` of mbd: a mechanism described by attributes on a struct of
//! parameters becomes exact, specialised equations of motion at compile time.
//!
//! Stages, each its own module: `parse` (attributes -> AST), `lowered` (the whole model
//! once, every expression a `syn`-free term, syntax errors collected), `lower` (terms ->
//! symbolic values over the model's names, with spanned errors), `model` (Lagrangian mechanics in minimal
//! coordinates, constraints, reactions), `sym` (the symbolic engine: hash-consed DAG,
//! exact derivatives), `codegen` (straight-line Rust).
//! The language itself is documented on the facade crate `mbd`.

mod ball;
mod branch;
mod check;
mod close;
mod closure;
mod codegen;
mod expand;
mod friction;
mod geometry;
mod guard;
mod hints;
mod linear;
mod lower;
mod lowered;
mod model;
mod parse;
mod repeat;
mod skeleton;
mod spatial;
mod sym;
mod tree;
mod velocity;

use proc_macro::TokenStream;
use syn::DeriveInput;

/// Derive the equations of motion of a mechanism; see the `mbd` crate for the language.
#[proc_macro_derive(
    Mechanism,
    attributes(
        mechanism,
        gravity,
        coords,
        drive,
        relaxed,
        constraint,
        particle,
        rigid,
        rigid3,
        body,
        chain,
        close,
        point,
        spring,
        damper,
        force,
        torque,
        generalized_force,
        potential,
        friction,
        output,
        input,
        event,
        init,
        repeat,
        default
    )
)]
pub fn derive_mechanism(input: TokenStream) -> TokenStream {
    // Parse, derive and drop on the derive's own stack: big input must not overflow rustc's.
    guard::on_big_stack(|| {
        let input = proc_macro2::TokenStream::from(input);
        if let Err(err) = guard::check_size(input.clone()) {
            return err.to_compile_error().into();
        }
        let input = match syn::parse2::<DeriveInput>(input) {
            Ok(input) => input,
            Err(err) => return err.to_compile_error().into(),
        };
        let source = proc_macro::Span::call_site().file();
        expand::derive(&input, &source).into()
    })
}
