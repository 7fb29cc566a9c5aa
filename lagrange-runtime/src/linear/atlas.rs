//! Linearisation of a system with an atlas in a chart that is regular at the
//! operating point.

use super::Linear;
use super::settings::Linearizer;
use super::tangent::{Held, column, step};
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
    /// # Errors
    /// [`Error::InvalidSettings`] for a bad singular tolerance or an [`Atlas`]
    /// whose twin disagrees with its layout; [`Error::NonPhysicalParameter`];
    /// whatever the forward dynamics report at a perturbed state.
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
        let (a, charts, _) = self.atlas_a(sys, (q, v), t, NoForcing)?;
        Ok(Linear::from_parts(
            a,
            DMatrix::zeros(2 * N, 0),
            states::<S, T, N, F>(charts.mask()),
            Vec::new(),
            N,
            None,
        ))
    }

    /// [`atlas`](Self::atlas) with the inputs held at `u`: A at (q, v, u)
    /// and B (2·N × P), ∂q̈/∂u in the same charts, both by central
    /// differences (in a second chart the inputs act through the twin's
    /// forces, as in [`ControlledSimulation::run_atlas`](crate::ControlledSimulation::run_atlas)).
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
        let (a, charts, (q, v)) = self.atlas_a(sys, (q, v), t, held(*u))?;
        let mut b = DMatrix::zeros(2 * N, P);
        for k in 0..P {
            let h = step(u[k].to_f64());
            let mut e = SVector::<T, P>::zeros();
            e[k] = T::lit(h);
            let at = |u: SVector<T, P>| {
                let dynamics = Dynamics::new(sys)
                    .with_singular_tolerance(T::lit(self.singular_tolerance))
                    .with_forcing(held(u));
                Charted::<S, T, N, F, _>::new(dynamics, &charts).acceleration(t, &q, &v)
            };
            let du = column(at(*u + e)?, at(*u - e)?, h);
            for i in 0..N {
                b[(N + i, k)] = du[i];
            }
        }
        let inputs = S::INPUTS.iter().map(|s| s.to_string()).collect();
        Ok(Linear::from_parts(
            a,
            b,
            states::<S, T, N, F>(charts.mask()),
            inputs,
            N,
            None,
        ))
    }

    /// A in regular charts at (q, v) with `forcing` added, the charts, and
    /// (q, v) read in them.
    #[allow(clippy::type_complexity)]
    fn atlas_a<S, T, G, const N: usize, const F: usize>(
        &self,
        sys: &S,
        (q, v): (&SVector<T, N>, &SVector<T, N>),
        t: T,
        forcing: G,
    ) -> Result<(DMatrix<f64>, Charts<T>, (SVector<T, N>, SVector<T, N>)), Error>
    where
        S: Atlas<T, N, F>,
        T: Real,
        G: TwinForcing<S, T, N, F>,
    {
        check_tolerance("singular tolerance", self.singular_tolerance)?;
        sys.check_parameters()?;
        if S::CONSTRAINED {
            return Err(Error::InvalidSettings(
                "the atlas's linearisation takes unconstrained systems: with constraints \
                 its states would not be independent"
                    .into(),
            ));
        }
        if !layout_agrees(sys) {
            return Err(Error::InvalidSettings(
                "the system's Atlas twin does not have the documented layout".into(),
            ));
        }
        let dynamics = Dynamics::new(sys)
            .with_singular_tolerance(T::lit(self.singular_tolerance))
            .with_forcing(forcing);
        let charts = Charts::new(S::EULER);
        let charted = Charted::<S, T, N, F, G>::new(dynamics, &charts);
        let (mut q, mut v) = (*q, *v);
        charts.enter_regular(t, &mut q, &mut v)?;
        let accel = |q: &SVector<T, N>, v: &SVector<T, N>| charted.acceleration(t, q, v);
        let mut a = DMatrix::zeros(2 * N, 2 * N);
        a.view_mut((0, N), (N, N)).fill_with_identity();
        for j in 0..N {
            let (hq, hv) = (step(q[j].to_f64()), step(v[j].to_f64()));
            let mut e = SVector::<T, N>::zeros();
            e[j] = T::lit(hq);
            let dq = column(accel(&(q + e), &v)?, accel(&(q - e), &v)?, hq);
            e[j] = T::lit(hv);
            let dv = column(accel(&q, &(v + e))?, accel(&q, &(v - e))?, hv);
            for i in 0..N {
                a[(N + i, j)] = dq[i];
                a[(N + i, N + j)] = dv[i];
            }
        }
        drop(charted);
        Ok((a, charts, (q, v)))
    }
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
