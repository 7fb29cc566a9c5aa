//! Numbers for reading written-out poses: reproducible random parameters
//! and configurations, expressions settled to numbers where they only look
//! parameter-dependent, and the numeric check of a joint's reading.

use lagrange_symbolic::{Context, Expr as Sym, Symbol, SymbolKind};

use super::Joint;
use crate::mat3::Mat3;
use crate::tree::BodyFault;
use crate::tree::frame::coordinate_name;

/// `e` as a number when it depends on parameters only in form: a parent
/// turned by a parameter angle leaves cos²w + sin²w in its child's relative
/// rotation, which the engine does not reduce to 1 but which evaluates to 1
/// at every parameter value. Probed at three random parameter sets; equal
/// values to 1e-13 give the number, snapped to 0 or ±1 within a few ulp (as
/// `mat3::cos_sin` snaps quarter turns). Anything that varies stays as it
/// is.
pub(super) fn settled(ctx: &mut Context, e: Sym) -> Sym {
    let v = match ctx.as_f64(e) {
        Some(v) => v,
        None => {
            let values: Vec<f64> = (11..14)
                .map(|seed| ctx.eval(e, &|s| probe(ctx, s, seed)))
                .collect();
            let v = values[0];
            let spread = values.iter().fold(0.0f64, |m, x| m.max((x - v).abs()));
            // A NaN (a parameter outside an expression's domain) keeps `e`
            // too (`f64::max` would pass over it in the spread).
            let finite = values.iter().all(|x| x.is_finite());
            if !(finite && spread <= 1e-13 * v.abs().max(1.0)) {
                return e;
            }
            v
        }
    };
    let near = v.round();
    if near.abs() <= 1.0 && (v - near).abs() <= 4.0 * f64::EPSILON * v.abs().max(1.0) {
        return ctx.int(near as i64);
    }
    // An exact number (a rational) stays exact.
    if ctx.as_f64(e).is_some() {
        e
    } else {
        ctx.float(v)
    }
}

/// Checks the joint's reading against the relative pose as written, at
/// random configurations and parameters.
pub(super) fn check(
    ctx: &Context,
    joint: &Joint,
    (rotation, origin): (&Mat3, &[Sym; 3]),
) -> Result<(), BodyFault> {
    for seed in 1..=3 {
        let env = |s: Symbol| probe(ctx, s, seed);
        let eval = |e: Sym| ctx.eval(e, &env);
        let actual_r = rotation.map(|row| row.map(eval));
        let actual_o = origin.map(eval);
        let (r, o) = predicted(ctx, joint, &env);
        let scale = 1.0 + actual_o.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let off_r = (0..9).fold(0.0f64, |m, k| {
            m.max((r[k / 3][k % 3] - actual_r[k / 3][k % 3]).abs())
        });
        let off_o = (0..3).fold(0.0f64, |m, k| m.max((o[k] - actual_o[k]).abs()));
        // `f64::max` passes over a NaN, so finiteness is checked apart.
        let finite = r
            .iter()
            .flatten()
            .chain(&o)
            .chain(actual_o.iter())
            .all(|x| x.is_finite())
            && actual_r.iter().flatten().all(|x| x.is_finite());
        let close = finite && off_r <= 1e-9 && off_o <= 1e-9 * scale;
        if !close {
            return Err(match joint.coordinate() {
                Some(q) => BodyFault::NotAJoint {
                    coordinate: coordinate_name(ctx, q),
                    off: off_r.max(off_o),
                },
                None => BodyFault::MovesWithoutCoordinate,
            });
        }
    }
    Ok(())
}

/// A reproducible value for symbol `s`: parameters in [0.5, 1.5] (lengths
/// and masses are positive), everything else in [−2, 2].
fn probe(ctx: &Context, s: Symbol, seed: u64) -> f64 {
    let mut z = (s.index() as u64) ^ seed.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    let unit = ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64;
    match ctx.symbol_kind(s) {
        SymbolKind::Parameter(_) => 0.5 + unit,
        _ => 4.0 * unit - 2.0,
    }
}

/// The joint's relative rotation and position at the values `env` gives.
fn predicted(
    ctx: &Context,
    joint: &Joint,
    env: &dyn Fn(Symbol) -> f64,
) -> ([[f64; 3]; 3], [f64; 3]) {
    let eval = |e: Sym| ctx.eval(e, env);
    let value = |q: usize| eval(ctx.coordinates()[q]);
    match joint {
        Joint::Fixed { rotation, origin } => (rotation.map(|r| r.map(eval)), origin.map(eval)),
        Joint::Prismatic {
            coordinate,
            rotation,
            origin,
            direction,
        } => {
            let q = value(*coordinate);
            let o = [0, 1, 2].map(|i| eval(origin[i]) + eval(direction[i]) * q);
            (rotation.map(|r| r.map(eval)), o)
        }
        Joint::Revolute {
            coordinate,
            turn,
            unturn,
            axis,
            a,
            s,
        } => {
            let c = value(*coordinate).cos();
            let sn = value(*coordinate).sin();
            let mut e = [[0.0; 3]; 3];
            let i = (axis + 1) % 3;
            let j = (axis + 2) % 3;
            (e[*axis][*axis], e[i][i], e[j][j], e[i][j], e[j][i]) = (1.0, c, c, -sn, sn);
            let r = mul(
                &mul(&turn.map(|r| r.map(eval)), &e),
                &unturn.map(|r| r.map(eval)),
            );
            let s = s.map(eval);
            let o = [0, 1, 2].map(|k| eval(a[k]) + (0..3).map(|l| r[k][l] * s[l]).sum::<f64>());
            (r, o)
        }
    }
}

fn mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}
