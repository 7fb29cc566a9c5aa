//! Scalar functions called by generated code.
//!
//! The derive macro emits calls such as `func::sin(x)` instead of method calls so
//! that the emitted tokens do not depend on which traits are in scope at the
//! user's site, and so that `abs`, which both `ComplexField` and `num_traits::Signed`
//! provide for a `RealField`, is never ambiguous. All of them are `#[inline(always)]`:
//! they cost nothing over the method call.

use crate::numeric::Real;
use nalgebra::{ComplexField, RealField};

macro_rules! unary {
    ($($(#[$doc:meta])* $name:ident;)*) => {$(
        $(#[$doc])*
        #[inline(always)]
        pub fn $name<T: Real>(x: T) -> T {
            ComplexField::$name(x)
        }
    )*};
}

unary! {
    /// Sine.
    sin;
    /// Cosine.
    cos;
    /// Tangent.
    tan;
    /// Arcsine.
    asin;
    /// Arccosine.
    acos;
    /// Arctangent.
    atan;
    /// Hyperbolic sine.
    sinh;
    /// Hyperbolic cosine.
    cosh;
    /// Hyperbolic tangent.
    tanh;
    /// Exponential.
    exp;
    /// Natural logarithm.
    ln;
    /// Square root.
    sqrt;
    /// Absolute value.
    abs;
}

/// (sin xₖ, cos xₖ) of several angles at once: what the emitted programs
/// call for the angles they read (the joint coordinates), once per piece of
/// a program, where its first sine or cosine is needed.
/// For `f64` the angles go through one SIMD kernel
/// ([`crate::numeric::sincos`]: within an ulp of the C library's `sin` and
/// `cos`, at a cost that does not depend on the angles; six angles in a
/// loop take about half the time of six `sincos` calls, and inside a
/// program the gain depends on the code around the call, see
/// `BENCHMARKS.md`); any other scalar takes [`sin`] and [`cos`] angle by
/// angle.
#[inline(always)]
pub fn sin_cos_many<T: Real, const K: usize>(x: [T; K]) -> ([T; K], [T; K]) {
    if let Some(&angles) = (&x as &dyn core::any::Any).downcast_ref::<[f64; K]>() {
        let (s, c) = crate::numeric::sincos::sin_cos_many(angles);
        return (s.map(T::lit), c.map(T::lit));
    }
    (x.map(sin), x.map(cos))
}

/// `x`, read on its own: for `f64`, through a register the compiler cannot
/// see into, so that neighbouring coordinates stay separate loads (see
/// [`crate::numeric::sincos`]'s `apart`); any other scalar as it is. The
/// emitted scalar programs read every coordinate `q[i]` through it.
///
/// ```
/// use lagrange_runtime::numeric::func::apart;
/// // The value is never changed, only where the compiler may load it from.
/// assert_eq!(apart(0.25f64).to_bits(), 0.25f64.to_bits());
/// assert_eq!(apart(-3.5f32), -3.5f32);
/// ```
#[inline(always)]
pub fn apart<T: Real>(x: T) -> T {
    if let Some(&value) = (&x as &dyn core::any::Any).downcast_ref::<f64>() {
        return T::lit(crate::numeric::sincos::apart(value));
    }
    x
}

/// `if test > 0 { positive } else { otherwise }`: the piecewise form of the
/// description language (comparisons, `sign`, `min`, `max`, `clamp`). Both
/// values are computed before the choice, so a branch that is not finite
/// where it is not taken does no harm.
#[inline(always)]
pub fn select<T: Real>(test: T, positive: T, otherwise: T) -> T {
    if test > T::zero() {
        positive
    } else {
        otherwise
    }
}

/// Four-quadrant arctangent of `y / x`.
#[inline(always)]
pub fn atan2<T: Real>(y: T, x: T) -> T {
    RealField::atan2(y, x)
}

/// `x` raised to an integer power.
#[inline(always)]
pub fn powi<T: Real>(x: T, n: i32) -> T {
    ComplexField::powi(x, n)
}

/// `x` raised to a real power.
#[inline(always)]
pub fn powf<T: Real>(x: T, y: T) -> T {
    ComplexField::powf(x, y)
}

/// x y + c: one fused multiply–add where the build targets a CPU with one
/// (`-C target-cpu=native` on most machines, or `-C target-feature=+fma`),
/// rounding once; otherwise the product and the sum apart, as written.
#[inline(always)]
pub fn mul_add<T: Real>(x: T, y: T, c: T) -> T {
    if cfg!(target_feature = "fma") {
        ComplexField::mul_add(x, y, c)
    } else {
        x * y + c
    }
}

/// The ratio of the smallest pivot to the largest, what the emitted
/// factorisations hand the singularity check; −1 where no pivot is positive
/// (two negative pivots would give a positive ratio, and M is then not
/// positive definite) or where one is not finite.
#[inline]
pub fn pivot_ratio<T: Real>(pivots: &[T]) -> T {
    let Some((&first, rest)) = pivots.split_first() else {
        return T::lit(-1.0);
    };
    if !pivots.iter().all(|d| d.is_finite()) {
        return T::lit(-1.0);
    }
    let (mut lo, mut hi) = (first, first);
    for &d in rest {
        if d < lo {
            lo = d;
        }
        if d > hi {
            hi = d;
        }
    }
    if hi > T::lit(0.0) {
        lo / hi
    } else {
        T::lit(-1.0)
    }
}

/// A literal constant in the scalar type.
#[inline(always)]
pub fn lit<T: Real>(x: f64) -> T {
    T::lit(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pivot_ratio_refuses_what_is_not_positive_definite() {
        assert_eq!(pivot_ratio(&[2.0, 0.5, 4.0]), 0.125);
        assert_eq!(pivot_ratio(&[-2.0, -1.0]), -1.0);
        assert!(pivot_ratio(&[1.0, -1.0]) < 0.0);
        assert_eq!(pivot_ratio(&[1.0, f64::NAN, 2.0]), -1.0);
        assert_eq!(pivot_ratio::<f64>(&[]), -1.0);
    }

    #[test]
    fn several_angles_at_once_within_an_ulp_for_f64_and_as_std_for_f32() {
        let x = [0.3, -1.2, 2.9, 7.5, -40.0];
        let (s, c) = sin_cos_many(x);
        for k in 0..5 {
            let ulp = f64::EPSILON * 1.0f64.max(x[k].sin().abs());
            assert!((s[k] - x[k].sin()).abs() <= ulp && (c[k] - x[k].cos()).abs() <= ulp);
        }
        let (s, c) = sin_cos_many(x.map(|x| x as f32));
        assert_eq!(s, x.map(|x| (x as f32).sin()));
        assert_eq!(c, x.map(|x| (x as f32).cos()));
    }

    #[test]
    fn agree_with_std_for_f64_and_f32() {
        let x = 0.3_f64;
        assert_eq!(sin(x), x.sin());
        assert_eq!(cos(x), x.cos());
        assert_eq!(tan(x), x.tan());
        assert_eq!(asin(x), x.asin());
        assert_eq!(acos(x), x.acos());
        assert_eq!(atan(x), x.atan());
        assert_eq!(sinh(x), x.sinh());
        assert_eq!(cosh(x), x.cosh());
        assert_eq!(tanh(x), x.tanh());
        assert_eq!(exp(x), x.exp());
        assert_eq!(ln(x), x.ln());
        assert_eq!(sqrt(x), x.sqrt());
        assert_eq!(abs(-x), x);
        assert_eq!(atan2(1.0, -1.0), 1.0_f64.atan2(-1.0));
        assert_eq!(powi(x, 3), x.powi(3));
        assert_eq!(powf(x, 2.5), x.powf(2.5));
        assert_eq!(lit::<f64>(0.1), 0.1);
        assert_eq!(lit::<f32>(0.1), 0.1_f32);
        assert_eq!(sin(0.5_f32), 0.5_f32.sin());
    }
}
