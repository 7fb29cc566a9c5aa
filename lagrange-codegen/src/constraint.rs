//! Constraint terms: the multiplier form (Lagrange's equations of the first kind)
//! and the reduced form on independent speeds (Maggi / Voronets / Gibbs–Appell).
//!
//! Both start from the velocity-level rows G q̇ + g = 0: a holonomic constraint
//! f(q,t) = 0 contributes Φ_q q̇ + Φ_t, a nonholonomic one its own expression
//! a(q,t)·q̇ + b(q,t) (linearity was proved while lowering).
//!
//! - Multipliers: G, g, Φ and γ = −(Ġ q̇ + ġ), the right-hand side of G q̈ = γ; the
//!   runtime solves the saddle-point system for q̈ and ν.
//! - Reduced: with K speeds u = U q̇ + u₀, the stacked rows A = [U; G], b = [u₀; g]
//!   read A q̇ + b = (u, 0), and their rates c = −(Ȧ q̇ + ḃ) give A q̈ = (u̇, 0) + c.
//!   The runtime solves A with pivoting at each state, so that W = A⁻¹[I; 0],
//!   κ = A⁻¹ c and Wᵀ M W u̇ = Wᵀ (Q − h − M κ) stay finite wherever A is regular.
//!   Solving A symbolically instead divides by pivots chosen once for all states,
//!   which vanish at regular states (a knife edge heading along y gets
//!   ẋ = (…)/cos θ). The projection is what the Gibbs function S = ½ Σ m |ξ̈|²
//!   yields when the dependent accelerations are eliminated (a test checks that).

use lagrange_symbolic::{Context, Expr as Sym};

use crate::lowered::ConstraintModel;

/// The multiplier form: K rows, holonomic first.
pub struct ConstraintSet {
    /// The rows' names, holonomic first.
    pub names: Vec<String>,
    /// How many of the K rows are holonomic.
    pub holonomic: usize,
    /// Φ(q,t) in the holonomic rows, 0 in the others.
    pub phi: Vec<Sym>,
    /// G (K × N), row-major.
    pub jacobian: Vec<Vec<Sym>>,
    /// g, so that the velocity constraint reads G q̇ + g = 0.
    pub velocity_term: Vec<Sym>,
    /// γ = −(Ġ q̇ + ġ).
    pub gamma: Vec<Sym>,
    /// Per point or body: coefficients indexed `[component][row]`; R = Σ_row coefficient · ν_row.
    pub reactions: Vec<(String, Vec<Vec<Sym>>)>,
    /// Derivatives for linearisation, if asked for (`emit(jacobians)`).
    pub derivatives: Option<ConstraintDerivatives>,
}

/// Derivatives of the multiplier form's terms with the accelerations a = q̈
/// (the acceleration symbols) and the multipliers ν (free symbols) held fixed.
pub struct ConstraintDerivatives {
    /// Free symbols standing for ν (emitted as `nu[k]`).
    pub nu_symbols: Vec<Sym>,
    /// ∂(Gᵀν)/∂q (N × N).
    pub force_q: Vec<Vec<Sym>>,
    /// ∂(γ − G a)/∂q (K × N).
    pub acceleration_q: Vec<Vec<Sym>>,
    /// ∂γ/∂q̇ (K × N).
    pub gamma_v: Vec<Vec<Sym>>,
    /// ∂(G q̇ + g)/∂q (K × N).
    pub velocity_q: Vec<Vec<Sym>>,
}

/// ∂e/∂x for every (e, x), collected: one row per expression.
fn jacobian(ctx: &mut Context, rows: &[Sym], wrt: &[Sym]) -> Vec<Vec<Sym>> {
    rows.iter()
        .map(|&r| {
            wrt.iter()
                .map(|&x| {
                    let d = ctx.diff(r, x);
                    ctx.collect(d)
                })
                .collect()
        })
        .collect()
}

/// Σ_j a_j x_j.
fn linear(ctx: &mut Context, a: &[Sym], x: &[Sym]) -> Sym {
    let terms: Vec<Sym> = a.iter().zip(x).map(|(&a, &x)| ctx.mul(a, x)).collect();
    ctx.sum(&terms)
}

/// The derivatives of Gᵀν, γ − G a, γ and G q̇ + g that linearising
/// M q̈ + h = Q + Gᵀν, G q̈ = γ needs.
pub fn constraint_derivatives(ctx: &mut Context, c: &ConstraintSet) -> ConstraintDerivatives {
    row_derivatives(ctx, "nu", &c.names, &c.jacobian, &c.velocity_term, &c.gamma)
}

/// ∂(Gᵀν)/∂q, ∂(γ − G a)/∂q, ∂γ/∂q̇ and ∂(G q̇ + g)/∂q for velocity rows
/// G q̇ + g with rates γ; ν are free symbols named `{prefix}:{row}`.
fn row_derivatives(
    ctx: &mut Context,
    prefix: &str,
    names: &[String],
    g: &[Vec<Sym>],
    g0: &[Sym],
    gamma: &[Sym],
) -> ConstraintDerivatives {
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let n = q.len();
    let k = names.len();
    let nu_symbols: Vec<Sym> = names
        .iter()
        .map(|name| ctx.free_symbol(&format!("{prefix}:{name}")))
        .collect();
    let generalized: Vec<Sym> = (0..n)
        .map(|i| {
            let column: Vec<Sym> = (0..k).map(|r| g[r][i]).collect();
            linear(ctx, &column, &nu_symbols)
        })
        .collect();
    let residual: Vec<Sym> = (0..k)
        .map(|r| {
            let ga = linear(ctx, &g[r], &qdd);
            ctx.sub(gamma[r], ga)
        })
        .collect();
    let velocity: Vec<Sym> = (0..k)
        .map(|r| {
            let gv = linear(ctx, &g[r], &qd);
            ctx.add(gv, g0[r])
        })
        .collect();
    ConstraintDerivatives {
        force_q: jacobian(ctx, &generalized, &q),
        acceleration_q: jacobian(ctx, &residual, &q),
        gamma_v: jacobian(ctx, gamma, &qd),
        velocity_q: jacobian(ctx, &velocity, &q),
        nu_symbols,
    }
}

/// The reduced form on K independent speeds: the N stacked velocity rows
/// A = [U; G], b = [u₀; g] (A q̇ + b = (u, 0)) and their rates c = −(Ȧ q̇ + ḃ)
/// (A q̈ = (u̇, 0) + c). The runtime solves them; nothing here divides.
pub struct Reduction {
    /// The speeds' names.
    pub names: Vec<String>,
    /// u(q, q̇, t) = U q̇ + u₀.
    pub speeds: Vec<Sym>,
    /// The rows' names: the speeds, then the constraints.
    pub rows: Vec<String>,
    /// A (N × N), row-major.
    pub matrix: Vec<Vec<Sym>>,
    /// b.
    pub free: Vec<Sym>,
    /// c = −(Ȧ q̇ + ḃ).
    pub rates: Vec<Sym>,
    /// Φ(q, t) of the holonomic constraints, whose rows follow the speeds':
    /// what builds a starting state on them.
    pub positions: Vec<Sym>,
    /// Whether the macro picked the speeds (velocities), so that the runtime
    /// may use other free velocities where the constraints fix these.
    pub free_speeds: bool,
    /// The rows' derivatives for linearisation, if asked for (`emit(jacobians)`):
    /// ∂(Aᵀν)/∂q, ∂(c − A a)/∂q, ∂c/∂q̇, ∂(A q̇ + b)/∂q.
    pub derivatives: Option<ConstraintDerivatives>,
}

/// The derivatives of the stacked rows that linearising the reduced form needs
/// (the runtime composes them with W and M).
pub fn reduced_derivatives(ctx: &mut Context, r: &Reduction) -> ConstraintDerivatives {
    row_derivatives(ctx, "mu", &r.rows, &r.matrix, &r.free, &r.rates)
}

/// A velocity-level row: G row, g, and (holonomic) Φ.
struct Row {
    g: Vec<Sym>,
    g0: Sym,
    phi: Option<Sym>,
}

fn rows(
    ctx: &mut Context,
    holonomic: &[ConstraintModel],
    nonholonomic: &[ConstraintModel],
) -> Vec<Row> {
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let t = ctx.time();
    let zero_vel: Vec<(Sym, Sym)> = {
        let z = ctx.zero();
        qd.iter().map(|&v| (v, z)).collect()
    };
    let mut out = Vec::new();
    for c in holonomic {
        let g = q.iter().map(|&qi| {
            let d = ctx.diff(c.value, qi);
            ctx.collect(d)
        });
        let g = g.collect();
        let g0 = ctx.diff(c.value, t);
        let g0 = ctx.collect(g0);
        out.push(Row {
            g,
            g0,
            phi: Some(c.value),
        });
    }
    for c in nonholonomic {
        let g = qd
            .iter()
            .map(|&v| {
                let d = ctx.diff(c.value, v);
                ctx.collect(d)
            })
            .collect();
        let g0 = ctx.substitute(c.value, &zero_vel);
        let g0 = ctx.collect(g0);
        out.push(Row { g, g0, phi: None });
    }
    out
}

/// γ = −d/dt(G q̇ + g) at q̈ = 0 for each row: the derivative along
/// (t → 1, q → q̇), the velocities' rates zero, in one forward pass.
fn rates(ctx: &mut Context, rows: &[Row]) -> Vec<Sym> {
    let qd = ctx.velocities();
    let mut along: Vec<(Sym, Sym)> = ctx.coordinates().into_iter().zip(qd.clone()).collect();
    let t = ctx.time();
    let one = ctx.one();
    along.push((t, one));
    rows.iter()
        .map(|r| {
            let e = linear(ctx, &r.g, &qd);
            let e = ctx.add(e, r.g0);
            let d = ctx.directional(e, &along);
            let d = ctx.neg(d);
            ctx.collect(d)
        })
        .collect()
}

/// G, g, Φ, γ and the reaction coefficients.
pub fn multiplier_form(
    ctx: &mut Context,
    holonomic: &[ConstraintModel],
    nonholonomic: &[ConstraintModel],
) -> ConstraintSet {
    let rows = rows(ctx, holonomic, nonholonomic);
    let k = rows.len();
    let gamma = rates(ctx, &rows);
    let zero = ctx.zero();
    let phi = rows
        .iter()
        .map(|r| r.phi.map_or(zero, |p| ctx.collect(p)))
        .collect();

    // Reactions: gather, per point or body, the coefficient of each row.
    let mut reactions: Vec<(String, Vec<Vec<Sym>>)> = Vec::new();
    for (row, c) in holonomic.iter().chain(nonholonomic).enumerate() {
        for (name, partials) in &c.cartesian {
            let entry = match reactions.iter().position(|(n, _)| n == name) {
                Some(i) => i,
                None => {
                    reactions.push((name.clone(), vec![vec![zero; k]; partials.len()]));
                    reactions.len() - 1
                }
            };
            for (comp, &p) in partials.iter().enumerate() {
                reactions[entry].1[comp][row] = ctx.collect(p);
            }
        }
    }

    ConstraintSet {
        names: holonomic
            .iter()
            .chain(nonholonomic)
            .map(|c| c.name.clone())
            .collect(),
        holonomic: holonomic.len(),
        phi,
        jacobian: rows.iter().map(|r| r.g.clone()).collect(),
        velocity_term: rows.iter().map(|r| r.g0).collect(),
        gamma,
        reactions,
        derivatives: None,
    }
}

/// Chooses independent velocities when the user gave no `speeds(...)` (named
/// by `velocities`: the coordinates', then each orientation's `name.wx` …): the
/// columns left without a pivot when the constraint rows are eliminated, so that
/// u = (q̇_j for those j). Pivots prefer constant entries (e.g. ẋ in a rolling
/// constraint) so the dependent velocities are solved for without division by a
/// function of q where possible.
pub fn default_speeds(
    ctx: &mut Context,
    holonomic: &[ConstraintModel],
    nonholonomic: &[ConstraintModel],
    velocities: &[String],
) -> Result<Vec<(String, Sym)>, String> {
    let rows = rows(ctx, holonomic, nonholonomic);
    let n = velocities.len();
    let mut a: Vec<Vec<Sym>> = rows.iter().map(|r| r.g.clone()).collect();
    let mut dependent = Vec::new();
    let mut used = vec![false; a.len()];
    for _ in 0..a.len() {
        let best = (0..n)
            .filter(|c| !dependent.contains(c))
            .filter_map(|c| choose_pivot(ctx, &a, c, &used).map(|r| (r, c)))
            .min_by_key(|&(r, c)| {
                let e = a[r][c];
                (ctx.as_f64(e).is_none(), ctx.node_count(e), c)
            });
        let Some((p, col)) = best else {
            return Err(
                "the constraints are not independent: their velocity rows are linearly dependent"
                    .to_string(),
            );
        };
        used[p] = true;
        dependent.push(col);
        eliminate(ctx, &mut a, p, col);
    }
    let qd = ctx.velocities();
    Ok((0..n)
        .filter(|j| !dependent.contains(j))
        .map(|j| (speed_name(&velocities[j]), qd[j]))
        .collect())
}

/// The name of the speed that is velocity `name` itself: `dot_x` for a
/// coordinate's, `turn_wx` for an orientation's angular velocity `turn.wx`.
fn speed_name(name: &str) -> String {
    match name.split_once('.') {
        Some((orientation, axis)) => format!("{orientation}_{axis}"),
        None => format!("dot_{name}"),
    }
}

/// Velocity `name` as the description writes it: `dot(x)` for a coordinate's,
/// `turn.wx` (body axes) for an orientation's angular velocity.
fn written(name: &str) -> String {
    if name.contains('.') {
        name.to_string()
    } else {
        format!("dot({name})")
    }
}

/// The row (not yet used) with the best pivot in column `col`: a nonzero
/// constant if any, else the smallest nonzero expression.
fn choose_pivot(ctx: &Context, a: &[Vec<Sym>], col: usize, used: &[bool]) -> Option<usize> {
    (0..a.len())
        .filter(|&r| !used[r] && !ctx.is_zero(a[r][col]))
        .min_by_key(|&r| {
            let e = a[r][col];
            (ctx.as_f64(e).is_none(), ctx.node_count(e), r)
        })
}

/// Eliminates column `col` from every row but `p`.
fn eliminate(ctx: &mut Context, a: &mut [Vec<Sym>], p: usize, col: usize) {
    let pivot = a[p][col];
    for r in 0..a.len() {
        if r == p || ctx.is_zero(a[r][col]) {
            continue;
        }
        let f = ctx.div(a[r][col], pivot);
        let f = ctx.simplify(f);
        for j in 0..a[r].len() {
            let s = ctx.mul(f, a[p][j]);
            let d = ctx.sub(a[r][j], s);
            a[r][j] = ctx.simplify(d);
        }
    }
}

/// The reduced form on the given speeds: the stacked rows and their rates.
///
/// # Errors
/// If speeds and constraints do not number the velocities, a speed is not
/// linear in them, or no assignment of rows to velocities exists (A singular
/// at every state, whatever the values).
pub fn reduce(
    ctx: &mut Context,
    holonomic: &[ConstraintModel],
    nonholonomic: &[ConstraintModel],
    speeds: &[(String, Sym)],
    velocities: &[String],
) -> Result<Reduction, String> {
    let n = velocities.len();
    let k = speeds.len();
    let constraints = rows(ctx, holonomic, nonholonomic);
    if k + constraints.len() != n {
        return Err(format!(
            "{k} speed{} and {} constraint{} do not make the {n} velocities: the reduced form needs speeds + constraints = degrees of freedom",
            if k == 1 { "" } else { "s" },
            constraints.len(),
            if constraints.len() == 1 { "" } else { "s" },
        ));
    }
    let mut stacked = speed_rows(ctx, speeds)?;
    stacked.extend(constraints);
    let matrix: Vec<Vec<Sym>> = stacked.iter().map(|r| r.g.clone()).collect();
    if let Some(col) = unassignable_column(ctx, &matrix) {
        return Err(format!(
            "the speeds and the constraints do not determine the velocity `{}`: choose speeds independent of the constraints",
            written(&velocities[col])
        ));
    }
    let rates = rates(ctx, &stacked);
    let mut rows: Vec<String> = speeds.iter().map(|(name, _)| name.clone()).collect();
    rows.extend(holonomic.iter().chain(nonholonomic).map(|c| c.name.clone()));
    Ok(Reduction {
        names: speeds.iter().map(|(name, _)| name.clone()).collect(),
        speeds: speeds.iter().map(|&(_, u)| ctx.collect(u)).collect(),
        rows,
        matrix,
        free: stacked.iter().map(|r| r.g0).collect(),
        rates,
        positions: holonomic.iter().map(|c| c.value).collect(),
        free_speeds: false,
        derivatives: None,
    })
}

/// The rows u = U q̇ + u₀ of the speeds.
fn speed_rows(ctx: &mut Context, speeds: &[(String, Sym)]) -> Result<Vec<Row>, String> {
    let qd = ctx.velocities();
    let zero = ctx.zero();
    let zero_vel: Vec<(Sym, Sym)> = qd.iter().map(|&v| (v, zero)).collect();
    speeds
        .iter()
        .map(|(name, u)| {
            let g: Vec<Sym> = qd
                .iter()
                .map(|&v| {
                    let d = ctx.diff(*u, v);
                    ctx.collect(d)
                })
                .collect();
            if g.iter().any(|&e| qd.iter().any(|&v| ctx.depends_on(e, v))) {
                return Err(format!("speed `{name}` must be linear in the velocities"));
            }
            let g0 = ctx.substitute(*u, &zero_vel);
            let g0 = ctx.collect(g0);
            Ok(Row { g, g0, phi: None })
        })
        .collect()
}

/// A column of the square matrix `a` that no row can be assigned to, if any
/// (by augmenting paths over the nonzero entries): the matrix is then singular
/// whatever its entries' values.
fn unassignable_column(ctx: &Context, a: &[Vec<Sym>]) -> Option<usize> {
    let n = a.len();
    let mut row_of: Vec<Option<usize>> = vec![None; n];
    fn augment(
        ctx: &Context,
        a: &[Vec<Sym>],
        col: usize,
        seen: &mut [bool],
        row_of: &mut [Option<usize>],
    ) -> bool {
        for r in 0..a.len() {
            if seen[r] || ctx.is_zero(a[r][col]) {
                continue;
            }
            seen[r] = true;
            // Row r is free, or the column holding it can move to another row.
            let free = match row_of[r] {
                None => true,
                Some(other) => augment(ctx, a, other, seen, row_of),
            };
            if free {
                row_of[r] = Some(col);
                return true;
            }
        }
        false
    }
    (0..n).find(|&col| !augment(ctx, a, col, &mut vec![false; n], &mut row_of))
}
