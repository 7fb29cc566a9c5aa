//! The contacts' rows: for each contact, the gap φ, its Jacobian row and the
//! bias J̇ q̇ of that row, and the same for the slip along each tangent, from
//! the multiplier form's derivation of a holonomic row (the gap) and
//! nonholonomic rows (the slips).

use lagrange_symbolic::{Context, Expr as Sym};

use crate::lowered::{ContactModel, OrientationModel};

/// One contact's laws and rows.
pub struct ContactRowsModel {
    /// The contact's name.
    pub name: String,
    /// Newton's coefficient of restitution.
    pub restitution: f64,
    /// Coulomb's coefficient of friction.
    pub friction: f64,
    /// φ(q).
    pub gap: Sym,
    /// ∂φ/∂q.
    pub normal: Vec<Sym>,
    /// J̇ q̇ of the normal row (−γ of the constraint φ = 0).
    pub normal_bias: Sym,
    /// Each tangent's row and its bias: two on a plane, none for a stop,
    /// one for a joint's dry friction.
    pub tangents: Vec<(Vec<Sym>, Sym)>,
    /// The touch event's function where it is not the gap (two spheres).
    pub approach: Option<Sym>,
    /// A joint's dry friction: `friction` is its bound, and its one
    /// tangent the coordinate's row.
    pub dry: bool,
}

impl ContactRowsModel {
    /// Every expression, in the order the emitted program lists them: φ, the
    /// normal row, its bias, then each tangent's row and bias.
    pub fn outputs(&self) -> Vec<Sym> {
        let mut out = vec![self.gap];
        out.extend(&self.normal);
        out.push(self.normal_bias);
        for (row, bias) in &self.tangents {
            out.extend(row);
            out.push(*bias);
        }
        out
    }
}

/// The rows of every contact, derived in each free orientation's chart θ
/// (the rates need the rows' θ-derivatives) and taken at its centre θ = 0,
/// where θ̇ is the angular velocity in body axes, as the equations are.
pub fn rows(
    ctx: &mut Context,
    contacts: &[ContactModel],
    orientations: &[OrientationModel],
) -> Vec<ContactRowsModel> {
    let mut rows = derived(ctx, contacts);
    if orientations.is_empty() {
        return rows;
    }
    let at = super::chart::centre(ctx, orientations);
    let norms = super::chart::unit_norms(ctx, orientations);
    let mut c = super::chart::AtCentre {
        ctx,
        at: &at,
        norms: &norms,
    };
    for r in &mut rows {
        r.gap = c.one(r.gap);
        c.all(&mut r.normal);
        r.normal_bias = c.one(r.normal_bias);
        for (row, bias) in &mut r.tangents {
            c.all(row);
            *bias = c.one(*bias);
        }
        if let Some(a) = &mut r.approach {
            *a = c.one(*a);
        }
    }
    rows
}

/// The rows in the coordinates as lowered (θ included).
fn derived(ctx: &mut Context, contacts: &[ContactModel]) -> Vec<ContactRowsModel> {
    contacts
        .iter()
        .map(|c| {
            let set =
                crate::constraint::multiplier_form(ctx, std::slice::from_ref(&c.gap), &c.slips);
            let bias: Vec<Sym> = (set.gamma.iter())
                .map(|&g| {
                    let b = ctx.neg(g);
                    ctx.collect(b)
                })
                .collect();
            let tangents = set.jacobian[1..]
                .iter()
                .cloned()
                .zip(bias[1..].iter().copied())
                .collect();
            let normal_bias = bias[0];
            ContactRowsModel {
                name: c.name.clone(),
                restitution: c.restitution,
                friction: c.friction,
                gap: set.phi[0],
                normal: set.jacobian[0].clone(),
                normal_bias,
                tangents,
                approach: c.approach,
                dry: c.dry,
            }
        })
        .collect()
}
