//! The pipeline: parse -> check -> mechanics -> codegen. Errors become `compile_error!`s,
//! beside the skeleton of the items the model would have had.

use crate::{check, codegen, model, parse, skeleton};
use proc_macro2::TokenStream;
use std::time::Instant;
use syn::DeriveInput;

/// With `MBD_EXPAND_DUMP=<dir>` set at build time, every derive writes its generated code to
/// `<dir>/<file>.<Struct>.rs` and its expansion time in seconds to `<dir>/<file>.<Struct>.time`
/// (`<file>`: the stem of the source file that derives it, so that two structs of one name in
/// different modules do not overwrite each other): how the `scaling` report measures the
/// macro apart from the rest of the build.
const DUMP_VAR: &str = "MBD_EXPAND_DUMP";

/// `source`: the path of the file the derive is in (for the dump's name).
pub fn derive(input: &DeriveInput, source: &str) -> TokenStream {
    let start = Instant::now();
    let out = match try_expand(input) {
        Ok(ts) => ts,
        Err((err, ast)) => {
            // The model's items still exist, so that uses of them add no errors.
            let errors = err.to_compile_error();
            let skeleton = ast.as_ref().map(skeleton::emit);
            quote::quote!(#errors #skeleton)
        }
    };
    if let Some(dir) = std::env::var_os(DUMP_VAR) {
        let stem = std::path::Path::new(source)
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        dump(
            std::path::Path::new(&dir),
            &format!("{stem}.{}", input.ident),
            &out,
            start.elapsed().as_secs_f64(),
        );
    }
    out
}

/// Best effort: a diagnostic aid must never break the build it measures.
fn dump(dir: &std::path::Path, name: &str, code: &TokenStream, seconds: f64) {
    let _ = std::fs::create_dir_all(dir);
    let _ = std::fs::write(dir.join(format!("{name}.rs")), code.to_string());
    let _ = std::fs::write(dir.join(format!("{name}.time")), format!("{seconds}\n"));
}

/// The generated code, or the errors with the parsed model when there is one.
type Failed = (syn::Error, Option<parse::Mechanism>);

fn try_expand(input: &DeriveInput) -> Result<TokenStream, Failed> {
    let ast = parse::Mechanism::read(input)?;
    let checked = check::check(input, &ast).and_then(|()| model::derive(&ast));
    match checked {
        Ok(eqs) => Ok(codegen::emit(&ast, &eqs)),
        Err(e) => Err((e, Some(ast))),
    }
}
