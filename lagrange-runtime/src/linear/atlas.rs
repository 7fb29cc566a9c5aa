//! Linearisation of a system with an atlas in a chart that is regular at the
//! operating point.

use super::Linear;
use super::constrained_tangent::{GroupForm, GroupStates};
use super::difference::{column, unit};
use super::settings::Linearizer;
use super::tangent::Held;
use crate::atlas::{Charted, Charts, TwinForcing, layout_agrees};
use crate::error::{Error, check_finite_inputs, check_tolerance};
use crate::mechanics::{Dynamics, NoForcing};
use crate::numeric::Real;
use crate::ode::SecondOrder;
use crate::system::{Atlas, DrivenAtlas};
use nalgebra::{DMatrix, SVector};

impl Linearizer {
    /// Linearises a system with an atlas (`emit(atlas)`) about (q, v), given
    /// in the user's coordinates, at time t, in charts that are regular there:
    /// each rotation whose own chart is poor at q (the upright of a z-x-z
    /// top) is read in its second chart, as
    /// [`Simulation::run_atlas`](crate::Simulation::run_atlas) would. The
    /// states are q then q̇ in those charts: a coordinate's name, with `@2`
    /// for an angle of a second chart (`theta@2`), and a prime for a rate.
    /// A by central differences of the forward dynamics (relative error about
    /// 1e-10).
    ///
    /// A steady motion in which only cyclic angles turn (a sleeping top spins
    /// in φ of either chart) linearises to a constant A: its stability reads
    /// off A's eigenvalues.
    ///
    /// With constraints (holonomic and nonholonomic, kept by multipliers) the
    /// model is on independent coordinates and speeds of those charts, chosen
    /// as [`constrained`](Self::constrained) chooses them (name them with
    /// [`coordinates`](Self::coordinates) and [`speeds`](Self::speeds), an
    /// angle of a second chart as `theta@2`), from the constraint rows in the
    /// charts: the user's, or the twin's read through ω = E q̇. The top held
    /// at its tip by three rows linearises at the upright to the pivoted
    /// top's A (`tests/atlas_constraints.rs`).
    ///
    /// # Errors
    /// [`Error::Settings`] for a bad singular tolerance or an [`Atlas`]
    /// whose twin disagrees with its layout; [`Error::NonPhysicalParameter`];
    /// whatever the forward dynamics report at a perturbed state. With
    /// constraints: [`LinearError::InconsistentOperatingPoint`](crate::LinearError::InconsistentOperatingPoint)
    /// naming the worst row, the partition's errors and
    /// [`Error::RedundantConstraints`].
    pub fn atlas<S, T, const N: usize, const F: usize>(
        &self,
        sys: &S,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
        t: T,
    ) -> Result<Linear, Error>
    where
        S: Atlas<T, N, F>,
        T: Real,
    {
        let none = SVector::<T, 0>::zeros();
        self.atlas_model(sys, (q, v, &none, t), |_| NoForcing, &[])
    }

    /// [`atlas`](Self::atlas) with the inputs held at `u`: A at (q, v, u)
    /// and B (2·N × P), ∂q̈/∂u in the same charts, both by central
    /// differences (in a second chart the inputs act through the twin's
    /// forces, as in [`Simulation::run_atlas`](crate::Simulation::run_atlas) with inputs).
    /// States as for [`atlas`](Self::atlas); the inputs are named as the
    /// system names them.
    ///
    /// # Errors
    /// As [`atlas`](Self::atlas); [`Error::NonFiniteInput`] for a non-finite
    /// entry of `u`.
    pub fn atlas_driven<S, T, const N: usize, const P: usize, const F: usize>(
        &self,
        sys: &S,
        q: &SVector<T, N>,
        v: &SVector<T, N>,
        u: &SVector<T, P>,
        t: T,
    ) -> Result<Linear, Error>
    where
        S: DrivenAtlas<T, N, P, F>,
        T: Real,
    {
        check_finite_inputs(&S::INPUTS, t, q, v, u)?;
        let held = |u: SVector<T, P>| Held { system: sys, u };
        self.atlas_model(sys, (q, v, u, t), held, &S::INPUTS)
    }

    /// The model in charts regular at (q, v), the inputs held at `u` acting
    /// through `forcing(u)`: A and B by central differences of the dynamics
    /// in those charts; with constraints, on independent coordinates and
    /// speeds of the charts, from the rows in them (the user's, or the
    /// twin's read through ω = E ẋ), as the constrained forms' tangent
    /// linearisations take them.
    fn atlas_model<S, T, G, H, const N: usize, const P: usize, const F: usize>(
        &self,
        sys: &S,
        (q, v, u, t): (&SVector<T, N>, &SVector<T, N>, &SVector<T, P>, T),
        forcing: H,
        inputs: &[&'static str],
    ) -> Result<Linear, Error>
    where
        S: Atlas<T, N, F>,
        T: Real,
        G: TwinForcing<S, T, N, F>,
        H: Fn(SVector<T, P>) -> G,
    {
        check_tolerance("Linearizer", "singular tolerance", self.tolerances.singular)?;
        sys.check_parameters()?;
        if !layout_agrees(sys) {
            return Err(crate::atlas::layout_error());
        }
        let charts = Charts::new(S::EULER);
        let mut q = *q;
        let mut v = *v;
        charts.enter_regular(t, &mut q, &mut v)?;
        let accel = |q: &SVector<T, N>, v: &SVector<T, N>, u: &SVector<T, P>| {
            let dynamics = Dynamics::new(sys)
                .with_singular_tolerance(T::lit(self.tolerances.singular))
                .with_forcing(forcing(*u));
            Charted::<S, T, N, F, G>::new(dynamics, &charts).acceleration(t, q, v)
        };
        let names = states::<S, T, N, F>(charts.mask());
        if !S::CONSTRAINED {
            let (a, b) = full_model(accel, (&q, &v, u))?;
            let inputs = inputs.iter().map(|s| s.to_string()).collect();
            return Ok(Linear::from_parts(a, b, names, inputs, N, None));
        }
        let charted = Charted::<S, T, N, F>::new(Dynamics::new(sys), &charts);
        let at = charted.rows(t, &q);
        let form = GroupForm {
            accel,
            rows: |q: &SVector<T, N>| {
                let r = charted.rows(t, q);
                (r.g, r.g0)
            },
            phi: at.phi,
            holonomic: at.holonomic,
            row_names: &at.names,
        };
        let directions: Vec<&str> = names[..N].iter().map(String::as_str).collect();
        let states = GroupStates {
            names: &names,
            partition: [&directions; 2],
            inputs,
        };
        self.group_model::<S, T, _, _, N, P, N>(form, (&q, &v, u, t), states)
    }
}

/// A = [[0, I], [∂a/∂q, ∂a/∂v]] and B = [0; ∂a/∂u] by central differences.
fn full_model<T, A, const N: usize, const P: usize>(
    accel: A,
    (q, v, u): (&SVector<T, N>, &SVector<T, N>, &SVector<T, P>),
) -> Result<(DMatrix<f64>, DMatrix<f64>), Error>
where
    T: Real,
    A: Fn(&SVector<T, N>, &SVector<T, N>, &SVector<T, P>) -> Result<SVector<T, N>, Error>,
{
    let mut a = DMatrix::zeros(2 * N, 2 * N);
    a.view_mut((0, N), (N, N)).fill_with_identity();
    for j in 0..N {
        let (h, e) = unit::<T, N>(j, q[j].to_f64());
        let dq = column(accel(&(q + e), v, u)?, accel(&(q - e), v, u)?, h);
        let (h, e) = unit::<T, N>(j, v[j].to_f64());
        let dv = column(accel(q, &(v + e), u)?, accel(q, &(v - e), u)?, h);
        for i in 0..N {
            a[(N + i, j)] = dq[i];
            a[(N + i, N + j)] = dv[i];
        }
    }
    let mut b = DMatrix::zeros(2 * N, P);
    for k in 0..P {
        let (h, e) = unit::<T, P>(k, u[k].to_f64());
        let du = column(accel(q, v, &(u + e))?, accel(q, v, &(u - e))?, h);
        for i in 0..N {
            b[(N + i, k)] = du[i];
        }
    }
    Ok((a, b))
}

/// q's names in the charts `second` (bit k: rotation k in its second chart),
/// then the rates with a prime.
fn states<S: Atlas<T, N, F>, T: Real, const N: usize, const F: usize>(second: u64) -> Vec<String> {
    let mut names: Vec<String> = S::COORDINATES.iter().map(|c| c.to_string()).collect();
    for (k, rotation) in S::EULER.iter().enumerate() {
        if second >> k & 1 == 1 {
            for &i in &rotation.coordinates {
                names[i].push_str("@2");
            }
        }
    }
    let rates: Vec<String> = names.iter().map(|n| format!("{n}'")).collect();
    names.extend(rates);
    names
}

/// In a second chart the held inputs act on the twin through its own forces.
impl<S, T, const N: usize, const P: usize, const F: usize> TwinForcing<S, T, N, F>
    for Held<'_, S, T, P>
where
    S: DrivenAtlas<T, N, P, F>,
    T: Real,
{
    fn free_force(
        &self,
        system: &S,
        t: T,
        _: (&SVector<T, N>, &SVector<T, N>),
        (qf, vf): (&SVector<T, F>, &SVector<T, N>),
    ) -> Result<SVector<T, N>, Error> {
        Ok(system.free_input_forces(qf, vf, &self.u, t))
    }
}
