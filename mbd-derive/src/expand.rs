//! The pipeline: parse -> check -> mechanics -> codegen. Errors become `compile_error!`s.

use crate::{codegen, model, parse};
use proc_macro2::TokenStream;
use syn::DeriveInput;

pub fn derive(input: &DeriveInput) -> TokenStream {
    match try_expand(input) {
        Ok(ts) => ts,
        Err(err) => err.to_compile_error(),
    }
}

fn try_expand(input: &DeriveInput) -> syn::Result<TokenStream> {
    let ast = parse::Mechanism::from_syn(input)?;
    let eqs = model::derive(&ast)?;
    Ok(codegen::emit(&ast, &eqs))
}
