//! Eigenvalues, modes, stability verdicts, parameter sweeps and stability
//! boundaries of a [`Linear`] model.

use super::jordan::growth_degree;
use super::{Linear, LinearError};
use crate::error::SettingsError;
use crate::error::{Error, check_tolerance};
use crate::numeric::root::brent_bracket;
use nalgebra::{Complex, DMatrix, DVector};

/// The eigenvalues of a real square matrix (nalgebra's Schur-based
/// `complex_eigenvalues`), sorted by decreasing real part, then decreasing
/// imaginary part.
fn eigenvalues_of(a: &DMatrix<f64>) -> Vec<Complex<f64>> {
    if a.is_empty() {
        return Vec::new();
    }
    let mut ev: Vec<Complex<f64>> = a.complex_eigenvalues().iter().copied().collect();
    ev.sort_by(|x, y| y.re.total_cmp(&x.re).then(y.im.total_cmp(&x.im)));
    ev
}

/// The states whose zero eigenvalues are structural, in the order found.
///
/// A state whose column of A is exactly zero (no state's rate depends on it: a
/// cyclic coordinate such as a wheel angle or a position on the plane) is
/// peeled off; then a state whose column is zero outside the rows already
/// peeled (the heading, which only moves the position), and so on. In the
/// peeled order A is block triangular, [[A_rr, 0], [A_pr, A_pp]] with A_pp
/// strictly triangular, so the spectrum is exactly eig(A_rr) and one zero per
/// peeled state. Computing them that way keeps the zeros exact: a numerical
/// eigen-solver on the whole of A turns a Jordan chain of zeros into a ring of
/// size √ε (±1.6e-7 on the bicycle), which would flip a verdict.
///
/// "Zero" is at round-off: |a_ij| ≤ 64 ε max|A|. A heading enters the rows of
/// the other states only through terms such as sin ψ cos ψ − cos ψ sin ψ, which
/// cancel to a few ulps rather than to 0; an entry that small moves an
/// eigenvalue by no more than it is.
fn structural_zero_states(a: &DMatrix<f64>) -> Vec<usize> {
    let n = a.nrows();
    let zero = 64.0 * f64::EPSILON * a.amax();
    let mut peeled = vec![false; n];
    let mut order = Vec::new();
    while let Some(j) =
        (0..n).find(|&j| !peeled[j] && (0..n).all(|i| peeled[i] || a[(i, j)].abs() <= zero))
    {
        peeled[j] = true;
        order.push(j);
    }
    order
}

/// The eigenvalues of the states that are not structural zeros, and the
/// structural states (see [`structural_zero_states`]).
fn split_spectrum(a: &DMatrix<f64>) -> (Vec<Complex<f64>>, Vec<usize>) {
    let structural = structural_zero_states(a);
    let rest: Vec<usize> = (0..a.nrows()).filter(|i| !structural.contains(i)).collect();
    let block = a.select_rows(rest.iter()).select_columns(rest.iter());
    (eigenvalues_of(&block), structural)
}

fn max_real(ev: &[Complex<f64>]) -> f64 {
    ev.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max)
}

/// An eigenvalue with its eigenvector.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// λ.
    pub eigenvalue: Complex<f64>,
    /// x with A x = λ x, scaled so that its largest component is exactly 1.
    pub vector: DVector<Complex<f64>>,
    /// |A x − λ x|∞ (with |x|∞ = 1): how well the pair satisfies the eigenproblem.
    pub residual: f64,
}

/// The stability verdict of a linear model, in Lyapunov's sense.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every eigenvalue has Re λ < −tolerance.
    AsymptoticallyStable,
    /// Bounded: max Re λ within ±tolerance, and every eigenvalue on the
    /// imaginary axis (to the tolerance) semisimple (as many eigenvectors as
    /// its multiplicity: an undamped oscillator's ±iω, a cyclic coordinate
    /// whose velocity is damped), none to the right of the axis.
    Marginal,
    /// Unstable with polynomial growth: nothing to the right of the axis,
    /// but an eigenvalue on it with a Jordan block of size `degree` + 1, so
    /// a perturbation along it grows like t^`degree` (the double integrator
    /// ẍ = 0: degree 1; a quadrotor's position ← velocity ← attitude ← rate
    /// at hover: degree 3).
    PolynomialGrowth {
        /// The power of t: the largest Jordan block on the axis, less one.
        degree: usize,
    },
    /// Some eigenvalue has Re λ > tolerance: exponential growth.
    Unstable,
}

/// A stability verdict with the figure it rests on.
#[derive(Clone, Debug, PartialEq)]
pub struct Stability {
    /// The verdict.
    pub verdict: Verdict,
    /// max Re λ.
    pub max_real: f64,
    /// The eigenvalue attaining it (the one with Im ≥ 0 of a complex pair).
    pub critical: Complex<f64>,
    /// The tolerance used.
    pub tolerance: f64,
    /// The states whose zero eigenvalues are structural (cyclic coordinates
    /// and what only they feed, see [`Linear::structural_zeros`]): their
    /// zeros are exact. They count in [`verdict`](Self::verdict) (a heading
    /// feeding a position is a Jordan block, polynomial growth) and not in
    /// [`without_structural`](Self::without_structural).
    pub structural: Vec<String>,
    /// The degree of polynomial growth along the eigenvalues on the axis
    /// (0: bounded there); see [`Verdict::PolynomialGrowth`].
    pub growth: usize,
    /// The verdict about the states that are not structural alone (a
    /// bicycle's lean and steer, its heading and position left out): the
    /// stability of the motion up to the cyclic coordinates. A model whose
    /// every state is structural is [`Verdict::Marginal`] here.
    pub without_structural: Verdict,
}

impl Linear {
    /// The eigenvalues of A, sorted by decreasing real part (then decreasing
    /// imaginary part). Computed by nalgebra's real Schur decomposition, without
    /// balancing.
    ///
    /// The zero eigenvalues of [structural](Self::structural_zeros) states are
    /// exact zeros, placed by the sort like any other eigenvalue.
    pub fn eigenvalues(&self) -> Vec<Complex<f64>> {
        let (mut ev, structural) = split_spectrum(self.a());
        ev.extend(structural.iter().map(|_| Complex::new(0.0, 0.0)));
        ev.sort_by(|x, y| y.re.total_cmp(&x.re).then(y.im.total_cmp(&x.im)));
        ev
    }

    /// The states whose zero eigenvalues are structural: no other state's rate
    /// depends on them, except states already in the list (a cyclic
    /// coordinate, a heading that only moves a position, a wheel's rate that
    /// only turns the wheel). Found from the zeros of A (at round-off), so they are the
    /// zeros a derived model's cyclic coordinates leave.
    pub fn structural_zeros(&self) -> Vec<String> {
        structural_zero_states(self.a())
            .into_iter()
            .map(|i| self.states()[i].clone())
            .collect()
    }

    /// The eigenvalues with their eigenvectors, in the order of
    /// [`eigenvalues`](Self::eigenvalues). Each eigenvector comes from inverse
    /// iteration on (A − σI) x_{k+1} = x_k with the complex shift σ the computed
    /// eigenvalue (nudged by a relative 1e-10 if A − σI is exactly singular),
    /// three steps from a fixed generic start vector. For a repeated eigenvalue the
    /// vector is one element of its eigenspace.
    pub fn modes(&self) -> Vec<Mode> {
        let n = self.a().nrows();
        let ac: DMatrix<Complex<f64>> = self.a().map(|x| Complex::new(x, 0.0));
        self.eigenvalues()
            .into_iter()
            .map(|lambda| {
                let scale = 1.0 + lambda.norm() + self.a().amax();
                let mut shift = lambda;
                let mut lu = shifted(&ac, shift).lu();
                if !lu.is_invertible() {
                    shift += Complex::new(1e-10 * scale, 1e-10 * scale);
                    lu = shifted(&ac, shift).lu();
                }
                // A generic start: every eigenvector has a component along it.
                let mut x: DVector<Complex<f64>> = DVector::from_fn(n, |i, _| {
                    Complex::new(1.0 + 0.37 * i as f64, 0.11 * i as f64)
                });
                for _ in 0..3 {
                    let y = lu.solve(&x).unwrap_or_else(|| {
                        shift += Complex::new(1e-10 * scale, 1e-10 * scale);
                        shifted(&ac, shift)
                            .lu()
                            .solve(&x)
                            .unwrap_or_else(|| x.clone())
                    });
                    x = normalise(y);
                }
                let residual = (&ac * &x - &x * lambda).camax();
                Mode {
                    eigenvalue: lambda,
                    vector: x,
                    residual,
                }
            })
            .collect()
    }

    /// The stability verdict with tolerance `tol` on the real parts (see
    /// [`Verdict`]).
    ///
    /// How it decides: an eigenvalue with Re λ > `tol` is
    /// [`Verdict::Unstable`]. Otherwise each eigenvalue with |Re λ| ≤ `tol`
    /// (and the exact zeros of the [structural](Self::structural_zeros)
    /// states) is tested for a Jordan block: its index ν, the k at which the
    /// kernel dimension of (A − λI)^k stops growing, singular values at most
    /// [`RANK_TOLERANCE`](super::RANK_TOLERANCE) · max(1, ‖A‖₂) counting as
    /// zero. ν > 1 anywhere is [`Verdict::PolynomialGrowth`] with degree
    /// ν − 1; all ν = 1 is [`Verdict::Marginal`] (bounded). The verdict
    /// about the non-structural states alone is
    /// [`Stability::without_structural`].
    ///
    /// # Errors
    /// [`Error::Settings`] if `tol` is negative or not finite (a
    /// negative tolerance would call an undamped oscillator asymptotically
    /// stable).
    pub fn stability(&self, tol: f64) -> Result<Stability, Error> {
        check_stability_tolerance(tol)?;
        let (ev, structural) = split_spectrum(self.a());
        let names = structural
            .iter()
            .map(|&i| self.states()[i].clone())
            .collect();
        let mut stability = stability_of(&ev, names, tol);
        stability.without_structural = stability.verdict;
        if stability.verdict == Verdict::Unstable {
            return Ok(stability);
        }
        let on_axis = axis_eigenvalues(&ev, !structural.is_empty(), tol, self.a().amax());
        stability.growth = growth_degree(self.a(), &on_axis);
        stability.verdict = match (stability.growth, on_axis.is_empty()) {
            (0, true) => stability.verdict,
            (0, false) => Verdict::Marginal,
            (degree, _) => Verdict::PolynomialGrowth { degree },
        };
        Ok(stability)
    }
}

/// The eigenvalues with |Re λ| ≤ tol and Im λ ≥ 0, one per cluster (a
/// Jordan block's computed eigenvalues spread by about ε^(1/m) ‖A‖), and 0
/// when there are structural zeros.
fn axis_eigenvalues(ev: &[Complex<f64>], zero: bool, tol: f64, scale: f64) -> Vec<Complex<f64>> {
    let apart = 1e-6 * scale.max(1.0);
    let mut out: Vec<Complex<f64>> = Vec::new();
    if zero {
        out.push(Complex::new(0.0, 0.0));
    }
    for &lambda in ev.iter().filter(|z| z.re.abs() <= tol && z.im >= -apart) {
        if out.iter().all(|mu| (lambda - mu).norm() > apart) {
            out.push(lambda);
        }
    }
    out
}

fn check_stability_tolerance(tol: f64) -> Result<(), Error> {
    check_tolerance("stability", "stability tolerance (on the real parts)", tol)
}

fn stability_of(ev: &[Complex<f64>], structural: Vec<String>, tol: f64) -> Stability {
    if ev.is_empty() && !structural.is_empty() {
        return Stability {
            verdict: Verdict::Marginal,
            max_real: 0.0,
            critical: Complex::new(0.0, 0.0),
            tolerance: tol,
            structural,
            growth: 0,
            without_structural: Verdict::Marginal,
        };
    }
    let max = max_real(ev);
    // Sorted by decreasing (re, im): the first one attaining the max has Im ≥ 0.
    let critical = ev.first().copied().unwrap_or(Complex::new(f64::NAN, 0.0));
    let verdict = if ev.is_empty() || max < -tol {
        Verdict::AsymptoticallyStable
    } else if max <= tol {
        Verdict::Marginal
    } else {
        Verdict::Unstable
    };
    Stability {
        verdict,
        max_real: if ev.is_empty() {
            f64::NEG_INFINITY
        } else {
            max
        },
        critical,
        tolerance: tol,
        structural,
        growth: 0,
        without_structural: verdict,
    }
}

fn shifted(a: &DMatrix<Complex<f64>>, s: Complex<f64>) -> DMatrix<Complex<f64>> {
    let mut m = a.clone();
    for i in 0..m.nrows() {
        m[(i, i)] -= s;
    }
    m
}

/// x scaled so that its largest component is exactly 1.
fn normalise(x: DVector<Complex<f64>>) -> DVector<Complex<f64>> {
    let (i, _) = x.iter().enumerate().fold((0, 0.0), |(bi, bn), (i, z)| {
        if z.norm() > bn {
            (i, z.norm())
        } else {
            (bi, bn)
        }
    });
    let p = x[i];
    if p.norm() == 0.0 || !p.norm().is_finite() {
        return x;
    }
    let mut y = x / p;
    y[i] = Complex::new(1.0, 0.0);
    y
}

/// The eigenvalues at one parameter value of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepPoint {
    /// The parameter.
    pub parameter: f64,
    /// The eigenvalues of the states that are not structural zeros, sorted as
    /// [`Linear::eigenvalues`].
    pub eigenvalues: Vec<Complex<f64>>,
    /// The states whose zero eigenvalues are structural (see
    /// [`Linear::structural_zeros`]), left out of `eigenvalues`.
    pub structural: Vec<String>,
}

impl SweepPoint {
    fn of(parameter: f64, lin: &Linear) -> Self {
        let (eigenvalues, structural) = split_spectrum(lin.a());
        let structural = structural
            .iter()
            .map(|&i| lin.states()[i].clone())
            .collect();
        Self {
            parameter,
            eigenvalues,
            structural,
        }
    }

    /// max Re λ over the eigenvalues that are not structural zeros (0 when
    /// every state is structural).
    pub fn max_real(&self) -> f64 {
        if self.eigenvalues.is_empty() && !self.structural.is_empty() {
            return 0.0;
        }
        max_real(&self.eigenvalues)
    }
}

/// The eigenvalues of a family of linear models over a parameter, with the
/// model itself, so that its stability boundaries can be refined; see
/// [`sweep`].
pub struct EigenSweep<F> {
    /// One point per parameter value, in the order given.
    pub points: Vec<SweepPoint>,
    model: F,
}

impl<F> std::fmt::Debug for EigenSweep<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EigenSweep")
            .field("points", &self.points)
            .finish_non_exhaustive()
    }
}

/// A located stability boundary: where max Re λ crosses the tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boundary {
    /// The parameter value of the crossing.
    pub parameter: f64,
    /// The final bracket [lo, hi] around it (max Re λ − tolerance changes sign
    /// across it unless it is exactly zero at `parameter`).
    pub bracket: (f64, f64),
    /// The critical eigenvalue at the boundary (Im ≥ 0 of a pair).
    pub eigenvalue: Complex<f64>,
    /// Whether the crossing is by a complex pair (a Hopf boundary, like the
    /// bicycle's weave speed) rather than a real eigenvalue (a divergence, like
    /// capsize).
    pub oscillatory: bool,
    /// Whether the model becomes unstable as the parameter increases through the
    /// boundary.
    pub destabilising: bool,
}

/// The eigenvalues of `model(p)` for every p in `parameters`. The sweep keeps
/// `model` to refine its [`boundaries`](EigenSweep::boundaries).
///
/// # Errors
/// The first error `model` returns.
pub fn sweep<F>(parameters: &[f64], mut model: F) -> Result<EigenSweep<F>, Error>
where
    F: FnMut(f64) -> Result<Linear, Error>,
{
    let points = parameters
        .iter()
        .map(|&p| Ok(SweepPoint::of(p, &model(p)?)))
        .collect::<Result<_, Error>>()?;
    Ok(EigenSweep { points, model })
}

impl<F> EigenSweep<F>
where
    F: FnMut(f64) -> Result<Linear, Error>,
{
    /// max Re λ at every point, as (parameter, max Re λ).
    pub fn max_real(&self) -> Vec<(f64, f64)> {
        self.points
            .iter()
            .map(|p| (p.parameter, p.max_real()))
            .collect()
    }

    /// The stability verdicts at every point, with tolerance `tol`: from the
    /// spectrum alone, about the states that are not structural (as
    /// [`Stability::without_structural`]); a sweep keeps no A, so a Jordan
    /// block on the axis is not looked for here (call
    /// [`Linear::stability`] on the model at a point for that).
    ///
    /// # Errors
    /// [`Error::Settings`] for a negative or non-finite `tol`.
    pub fn verdicts(&self, tol: f64) -> Result<Vec<(f64, Verdict)>, Error> {
        check_stability_tolerance(tol)?;
        Ok(self
            .points
            .iter()
            .map(|p| {
                let stab = stability_of(&p.eigenvalues, p.structural.clone(), tol);
                (p.parameter, stab.verdict)
            })
            .collect())
    }

    /// The stability boundaries: every pair of neighbouring sweep points across
    /// which max Re λ − `tol` changes sign brackets one, refined by Brent's
    /// method on p ↦ max Re λ(model(p)) − `tol` until the bracket is within
    /// `rtol` · |p| (at least 4 ε |p| is reachable: Brent stops there). max Re λ is
    /// continuous but has kinks where the critical eigenvalue changes; Brent keeps
    /// a bracket, so a kink slows it down but cannot lose the crossing. A sweep
    /// too coarse to see a crossing (two within one interval) misses it.
    /// Structural zero eigenvalues take no part (see [`SweepPoint::max_real`]).
    ///
    /// # Errors
    /// The first error the model returns; [`LinearError::BoundaryNotResolved`]
    /// if the bracket is not within `rtol` after Brent stops;
    /// [`Error::Settings`] for a negative or non-finite `tol` or `rtol`.
    pub fn boundaries(&mut self, tol: f64, rtol: f64) -> Result<Vec<Boundary>, Error> {
        check_stability_tolerance(tol)?;
        if !(rtol.is_finite() && rtol >= 0.0) {
            return Err(SettingsError::Value {
                owner: "stability boundary",
                setting: "relative tolerance rtol",
                value: rtol,
                requirement: "non-negative and finite".into(),
            }
            .into());
        }
        let mut out = Vec::new();
        for k in 1..self.points.len() {
            let a = &self.points[k - 1];
            let b = &self.points[k];
            let fa = a.max_real() - tol;
            let fb = b.max_real() - tol;
            if (fa > 0.0) != (fb > 0.0) {
                let ends = [(a.parameter, fa), (b.parameter, fb)];
                out.push(locate(&mut self.model, ends, tol, rtol)?);
            }
        }
        Ok(out)
    }
}

/// max Re λ − `tol` of `model(p)`, over the states that are not structural.
fn margin<F>(model: &mut F, p: f64, tol: f64) -> Result<f64, Error>
where
    F: FnMut(f64) -> Result<Linear, Error>,
{
    Ok(SweepPoint::of(p, &model(p)?).max_real() - tol)
}

/// The boundary inside one bracket [(a, f(a)), (b, f(b))] of a sign change.
fn locate<F>(model: &mut F, ends: [(f64, f64); 2], tol: f64, rtol: f64) -> Result<Boundary, Error>
where
    F: FnMut(f64) -> Result<Linear, Error>,
{
    let [(a, fa), (b, fb)] = ends;
    let mut failure: Option<Error> = None;
    let f = |p: f64| {
        if failure.is_some() {
            return 0.0;
        }
        margin(model, p, tol).unwrap_or_else(|e| {
            failure = Some(e);
            0.0
        })
    };
    let (p, _, c, _) = brent_bracket(f, a, b, fa, fb);
    if let Some(e) = failure {
        return Err(e);
    }
    let lo = p.min(c);
    let hi = p.max(c);
    // Brent's own stopping rule is 4 ε |p| (+ the smallest normal).
    let reachable = 4.0 * f64::EPSILON * p.abs() + f64::MIN_POSITIVE;
    if hi - lo > (rtol * p.abs()).max(reachable) {
        return Err(LinearError::BoundaryNotResolved {
            lo,
            hi,
            tolerance: rtol,
        }
        .into());
    }
    let z = model(p)?.stability(tol)?.critical;
    Ok(Boundary {
        parameter: p,
        bracket: (lo, hi),
        eigenvalue: z,
        oscillatory: z.im.abs() > 1e-8 * (1.0 + z.norm()),
        destabilising: (fb > 0.0) == (b > a),
    })
}
