//! The `#[derive(Mechanism)]` of mbd.

use proc_macro::TokenStream;

mod sym;

/// Derive the equations of motion of a mechanism described by `#[mbd(...)]` attributes.
#[proc_macro_derive(Mechanism, attributes(mbd))]
pub fn derive_mechanism(input: TokenStream) -> TokenStream {
    let _ = input;
    TokenStream::new()
}
