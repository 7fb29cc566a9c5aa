//! Lagrange's equations of the second kind, derived symbolically.
//!
//! Input: the lowered description (positions ξ_ν(q,t), masses, gravity, potential,
//! forces, dissipation). Output: a [`Model`] holding M(q,t), h(q,q̇,t), Q(q,q̇,t) and
//! the energies as expressions in one [`Context`], ready for `emit`.
//!
//! h is derived twice — by the d'Alembert projection h = Σ m Jᵀκ and by
//! differentiating T (the Christoffel route) — and the cheaper program is kept.
//! The two must agree; a test checks that numerically.

use lagrange_symbolic::{Context, Expr as Sym, Program};

/// A point mass after lowering.
pub struct PointModel {
    pub name: String,
    pub mass: Sym,
    pub position: Vec<Sym>,
}

/// The lowered description: everything as expressions, names resolved.
pub struct Lowered {
    pub ctx: Context,
    pub coordinates: Vec<String>,
    pub parameters: Vec<String>,
    pub points: Vec<PointModel>,
    pub gravity: Option<Vec<Sym>>,
    pub potential: Option<Sym>,
    pub dissipation: Option<Sym>,
    /// (point index, Cartesian force)
    pub forces: Vec<(usize, Vec<Sym>)>,
    /// (coordinate index, generalized force)
    pub generalized_forces: Vec<(usize, Sym)>,
}

/// Which derivation of h the emitted code uses.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum BiasRoute {
    /// h = Σ_ν m_ν J_νᵀ κ_ν (d'Alembert's principle).
    Projection,
    /// h = d/dt ∂T/∂q̇ − ∂T/∂q with q̈ = 0 (Christoffel symbols, rheonomic terms).
    Christoffel,
}

/// The equations of motion M q̈ + h = Q and the energies, as expressions.
pub struct Model {
    pub ctx: Context,
    pub coordinates: Vec<String>,
    pub parameters: Vec<String>,
    pub rheonomic: bool,
    /// Row-major N×N, symmetric (the same `Sym` at (i,j) and (j,i)).
    pub mass: Vec<Vec<Sym>>,
    pub bias: Vec<Sym>,
    pub forces: Vec<Sym>,
    /// Q − h, the right-hand side the integrators need.
    pub rhs: Vec<Sym>,
    pub kinetic: Sym,
    pub potential: Sym,
    pub integral: Sym,
    pub bias_route: BiasRoute,
    /// The route not chosen, kept so tests can check the two agree.
    pub bias_other: Vec<Sym>,
}

impl Model {
    pub fn dof(&self) -> usize {
        self.coordinates.len()
    }
}

/// Per-point kinematics: ξ, ξ̇, J = ∂ξ/∂q, ∂ξ/∂t and κ = ξ̈ − J q̈.
struct Kinematics {
    mass: Sym,
    velocity: Vec<Sym>,
    jacobian: Vec<Vec<Sym>>, // [component][coordinate]
    partial_t: Vec<Sym>,
    kappa: Vec<Sym>,
    position: Vec<Sym>,
}

pub fn derive(lowered: Lowered) -> Model {
    let Lowered {
        mut ctx,
        coordinates,
        parameters,
        points,
        gravity,
        potential,
        dissipation,
        forces,
        generalized_forces,
    } = lowered;
    let q = ctx.coordinates();
    let qd = ctx.velocities();
    let qdd = ctx.accelerations();
    let t = ctx.time();
    let n = q.len();
    let zero_acc: Vec<(Sym, Sym)> = {
        let z = ctx.zero();
        qdd.iter().map(|&a| (a, z)).collect()
    };

    // sin/cos of sums of coordinates are expanded into products of sin/cos of the
    // coordinates themselves, so an n-link chain costs ~2n transcendental calls.
    let kin: Vec<Kinematics> = points
        .iter()
        .map(|p| {
            let position: Vec<Sym> = p.position.iter().map(|&x| ctx.expand_trig(x)).collect();
            let velocity: Vec<Sym> = position.iter().map(|&x| ctx.time_derivative(x)).collect();
            let jacobian = position
                .iter()
                .map(|&x| q.iter().map(|&qi| ctx.diff(x, qi)).collect())
                .collect();
            let partial_t = position.iter().map(|&x| ctx.diff(x, t)).collect();
            let kappa = velocity
                .iter()
                .map(|&v| {
                    let a = ctx.time_derivative(v);
                    ctx.substitute(a, &zero_acc)
                })
                .collect();
            Kinematics {
                mass: p.mass,
                velocity,
                jacobian,
                partial_t,
                kappa,
                position,
            }
        })
        .collect();
    let rheonomic = kin
        .iter()
        .any(|k| k.partial_t.iter().any(|&x| !ctx.is_zero(x)));

    let mass = mass_matrix(&mut ctx, &kin, n);
    let projection = bias_projection(&mut ctx, &kin, n);

    let kinetic = {
        let terms: Vec<Sym> = kin
            .iter()
            .map(|k| {
                let sq = dot(&mut ctx, &k.velocity, &k.velocity);
                ctx.mul(k.mass, sq)
            })
            .collect();
        let s = ctx.sum(&terms);
        let half = ctx.rational(1, 2);
        let e = ctx.mul(half, s);
        ctx.collect(e)
    };
    let christoffel: Vec<Sym> = (0..n)
        .map(|i| {
            let p = ctx.diff(kinetic, qd[i]);
            let dp = ctx.time_derivative(p);
            let dp = ctx.substitute(dp, &zero_acc);
            let dq = ctx.diff(kinetic, q[i]);
            let h = ctx.sub(dp, dq);
            ctx.collect(h)
        })
        .collect();

    let cost = |ctx: &Context, h: &[Sym]| Program::new(ctx, h).op_count().weighted();
    let (bias_route, bias, bias_other) = if cost(&ctx, &projection) <= cost(&ctx, &christoffel) {
        (BiasRoute::Projection, projection, christoffel)
    } else {
        (BiasRoute::Christoffel, christoffel, projection)
    };

    // Potential energy: the user's V plus the potential of uniform gravity, −Σ m g·ξ.
    let potential_total = {
        let mut terms = Vec::new();
        if let Some(v) = potential {
            terms.push(v);
        }
        if let Some(g) = &gravity {
            for k in &kin {
                let gx = dot(&mut ctx, g, &k.position);
                let mg = ctx.mul(k.mass, gx);
                terms.push(ctx.neg(mg));
            }
        }
        let v = ctx.sum(&terms);
        ctx.collect(v)
    };

    let generalized = generalized_forces_of(
        &mut ctx,
        &kin,
        &q,
        &qd,
        potential_total,
        dissipation,
        &forces,
        &generalized_forces,
    );
    let rhs: Vec<Sym> = (0..n)
        .map(|i| {
            let r = ctx.sub(generalized[i], bias[i]);
            ctx.collect(r)
        })
        .collect();

    let integral = if rheonomic {
        // Jacobi integral T2 − T0 + V (Suslov 32.56).
        let t2 = {
            let terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let jv: Vec<Sym> = k
                        .jacobian
                        .iter()
                        .map(|row| {
                            let ts: Vec<Sym> =
                                row.iter().zip(&qd).map(|(&j, &v)| ctx.mul(j, v)).collect();
                            ctx.sum(&ts)
                        })
                        .collect();
                    let sq = dot(&mut ctx, &jv, &jv);
                    ctx.mul(k.mass, sq)
                })
                .collect();
            let s = ctx.sum(&terms);
            let half = ctx.rational(1, 2);
            ctx.mul(half, s)
        };
        let t0 = {
            let terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let sq = dot(&mut ctx, &k.partial_t, &k.partial_t);
                    ctx.mul(k.mass, sq)
                })
                .collect();
            let s = ctx.sum(&terms);
            let half = ctx.rational(1, 2);
            ctx.mul(half, s)
        };
        let e = ctx.sub(t2, t0);
        let e = ctx.add(e, potential_total);
        ctx.collect(e)
    } else {
        let e = ctx.add(kinetic, potential_total);
        ctx.collect(e)
    };

    Model {
        ctx,
        coordinates,
        parameters,
        rheonomic,
        mass,
        bias,
        forces: generalized,
        rhs,
        kinetic,
        potential: potential_total,
        integral,
        bias_route,
        bias_other,
    }
}

fn dot(ctx: &mut Context, a: &[Sym], b: &[Sym]) -> Sym {
    let terms: Vec<Sym> = a.iter().zip(b).map(|(&x, &y)| ctx.mul(x, y)).collect();
    ctx.sum(&terms)
}

/// M_ij = Σ_ν m_ν (J_ν)_·iᵀ (J_ν)_·j, then factored so common factors are computed once.
fn mass_matrix(ctx: &mut Context, kin: &[Kinematics], n: usize) -> Vec<Vec<Sym>> {
    let mut m = vec![vec![ctx.zero(); n]; n];
    for i in 0..n {
        for j in i..n {
            let terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let ci: Vec<Sym> = k.jacobian.iter().map(|row| row[i]).collect();
                    let cj: Vec<Sym> = k.jacobian.iter().map(|row| row[j]).collect();
                    let d = dot(ctx, &ci, &cj);
                    ctx.mul(k.mass, d)
                })
                .collect();
            let s = ctx.sum(&terms);
            let s = ctx.collect(s);
            m[i][j] = s;
            m[j][i] = s;
        }
    }
    m
}

/// h_i = Σ_ν m_ν (J_ν)_·iᵀ κ_ν.
fn bias_projection(ctx: &mut Context, kin: &[Kinematics], n: usize) -> Vec<Sym> {
    (0..n)
        .map(|i| {
            let terms: Vec<Sym> = kin
                .iter()
                .map(|k| {
                    let ci: Vec<Sym> = k.jacobian.iter().map(|row| row[i]).collect();
                    let d = dot(ctx, &ci, &k.kappa);
                    ctx.mul(k.mass, d)
                })
                .collect();
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect()
}

/// Q = −∂V/∂q + Σ_ν J_νᵀ F_ν − ∂D/∂q̇ + explicit generalized forces (Suslov 32.28–32.31).
#[allow(clippy::too_many_arguments)]
fn generalized_forces_of(
    ctx: &mut Context,
    kin: &[Kinematics],
    q: &[Sym],
    qd: &[Sym],
    potential: Sym,
    dissipation: Option<Sym>,
    forces: &[(usize, Vec<Sym>)],
    generalized: &[(usize, Sym)],
) -> Vec<Sym> {
    (0..q.len())
        .map(|i| {
            let mut terms = Vec::new();
            let dv = ctx.diff(potential, q[i]);
            terms.push(ctx.neg(dv));
            for (p, f) in forces {
                let ci: Vec<Sym> = kin[*p].jacobian.iter().map(|row| row[i]).collect();
                terms.push(dot(ctx, &ci, f));
            }
            if let Some(d) = dissipation {
                let dd = ctx.diff(d, qd[i]);
                terms.push(ctx.neg(dd));
            }
            for (c, g) in generalized {
                if *c == i {
                    terms.push(*g);
                }
            }
            let s = ctx.sum(&terms);
            ctx.collect(s)
        })
        .collect()
}
