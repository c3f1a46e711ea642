//! The pipeline: parse -> check -> lower (`syn`-free) -> mechanics -> codegen. Errors become `compile_error!`s,
//! beside the skeleton of the items the model would have had.

use crate::{check, codegen, lowered, model, parse, repeat, skeleton};
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
            let skeleton = ast.as_deref().map(skeleton::emit);
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
type Failed = (syn::Error, Option<Box<parse::Mechanism>>);

fn try_expand(input: &DeriveInput) -> Result<TokenStream, Failed> {
    let (input, repeated) = repeat::expand(input);
    let ast = parse::Mechanism::read(&input)?;
    if let Some(e) = repeated {
        return Err((e, Some(Box::new(ast))));
    }
    let checked = check::check(&input, &ast).and_then(|()| {
        let mut errors = parse::Errors::default();
        let lowered = lowered::lower(&ast, &mut errors);
        model::derive(lowered, errors)
    });
    match checked {
        Ok(eqs) => Ok(codegen::emit(&ast, &eqs)),
        Err(e) => Err((e, Some(Box::new(ast)))),
    }
}

#[cfg(test)]
mod tests {
    //! The derive as a library function on random attribute sets: every input gets either
    //! errors (`compile_error!`s with a message) or generated items that parse as Rust;
    //! never a panic.
    use proptest::prelude::*;
    use proptest::strategy::ValueTree;

    const VALUES: &[&str] = &[
        "1.0",
        "0.5",
        "2.0 * p0",
        "p1",
        "-1.0",
        "0.0",
        "2.5",
        "p0",
        "-p1",
        "p0 - p1",
        "t",
        "x",
        "1e400",
        "0.0 / 0.0",
        "PI",
        "pi",
        "sqrt(-1.0)",
        "std::f64::consts::FRAC_PI_2",
        "f64::NAN",
    ];
    const EXPRS: &[&str] = &[
        "x",
        "y",
        "0.5 * y",
        "x + 1.0",
        "y * p0",
        "theta",
        "sin(x)",
        "x * x + y",
        "t",
        "link_q1",
        "p0 * x",
        "der(x)",
        "abs(x)",
        "position(b0)[0]",
        "1.0 / 0.0",
        "x ^ 2",
        "b0",
        "velocity(link_1, [0.0, -1.0])[1]",
    ];
    const DEFAULTS: &[&str] = &[
        "1.0",
        "0.5",
        "2.0",
        "3.0",
        "1.5",
        "0.25",
        "-1.0",
        "0.0 / 0.0",
        "x",
        "1e400",
    ];
    const COORDS: &[&str] = &["x", "y", "theta", "link_q1", "b0_rx", "x_dot", "t"];
    const OPTIONS: &[&str] = &[
        "planar",
        "spatial",
        "recursive",
        "mass_matrix",
        "jacobian",
        "planar, spatial",
        "recursive, mass_matrix",
        "bogus",
    ];
    const DIRECTIONS: &[&str] = &["rising", "falling", "rising, falling", "terminal", "", "up"];

    /// One attribute from template `kind` with choices `c` (indices, taken modulo).
    fn attribute(kind: usize, c: &[usize]) -> String {
        // Mostly one of a pool's first (sensible) entries, else any: random sets that are
        // all mistakes would only test the first error.
        let pick = |pool: &[&'static str], sensible: usize, i: usize| {
            pool[if c[i] < 40 {
                c[i] % sensible
            } else {
                c[i] % pool.len()
            }]
        };
        let v = |i: usize| pick(VALUES, 4, i);
        let e = |i: usize| pick(EXPRS, 5, i);
        let q = |i: usize| pick(COORDS, 2, i);
        let k = c[7] % 3;
        match kind % 19 {
            0 => format!("#[mechanism({})]", OPTIONS[c[0] % OPTIONS.len()]),
            1 => "#[gravity(0.0, -9.81)]".into(),
            2 => "#[gravity(0.0, 0.0, -9.81)]".into(),
            3 => format!("#[coords({}, {})]", q(0), q(1)),
            4 => format!("#[drive({} = {})]", q(0), e(1)),
            5 => format!(
                "#[particle(b{k}, mass = {}, at = [{}, {}])]",
                v(0),
                e(1),
                e(2)
            ),
            6 => format!(
                "#[rigid(b{k}, mass = {}, inertia = {}, at = [{}, {}], angle = {})]",
                v(0),
                v(1),
                e(2),
                e(3),
                e(4)
            ),
            7 => format!(
                "#[rigid3(b{k}, mass = {}, inertia = diag({}, 1.0, {}), at = [{}, 0.0, 0.0], rotation = rot_z({}))]",
                v(0),
                v(1),
                v(2),
                e(3),
                e(4)
            ),
            8 => format!(
                "#[body(b{k}, parent = ground, joint = revolute({}), com = [0.0, -0.5], mass = {}, inertia = {}{})]",
                q(0),
                v(1),
                v(2),
                if c[3].is_multiple_of(2) {
                    ", reaction"
                } else {
                    ""
                }
            ),
            9 => format!(
                "#[chain(link, n = {}, joint = revolute, length = {}, mass = {})]",
                c[0] % 4,
                v(1),
                v(2)
            ),
            10 => format!(
                "#[spring(s{k}, from = [0.0, 0.0], to = b0, k = {}, length = {})]",
                v(0),
                v(1)
            ),
            11 => format!("#[damper(d{k}, from = [0.0, 0.0], to = b0, c = {})]", v(0)),
            12 => format!(
                "#[friction(along = {}, mu = {}, normal = {})]",
                q(0),
                v(1),
                v(2)
            ),
            13 => format!(
                "#[generalized_force(f{k}, along = {}, value = {})]",
                q(0),
                e(1)
            ),
            14 => format!("#[constraint({} == {})]", e(0), e(1)),
            15 => format!(
                "#[event(e{k} = {}, {})]",
                e(0),
                DIRECTIONS[c[1] % DIRECTIONS.len()]
            ),
            16 => format!("#[output(o{k} = {})]", e(0)),
            17 => format!("#[init({} = {})]", q(0), v(1)),
            _ => format!("#[torque(m{k}, on = b{}, value = {})]", c[1] % 3, e(2)),
        }
    }

    fn source(attrs: &[(usize, Vec<usize>)], defaults: &[usize]) -> String {
        let attrs: Vec<String> = attrs.iter().map(|(k, c)| attribute(*k, c)).collect();
        let params: Vec<String> = (0..2)
            .map(|i| match defaults[i] % (DEFAULTS.len() + 1) {
                0 => format!("p{i}: f64,"),
                d => format!("#[default({})] p{i}: f64,", DEFAULTS[d - 1]),
            })
            .collect();
        // Half the inputs extend a valid model, so that random additions are also tried
        // on something that would compile.
        let base = if defaults[0].is_multiple_of(2) {
            "#[coords(x, y)]\n#[particle(b0, mass = 1.0, at = [x, y])]\n"
        } else {
            ""
        };
        format!(
            "{base}{}\npub struct M {{ {} }}",
            attrs.join("\n"),
            params.join(" ")
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]
        #[test]
        fn random_attribute_sets_give_errors_or_code_never_a_panic(
            attrs in prop::collection::vec((0usize..19, prop::collection::vec(0usize..64, 8)), 1..7),
            defaults in prop::collection::vec(0usize..64, 2),
        ) {
            let src = source(&attrs, &defaults);
            let input: syn::DeriveInput = syn::parse_str(&src).expect("the generator writes Rust");
            let out = std::panic::catch_unwind(|| super::derive(&input, "proptest.rs"));
            prop_assert!(out.is_ok(), "the derive panicked on\n{}", src);
            let out = out.expect("checked").to_string();
            let file: syn::File = syn::parse2(out.parse().expect("tokens")).expect("items");
            if out.contains("compile_error") {
                // Each error carries a message (not an empty `compile_error!("")`).
                prop_assert!(!out.contains("compile_error ! { \"\" }"), "{}", src);
            } else {
                prop_assert!(!file.items.is_empty(), "no items and no error for\n{}", src);
            }
        }
    }

    /// The property's generator reaches valid models too, not only errors (a deterministic
    /// sample of the same strategy).
    #[test]
    fn the_generator_reaches_models_and_errors() {
        let runner = || {
            let mut rng = proptest::test_runner::TestRunner::deterministic();
            let strategy = (
                prop::collection::vec((0usize..19, prop::collection::vec(0usize..64, 8)), 1..4),
                prop::collection::vec(0usize..64, 2),
            );
            let mut counts = [0usize; 2];
            for _ in 0..200 {
                let (attrs, defaults) = strategy.new_tree(&mut rng).expect("value").current();
                let input: syn::DeriveInput =
                    syn::parse_str(&source(&attrs, &defaults)).expect("Rust");
                let out = super::derive(&input, "t.rs").to_string();
                counts[usize::from(out.contains("compile_error"))] += 1;
            }
            counts
        };
        let [models, errors] = runner();
        eprintln!("{models} models, {errors} errors");
        assert!(
            models >= 20 && errors >= 20,
            "{models} models, {errors} errors"
        );
    }

    /// A fixed sample the property may not reach: each is an error or code, never a panic.
    #[test]
    fn known_troublemakers() {
        for src in [
            "#[chain(link, n = 0, joint = revolute, length = 1.0, mass = 1.0)] pub struct M {}",
            "#[coords(x)] #[particle(b, mass = 1.0, at = [x])] pub struct M {}",
            "#[mechanism(spatial)] #[coords(x)] #[rigid(b, mass = 1.0, inertia = 1.0, at = [x, 0.0], angle = x)] pub struct M {}",
            "#[coords(x)] #[particle(b, mass = 1.0, at = [x, 0.0])] #[event(e = x)] #[event(e = x)] pub struct M {}",
            "pub struct M(f64);",
            "pub enum M { A }",
        ] {
            let input: syn::DeriveInput = syn::parse_str(src).expect("Rust");
            let out = std::panic::catch_unwind(|| super::derive(&input, "t.rs"));
            assert!(out.is_ok(), "panicked on {src}");
        }
    }
}
