//! What every part of the model answers: the expressions the generated code
//! evaluates of it (for the questions asked of all of them, such as which
//! coordinates they read).

use lagrange_symbolic::Expr as Sym;

/// A part of the model as the expressions the generated code evaluates of it,
/// for the questions asked of all of them (which coordinates they read).
pub trait Expressions {
    /// Appends the part's expressions to `out`.
    fn expressions(&self, out: &mut Vec<Sym>);
}

impl<T: Expressions> Expressions for Option<T> {
    fn expressions(&self, out: &mut Vec<Sym>) {
        if let Some(part) = self {
            part.expressions(out);
        }
    }
}

/// Appends the entries of matrices, row by row.
pub(super) fn entries<'a>(
    out: &mut Vec<Sym>,
    matrices: impl IntoIterator<Item = &'a Vec<Vec<Sym>>>,
) {
    for m in matrices {
        out.extend(m.iter().flatten());
    }
}
