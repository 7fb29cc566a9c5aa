//! Constraint terms: the multiplier form (Lagrange's equations of the first kind)
//! and the reduced form on independent speeds (Maggi / Voronets / Gibbs–Appell).
//!
//! Both start from the velocity-level rows G q̇ + g = 0: a holonomic constraint
//! f(q,t) = 0 contributes Φ_q q̇ + Φ_t, a nonholonomic one its own expression
//! a(q,t)·q̇ + b(q,t) (linearity was proved while lowering).
//!
//! - Multipliers: G, g, Φ and γ = −(Ġ q̇ + ġ), the right-hand side of G q̈ = γ; the
//!   runtime solves the saddle-point system for q̈ and ν.
//! - Reduced: with K speeds u = U q̇ + u₀ chosen so that [U; G] is invertible,
//!   q̇ = W u + w solves [U; G] q̇ = [u − u₀; −g] symbolically. Projecting
//!   M q̈ + h = Q + Gᵀν onto W (G W = 0 removes ν) with q̈ = W u̇ + κ gives
//!   Wᵀ M W u̇ = Wᵀ (Q − h − M κ), which is what the Gibbs function S = ½ Σ m |ξ̈|²
//!   yields when the dependent accelerations are eliminated (a test checks that).

use lagrange_symbolic::{Context, Expr as Sym};

/// One constraint after lowering and composition with ξ(q,t).
pub struct ConstraintModel {
    pub name: String,
    /// f(q,t) for a holonomic constraint, a(q,t)·q̇ + b(q,t) for a nonholonomic one.
    pub value: Sym,
    /// For each point or body named in the constraint: ∂f/∂ξ (holonomic) or ∂f/∂ξ̇
    /// (nonholonomic) per Cartesian component, composed with ξ(q,t). The reaction of
    /// this constraint on that point is its multiplier times this vector.
    pub cartesian: Vec<(String, Vec<Sym>)>,
}

/// The multiplier form: K rows, holonomic first.
pub struct ConstraintSet {
    pub names: Vec<String>,
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
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let (n, k) = (q.len(), c.names.len());
    let nu_symbols: Vec<Sym> = c
        .names
        .iter()
        .map(|name| ctx.free_symbol(&format!("nu:{name}")))
        .collect();
    let generalized: Vec<Sym> = (0..n)
        .map(|i| {
            let column: Vec<Sym> = (0..k).map(|r| c.jacobian[r][i]).collect();
            linear(ctx, &column, &nu_symbols)
        })
        .collect();
    let residual: Vec<Sym> = (0..k)
        .map(|r| {
            let ga = linear(ctx, &c.jacobian[r], &qdd);
            ctx.sub(c.gamma[r], ga)
        })
        .collect();
    let velocity: Vec<Sym> = (0..k)
        .map(|r| {
            let gv = linear(ctx, &c.jacobian[r], &qd);
            ctx.add(gv, c.velocity_term[r])
        })
        .collect();
    ConstraintDerivatives {
        force_q: jacobian(ctx, &generalized, &q),
        acceleration_q: jacobian(ctx, &residual, &q),
        gamma_v: jacobian(ctx, &c.gamma, &qd),
        velocity_q: jacobian(ctx, &velocity, &q),
        nu_symbols,
    }
}

/// The reduced form on K independent speeds.
pub struct Reduction {
    pub names: Vec<String>,
    /// Free symbols standing for u in `velocities`, `kappa`, `mass`, `rhs`.
    pub speed_symbols: Vec<Sym>,
    /// u(q, q̇, t) = U q̇ + u₀.
    pub speeds: Vec<Sym>,
    /// q̇(q, u, t) = W u + w.
    pub velocities: Vec<Sym>,
    /// W (N × K).
    pub w_matrix: Vec<Vec<Sym>>,
    /// κ = Ẇ u + ẇ, so that q̈ = W u̇ + κ.
    pub kappa: Vec<Sym>,
    /// M* = Wᵀ M W (K × K).
    pub mass: Vec<Vec<Sym>>,
    /// F* = Wᵀ (Q − h − M κ).
    pub rhs: Vec<Sym>,
    /// Derivatives for linearisation, if asked for (`emit(jacobians)`).
    pub derivatives: Option<ReducedDerivatives>,
}

/// Derivatives of the reduced equations at fixed u, u̇ and an extra generalized
/// force e, with F*(e) = Wᵀ (Q − h − M κ + e).
pub struct ReducedDerivatives {
    /// Free symbols standing for u̇ (emitted as `du[k]`).
    pub rate_symbols: Vec<Sym>,
    /// Free symbols standing for e (emitted as `e[i]`).
    pub force_symbols: Vec<Sym>,
    /// ∂(F*(e) − M* u̇)/∂q (K × N).
    pub dynamics_q: Vec<Vec<Sym>>,
    /// ∂F*/∂u (K × K).
    pub force_u: Vec<Vec<Sym>>,
    /// ∂(W u + w)/∂q (N × N).
    pub velocities_q: Vec<Vec<Sym>>,
}

/// The derivatives of the reduced equations that linearising
/// M* u̇ = F*, q̇ = W u + w needs.
pub fn reduced_derivatives(
    ctx: &mut Context,
    r: &Reduction,
    coordinates: &[String],
) -> ReducedDerivatives {
    let q = ctx.coordinates();
    let (n, k) = (q.len(), r.names.len());
    let rate_symbols: Vec<Sym> = r
        .names
        .iter()
        .map(|name| ctx.free_symbol(&format!("du:{name}")))
        .collect();
    let force_symbols: Vec<Sym> = coordinates
        .iter()
        .map(|name| ctx.free_symbol(&format!("e:{name}")))
        .collect();
    let residual: Vec<Sym> = (0..k)
        .map(|a| {
            let column: Vec<Sym> = (0..n).map(|i| r.w_matrix[i][a]).collect();
            let we = linear(ctx, &column, &force_symbols);
            let mu = linear(ctx, &r.mass[a], &rate_symbols);
            let f = ctx.add(r.rhs[a], we);
            ctx.sub(f, mu)
        })
        .collect();
    ReducedDerivatives {
        dynamics_q: jacobian(ctx, &residual, &q),
        force_u: jacobian(ctx, &r.rhs, &r.speed_symbols),
        velocities_q: jacobian(ctx, &r.velocities, &q),
        rate_symbols,
        force_symbols,
    }
}

/// The unconstrained equations the reduced form projects.
pub struct Dynamics<'a> {
    pub mass: &'a [Vec<Sym>],
    /// Q − h.
    pub rhs: &'a [Sym],
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

/// G, g, Φ, γ and the reaction coefficients.
pub fn multiplier_form(
    ctx: &mut Context,
    holonomic: &[ConstraintModel],
    nonholonomic: &[ConstraintModel],
) -> ConstraintSet {
    let qd = ctx.velocities();
    let zero_acc: Vec<(Sym, Sym)> = {
        let z = ctx.zero();
        ctx.accelerations().into_iter().map(|a| (a, z)).collect()
    };
    let rows = rows(ctx, holonomic, nonholonomic);
    let k = rows.len();
    let mut gamma = Vec::with_capacity(k);
    for r in &rows {
        // γ = −d/dt(G q̇ + g) at q̈ = 0.
        let terms: Vec<Sym> = r.g.iter().zip(&qd).map(|(&a, &v)| ctx.mul(a, v)).collect();
        let mut e = ctx.sum(&terms);
        e = ctx.add(e, r.g0);
        let d = ctx.time_derivative(e);
        let d = ctx.substitute(d, &zero_acc);
        let d = ctx.neg(d);
        gamma.push(ctx.collect(d));
    }
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

/// Chooses independent velocities when the user gave no `speeds(...)`: the
/// columns left without a pivot when the constraint rows are eliminated, so that
/// u = (q̇_j for those j). Pivots prefer constant entries (e.g. ẋ in a rolling
/// constraint) so the dependent velocities are solved for without division by a
/// function of q where possible.
pub fn default_speeds(
    ctx: &mut Context,
    holonomic: &[ConstraintModel],
    nonholonomic: &[ConstraintModel],
    coordinates: &[String],
) -> Result<Vec<(String, Sym)>, String> {
    let rows = rows(ctx, holonomic, nonholonomic);
    let n = coordinates.len();
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
        eliminate(ctx, &mut a, p, col, &mut []);
    }
    let qd = ctx.velocities();
    Ok((0..n)
        .filter(|j| !dependent.contains(j))
        .map(|j| (format!("dot_{}", coordinates[j]), qd[j]))
        .collect())
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

/// Eliminates column `col` from every row but `p`, applying the same operations
/// to the right-hand sides `b` (one vector per row).
fn eliminate(ctx: &mut Context, a: &mut [Vec<Sym>], p: usize, col: usize, b: &mut [Vec<Sym>]) {
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
        if !b.is_empty() {
            for j in 0..b[r].len() {
                let s = ctx.mul(f, b[p][j]);
                let d = ctx.sub(b[r][j], s);
                b[r][j] = ctx.simplify(d);
            }
        }
    }
}

/// The reduced equations on the given speeds.
pub fn reduce(
    ctx: &mut Context,
    dynamics: &Dynamics,
    holonomic: &[ConstraintModel],
    nonholonomic: &[ConstraintModel],
    speeds: &[(String, Sym)],
    coordinates: &[String],
) -> Result<Reduction, String> {
    let qd = ctx.velocities();
    let n = qd.len();
    let k = speeds.len();
    let zero_vel: Vec<(Sym, Sym)> = {
        let z = ctx.zero();
        qd.iter().map(|&v| (v, z)).collect()
    };
    let rows = rows(ctx, holonomic, nonholonomic);
    if k + rows.len() != n {
        return Err(format!(
            "{k} speed{} and {} constraint{} do not make the {n} velocities: the reduced form needs speeds + constraints = degrees of freedom",
            if k == 1 { "" } else { "s" },
            rows.len(),
            if rows.len() == 1 { "" } else { "s" },
        ));
    }
    let speed_symbols: Vec<Sym> = speeds
        .iter()
        .map(|(name, _)| ctx.free_symbol(&format!("u:{name}")))
        .collect();

    // [U; G] q̇ = [u − u₀; −g], solved by Gauss–Jordan elimination. Right-hand sides
    // are stored as K + 1 columns: the coefficients of u and the constant part.
    let (zero, one) = (ctx.zero(), ctx.one());
    let mut a: Vec<Vec<Sym>> = Vec::with_capacity(n);
    let mut b: Vec<Vec<Sym>> = Vec::with_capacity(n);
    for (i, (_, u)) in speeds.iter().enumerate() {
        let row: Vec<Sym> = qd
            .iter()
            .map(|&v| {
                let d = ctx.diff(*u, v);
                ctx.simplify(d)
            })
            .collect();
        if row
            .iter()
            .any(|&e| qd.iter().any(|&v| ctx.depends_on(e, v)))
        {
            return Err(format!(
                "speed `{}` must be linear in the velocities",
                speeds[i].0
            ));
        }
        a.push(row);
        let u0 = ctx.substitute(*u, &zero_vel);
        let mut rhs = vec![zero; k + 1];
        rhs[i] = one;
        rhs[k] = ctx.neg(u0);
        b.push(rhs);
    }
    for r in &rows {
        a.push(r.g.clone());
        let mut rhs = vec![zero; k + 1];
        rhs[k] = ctx.neg(r.g0);
        b.push(rhs);
    }
    let mut used = vec![false; n];
    let mut pivot_of_col = vec![0; n];
    for col in 0..n {
        let Some(p) = choose_pivot(ctx, &a, col, &used) else {
            return Err(format!(
                "the speeds and the constraints do not determine the velocity `dot({})`: choose speeds independent of the constraints",
                coordinates[col]
            ));
        };
        used[p] = true;
        pivot_of_col[col] = p;
        eliminate(ctx, &mut a, p, col, &mut b);
    }
    // Now a is diagonal up to row order: q̇_col = b[p] / a[p][col].
    let mut w_matrix = vec![vec![zero; k]; n];
    let mut w_vec = vec![zero; n];
    for col in 0..n {
        let p = pivot_of_col[col];
        let d = a[p][col];
        for j in 0..k {
            let e = ctx.div(b[p][j], d);
            w_matrix[col][j] = ctx.simplify(e);
        }
        let e = ctx.div(b[p][k], d);
        w_vec[col] = ctx.simplify(e);
    }
    let velocities: Vec<Sym> = (0..n)
        .map(|i| {
            let mut terms: Vec<Sym> = (0..k)
                .map(|j| ctx.mul(w_matrix[i][j], speed_symbols[j]))
                .collect();
            terms.push(w_vec[i]);
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect();
    let to_speeds: Vec<(Sym, Sym)> = qd.iter().copied().zip(velocities.iter().copied()).collect();

    // κ = d/dt (W u + w) at fixed u, with q̇ = W u + w.
    let kappa: Vec<Sym> = velocities
        .iter()
        .map(|&v| {
            let d = ctx.time_derivative(v);
            let d = ctx.substitute(d, &to_speeds);
            ctx.collect(d)
        })
        .collect();
    let rhs_full: Vec<Sym> = dynamics
        .rhs
        .iter()
        .map(|&r| ctx.substitute(r, &to_speeds))
        .collect();
    // F = Q − h − M κ, then projected.
    let force: Vec<Sym> = (0..n)
        .map(|i| {
            let terms: Vec<Sym> = (0..n)
                .map(|j| ctx.mul(dynamics.mass[i][j], kappa[j]))
                .collect();
            let mk = ctx.sum(&terms);
            ctx.sub(rhs_full[i], mk)
        })
        .collect();
    let rhs: Vec<Sym> = (0..k)
        .map(|a_| {
            let terms: Vec<Sym> = (0..n).map(|i| ctx.mul(w_matrix[i][a_], force[i])).collect();
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect();
    let mut mass = vec![vec![zero; k]; k];
    for a_ in 0..k {
        for c in a_..k {
            let mut terms = Vec::new();
            for i in 0..n {
                if ctx.is_zero(w_matrix[i][a_]) {
                    continue;
                }
                for j in 0..n {
                    let mw = ctx.mul(dynamics.mass[i][j], w_matrix[j][c]);
                    terms.push(ctx.mul(w_matrix[i][a_], mw));
                }
            }
            let s = ctx.sum(&terms);
            let s = ctx.simplify(s);
            let s = ctx.collect(s);
            mass[a_][c] = s;
            mass[c][a_] = s;
        }
    }
    Ok(Reduction {
        names: speeds.iter().map(|(n, _)| n.clone()).collect(),
        speed_symbols,
        speeds: speeds.iter().map(|&(_, u)| ctx.collect(u)).collect(),
        velocities,
        w_matrix,
        kappa,
        mass,
        rhs,
        derivatives: None,
    })
}
