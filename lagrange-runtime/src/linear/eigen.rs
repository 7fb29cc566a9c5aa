//! Eigenvalues, modes, stability verdicts, parameter sweeps and stability
//! boundaries of a [`Linear`] model.

use super::{Linear, LinearError};
use crate::error::Error;
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

/// The stability verdict of a linear model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every eigenvalue has Re λ < −tolerance.
    AsymptoticallyStable,
    /// max Re λ within ±tolerance: eigenvalues on the imaginary axis (to the
    /// tolerance), none to the right of it. Marginal in the spectral sense: a
    /// repeated eigenvalue on the axis with a Jordan block still grows
    /// polynomially.
    Marginal,
    /// Some eigenvalue has Re λ > tolerance.
    Unstable,
}

/// A stability verdict with the figure it rests on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stability {
    /// The verdict.
    pub verdict: Verdict,
    /// max Re λ.
    pub max_real: f64,
    /// The eigenvalue attaining it (the one with Im ≥ 0 of a complex pair).
    pub critical: Complex<f64>,
    /// The tolerance used.
    pub tolerance: f64,
}

impl Linear {
    /// The eigenvalues of A, sorted by decreasing real part (then decreasing
    /// imaginary part). Computed by nalgebra's real Schur decomposition, without
    /// balancing.
    pub fn eigenvalues(&self) -> Vec<Complex<f64>> {
        eigenvalues_of(self.a())
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
    pub fn stability(&self, tol: f64) -> Stability {
        stability_of(&self.eigenvalues(), tol)
    }
}

fn stability_of(ev: &[Complex<f64>], tol: f64) -> Stability {
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
    /// The eigenvalues, sorted as [`Linear::eigenvalues`].
    pub eigenvalues: Vec<Complex<f64>>,
}

impl SweepPoint {
    /// max Re λ.
    pub fn max_real(&self) -> f64 {
        max_real(&self.eigenvalues)
    }
}

/// The eigenvalues of a family of linear models over a parameter; see [`sweep`].
#[derive(Clone, Debug, PartialEq)]
pub struct EigenSweep {
    /// One point per parameter value, in the order given.
    pub points: Vec<SweepPoint>,
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

/// The eigenvalues of `model(p)` for every p in `parameters`.
///
/// # Errors
/// The first error `model` returns.
pub fn sweep<F>(parameters: &[f64], mut model: F) -> Result<EigenSweep, Error>
where
    F: FnMut(f64) -> Result<Linear, Error>,
{
    let points = parameters
        .iter()
        .map(|&p| {
            Ok(SweepPoint {
                parameter: p,
                eigenvalues: model(p)?.eigenvalues(),
            })
        })
        .collect::<Result<_, Error>>()?;
    Ok(EigenSweep { points })
}

impl EigenSweep {
    /// max Re λ at every point, as (parameter, max Re λ).
    pub fn max_real(&self) -> Vec<(f64, f64)> {
        self.points
            .iter()
            .map(|p| (p.parameter, p.max_real()))
            .collect()
    }

    /// The stability verdicts at every point, with tolerance `tol`.
    pub fn verdicts(&self, tol: f64) -> Vec<(f64, Verdict)> {
        self.points
            .iter()
            .map(|p| (p.parameter, stability_of(&p.eigenvalues, tol).verdict))
            .collect()
    }

    /// The stability boundaries: every pair of neighbouring sweep points across
    /// which max Re λ − `tol` changes sign brackets one, refined by Brent's
    /// method on p ↦ max Re λ(model(p)) − `tol` until the bracket is within
    /// `rtol` · |p| (at least 4 ε |p| is reachable: Brent stops there). max Re λ is
    /// continuous but has kinks where the critical eigenvalue changes; Brent keeps
    /// a bracket, so a kink slows it down but cannot lose the crossing. A sweep
    /// too coarse to see a crossing (two within one interval) misses it.
    ///
    /// # Errors
    /// The first error `model` returns; [`LinearError::BoundaryNotResolved`] if
    /// the bracket is not within `rtol` after Brent stops;
    /// [`Error::InvalidSettings`] for a negative or non-finite `rtol`.
    pub fn boundaries<F>(&self, mut model: F, tol: f64, rtol: f64) -> Result<Vec<Boundary>, Error>
    where
        F: FnMut(f64) -> Result<Linear, Error>,
    {
        if !(rtol.is_finite() && rtol >= 0.0 && tol.is_finite()) {
            return Err(Error::InvalidSettings(format!(
                "boundary tolerances must be finite and rtol >= 0, got tol = {tol}, rtol = {rtol}"
            )));
        }
        let mut out = Vec::new();
        for w in self.points.windows(2) {
            let (fa, fb) = (w[0].max_real() - tol, w[1].max_real() - tol);
            if (fa > 0.0) == (fb > 0.0) {
                continue;
            }
            let (a, b) = (w[0].parameter, w[1].parameter);
            let mut failure: Option<Error> = None;
            let (p, _, c, _) = brent_bracket(
                |p: f64| {
                    if failure.is_some() {
                        return 0.0;
                    }
                    match model(p) {
                        Ok(lin) => max_real(&lin.eigenvalues()) - tol,
                        Err(e) => {
                            failure = Some(e);
                            0.0
                        }
                    }
                },
                a,
                b,
                fa,
                fb,
            );
            if let Some(e) = failure {
                return Err(e);
            }
            let (lo, hi) = (p.min(c), p.max(c));
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
            let stab = model(p)?.stability(tol);
            let z = stab.critical;
            out.push(Boundary {
                parameter: p,
                bracket: (lo, hi),
                eigenvalue: z,
                oscillatory: z.im.abs() > 1e-8 * (1.0 + z.norm()),
                destabilising: (fb > 0.0) == (b > a),
            });
        }
        Ok(out)
    }
}
