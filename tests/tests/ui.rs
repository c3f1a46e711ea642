//! Compile-time model checking: every mistake in `tests/ui/**` must be rejected by
//! `#[derive(Mechanism)]` with a clear message pointing at the wrong tokens (the expected
//! compiler output is pinned in the `.stderr` next to each case), and every model in
//! `tests/ui-pass/` must compile.

//!
//! The toolchain is pinned by `rust-toolchain.toml` (rustc's wording and layout of
//! diagnostics change between releases), so the suite runs wherever the workspace builds.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("ui/**/*.rs");
    t.pass("ui-pass/*.rs");
}
