//! The equations of motion M q̈ + h = Q with Q − h, assembled from the route
//! kept.

use lagrange_symbolic::{Context, Expr as Sym};

use super::expressions::{Expressions, entries};
use super::generic::{BiasRoute, GenericTerms};
use super::recursive::RecursiveTerms;

/// M q̈ + h = Q at zero input, by the route chosen, with Q − h.
pub struct EquationsOfMotion {
    /// Row-major N×N, symmetric (the same `Sym` at (i,j) and (j,i)).
    pub mass: Vec<Vec<Sym>>,
    /// h(q, q̇, t): the Coriolis, centrifugal and rheonomic terms.
    pub bias: Vec<Sym>,
    /// Q with gravity's share.
    pub forces: Vec<Sym>,
    /// Q − h, the right-hand side the integrators need.
    pub rhs: Vec<Sym>,
    /// Whether the positions depend on t explicitly.
    pub rheonomic: bool,
    /// How M and h were derived.
    pub derivation: Derivation,
}

/// The route M and h were derived by, why, and the other route's h.
pub struct Derivation {
    /// The route M and h were derived by.
    pub route: BiasRoute,
    /// Why M and h are not by the recursive route: which body or point, and
    /// what about it (`None` when they are).
    pub reason: Option<String>,
    /// h by the route not chosen, kept so tests can check the two agree (empty
    /// when only the recursive route was derived).
    pub other_bias: Vec<Sym>,
}

impl Expressions for EquationsOfMotion {
    fn expressions(&self, out: &mut Vec<Sym>) {
        entries(out, [&self.mass]);
        out.extend(&self.bias);
        out.extend(&self.forces);
        out.extend(&self.rhs);
    }
}

/// Q at zero input, as the routes need it.
pub(super) struct Generalized<'a> {
    /// Q, without gravity's share on the recursive route.
    pub forces: &'a [Sym],
    /// −Σ m g·ξ alone (the recursive route adds its gradient back into Q).
    pub gravity_potential: Sym,
}

/// Assembles M, h and Q − h from the route kept: the recursive right-hand side is
/// Q (without gravity) − (h − Q_gravity), and its Q gets gravity's share back for
/// the `forces` output.
pub(super) fn equations(
    ctx: &mut Context,
    recursive: Option<RecursiveTerms>,
    generic: Option<GenericTerms>,
    q_at_zero: Generalized,
    rheonomic: bool,
    reason: Option<String>,
) -> EquationsOfMotion {
    let q = ctx.coordinates();
    let n = q.len();
    let generalized = q_at_zero.forces;
    match recursive {
        Some(r) => {
            let rhs: Vec<Sym> = (0..n)
                .map(|i| ctx.sub(generalized[i], r.with_gravity[i]))
                .collect();
            let total = (0..n)
                .map(|i| {
                    let dv = ctx.diff(q_at_zero.gravity_potential, q[i]);
                    let e = ctx.sub(generalized[i], dv);
                    ctx.collect(e)
                })
                .collect();
            EquationsOfMotion {
                mass: r.mass,
                bias: r.bias,
                forces: total,
                rhs,
                rheonomic,
                derivation: Derivation {
                    route: BiasRoute::Recursive,
                    reason,
                    other_bias: generic.map(|g| g.bias).unwrap_or_default(),
                },
            }
        }
        None => {
            let g = generic.expect("the generic route was derived");
            let rhs: Vec<Sym> = (0..n)
                .map(|i| {
                    let r = ctx.sub(generalized[i], g.bias[i]);
                    ctx.collect(r)
                })
                .collect();
            EquationsOfMotion {
                mass: g.mass,
                bias: g.bias,
                forces: generalized.to_vec(),
                rhs,
                rheonomic,
                derivation: Derivation {
                    route: g.route,
                    reason,
                    other_bias: g.other,
                },
            }
        }
    }
}
