//! Big input never overflows the stack.
//!
//! Machine-generated models are long: a potential of thousands of terms, expressions nested
//! hundreds of parentheses deep. `syn`'s expression parser, the lowering of expressions and the
//! drop and clone of a parsed expression all recurse once per nesting level (a left-deep sum
//! nests once per term), and rustc runs a derive on a stack of a few megabytes: beyond it,
//! `SIGSEGV`, no span, no mention of mbd.
//!
//! So the whole derive runs on a stack of its own, [`STACK`] bytes (address space: only the
//! pages a model uses are ever touched), and the lowering grows it further where it recurses
//! ([`recurse`]). What no guard inside `syn` can cover is bounded before `syn` sees the input,
//! by an iterative scan of the tokens: at most [`MAX_TOKENS`] tokens, and at most
//! [`MAX_DEPTH`] levels of nesting, counting brackets, runs of prefix operators (`- - x`,
//! `!`, `&`, keywords), and every `|` and `<` of a bracket (closures `|a| |b| ..` and generic
//! types `A<A<..>>` nest without a bracket or an operator run): the constructs that make
//! `syn` recurse.
//! Past either, a spanned error says so. Each bound leaves the stack a wide margin (measured
//! on the unoptimised derive, the largest frames: see `tests/tests/big_input.rs`).

use proc_macro2::{Span, TokenStream, TokenTree};

/// The derive's own stack: 256 MiB of address space, committed page by page as used (the
/// worst inputs within the limits below touch a few tens of megabytes of it).
pub const STACK: usize = 1 << 28;

/// Most tokens in one derive input (a sum of 8000 terms `c * k * x * x` is 64 000).
pub const MAX_TOKENS: usize = 2_000_000;

/// Deepest nesting of brackets and prefix operators in one derive input.
pub const MAX_DEPTH: usize = 2_000;

/// Room left before the lowering grows its stack, and by how much it grows it.
const RED_ZONE: usize = 256 * 1024;
const GROWTH: usize = 16 * 1024 * 1024;

/// Run `f` (the whole derive: parse, mechanics, codegen, drops) on a stack of [`STACK`] bytes.
pub fn on_big_stack<R>(f: impl FnOnce() -> R) -> R {
    stacker::grow(STACK, f)
}

/// Run one level of a recursion over user expressions, growing the stack when it runs low.
pub fn recurse<R>(f: impl FnOnce() -> R) -> R {
    stacker::maybe_grow(RED_ZONE, GROWTH, f)
}

/// Keywords after which `syn` parses an expression by recursion (`return x`, `move || x`).
const PREFIX_KEYWORDS: &[&str] = &[
    "return", "break", "yield", "let", "move", "static", "async", "raw", "const", "mut", "ref",
    "box", "become", "do", "fn", "impl", "dyn", "for", "in", "where",
];

/// Punctuation that opens a nesting `syn` parses by recursion even between operands
/// (closure parameters, generic arguments): counted for the whole bracket, not reset.
const STICKY: &[char] = &['|', '<'];

/// Check the size of `input` without recursion: a spanned error past [`MAX_TOKENS`] or
/// [`MAX_DEPTH`].
pub fn check_size(input: TokenStream) -> syn::Result<()> {
    let mut tokens = 0usize;
    // Each open group: its tokens still to scan, and the depth of its contents.
    let mut open: Vec<(proc_macro2::token_stream::IntoIter, usize)> = vec![(input.into_iter(), 0)];
    // Prefix operators since the last operand; `STICKY` tokens of the bracket being scanned
    // (a stack, one per open bracket, restored when the bracket closes).
    let mut run = 0usize;
    let mut sticky = vec![0usize];
    while let Some((iter, depth)) = open.last_mut() {
        let depth = *depth + sticky.last().copied().unwrap_or(0);
        let Some(tt) = iter.next() else {
            open.pop();
            sticky.pop();
            run = 0;
            continue;
        };
        tokens += 1;
        if tokens > MAX_TOKENS {
            return Err(too_big(tt.span(), format!("more than {MAX_TOKENS} tokens")));
        }
        match &tt {
            TokenTree::Punct(p) if STICKY.contains(&p.as_char()) => {
                if let Some(n) = sticky.last_mut() {
                    *n += 1;
                }
            }
            // A closing `>` ends a nesting its `<` counted.
            TokenTree::Punct(p) if p.as_char() == '>' => {}
            TokenTree::Punct(_) => run += 1,
            TokenTree::Ident(i) if PREFIX_KEYWORDS.contains(&i.to_string().as_str()) => run += 1,
            TokenTree::Ident(_) | TokenTree::Literal(_) => run = 0,
            TokenTree::Group(g) => {
                let inner = depth + run + 1;
                if inner > MAX_DEPTH {
                    return Err(too_big(
                        g.span_open(),
                        format!("nested more than {MAX_DEPTH} levels deep"),
                    ));
                }
                run = 0;
                open.push((g.stream().into_iter(), inner));
                sticky.push(0);
                continue;
            }
        }
        if depth + run > MAX_DEPTH {
            return Err(too_big(
                tt.span(),
                format!("nested more than {MAX_DEPTH} levels deep"),
            ));
        }
    }
    Ok(())
}

fn too_big(span: Span, what: String) -> syn::Error {
    syn::Error::new(
        span,
        format!(
            "this mechanism is too big for the derive: {what} (its limits: at most {MAX_TOKENS} \
             tokens and {MAX_DEPTH} levels of brackets and prefix operators)"
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::str::FromStr;

    fn ts(s: &str) -> TokenStream {
        TokenStream::from_str(s).unwrap()
    }

    #[test]
    fn nesting_is_measured_by_brackets_and_prefix_runs() {
        let deep = |n: usize| format!("{}x{}", "(".repeat(n), ")".repeat(n));
        assert!(check_size(ts(&deep(MAX_DEPTH))).is_ok());
        assert!(check_size(ts(&deep(MAX_DEPTH + 1))).is_err());
        let minus = |n: usize| format!("a + {}x", "- ".repeat(n));
        // `a +` and the run: the `+` counts as one more operator.
        assert!(check_size(ts(&minus(MAX_DEPTH - 1))).is_ok());
        assert!(check_size(ts(&minus(MAX_DEPTH))).is_err());
        // A long flat sum is shallow: operands end each run.
        let sum = vec!["k * x"; 10_000].join(" + ");
        assert!(check_size(ts(&sum)).is_ok());
        // Closures and generics nest between operands: every `|` and `<` counts.
        let closures = |n: usize| format!("{}x", "|a| ".repeat(n));
        assert!(check_size(ts(&closures(MAX_DEPTH / 2))).is_ok());
        assert!(check_size(ts(&closures(MAX_DEPTH / 2 + 1))).is_err());
        let generic = |n: usize| format!("x as {}f64{}", "A<".repeat(n), ">".repeat(n));
        assert!(check_size(ts(&generic(MAX_DEPTH - 1))).is_ok());
        assert!(check_size(ts(&generic(MAX_DEPTH + 1))).is_err());
    }

    #[test]
    fn the_stack_grows_for_deep_recursion() {
        fn depth(n: usize) -> usize {
            if n == 0 {
                0
            } else {
                recurse(|| 1 + depth(n - 1))
            }
        }
        // Far past what an 8 MB stack holds for a non-trivial frame.
        assert_eq!(depth(1_000_000), 1_000_000);
    }
}
