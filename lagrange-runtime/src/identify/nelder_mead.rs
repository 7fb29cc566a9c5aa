//! A compact Nelder–Mead simplex minimiser (Nelder and Mead 1965, with the
//! standard coefficients of Lagarias, Reeds, Wright and Wright 1998):
//! derivative-free, for the exciting trajectory's condition number, whose
//! gradient (through a singular value decomposition) is not worth its cost
//! at a few tens of unknowns.

use nalgebra::DVector;

/// Reflection, expansion, contraction and shrink coefficients.
const REFLECT: f64 = 1.0;
const EXPAND: f64 = 2.0;
const CONTRACT: f64 = 0.5;
const SHRINK: f64 = 0.5;

/// The best point found and its value, and the evaluations spent.
pub(super) struct Minimum {
    pub(super) x: DVector<f64>,
    pub(super) value: f64,
    pub(super) evaluations: usize,
}

/// Minimises `f` from `start`, the first simplex `start` and `start + step
/// e_k`, for at most `iterations` simplex steps, stopping early once the
/// values over the simplex differ by less than `tolerance`. A value that is
/// not a number counts as +∞ (a worst point, never kept as the best).
pub(super) fn minimise(
    f: &mut dyn FnMut(&DVector<f64>) -> f64,
    start: &DVector<f64>,
    step: f64,
    iterations: usize,
    tolerance: f64,
) -> Minimum {
    let n = start.len();
    let mut evaluations = 0;
    let mut eval = |x: &DVector<f64>| {
        evaluations += 1;
        let value = f(x);
        if value.is_nan() { f64::INFINITY } else { value }
    };
    let mut simplex: Vec<(DVector<f64>, f64)> = (0..=n)
        .map(|k| {
            let mut x = start.clone();
            if k > 0 {
                x[k - 1] += step;
            }
            let value = eval(&x);
            (x, value)
        })
        .collect();
    for _ in 0..iterations {
        simplex.sort_by(|p, q| p.1.total_cmp(&q.1));
        let (best, worst) = (simplex[0].1, simplex[n].1);
        if n == 0 || (worst - best).abs() <= tolerance * (1.0 + best.abs()) {
            break;
        }
        let centroid = simplex[..n].iter().fold(DVector::zeros(n), |c, p| c + &p.0) / n as f64;
        let toward = |t: f64| &centroid + (&centroid - &simplex[n].0) * t;
        let reflected = toward(REFLECT);
        let fr = eval(&reflected);
        if fr < best {
            let expanded = toward(REFLECT * EXPAND);
            let fe = eval(&expanded);
            simplex[n] = if fe < fr {
                (expanded, fe)
            } else {
                (reflected, fr)
            };
        } else if fr < simplex[n - 1].1 {
            simplex[n] = (reflected, fr);
        } else {
            // Contract outside when the reflection beat the worst point,
            // inside when it did not.
            let (t, bound) = if fr < worst {
                (REFLECT * CONTRACT, fr)
            } else {
                (-CONTRACT, worst)
            };
            let contracted = toward(t);
            let fc = eval(&contracted);
            if fc <= bound {
                simplex[n] = (contracted, fc);
            } else {
                let first = simplex[0].0.clone();
                for p in simplex.iter_mut().skip(1) {
                    p.0 = &first + (&p.0 - &first) * SHRINK;
                    p.1 = eval(&p.0);
                }
            }
        }
    }
    simplex.sort_by(|p, q| p.1.total_cmp(&q.1));
    let (x, value) = simplex.swap_remove(0);
    Minimum {
        x,
        value,
        evaluations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's valley, minimum 0 at (1, 1), from the textbook start.
    #[test]
    fn finds_the_bottom_of_rosenbrocks_valley() {
        let mut f = |x: &DVector<f64>| (1.0 - x[0]).powi(2) + 100.0 * (x[1] - x[0] * x[0]).powi(2);
        let start = DVector::from_vec(vec![-1.2, 1.0]);
        let found = minimise(&mut f, &start, 0.5, 2000, 1e-16);
        assert!(
            (found.x[0] - 1.0).abs() < 1e-5 && (found.x[1] - 1.0).abs() < 1e-5,
            "{}",
            found.x
        );
        assert!(found.value < 1e-10);
        assert!(found.evaluations < 1000, "{}", found.evaluations);
    }

    /// A value that is not a number is never the best point.
    #[test]
    fn nan_counts_as_the_worst() {
        let mut f = |x: &DVector<f64>| {
            if x[0] < 0.0 {
                f64::NAN
            } else {
                (x[0] - 2.0).powi(2)
            }
        };
        let found = minimise(&mut f, &DVector::from_vec(vec![0.5]), 1.0, 200, 1e-14);
        assert!((found.x[0] - 2.0).abs() < 1e-5, "{}", found.x);
    }
}
