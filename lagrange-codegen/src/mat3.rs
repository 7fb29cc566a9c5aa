//! 3×3 matrices of expressions, shared by the rotations of the lowering and the
//! recursions of the derivation (so neither stage imports the other for it).

use lagrange_symbolic::Expr as Sym;

/// A 3×3 matrix of expressions, row-major.
pub type Mat3 = [[Sym; 3]; 3];

/// Aᵀ (no new nodes: entries are only moved).
pub fn transpose(a: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[j][i]))
}
