//! Where bodies and masses sit on the links, as both readings of a tree
//! (from rotation factors in `detect`, from written-out poses in `written`)
//! hand them to the mass attachment, and the small questions both ask of
//! symbols.

use lagrange_symbolic::{Context, Expr as Sym, SymbolKind};

use crate::mat3::Mat3;

/// Whether `e` depends on parameters only (fixed in space and time).
pub(super) fn fixed(ctx: &Context, e: Sym) -> bool {
    ctx.free_symbols(e)
        .iter()
        .all(|&s| matches!(ctx.symbol_kind(s), SymbolKind::Parameter(_)))
}

/// The name of coordinate `i`, for the reasons.
pub(super) fn coordinate_name(ctx: &Context, i: usize) -> String {
    let q = ctx.coordinates()[i];
    ctx.as_symbol(q)
        .map_or_else(String::new, |s| ctx.symbol_name(s).to_string())
}

/// Where a body sits: the link it is fixed in (`None`: fixed in space), its
/// reference point in that link's axes (or in world axes), and the rotation
/// from its own axes to the link's.
#[derive(Clone, Copy)]
pub(super) struct Frame {
    pub link: Option<usize>,
    pub origin: [Sym; 3],
    pub rotation: Mat3,
}

/// A point mass's body and its offset in that body's axes (`None`: fixed in
/// no body).
pub(super) type PlacedMass = Option<(usize, Vec<Sym>)>;
