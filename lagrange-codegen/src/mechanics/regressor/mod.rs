//! The dynamics regressor (`emit(regressor)`): Y(q, q̇, q̈, t) with
//! M q̈ + h − Q_gravity = Y π, π the inertial parameters; the energy
//! regressor Y_E with T + V_gravity = Y_E π, and the momentum regressor
//! Y_p with p = ∂T/∂q̇ = Y_p π.
//!
//! The equations of motion are linear in each body's ten inertial
//! parameters, in Pinocchio's order (`Inertia::toDynamicParameters`)
//! [m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz], c the centre of mass
//! and I the inertia about the body's reference point, both in the body's
//! axes; a point mass has the one parameter m (its place is part of the
//! description, not of π). Q's other forces (the user's potential, springs,
//! dampers, forces, inputs) and the constraints' reactions are not linear
//! in π and stay outside Y, on both routes: Y is the unconstrained
//! equations' M q̈ + h less gravity's share of Q.
//!
//! Y is built by one of two routes. On a kinematic tree (the recursive
//! route) the parameters are made fresh symbols of the engine and handed to
//! the tree the description spans as its masses; Y is then built on the
//! tree by joint axes carried outward to meet each body's regressor
//! (`tree::regressor`), each column the derivative of τ by one parameter,
//! and the base parameters are found in closed form (`base_parameters`).
//! Elsewhere
//! (`generic`) column k is the Euler–Lagrange operator applied to the
//! parameter's share of the Lagrangian, T_k − V_k (`energy`), with the same
//! π and names, so that identification reads both alike.
//!
//! The tree's mass attachment takes point masses at fixed places and
//! rotational inertias; a body's parameters are handed to it as such, which
//! is linear in π: a mass m − Σ h_k at the reference point, a mass h_k at
//! the unit point e_k of each axis (giving the first moment h = m c, and
//! h_k (1 − e_k e_kᵀ) of rotational inertia that the tensor handed over
//! takes back), and the tensor I − Σ h_k (1 − e_k e_kᵀ).
//!
//! After the bodies' parameters come the joints' (`joints`): each joint's
//! damping, armature and friction, one column with one entry on its row.

mod energy;
mod generic;
mod joints;

use lagrange_symbolic::{Context, Expr as Sym};

use super::Route;
use super::base_parameters::{BaseForm, OwnColumn};
use super::expressions::Expressions;
use crate::lowered::{JointCoefficient, PointModel, Skeleton, SpinModel};
use crate::mat3::{Mat3, parallel_axis};
use energy::Column;

/// Y and what π is.
pub struct Regressor {
    /// Y row by row: `rows[i][k]` = ∂τ_i/∂π_k, free of π.
    pub rows: Vec<Vec<Sym>>,
    /// π's names in its order: `body.m`, `body.mx`, `body.my`, `body.mz`,
    /// `body.Ixx`, `body.Ixy`, `body.Iyy`, `body.Ixz`, `body.Iyz`,
    /// `body.Izz` per body, `point.m` per point mass, in the description's
    /// order once its items are put in dependency order; then `q.damping`,
    /// `q.friction`, `q.armature` per joint that has them.
    pub names: Vec<String>,
    /// π in the struct's parameters.
    pub parameters: Vec<Sym>,
    /// The energy regressor Y_E(q, q̇, t), one entry per parameter:
    /// T + V_gravity = Y_E π.
    pub energy: Vec<Sym>,
    /// The momentum regressor Y_p(q, q̇, t) row by row: `momentum[i][k]` =
    /// ∂T_k/∂q̇_i, so that p = ∂T/∂q̇ = Y_p π.
    pub momentum: Vec<Vec<Sym>>,
    /// How Y was built.
    pub route: RegressorRoute,
    /// The base parameters in closed form, for the texts (None off the
    /// tree route and on a tree with a free orientation).
    pub base: Option<BaseForm>,
}

/// How Y was built.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RegressorRoute {
    /// On the kinematic tree (`tree::regressor`: joint axes carried outward
    /// to each link's body regressor).
    Recursive,
    /// By the Euler–Lagrange operator on each parameter's share of L, and
    /// why: the reason there is no tree, or that the generic route was asked
    /// for.
    Lagrange(String),
}

impl Expressions for Regressor {
    fn expressions(&self, out: &mut Vec<Sym>) {
        out.extend(self.rows.iter().flatten());
        out.extend(&self.parameters);
        out.extend(&self.energy);
        out.extend(self.momentum.iter().flatten());
    }
}

/// The suffixes of a body's ten parameters, in π's order.
const BODY: [&str; 10] = [
    "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

/// What the description's masses are, as the tree detection reads them.
pub(super) struct MassModel<'a> {
    pub points: &'a [PointModel],
    pub spins: &'a [SpinModel],
    pub skeleton: &'a mut Skeleton,
    pub gravity: Option<&'a [Sym]>,
}

/// Y on the tree the description spans (`tree::regressor`), or by the
/// Euler–Lagrange operator where there is no tree or `route` asks for the
/// generic route; the joints' coefficients' columns after the bodies'.
pub(super) fn regressor(
    ctx: &mut Context,
    m: MassModel,
    joints: &[JointCoefficient],
    route: Route,
) -> Regressor {
    let mut p = Parametrised {
        inertias: m.spins.iter().map(|s| s.inertia).collect(),
        ..Parametrised::default()
    };
    for (i, point) in m.points.iter().enumerate() {
        let at = m.skeleton.masses[i].clone();
        let body = m.spins.iter().position(|s| s.name == point.name);
        match (body, &at) {
            (Some(b), Some((_, offset))) => p.body(ctx, &m, (point, b, offset)),
            _ => p.point(ctx, point, at, m.gravity),
        }
    }
    let joints = joints::columns(ctx, joints);
    let own: Vec<&OwnColumn> = joints.iter().map(|j| &j.column).collect();
    let tree_rows = match route {
        Route::Generic => Err("the generic route was asked for".to_string()),
        Route::Auto | Route::Recursive => on_tree(ctx, m, &p, &own).map_err(|why| why.to_string()),
    };
    let (rows, route, base) = match tree_rows {
        Ok((rows, base)) => (rows, RegressorRoute::Recursive, base),
        Err(why) => (
            generic::rows(ctx, &p.columns),
            RegressorRoute::Lagrange(why),
            None,
        ),
    };
    let momentum = energy::momentum(ctx, &p.columns);
    let mut regressor = Regressor {
        rows,
        names: p.names,
        parameters: p.parameters,
        energy: p.columns.iter().map(|c| c.energy).collect(),
        momentum,
        route,
        base,
    };
    regressor.append(ctx, &joints);
    regressor
}

impl Regressor {
    /// The joints' columns after the bodies': one entry on the joint's row
    /// of Y (and of Y_p), zeros on the others.
    fn append(&mut self, ctx: &mut Context, joints: &[joints::JointColumn]) {
        let zero = ctx.zero();
        for j in joints {
            let c = &j.column;
            for (i, row) in self.rows.iter_mut().enumerate() {
                row.push(if i == c.row { c.entry } else { zero });
            }
            for (i, row) in self.momentum.iter_mut().enumerate() {
                row.push(if i == c.row { j.momentum } else { zero });
            }
            self.names.push(c.name.clone());
            self.parameters.push(j.value);
            self.energy.push(j.energy);
        }
    }
}

/// Y's rows on the tree and the base parameters in closed form, or why
/// there is no tree.
fn on_tree(
    ctx: &mut Context,
    m: MassModel,
    p: &Parametrised,
    joints: &[&OwnColumn],
) -> Result<(Vec<Vec<Sym>>, Option<BaseForm>), crate::tree::NotATree> {
    let spins: Vec<SpinModel> = (m.spins.iter().zip(&p.inertias))
        .map(|(s, &inertia)| SpinModel {
            name: s.name.clone(),
            inertia,
            omega: s.omega,
        })
        .collect();
    // The detection reads where the masses sit off the skeleton: handed the
    // parametrised ones for this reading alone.
    let kept = std::mem::replace(&mut m.skeleton.masses, p.placed.clone());
    let masses = (&p.points[..], &spins[..], &*m.skeleton);
    let tree = super::recursive::detect(ctx, Route::Recursive, masses, m.gravity);
    m.skeleton.masses = kept;
    let tree = tree?;
    let rows = crate::tree::regressor(ctx, &tree, &p.symbols);
    let symbols: Vec<Sym> = (p.symbols.iter().copied())
        .chain(joints.iter().map(|j| j.symbol))
        .collect();
    let names: Vec<String> = (p.names.iter().cloned())
        .chain(joints.iter().map(|j| j.name.clone()))
        .collect();
    let all = (&symbols[..], &names[..]);
    let base = super::base_parameters::closed_form(ctx, &tree, all, joints);
    Ok((rows, base))
}

/// The description's masses with π's symbols in place of their values, and
/// what is read off them on the way.
#[derive(Default)]
struct Parametrised {
    /// π's symbols, names and values in the struct's parameters.
    symbols: Vec<Sym>,
    names: Vec<String>,
    parameters: Vec<Sym>,
    /// Each parameter's share of the energies.
    columns: Vec<Column>,
    /// The point masses the tree's attachment takes, and where they sit.
    points: Vec<PointModel>,
    placed: Vec<PlacedMass>,
    /// The bodies' rotational inertias, parallel to the spins.
    inertias: Vec<Mat3>,
}

/// Where a point mass sits: its body and its offset in the body's axes.
type PlacedMass = Option<(usize, Vec<Sym>)>;

impl Parametrised {
    /// A point mass: its one parameter m.
    fn point(&mut self, ctx: &mut Context, point: &PointModel, at: PlacedMass, g: Option<&[Sym]>) {
        let mass = ctx.free_symbol(&format!("__pi_{}_m", point.name));
        self.symbols.push(mass);
        self.names.push(format!("{}.m", point.name));
        self.parameters.push(point.mass);
        self.columns.push(energy::point(ctx, &point.position, g));
        self.points.push(moved(point, mass));
        self.placed.push(at);
    }

    /// Body `b`, whose centre is `point` at `offset` in its axes: its ten
    /// parameters, handed to the attachment as four point masses and a
    /// tensor.
    fn body(
        &mut self,
        ctx: &mut Context,
        m: &MassModel,
        (point, b, offset): (&PointModel, usize, &[Sym]),
    ) {
        let pi: [Sym; 10] = BODY.map(|s| ctx.free_symbol(&format!("__pi_{}_{s}", point.name)));
        self.symbols.extend(pi);
        self.names
            .extend(BODY.map(|s| format!("{}.{s}", point.name)));
        let inertia = &m.spins[b].inertia;
        self.parameters
            .extend(body_parameters(ctx, point.mass, offset, inertia));
        let frame = &m.skeleton.bodies[b];
        let placed_at = (&frame.reference[..], &frame.matrix);
        let columns = energy::body(ctx, placed_at, m.spins[b].omega, m.gravity);
        self.columns.extend(columns);
        let [mass, hx, hy, hz, ixx, ixy, iyy, ixz, iyz, izz] = pi;
        let h = [hx, hy, hz];
        let all = ctx.sum(&h);
        let at_origin = ctx.sub(mass, all);
        let zero = ctx.zero();
        let one = ctx.one();
        self.points.push(moved(point, at_origin));
        self.placed.push(Some((b, vec![zero; 3])));
        for (k, &hk) in h.iter().enumerate() {
            let mut unit = vec![zero; 3];
            unit[k] = one;
            self.points.push(moved(point, hk));
            self.placed.push(Some((b, unit)));
        }
        // I − Σ h_k (1 − e_k e_kᵀ): each diagonal entry less the other two
        // axes' first moments.
        let less = |ctx: &mut Context, d: Sym, a: Sym, b: Sym| {
            let both = ctx.add(a, b);
            ctx.sub(d, both)
        };
        let xx = less(ctx, ixx, hy, hz);
        let yy = less(ctx, iyy, hx, hz);
        let zz = less(ctx, izz, hx, hy);
        self.inertias[b] = [[xx, ixy, ixz], [ixy, yy, iyz], [ixz, iyz, zz]];
    }
}

/// A point mass with its mass replaced.
fn moved(point: &PointModel, mass: Sym) -> PointModel {
    PointModel {
        name: point.name.clone(),
        mass,
        position: point.position.clone(),
    }
}

/// A body's π from its mass, centre `c` in body axes and inertia about the
/// centre: [m, m c, I + m(|c|² 1 − c cᵀ)] in π's order.
fn body_parameters(ctx: &mut Context, mass: Sym, c: &[Sym], about_centre: &Mat3) -> [Sym; 10] {
    let c = [c[0], c[1], c[2]];
    let first = c.map(|x| ctx.mul(mass, x));
    let shift = parallel_axis(ctx, mass, c);
    let i = [0, 1, 2].map(|r| [0, 1, 2].map(|k| ctx.add(about_centre[r][k], shift[r][k])));
    [
        mass, first[0], first[1], first[2], i[0][0], i[0][1], i[1][1], i[0][2], i[1][2], i[2][2],
    ]
}
