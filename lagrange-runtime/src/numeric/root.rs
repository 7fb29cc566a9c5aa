//! Scalar root finding on a bracket, for event location on dense output.

use crate::numeric::Real;
use crate::numeric::func::abs;

/// Brent's method (zeroin): a root of `f` in [a, b] given f(a), f(b) of opposite
/// signs, to within 4 ε |root| (plus the smallest normal number, so that a root at
/// zero terminates).
///
/// Inverse quadratic interpolation when it behaves, bisection when it does not, so
/// the bracket shrinks at least geometrically and converges superlinearly on smooth
/// functions: a dozen evaluations of a dense-output polynomial typically.
pub(crate) fn brent<T: Real>(f: impl FnMut(T) -> T, a: T, b: T, fa: T, fb: T) -> T {
    brent_bracket(f, a, b, fa, fb).0
}

/// [`brent`] returning the final bracket: `(b, fb, c, fc)` with b the best
/// estimate of the root and c the other end of the bracket, |b − c| within the
/// tolerance and f(c) of the opposite sign of f(b) unless f(b) = 0. The event
/// layer uses it to stop on the chosen side of a crossing.
pub(crate) fn brent_bracket<T: Real>(
    mut f: impl FnMut(T) -> T,
    mut a: T,
    mut b: T,
    mut fa: T,
    mut fb: T,
) -> (T, T, T, T) {
    let eps = T::default_epsilon();
    // Zero for f32 (underflow); the loop is bounded anyway.
    let floor = T::lit(f64::MIN_POSITIVE);
    let two = T::lit(2.0);
    let half = T::lit(0.5);
    let three = T::lit(3.0);
    let mut c = a;
    let mut fc = fa;
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if (fb > T::zero()) == (fc > T::zero()) {
            // b and c on the same side: restore the bracket [b, a].
            (c, fc) = (a, fa);
            d = b - a;
            e = d;
        }
        if abs(fc) < abs(fb) {
            (a, fa) = (b, fb);
            (b, fb) = (c, fc);
            (c, fc) = (a, fa);
        }
        let tol = two * eps * abs(b) + floor;
        let xm = half * (c - b);
        if abs(xm) <= tol || fb == T::zero() {
            return (b, fb, c, fc);
        }
        if abs(e) >= tol && abs(fa) > abs(fb) {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                // Secant.
                p = two * xm * s;
                q = T::one() - s;
            } else {
                // Inverse quadratic interpolation.
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (two * xm * qq * (qq - r) - (b - a) * (r - T::one()));
                q = (qq - T::one()) * (r - T::one()) * (s - T::one());
            }
            if p > T::zero() {
                q = -q;
            }
            p = abs(p);
            let min1 = three * xm * q - abs(tol * q);
            let min2 = abs(e * q);
            if two * p < min1.min(min2) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        (a, fa) = (b, fb);
        b += if abs(d) > tol {
            d
        } else if xm > T::zero() {
            tol
        } else {
            -tol
        };
        fb = f(b);
    }
    (b, fb, c, fc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_roots_to_full_precision() {
        let f = |x: f64| x.cos() - x;
        let r = brent(f, 0.0, 1.0, f(0.0), f(1.0));
        assert!((r - 0.739_085_133_215_160_6).abs() < 4e-16, "{r}");
        let g = |x: f64| x * x * x - 2.0;
        let r = brent(g, 3.0, 0.0, g(3.0), g(0.0));
        assert!((r - 2f64.cbrt()).abs() < 1e-15, "{r}");
        // A root at zero terminates.
        let r = brent(|x: f64| x, -1.0, 2.0, -1.0, 2.0);
        assert!(r.abs() < 1e-300);
        // Counting evaluations: superlinear, not bisection's ~52.
        let mut n = 0;
        let _ = brent(
            |x: f64| {
                n += 1;
                (x - 0.3).sin() * (1.0 + x * x)
            },
            0.0,
            1.0,
            (-0.3f64).sin(),
            0.7f64.sin() * 2.0,
        );
        assert!(n < 15, "{n} evaluations");
    }
}
