//! Repeated cells, expanded before anything else reads the attributes:
//!
//! ```text
//! #[repeat(i in 0..40,
//!     body(crank[i], joint = revolute(c[i]), at = [i * l, 0.0], ..),
//!     close(pin[i], a = coupler[i], at_a = [l, 0.0], b = crank[i + 1], at_b = [l, 0.0]))]
//! ```
//!
//! stamps its attributes once per index, in order (`i = 0`: `body(crank0, ..)`,
//! `close(pin0, .., b = crank1, ..)`, then `i = 1`, ...). A name followed by `[..]` naming
//! the index is that name with the integer value appended (`crank[i + 1]` -> `crank1`); the
//! index alone is its value as a float literal (`i * l` -> `0.0 * l`); `p[0]` without the
//! index stays a component. Everything else is copied as written, so a repeated model is
//! exactly the model written out.

use proc_macro2::{Delimiter, Group, Ident, Literal, Span, TokenStream, TokenTree};
use quote::quote;
use syn::parse::{ParseStream, Parser};
use syn::spanned::Spanned;
use syn::{Attribute, DeriveInput, Token};

/// The input with every `#[repeat(..)]` replaced by its attributes; a malformed one is
/// dropped and reported.
pub fn expand(input: &DeriveInput) -> (DeriveInput, Option<syn::Error>) {
    let mut out = input.clone();
    out.attrs.clear();
    let mut errors: Option<syn::Error> = None;
    for attr in &input.attrs {
        if !attr.path().is_ident("repeat") {
            out.attrs.push(attr.clone());
            continue;
        }
        match stamp(attr) {
            Ok(attrs) => out.attrs.extend(attrs),
            Err(e) => match &mut errors {
                Some(all) => all.combine(e),
                None => errors = Some(e),
            },
        }
    }
    (out, errors)
}

/// Largest number of cells one `repeat` may stamp (a typo such as `0..4000000` would
/// otherwise stall the compiler).
const MAX_CELLS: i64 = 10_000;

fn stamp(attr: &Attribute) -> syn::Result<Vec<Attribute>> {
    let (var, range, items) = attr.parse_args_with(header)?;
    let mut attrs = Vec::new();
    for k in range {
        for (name, body) in &items {
            let body = substitute(body.clone(), &var, k)?;
            let tokens = quote!(#[#name(#body)]);
            attrs.extend(Attribute::parse_outer.parse2(tokens)?);
        }
    }
    Ok(attrs)
}

type Header = (Ident, std::ops::Range<i64>, Vec<(Ident, TokenStream)>);

/// `i in a..b` (or `a..=b`), then `name(..)` items.
fn header(input: ParseStream) -> syn::Result<Header> {
    let var: Ident = input.parse()?;
    input.parse::<Token![in]>()?;
    let start: syn::LitInt = input.parse()?;
    let inclusive = if input.peek(Token![..=]) {
        input.parse::<Token![..=]>()?;
        true
    } else {
        input.parse::<Token![..]>()?;
        false
    };
    let end: syn::LitInt = input.parse()?;
    let (a, b) = (start.base10_parse::<i64>()?, end.base10_parse::<i64>()?);
    let b = if inclusive { b + 1 } else { b };
    if b <= a || b - a > MAX_CELLS {
        let why = format!("`repeat` needs a range of 1 to {MAX_CELLS} indices, e.g. `i in 0..40`");
        return Err(syn::Error::new(end.span(), why));
    }
    let mut items = Vec::new();
    while !input.is_empty() {
        input.parse::<Token![,]>()?;
        if input.is_empty() {
            break;
        }
        let name: Ident = input.parse()?;
        if name == "repeat" {
            return Err(syn::Error::new(name.span(), "`repeat` cannot be nested"));
        }
        let body;
        syn::parenthesized!(body in input);
        items.push((name, body.parse::<TokenStream>()?));
    }
    if items.is_empty() {
        let why = "`repeat` needs attributes to stamp, e.g. `repeat(i in 0..3, body(link[i], ..))`";
        return Err(syn::Error::new(var.span(), why));
    }
    Ok((var, a..b, items))
}

/// One cell's tokens: `name[..index..]` -> `name<value>`, the index alone -> its value.
fn substitute(tokens: TokenStream, var: &Ident, k: i64) -> syn::Result<TokenStream> {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut out = Vec::with_capacity(trees.len());
    let mut i = 0;
    while i < trees.len() {
        match (&trees[i], trees.get(i + 1)) {
            (TokenTree::Ident(name), Some(TokenTree::Group(g)))
                if g.delimiter() == Delimiter::Bracket && mentions(g.stream(), var) =>
            {
                let value = index(g, var, k)?;
                out.push(TokenTree::Ident(Ident::new(
                    &format!("{name}{value}"),
                    name.span(),
                )));
                i += 2;
                continue;
            }
            (TokenTree::Ident(id), _) if id == var => {
                let mut lit = Literal::f64_unsuffixed(k as f64);
                lit.set_span(id.span());
                out.push(TokenTree::Literal(lit));
            }
            (TokenTree::Group(g), _) => {
                let mut inner = Group::new(g.delimiter(), substitute(g.stream(), var, k)?);
                inner.set_span(g.span());
                out.push(TokenTree::Group(inner));
            }
            (other, _) => out.push(other.clone()),
        }
        i += 1;
    }
    Ok(out.into_iter().collect())
}

fn mentions(tokens: TokenStream, var: &Ident) -> bool {
    tokens.into_iter().any(|t| match t {
        TokenTree::Ident(id) => id == *var,
        TokenTree::Group(g) => mentions(g.stream(), var),
        _ => false,
    })
}

/// The integer value of an index expression (`i`, `i + 1`, `2 * i - 1`, ..) at `var = k`.
fn index(g: &Group, var: &Ident, k: i64) -> syn::Result<i64> {
    let e: syn::Expr = syn::parse2(g.stream())?;
    let v = int(&e, var, k)?;
    if v < 0 {
        let why = format!("this index is {v} at `{var} = {k}`: names take indices >= 0");
        return Err(syn::Error::new(g.span(), why));
    }
    Ok(v)
}

fn int(e: &syn::Expr, var: &Ident, k: i64) -> syn::Result<i64> {
    use syn::{BinOp, Expr as E};
    let fail = |span: Span| {
        let why = format!("an index is integer arithmetic (`+ - * / %`) of `{var}` and integers");
        Err(syn::Error::new(span, why))
    };
    match e {
        E::Lit(syn::ExprLit {
            lit: syn::Lit::Int(n),
            ..
        }) => n.base10_parse(),
        E::Path(p) if p.path.is_ident(var) => Ok(k),
        E::Paren(p) => int(&p.expr, var, k),
        E::Unary(syn::ExprUnary {
            op: syn::UnOp::Neg(_),
            expr,
            ..
        }) => Ok(-int(expr, var, k)?),
        E::Binary(b) => {
            let (x, y) = (int(&b.left, var, k)?, int(&b.right, var, k)?);
            let v = match b.op {
                BinOp::Add(_) => x.checked_add(y),
                BinOp::Sub(_) => x.checked_sub(y),
                BinOp::Mul(_) => x.checked_mul(y),
                BinOp::Div(_) => x.checked_div(y),
                BinOp::Rem(_) => x.checked_rem(y),
                _ => return fail(b.op.span()),
            };
            v.map_or_else(|| fail(e.span()), Ok)
        }
        other => fail(other.span()),
    }
}
