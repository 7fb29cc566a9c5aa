//! The pieces `describe` builds the description's items from, as tokens:
//! names, numbers and rotation products. Nothing here writes source text to
//! be parsed back, and nothing panics: a name is made only of the characters
//! an identifier may hold, and a number that no literal spells is refused.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{ToTokens, quote};

/// A link's or joint's name as an identifier: other characters become `_`, a
/// leading digit gets a `_` before it, a keyword or a name the description
/// reserves (`t`, `pi`, `PI`, `dot`) one after it.
pub fn identifier(name: &str) -> Ident {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    // `s` is ASCII letters, digits and `_`, and starts with no digit: an
    // identifier or a keyword, which `Ident::new` takes either way; syn's
    // `Ident` parser is what tells a keyword (or a lone `_`) apart.
    let candidate = Ident::new(&s, Span::call_site());
    let keyword = syn::parse2::<syn::Ident>(candidate.to_token_stream()).is_err();
    if keyword || crate::check::RESERVED.contains(&s.as_str()) {
        s.push('_');
        return Ident::new(&s, Span::call_site());
    }
    candidate
}

/// `(x)`, or `(-x)` for a negative x (and for −0): an unsuffixed f64 literal
/// spelled with the shortest digits that read back as exactly x. `None` for
/// an infinity or a NaN, which no literal spells.
pub fn number(x: f64) -> Option<TokenStream> {
    if !x.is_finite() {
        return None;
    }
    let digits = Literal::f64_unsuffixed(x.abs());
    Some(match x.is_sign_negative() {
        true => quote!((-#digits)),
        false => quote!((#digits)),
    })
}

/// The rotation `f₁ * f₂ * ..`, or `rot_z(0)` (no turn) for no factors.
pub fn product(factors: &[TokenStream]) -> TokenStream {
    let Some((first, rest)) = factors.split_first() else {
        return quote!(rot_z(0));
    };
    let mut out = first.clone();
    for f in rest {
        out.extend(quote!(* #f));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_identifiers_the_description_accepts() {
        for (name, id) in [
            ("shoulder", "shoulder"),
            ("arm-1 link", "arm_1_link"),
            ("3dof", "_3dof"),
            ("", "__"),
            ("_", "__"),
            ("fn", "fn_"),
            ("self", "self_"),
            ("pi", "pi_"),
            ("t", "t_"),
            ("épaule", "_paule"),
        ] {
            assert_eq!(identifier(name).to_string(), id, "{name}");
        }
    }

    #[test]
    fn numbers_read_back_bit_for_bit() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -0.5,
            0.1,
            1e-7,
            -1e300,
            5e-324,
            std::f64::consts::FRAC_PI_2,
            0.649262481663582,
        ] {
            let tokens = number(x).unwrap();
            let e: syn::Expr = syn::parse2(tokens.clone()).unwrap();
            let syn::Expr::Paren(p) = e else {
                panic!("{tokens}")
            };
            let (negative, lit) = match *p.expr {
                syn::Expr::Unary(u) => (true, *u.expr),
                other => (false, other),
            };
            let syn::Expr::Lit(syn::ExprLit {
                lit: syn::Lit::Float(f),
                ..
            }) = lit
            else {
                panic!("{tokens}")
            };
            let back: f64 = f.base10_parse().unwrap();
            let back = if negative { -back } else { back };
            assert_eq!(back.to_bits(), x.to_bits(), "{tokens}");
        }
        assert!(number(f64::INFINITY).is_none());
        assert!(number(f64::NAN).is_none());
    }

    #[test]
    fn a_product_of_no_factors_is_no_turn() {
        assert_eq!(product(&[]).to_string(), "rot_z (0)");
        let factors = [quote!(rot_z(q)), quote!(rot_x((0.5)))];
        assert_eq!(product(&factors).to_string(), "rot_z (q) * rot_x ((0.5))");
    }
}
