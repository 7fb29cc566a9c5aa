//! Error collector, as in serde_derive's `Ctxt`: every stage pushes its errors here
//! and carries on, so the user sees all of them at once, each at its own token.
//!
//! The collector must be consumed, by [`Ctxt::check`] or [`Ctxt::finish`],
//! before anything is emitted: that is where the errors come out, and
//! dropping a collector unchecked panics (in tests, and in the derive, whose
//! panics become an error at the struct's name), so no error can be lost.

use std::cell::RefCell;
use std::fmt::Display;

use proc_macro2::Span;
use quote::ToTokens;

/// Collects the errors of one derive, so that all of them are reported at once
/// (each at its token). Must be consumed by `check`; dropping it unchecked is a
/// bug, caught by a panic in `Drop`.
pub struct Ctxt {
    /// The errors in the order they were found; `None` once checked.
    errors: RefCell<Option<Vec<syn::Error>>>,
}

impl Ctxt {
    /// An empty collection.
    pub fn new() -> Self {
        Ctxt {
            errors: RefCell::new(Some(Vec::new())),
        }
    }

    /// Records an error spanning the given tokens.
    pub fn error_spanned_by<A: ToTokens, M: Display>(&self, obj: A, msg: M) {
        self.syn_error(syn::Error::new_spanned(obj.into_token_stream(), msg));
    }

    /// Records an error at one span.
    pub fn error_at<M: Display>(&self, span: Span, msg: M) {
        self.syn_error(syn::Error::new(span, msg));
    }

    /// Records an already-built syn error (from a parser).
    pub fn syn_error(&self, err: syn::Error) {
        // `errors` is `None` only inside `check`, which owns the collector.
        if let Some(errors) = self.errors.borrow_mut().as_mut() {
            errors.push(err);
        }
    }

    /// Whether an error has been recorded; for a stage deciding whether to
    /// go on (the errors themselves come out of [`Ctxt::check`]).
    pub fn has_errors(&self) -> bool {
        self.errors.borrow().as_ref().is_some_and(|e| !e.is_empty())
    }

    /// Consumes the collector: every error recorded, combined into one in the
    /// order they were found, or `Ok` if there was none.
    pub fn check(self) -> Result<(), syn::Error> {
        let mut errors = self.errors.take().into_iter().flatten();
        let Some(mut combined) = errors.next() else {
            return Ok(());
        };
        for e in errors {
            combined.combine(e);
        }
        Err(combined)
    }

    /// Consumes the collector with what the stages produced: the errors if
    /// any were recorded (even beside a value), else the value. Stages that
    /// produced nothing and recorded nothing are a bug, reported at `span`
    /// rather than dropped.
    pub fn finish<T>(self, produced: Option<T>, span: Span) -> Result<T, syn::Error> {
        self.check()?;
        produced.ok_or_else(|| {
            syn::Error::new(
                span,
                "internal error in #[derive(Lagrangian)]: a stage gave up without saying why; \
                 this is a bug in lagrange, please report it with this description",
            )
        })
    }
}

impl Default for Ctxt {
    fn default() -> Self {
        Self::new()
    }
}

impl Drop for Ctxt {
    /// An unchecked collector may hold errors no one will see: a bug, as in
    /// serde_derive, caught wherever a test or an expansion drops one (not
    /// while already unwinding, which would abort).
    fn drop(&mut self) {
        if !std::thread::panicking() && self.errors.get_mut().is_some() {
            panic!("an error collector (`Ctxt`) was dropped without `check`");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_combines_the_errors_in_their_order() {
        let cx = Ctxt::new();
        assert!(!cx.has_errors());
        cx.error_at(Span::call_site(), "first");
        cx.error_at(Span::call_site(), "second");
        assert!(cx.has_errors());
        let e = cx.check().unwrap_err();
        let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
        assert_eq!(messages, ["first", "second"]);
    }

    #[test]
    fn finish_hands_on_a_value_only_without_errors() {
        let span = Span::call_site();
        assert_eq!(Ctxt::new().finish(Some(3), span).unwrap(), 3);
        let cx = Ctxt::new();
        cx.error_at(span, "wrong");
        assert_eq!(cx.finish(Some(3), span).unwrap_err().to_string(), "wrong");
        let gave_up = Ctxt::new().finish(None::<i32>, span).unwrap_err();
        assert!(gave_up.to_string().contains("internal error"), "{gave_up}");
    }

    #[test]
    #[should_panic(expected = "dropped without `check`")]
    fn dropping_an_unchecked_collector_is_a_bug() {
        let cx = Ctxt::new();
        cx.error_at(Span::call_site(), "lost");
        drop(cx);
    }
}
