//! Small vector algebra over expressions, in the order of operations the
//! derivation has always used (node order shows in the emitted code).

use lagrange_symbolic::{Context, Expr as Sym};

use crate::mat3::Mat3;

pub(super) fn mat_vec(ctx: &mut Context, a: &Mat3, v: &[Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| dot(ctx, &a[i], v))
}

pub(super) fn cross(ctx: &mut Context, a: &[Sym; 3], b: &[Sym; 3]) -> [Sym; 3] {
    [0, 1, 2].map(|i| {
        let j = (i + 1) % 3;
        let k = (i + 2) % 3;
        let p = ctx.mul(a[j], b[k]);
        let m = ctx.mul(a[k], b[j]);
        ctx.sub(p, m)
    })
}

pub(super) fn dot(ctx: &mut Context, a: &[Sym], b: &[Sym]) -> Sym {
    let terms: Vec<Sym> = a.iter().zip(b).map(|(&x, &y)| ctx.mul(x, y)).collect();
    ctx.sum(&terms)
}
