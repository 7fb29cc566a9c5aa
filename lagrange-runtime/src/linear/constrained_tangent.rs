//! Linearisation of a constrained system whose configuration holds
//! orientations, in the tangent space, in axes fixed in space.
//!
//! A state near the operating point (q*, v*) is q = q* ⊕ δ (an ordinary
//! coordinate moved by its δ, an orientation turned by the rotation vector δθ,
//! q* ⊗ exp(δθ)) with v = v* + δv_b, v holding each orientation's angular
//! velocity in body axes. The multiplier form's accelerations a(q, v) (the
//! saddle-point solve of [`ConstrainedDynamics`]) are differentiated by
//! central differences on the group, column by column:
//!
//! ```text
//! X_q = ∂a/∂δ,   X_v = ∂a/∂v,   X_u = ∂a/∂u,   D = ∂(G v* + g)/∂δ
//! ```
//!
//! (G's columns are the tangent directions, so Φ_δ is G's holonomic rows),
//! each step the cube root of the scalar's epsilon times the entry's scale (1
//! for δ, max(1, |v_j|), max(1, |u_k|)): a relative error about 1e-10. An
//! entry below the difference's round-off is set to zero (see `column`).
//!
//! **Axes.** The perturbation of an orientation is read in the axes of its body
//! at the operating point, held fixed in space while the body turns on (not
//! the turning body axes of [`Linearizer::tangent`]): δθ as above at t0, and
//! δω = R*ᵀ(ω − ω*) with ω, ω* in space axes, so that
//!
//! ```text
//! δθ̇ = δω + ω* × δθ,     δv_b = δω + ω* × δθ (the body-axis change),
//! δω̇ = δa_ω + δθ × a*_ω
//! ```
//!
//! A body spinning steadily about an axis of symmetry (a disk rolling
//! upright, a sphere rolling straight, a sleeping top) is then an
//! equilibrium of a constant A, whose eigenvalues give its stability; in body
//! axes the perturbations would be carried round by the spin and A would
//! change with it. With W the block-diagonal \[ω*\]× (zero on the ordinary
//! coordinates) the full tangent model is
//!
//! ```text
//! δ̇ = W δ + δv,   δv̇ = (X_q + X_v W − [a*_ω]×) δ + X_v δv + X_u δu,
//! Φ_δ δ = 0,      G δv + (D + G W) δ = 0
//! ```
//!
//! and the independent coordinates and speeds, the embeddings
//! δ = C_q δ_i, δv = C_v δv_s + C_vq δ_i and the restriction follow
//! [`Linearizer::constrained`], with the kinematic rows W C_q + C_vq.

use super::Linear;
use super::dense::{dm, dv, finite};
use super::difference::{column, difference, unit};
use super::partition::{Partition, embeddings, holonomic};
use super::settings::{Linearizer, OperatingPoint};
use super::tangent::{Held, states};
use crate::error::{Error, to_vec, unit_quaternions};
use crate::mechanics::constraint::ConstrainedDynamics;
use crate::numeric::Real;
use crate::numeric::orientation;
use crate::system::{Constrained, Driven, Lagrangian};
use nalgebra::{DMatrix, DVector, SVector};

/// A constrained form as its tangent linearisation reads it: its
/// accelerations a(q, v, u), its rows (G, g) at q, Φ at the point (the
/// first `holonomic` rows), and the rows' names.
pub(super) struct GroupForm<'n, A, R> {
    pub accel: A,
    pub rows: R,
    pub phi: DVector<f64>,
    pub holonomic: usize,
    pub row_names: &'n [&'static str],
}

/// The names of a tangent model: its 2N states (directions, then rates),
/// the names the partition reads for coordinates and speeds, its inputs.
pub(super) struct GroupStates<'n> {
    pub names: &'n [String],
    pub partition: [&'n [&'n str]; 2],
    pub inputs: &'n [&'static str],
}

/// The constrained dynamics' derivatives at the operating point: X_q, X_v,
/// X_u and D as the module describes, and G.
struct Slopes {
    xq: DMatrix<f64>,
    xv: DMatrix<f64>,
    xu: DMatrix<f64>,
    dvel: DMatrix<f64>,
    g: DMatrix<f64>,
}

impl Linearizer {
    /// Linearises a constrained system (multiplier form) whose configuration
    /// holds orientations (unit quaternions, `orientation(..)` in a
    /// description; q has Q entries, v has N) about a consistent point
    /// ([`OperatingPoint::on_group`], inputs with
    /// [`input`](OperatingPoint::input)), in independent coordinates and
    /// speeds of the tangent space.
    ///
    /// A consistent point comes from
    /// [`project_consistent`](crate::project_consistent) (generic over Q).
    ///
    /// This is the call for a constrained system with orientations (the rolling
    /// disk or sphere with a quaternion); [`constrained`](Self::constrained)
    /// is the one for a constrained system in coordinates alone (Q = N),
    /// from the symbolic derivatives. This one accepts that case too, and then
    /// reads the same model by central differences.
    ///
    /// **States.** The coordinates are the tangent directions, named as
    /// [`tangent`](Self::tangent) names them: an ordinary coordinate's own
    /// name, an orientation's rotation vector `<name>.θx`, `<name>.θy`,
    /// `<name>.θz`; the speeds are the velocities' changes, named as
    /// [`tangent`](Self::tangent) names them (`x'`, `<name>.wx`, …). Name independent
    /// ones with [`coordinates`](Self::coordinates) (tangent directions) and
    /// [`speeds`](Self::speeds) (velocities); the rest are chosen as
    /// [`Linearizer`] describes.
    ///
    /// **Velocity frame.** An orientation's δθ and δω are components along its
    /// body axes at the operating point, held fixed in space while the body
    /// turns on: δω = R*ᵀ(ω − ω*), ω in space axes (the body-axis change is
    /// δω + ω* × δθ). A body spinning steadily about an axis of symmetry is
    /// then an equilibrium of the linear model (a constant A), as in an
    /// Euler-angle chart whose spin angle is cyclic; the module source has
    /// the equations.
    ///
    /// **Derivatives.** Central differences on the group (q ⊕ εδ) of the
    /// multiplier form's accelerations, of G q̇ + g and of the inputs'
    /// effect, each step ε = ∛(machine epsilon) · max(1, |x|): a relative
    /// error about 1e-10. No second-order form.
    ///
    /// # Errors
    /// [`Error::NonUnitQuaternion`] for a quaternion further than the
    /// tolerance from unit norm; [`LinearError::InconsistentOperatingPoint`](crate::LinearError::InconsistentOperatingPoint)
    /// naming the residuals and the worst constraint;
    /// [`LinearError::InvalidPartition`](crate::LinearError::InvalidPartition),
    /// [`LinearError::SingularPartition`](crate::LinearError::SingularPartition)
    /// for a bad choice of independent coordinates or speeds;
    /// [`Error::RedundantConstraints`]; [`Error::SingularMassMatrix`];
    /// [`Error::NonFiniteState`] (also at a perturbed state). Before any of
    /// these: [`Error::Settings`], [`Error::NonPhysicalParameter`] and
    /// [`Error::NonFiniteInput`], as [`constrained`](Self::constrained).
    pub fn constrained_tangent<
        S,
        T,
        const N: usize,
        const K: usize,
        const P: usize,
        const U: usize,
        const Q: usize,
    >(
        &self,
        sys: &S,
        op: &OperatingPoint<T, N, U, Q>,
    ) -> Result<Linear, Error>
    where
        S: Constrained<T, N, K, Q> + Driven<T, N, P, Q>,
        T: Real,
    {
        let (u, q, v, t) = self.point_on_group(sys, op)?;
        let accel = |q: &SVector<T, Q>, v: &SVector<T, N>, u: &SVector<T, P>| {
            let held = Held { system: sys, u: *u };
            let solution = ConstrainedDynamics::<_, _, K>::new(sys)
                .with_singular_tolerance(T::lit(self.tolerances.singular))
                .with_redundant_tolerance(T::lit(self.tolerances.redundant))
                .with_forcing(held)
                .solve(t, q, v)?;
            Ok(solution.accelerations)
        };
        let rows = |q: &SVector<T, Q>| {
            let (g, g0) = sys.constraint_jacobian(q, t);
            (dm(&g), dv(&g0))
        };
        let h = holonomic::<S, T, N, K, Q>();
        let phi = dv(&sys.constraint_positions(&q, t)).rows(0, h).into_owned();
        let names = states::<S, T, N, Q>();
        let directions: Vec<&str> = names[..N].iter().map(String::as_str).collect();
        let form = GroupForm {
            accel,
            rows,
            phi,
            holonomic: h,
            row_names: &S::CONSTRAINTS,
        };
        let states = GroupStates {
            names: &names,
            partition: [&directions, &S::VELOCITIES],
            inputs: &S::INPUTS,
        };
        self.group_model::<S, T, _, _, N, P, Q>(form, (&q, &v, &u, t), states)
    }

    /// A constrained form's linear model on the group at (q, v, u, t), the
    /// part every tangent linearisation of constraints shares: the point
    /// checked against the rows, the derivatives by central differences on
    /// the group, the independent states chosen, the model in axes fixed at
    /// the point (no turn without orientations), named by `states`.
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] (also at a perturbed state);
    /// [`LinearError::InconsistentOperatingPoint`](crate::LinearError::InconsistentOperatingPoint)
    /// naming the worst row; the partition's errors;
    /// [`Error::RedundantConstraints`] naming the dependent rows; whatever
    /// `accel` reports.
    pub(super) fn group_model<S, T, A, R, const N: usize, const P: usize, const Q: usize>(
        &self,
        form: GroupForm<'_, A, R>,
        (q, v, u, t): (&SVector<T, Q>, &SVector<T, N>, &SVector<T, P>, T),
        states: GroupStates<'_>,
    ) -> Result<Linear, Error>
    where
        S: Lagrangian<T, N, Q>,
        T: Real,
        A: Fn(&SVector<T, Q>, &SVector<T, N>, &SVector<T, P>) -> Result<SVector<T, N>, Error>,
        R: Fn(&SVector<T, Q>) -> (DMatrix<f64>, DVector<f64>),
    {
        let GroupForm {
            accel,
            rows,
            phi,
            holonomic,
            row_names,
        } = form;
        let (g, g0) = rows(q);
        let vel = g * dv(v) + g0;
        if !(phi.iter().chain(vel.iter()).all(|x| x.is_finite())) {
            return Err(Error::non_finite(t, q, v));
        }
        self.within_tolerance([&phi, &vel], (t, q, &S::COORDINATES), row_names)?;
        let a0 = accel(q, v, u)?;
        let step = |d: &SVector<T, N>| orientation::plus(S::ORIENTATIONS, q, d);
        let mut slopes = differences(accel, rows, (q, v, u), step)?;
        let part = self.split(&slopes.g, holonomic, states.partition, |ratio, r| {
            Error::RedundantConstraints {
                t: t.to_f64(),
                q: to_vec(q),
                coordinates: S::COORDINATES.to_vec(),
                ratio,
                dependent: r.iter().map(|&i| row_names[i]).collect(),
            }
        })?;
        let kinematics = fixed_axes::<S, T, N, Q>(&mut slopes, v, &a0);
        let (a, b) = assemble(&part, &slopes, &kinematics, holonomic);
        if !(finite(&a) && finite(&b)) {
            return Err(Error::non_finite(t, q, v));
        }
        Ok(self.model(&part, (a, b), states.names, states.inputs))
    }

    /// The linear model in the partition's independent states, named as
    /// `names` (the N tangent directions, then the N velocities).
    pub(super) fn model(
        &self,
        part: &Partition,
        (a, b): (DMatrix<f64>, DMatrix<f64>),
        names: &[String],
        inputs: &[&str],
    ) -> Linear {
        let ni = part.ci.len();
        let n = names.len() / 2;
        let mut states: Vec<String> = part.ci.iter().map(|&i| names[i].clone()).collect();
        states.extend(part.si.iter().map(|&i| names[n + i].clone()));
        let named = |names: &Option<Vec<String>>| names.as_ref().map_or(0, Vec::len);
        let mut completed = states[named(&self.coordinates)..ni].to_vec();
        completed.extend(states[ni + named(&self.speeds)..].iter().cloned());
        let inputs = inputs.iter().map(|s| s.to_string()).collect();
        Linear::from_parts(a, b, states, inputs, ni, None).with_completed(completed)
    }

    /// The inputs at the point, and the point itself with unit quaternions.
    ///
    /// # Errors
    /// Those of `inputs_at`; [`Error::NonFiniteState`];
    /// [`Error::NonUnitQuaternion`].
    #[allow(clippy::type_complexity)]
    pub(super) fn point_on_group<
        S,
        T,
        const N: usize,
        const P: usize,
        const U: usize,
        const Q: usize,
    >(
        &self,
        sys: &S,
        op: &OperatingPoint<T, N, U, Q>,
    ) -> Result<(SVector<T, P>, SVector<T, Q>, SVector<T, N>, T), Error>
    where
        S: Driven<T, N, P, Q>,
        T: Real,
    {
        let u = self.inputs_at(sys, op)?;
        let v = op.v;
        let t = op.t;
        if !(t.is_finite() && finite(&dm(&op.q)) && finite(&dm(&v))) {
            return Err(Error::non_finite(t, &op.q, &v));
        }
        let q = unit_quaternions(S::ORIENTATIONS, &S::COORDINATES, op.q)?;
        Ok((u, q, v, t))
    }
}

/// X_q, X_v, X_u and D by central differences at (q, v, u, t), body axes;
/// `accel` is the form's a(q, v, u), `rows` the constraint rows (G, g) at q.
fn differences<T, A, R, const N: usize, const P: usize, const Q: usize>(
    accel: A,
    rows: R,
    (q, v, u): (&SVector<T, Q>, &SVector<T, N>, &SVector<T, P>),
    advance: impl Fn(&SVector<T, N>) -> SVector<T, Q>,
) -> Result<Slopes, Error>
where
    T: Real,
    A: Fn(&SVector<T, Q>, &SVector<T, N>, &SVector<T, P>) -> Result<SVector<T, N>, Error>,
    R: Fn(&SVector<T, Q>) -> (DMatrix<f64>, DVector<f64>),
{
    let velocity = |d: SVector<T, N>| {
        let (g, g0) = rows(&advance(&d));
        (g * dv(v) + g0).iter().copied().collect::<Vec<f64>>()
    };
    let along = |d: SVector<T, N>| accel(&advance(&d), v, u);
    let g = rows(q).0;
    let k = g.nrows();
    let mut s = Slopes {
        xq: DMatrix::zeros(N, N),
        xv: DMatrix::zeros(N, N),
        xu: DMatrix::zeros(N, P),
        dvel: DMatrix::zeros(k, N),
        g,
    };
    for j in 0..N {
        let (h, e) = unit::<T, N>(j, 1.0);
        set(&mut s.xq, j, column(along(e)?, along(-e)?, h));
        let plus = velocity(e);
        let minus = velocity(-e);
        set(&mut s.dvel, j, difference::<T>(&plus, &minus, h));
        let (h, e) = unit::<T, N>(j, v[j].to_f64());
        let rates = column(accel(q, &(v + e), u)?, accel(q, &(v - e), u)?, h);
        set(&mut s.xv, j, rates);
    }
    for k in 0..P {
        let (h, e) = unit::<T, P>(k, u[k].to_f64());
        set(
            &mut s.xu,
            k,
            column(accel(q, v, &(u + e))?, accel(q, v, &(u - e))?, h),
        );
    }
    Ok(s)
}

fn set(m: &mut DMatrix<f64>, j: usize, column: Vec<f64>) {
    for (i, x) in column.into_iter().enumerate() {
        m[(i, j)] = x;
    }
}

/// Re-reads the body-axis derivatives in fixed axes (the module's equations):
/// X_q + X_v W − \[a*_ω\]× and D + G W; returns W, the kinematic rows' δ term.
fn fixed_axes<S, T, const N: usize, const Q: usize>(
    s: &mut Slopes,
    v: &SVector<T, N>,
    a: &SVector<T, N>,
) -> DMatrix<f64>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    let w = spins::<S, T, N, Q>(v);
    s.xq = &s.xq + &s.xv * &w - spins::<S, T, N, Q>(a);
    s.dvel = &s.dvel + &s.g * &w;
    w
}

/// The block-diagonal \[x_o\]× of each orientation's three entries of x (zero
/// on the ordinary coordinates): \[x\]× δ = x × δ.
fn spins<S, T, const N: usize, const Q: usize>(x: &SVector<T, N>) -> DMatrix<f64>
where
    S: Lagrangian<T, N, Q>,
    T: Real,
{
    let mut m = DMatrix::zeros(N, N);
    for o in S::ORIENTATIONS {
        let [a, b, c] = [0, 1, 2].map(|k| x[o.v + k].to_f64());
        let block = [[0.0, -c, b], [c, 0.0, -a], [-b, a, 0.0]];
        for (i, row) in block.iter().enumerate() {
            for (j, &e) in row.iter().enumerate() {
                m[(o.v + i, o.v + j)] = e;
            }
        }
    }
    m
}

/// A and B in (δ_i, δv_s) from the full tangent model (the module's
/// equations) and the embeddings of the partition.
fn assemble(
    part: &Partition,
    s: &Slopes,
    kinematics: &DMatrix<f64>,
    holonomic: usize,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let (cq, cv, cvq) = embeddings(part, &s.g, &s.dvel, holonomic);
    let ni = part.ci.len();
    let ns = part.si.len();
    let top = kinematics * &cq + &cvq;
    let a21 = (&s.xq * &cq + &s.xv * &cvq).select_rows(part.si.iter());
    let a22 = (&s.xv * &cv).select_rows(part.si.iter());
    let mut a = DMatrix::zeros(ni + ns, ni + ns);
    a.view_mut((0, 0), (ni, ni))
        .copy_from(&top.select_rows(part.ci.iter()));
    a.view_mut((0, ni), (ni, ns))
        .copy_from(&cv.select_rows(part.ci.iter()));
    a.view_mut((ni, 0), (ns, ni)).copy_from(&a21);
    a.view_mut((ni, ni), (ns, ns)).copy_from(&a22);
    let p = s.xu.ncols();
    let mut b = DMatrix::zeros(ni + ns, p);
    b.view_mut((ni, 0), (ns, p))
        .copy_from(&s.xu.select_rows(part.si.iter()));
    (a, b)
}
