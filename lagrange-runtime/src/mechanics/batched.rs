//! Many states per call (`emit(batched)`): the emitted q̈ and derivative
//! programs over [`F64x4`], four states in the four lanes of one value, for
//! ensembles, sampling-based planners and rollouts; and their checked
//! reading over a slice of states of any length (the last call's spare lanes
//! padded), each state's result checked as the scalar reading checks it.

use nalgebra::{SMatrix, SVector};

use super::derivatives::{AccelerationDerivatives, Differentiable};
use super::dynamics::{Dynamics, all_finite, on_sphere, refuse_constrained};
use super::forcing::NoForcing;
use crate::error::{Error, SettingsError, check_finite_inputs, check_tolerance};
use crate::numeric::lanes::F64x4;
use crate::system::Lagrangian;

/// A system whose derive emitted q̈ over four states at once
/// (`emit(batched)` beside `articulated` or `jacobians`, for a system
/// without constraints): the program the scalar q̈ runs (the route
/// `articulated` chose, [`Lagrangian::FORWARD_ROUTE`], else the
/// factorisation of `jacobians`' program), with [`F64x4`] for `f64`. Read it through
/// [`batched_accelerations`], which checks each state and its result.
#[diagnostic::on_unimplemented(
    message = "`{Self}` does not emit its q̈ over many states at once",
    label = "needs `Batched`",
    note = "add `batched` to the description's `emit(...)`, beside `articulated` or `jacobians`"
)]
pub trait Batched<const N: usize, const Q: usize = N>: Lagrangian<f64, N, Q> {
    /// q̈ at four states (lane k of every argument is state k), unchecked,
    /// with each lane's ratio of M's smallest pivot to its largest (as
    /// [`Lagrangian::forward_dynamics`] gives it). Each lane equals the
    /// scalar program's result at that lane's state, bit for bit.
    fn acceleration_lanes_unchecked(
        &self,
        q: &[F64x4; Q],
        v: &[F64x4; N],
        tau: &[F64x4; N],
        t: F64x4,
    ) -> ([F64x4; N], F64x4);
}

/// q̈ and its derivatives at four states, lane k state k: what
/// [`AccelerationDerivatives`] holds, with matrices as arrays of columns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneDerivatives<const N: usize> {
    /// q̈.
    pub acceleration: [F64x4; N],
    /// ∂q̈/∂δ, `dq[j][i]` = ∂q̈ᵢ/∂δⱼ.
    pub dq: [[F64x4; N]; N],
    /// ∂q̈/∂q̇, by columns.
    pub dv: [[F64x4; N]; N],
    /// ∂q̈/∂τ = M⁻¹, by columns.
    pub dtau: [[F64x4; N]; N],
}

impl<const N: usize> LaneDerivatives<N> {
    /// The derivatives in lane `k` (panics for `k ≥ 4`).
    pub fn lane(&self, k: usize) -> AccelerationDerivatives<f64, N> {
        // Column by column into nalgebra's column-major storage.
        let matrix = |m: &[[F64x4; N]; N]| {
            let mut columns = [[0.0; N]; N];
            for (column, lanes) in columns.iter_mut().zip(m) {
                for (x, lanes) in column.iter_mut().zip(lanes) {
                    *x = lanes.lane_in_place(k);
                }
            }
            SMatrix::from_data(nalgebra::ArrayStorage(columns))
        };
        AccelerationDerivatives {
            acceleration: unpack(&self.acceleration, k),
            dq: matrix(&self.dq),
            dv: matrix(&self.dv),
            dtau: matrix(&self.dtau),
        }
    }
}

/// A system whose derive emitted q̈ and its derivatives over four states at
/// once (`emit(batched, jacobians)` on a system without constraints): the
/// program of [`Differentiable`] with [`F64x4`] for `f64`. Read it through
/// [`batched_acceleration_derivatives`].
#[diagnostic::on_unimplemented(
    message = "`{Self}` does not emit q̈'s derivatives over many states at once",
    label = "needs `BatchedDifferentiable`",
    note = "add `batched` and `jacobians` to the description's `emit(...)`"
)]
pub trait BatchedDifferentiable<const N: usize, const Q: usize = N>:
    Differentiable<f64, N, Q>
{
    /// [`Differentiable::acceleration_derivatives_unchecked`] at four states
    /// (lane k of every argument is state k), with each lane's pivot ratio;
    /// each lane equals the scalar program's result, bit for bit.
    fn acceleration_derivatives_lanes_unchecked(
        &self,
        q: &[F64x4; Q],
        v: &[F64x4; N],
        tau: &[F64x4; N],
        t: F64x4,
    ) -> (LaneDerivatives<N>, F64x4);
}

/// One state of a batch, checked: q with its quaternions on the unit sphere,
/// or the error the scalar reading reports for it.
type Checked<const N: usize, const Q: usize> = Result<SVector<f64, Q>, Error>;

/// The states of a batch: q, v and τ, one of each per state.
type States<'a, const N: usize, const Q: usize> = (
    &'a [SVector<f64, Q>],
    &'a [SVector<f64, N>],
    &'a [SVector<f64, N>],
);

impl<S> Dynamics<'_, S, f64, NoForcing> {
    /// q̈ = M⁻¹(Q − h + τ) at each state (`q[i]`, `v[i]`, `tau[i]`) at time
    /// `t`, four states per call of the system's batched program; each
    /// result checked as [`Dynamics::acceleration`] checks it, so a state's
    /// error leaves the others' results alone.
    ///
    /// # Errors
    /// [`SettingsError::Lengths`] (in [`Error::Settings`]) if `q`, `v` and
    /// `tau` differ in length; then per state, in the inner `Result`s.
    pub fn batched_accelerations<const N: usize, const Q: usize>(
        &self,
        t: f64,
        q: &[SVector<f64, Q>],
        v: &[SVector<f64, N>],
        tau: &[SVector<f64, N>],
    ) -> Result<Vec<Result<SVector<f64, N>, Error>>, Error>
    where
        S: Batched<N, Q>,
    {
        let program =
            |q: &_, v: &_, tau: &_, t| self.system().acceleration_lanes_unchecked(q, v, tau, t);
        self.in_lanes(t, (q, v, tau), program, |(a, ratio), k, (q, v)| {
            self.pivot_check(t, q, ratio.lane(k))?;
            let a = unpack(a, k);
            finite(a.as_slice(), t, q, v).map(|()| a)
        })
    }

    /// q̈ and its derivatives at each state, four per call of the system's
    /// batched program; each checked as [`Dynamics::emitted_derivatives`]
    /// checks it.
    ///
    /// # Errors
    /// [`SettingsError::Lengths`] (in [`Error::Settings`]) if `q`, `v` and
    /// `tau` differ in length; then per state, in the inner `Result`s.
    pub fn batched_derivatives<const N: usize, const Q: usize>(
        &self,
        t: f64,
        q: &[SVector<f64, Q>],
        v: &[SVector<f64, N>],
        tau: &[SVector<f64, N>],
    ) -> Result<Vec<Result<AccelerationDerivatives<f64, N>, Error>>, Error>
    where
        S: BatchedDifferentiable<N, Q>,
    {
        let program = |q: &_, v: &_, tau: &_, t| {
            (self.system()).acceleration_derivatives_lanes_unchecked(q, v, tau, t)
        };
        self.in_lanes(t, (q, v, tau), program, |(d, ratio), k, (q, v)| {
            self.pivot_check(t, q, ratio.lane(k))?;
            let d = d.lane(k);
            let parts = [
                d.acceleration.as_slice(),
                d.dq.as_slice(),
                d.dv.as_slice(),
                d.dtau.as_slice(),
            ];
            let all = parts.iter().all(|p| all_finite(p));
            match all {
                true => Ok(d),
                false => Err(Error::non_finite(t, q, v)),
            }
        })
    }

    /// Runs `program` on the states four at a time and `read`s each
    /// state's result from its lane; the states' checks come first, and a
    /// state that fails them is reported without reading its lane.
    fn in_lanes<const N: usize, const Q: usize, P, R>(
        &self,
        t: f64,
        (q, v, tau): States<'_, N, Q>,
        program: impl Fn(&[F64x4; Q], &[F64x4; N], &[F64x4; N], F64x4) -> P,
        read: impl Fn(&P, usize, (&SVector<f64, Q>, &SVector<f64, N>)) -> Result<R, Error>,
    ) -> Result<Vec<Result<R, Error>>, Error>
    where
        S: Lagrangian<f64, N, Q>,
    {
        if !(q.len() == v.len() && q.len() == tau.len()) {
            let what = format!(
                "{} q, {} v and {} τ given; one of each per state",
                q.len(),
                v.len(),
                tau.len()
            );
            let owner = "batched q̈";
            return Err(SettingsError::Lengths { owner, what }.into());
        }
        // The checks that do not depend on the state, once (see `group`).
        refuse_constrained::<S, f64, N, Q>();
        let tolerance = self.singular_tolerance();
        let settled =
            t.is_finite() && check_tolerance("Dynamics", "singular tolerance", tolerance).is_ok();
        let mut out = Vec::with_capacity(q.len());
        for start in (0..q.len()).step_by(F64x4::LANES) {
            let end = (start + F64x4::LANES).min(q.len());
            let states = (&q[start..end], &v[start..end], &tau[start..end]);
            self.group(t, states, settled, (&program, &read), &mut out);
        }
        Ok(out)
    }

    /// One call of `program` on at most four states, each state's result
    /// read into `out`. Where the settings passed (`settled`) and every
    /// entry of the group is finite, a state needs nothing more than the
    /// scalar reading's quaternions put on the unit sphere, and the checks
    /// cost a fraction of the program; otherwise each state is checked as
    /// the scalar reading checks it (a per-state `Result` built and moved,
    /// which had cost as much as the UR5's program), its error its own.
    #[allow(clippy::type_complexity)]
    fn group<const N: usize, const Q: usize, P, R>(
        &self,
        t: f64,
        (q, v, tau): States<'_, N, Q>,
        settled: bool,
        (program, read): (
            &impl Fn(&[F64x4; Q], &[F64x4; N], &[F64x4; N], F64x4) -> P,
            &impl Fn(&P, usize, (&SVector<f64, Q>, &SVector<f64, N>)) -> Result<R, Error>,
        ),
        out: &mut Vec<Result<R, Error>>,
    ) where
        S: Lagrangian<f64, N, Q>,
    {
        // Spare lanes repeat the last state; a failed state's lane runs on
        // what it was given, and lanes do not mix.
        let at = |k: usize| k.min(q.len() - 1);
        let run = |units: [SVector<f64, Q>; 4]| {
            let (v, tau) = (pack(|k| &v[at(k)]), pack(|k| &tau[at(k)]));
            program(&pack(|k| &units[k]), &v, &tau, F64x4::splat(t))
        };
        let finite = |(q, (v, tau)): (&SVector<f64, Q>, (&SVector<f64, N>, _))| {
            let parts = [q.as_slice(), v.as_slice(), SVector::as_slice(tau)];
            parts.iter().all(|part| all_finite(part))
        };
        if settled && q.iter().zip(v.iter().zip(tau)).all(finite) {
            let results = run(core::array::from_fn(|k| {
                on_sphere::<S, f64, N, Q>(&q[at(k)])
            }));
            out.extend((0..q.len()).map(|k| read(&results, k, (&q[k], &v[k]))));
            return;
        }
        let checked: [Option<Checked<N, Q>>; 4] = core::array::from_fn(|k| {
            (k < q.len()).then(|| self.check_state(t, &q[k], &v[k], &tau[k]))
        });
        let results = run(core::array::from_fn(|k| match &checked[at(k)] {
            Some(Ok(unit)) => *unit,
            _ => q[at(k)],
        }));
        for (k, state) in checked.into_iter().flatten().enumerate() {
            out.push(state.and_then(|_| read(&results, k, (&q[k], &v[k]))));
        }
    }

    /// The scalar reading's checks of one state, in its order: t, q and v
    /// finite, τ finite, q's quaternions put on the unit sphere.
    fn check_state<const N: usize, const Q: usize>(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        v: &SVector<f64, N>,
        tau: &SVector<f64, N>,
    ) -> Checked<N, Q>
    where
        S: Lagrangian<f64, N, Q>,
    {
        let (unit, _) = self.checked(t, q, v)?;
        check_finite_inputs(&S::VELOCITIES, t, q, v, tau)?;
        Ok(unit)
    }

    /// [`Error::SingularMassMatrix`] where M's pivot ratio at q is not
    /// finite or below the singular tolerance.
    fn pivot_check<const N: usize, const Q: usize>(
        &self,
        t: f64,
        q: &SVector<f64, Q>,
        ratio: f64,
    ) -> Result<(), Error>
    where
        S: Lagrangian<f64, N, Q>,
    {
        // The ratio is at most 1, and −1 for a pivot that is not finite.
        if ratio.is_finite() && ratio >= self.singular_tolerance() {
            return Ok(());
        }
        let m = (self.system()).mass_matrix(&on_sphere::<S, f64, N, Q>(q), t);
        let names = (&S::VELOCITIES[..], S::ATLAS);
        Err(Error::singular_mass(t, q, ratio, &m, names))
    }
}

fn finite<const N: usize, const Q: usize>(
    xs: &[f64],
    t: f64,
    q: &SVector<f64, Q>,
    v: &SVector<f64, N>,
) -> Result<(), Error> {
    if all_finite(xs) {
        Ok(())
    } else {
        Err(Error::non_finite(t, q, v))
    }
}

/// Four vectors as one vector of lanes: lane k is `lane(k)`.
fn pack<'a, const K: usize>(lane: impl Fn(usize) -> &'a SVector<f64, K>) -> [F64x4; K] {
    let vectors = [lane(0), lane(1), lane(2), lane(3)];
    core::array::from_fn(|i| F64x4::from_array(vectors.map(|x| x[i])))
}

/// Lane `k` of a vector of lanes.
fn unpack<const K: usize>(lanes: &[F64x4; K], k: usize) -> SVector<f64, K> {
    SVector::from_fn(|i, _| lanes[i].lane_in_place(k))
}

/// q̈ of `sys` at each state (`q[i]`, `v[i]`, `tau[i]`) at time `t`, four
/// states per call of the program `emit(batched)` emits, with the default
/// singular tolerance; each result checked as
/// [`accelerations`](crate::mechanics::accelerations) checks it, so one
/// state's error leaves the others' results alone. See
/// [`Dynamics::batched_accelerations`].
///
/// # Errors
/// Per state: [`Error::NonFiniteState`], [`Error::NonFiniteInput`] (τ) or
/// [`Error::SingularMassMatrix`].
///
/// [`SettingsError::Lengths`] (in [`Error::Settings`]), for the whole
/// batch, if `q`, `v` and `tau` differ in length.
pub fn batched_accelerations<S, const N: usize, const Q: usize>(
    sys: &S,
    q: &[SVector<f64, Q>],
    v: &[SVector<f64, N>],
    tau: &[SVector<f64, N>],
    t: f64,
) -> Result<Vec<Result<SVector<f64, N>, Error>>, Error>
where
    S: Batched<N, Q>,
{
    Dynamics::<S, f64, NoForcing>::new(sys).batched_accelerations(t, q, v, tau)
}

/// q̈ of `sys` and its derivatives ∂q̈/∂δ, ∂q̈/∂q̇ and ∂q̈/∂τ = M⁻¹ at each
/// state, four per call of the program `emit(batched, jacobians)` emits;
/// each checked as [`acceleration_derivatives`](crate::acceleration_derivatives)
/// checks it. See [`Dynamics::batched_derivatives`].
///
/// # Errors
/// Per state, as [`batched_accelerations`].
///
/// [`SettingsError::Lengths`] (in [`Error::Settings`]), for the whole
/// batch, if `q`, `v` and `tau` differ in length.
pub fn batched_acceleration_derivatives<S, const N: usize, const Q: usize>(
    sys: &S,
    q: &[SVector<f64, Q>],
    v: &[SVector<f64, N>],
    tau: &[SVector<f64, N>],
    t: f64,
) -> Result<Vec<Result<AccelerationDerivatives<f64, N>, Error>>, Error>
where
    S: BatchedDifferentiable<N, Q>,
{
    Dynamics::<S, f64, NoForcing>::new(sys).batched_derivatives(t, q, v, tau)
}
