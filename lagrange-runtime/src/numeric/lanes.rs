//! Four `f64` states in one value: the scalar of the batched programs
//! (`emit(batched)`), each operation applied lane by lane.
//!
//! [`F64x4`] wraps `wide::f64x4` (the crate nalgebra's `simba` already
//! depends on), which is one 256-bit AVX register where the build targets
//! AVX (`-C target-cpu=native` on most machines), two 128-bit SSE2 or NEON
//! registers otherwise, and plain `f64`s on any other target: it builds on
//! stable Rust everywhere. [`func`] holds the functions the emitted code
//! calls, each giving in every lane what [`crate::numeric::func`]'s does for `f64`,
//! bit for bit (see there for why).

use core::ops::{Add, Div, Mul, Neg, Sub};

/// Four `f64` lanes, one state's value in each; arithmetic is lane by lane
/// and rounds as `f64` arithmetic does.
///
/// ```
/// use lagrange_runtime::numeric::lanes::F64x4;
/// let x = F64x4::from_array([1.0, 2.0, 3.0, 4.0]);
/// let y = x * F64x4::splat(2.0) + F64x4::splat(0.5);
/// assert_eq!(y.to_array(), [2.5, 4.5, 6.5, 8.5]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(transparent)]
pub struct F64x4(wide::f64x4);

impl F64x4 {
    /// The number of lanes, 4.
    pub const LANES: usize = 4;

    /// `x` in every lane.
    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        F64x4(wide::f64x4::splat(x))
    }

    /// One value per lane.
    #[inline(always)]
    pub fn from_array(lanes: [f64; 4]) -> Self {
        F64x4(wide::f64x4::new(lanes))
    }

    /// The lanes' values.
    #[inline(always)]
    pub fn to_array(self) -> [f64; 4] {
        self.0.to_array()
    }

    /// The value in lane `k` (panics for `k ≥ 4`).
    #[inline(always)]
    pub fn lane(self, k: usize) -> f64 {
        self.0.as_array()[k]
    }

    /// The value in lane `k` read in place (panics for `k ≥ 4`): one load
    /// from where the value lies, where [`lane`](Self::lane) of a copy goes
    /// through a store and a load of the whole register.
    #[inline(always)]
    pub(crate) fn lane_in_place(&self, k: usize) -> f64 {
        self.0.as_array()[k]
    }

    /// `f` applied to each lane.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f64) -> f64) -> Self {
        F64x4::from_array(self.to_array().map(f))
    }

    /// `f` applied to each pair of lanes.
    #[inline(always)]
    pub fn zip_map(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let (a, b) = (self.to_array(), other.to_array());
        F64x4::from_array([f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])])
    }
}

macro_rules! binary {
    ($($trait:ident $method:ident;)*) => {$(
        impl $trait for F64x4 {
            type Output = F64x4;
            #[inline(always)]
            fn $method(self, rhs: F64x4) -> F64x4 {
                F64x4($trait::$method(self.0, rhs.0))
            }
        }
    )*};
}

binary! {
    Add add;
    Sub sub;
    Mul mul;
    Div div;
}

impl Neg for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn neg(self) -> F64x4 {
        F64x4(-self.0)
    }
}

/// The functions the batched programs call, lane by lane: the counterparts
/// of [`crate::numeric::func`] over [`F64x4`].
///
/// Each gives in every lane exactly what [`crate::numeric::func`] gives for that
/// lane's `f64`, so a batched program's lane equals the scalar program's
/// result bit for bit: +, −, ×, ÷, √ and |x| are correctly rounded in both
/// (one SIMD instruction each); `mul_add` fuses exactly where the scalar one
/// does (where the build targets FMA); the joint angles' sines and cosines
/// (`sin_cos_many`) go through the same SIMD kernel as the scalar programs'
/// (`numeric::sincos`); the other transcendental functions (sin, cos of
/// other arguments, atan2, exp, ...) and the powers call the scalar ones lane
/// by lane, since SIMD approximations of them would round differently.
pub mod func {
    use super::F64x4;
    use crate::numeric::func as scalar;

    macro_rules! unary {
        ($($(#[$doc:meta])* $name:ident;)*) => {$(
            $(#[$doc])*
            #[inline(always)]
            pub fn $name(x: F64x4) -> F64x4 {
                x.map(scalar::$name::<f64>)
            }
        )*};
    }

    unary! {
        /// Sine, lane by lane.
        sin;
        /// Cosine, lane by lane.
        cos;
        /// Tangent, lane by lane.
        tan;
        /// Arcsine, lane by lane.
        asin;
        /// Arccosine, lane by lane.
        acos;
        /// Arctangent, lane by lane.
        atan;
        /// Hyperbolic sine, lane by lane.
        sinh;
        /// Hyperbolic cosine, lane by lane.
        cosh;
        /// Hyperbolic tangent, lane by lane.
        tanh;
        /// Exponential, lane by lane.
        exp;
        /// Natural logarithm, lane by lane.
        ln;
    }

    /// (sin xₖ, cos xₖ) of several angles, four states each: in every lane
    /// what [`crate::numeric::func::sin_cos_many`] gives for that lane's
    /// `f64`s, bit for bit (the same kernel, whose result does not depend on
    /// the lane an angle sits in).
    #[inline(always)]
    pub fn sin_cos_many<const K: usize>(x: [F64x4; K]) -> ([F64x4; K], [F64x4; K]) {
        // A plain loop: the arrays' `map` is a call the compiler may keep
        // out of line inside a long program (three calls in the xArm7's,
        // which ran 17 % slower so).
        let (mut sin, mut cos) = ([F64x4::splat(0.0); K], [F64x4::splat(0.0); K]);
        for k in 0..K {
            let (s, c) = crate::numeric::sincos::sin_cos_lanes(x[k].0);
            (sin[k], cos[k]) = (F64x4(s), F64x4(c));
        }
        (sin, cos)
    }

    /// Square root (correctly rounded, as `f64::sqrt`).
    #[inline(always)]
    pub fn sqrt(x: F64x4) -> F64x4 {
        F64x4(x.0.sqrt())
    }

    /// Absolute value.
    #[inline(always)]
    pub fn abs(x: F64x4) -> F64x4 {
        F64x4(x.0.abs())
    }

    /// In each lane, `positive` where `test > 0`, else `otherwise` (a NaN
    /// test gives `otherwise`, as [`crate::numeric::func::select`] does).
    #[inline(always)]
    pub fn select(test: F64x4, positive: F64x4, otherwise: F64x4) -> F64x4 {
        let mask = test.0.simd_gt(wide::f64x4::ZERO);
        F64x4(mask.select(positive.0, otherwise.0))
    }

    /// Four-quadrant arctangent of `y / x`, lane by lane.
    #[inline(always)]
    pub fn atan2(y: F64x4, x: F64x4) -> F64x4 {
        y.zip_map(x, scalar::atan2::<f64>)
    }

    /// `x` raised to an integer power, lane by lane.
    #[inline(always)]
    pub fn powi(x: F64x4, n: i32) -> F64x4 {
        x.map(|x| scalar::powi::<f64>(x, n))
    }

    /// `x` raised to a real power, lane by lane.
    #[inline(always)]
    pub fn powf(x: F64x4, y: F64x4) -> F64x4 {
        x.zip_map(y, scalar::powf::<f64>)
    }

    /// x y + c, fused exactly where [`crate::numeric::func::mul_add`] is (a build
    /// targeting FMA), else the product and the sum apart.
    #[inline(always)]
    pub fn mul_add(x: F64x4, y: F64x4, c: F64x4) -> F64x4 {
        if cfg!(target_feature = "fma") {
            F64x4(x.0.mul_add(y.0, c.0))
        } else {
            x * y + c
        }
    }

    /// `x` in every lane: the batched programs' constants and parameters.
    #[inline(always)]
    pub fn splat(x: f64) -> F64x4 {
        F64x4::splat(x)
    }

    /// Each lane's ratio of the smallest pivot to the largest, as
    /// [`crate::numeric::func::pivot_ratio`] gives it.
    #[inline]
    pub fn pivot_ratio<const K: usize>(pivots: &[F64x4; K]) -> F64x4 {
        let lane = |k: usize| scalar::pivot_ratio(&pivots.map(|p| p.lane(k)));
        F64x4::from_array([lane(0), lane(1), lane(2), lane(3)])
    }
}

#[cfg(test)]
mod tests {
    use super::func;
    use super::*;

    const XS: [f64; 4] = [0.3, -1.7, 2.5e-3, 4.0];

    #[test]
    fn each_lane_is_the_scalar_function_s_bit_for_bit() {
        let x = F64x4::from_array(XS);
        let y = F64x4::from_array([1.1, 0.2, -3.0, 0.0]);
        let check = |lanes: F64x4, f: &dyn Fn(usize) -> f64| {
            for k in 0..4 {
                assert_eq!(lanes.lane(k).to_bits(), f(k).to_bits(), "lane {k}");
            }
        };
        check(func::sin(x), &|k| XS[k].sin());
        check(func::cos(x), &|k| XS[k].cos());
        check(func::sqrt(func::abs(x)), &|k| XS[k].abs().sqrt());
        check(x / y, &|k| XS[k] / y.lane(k));
        check(-x, &|k| -XS[k]);
        check(func::atan2(x, y), &|k| XS[k].atan2(y.lane(k)));
        check(func::powi(x, 3), &|k| XS[k].powi(3));
        check(func::mul_add(x, y, x), &|k| {
            crate::numeric::func::mul_add(XS[k], y.lane(k), XS[k])
        });
        check(func::select(y, x, y), &|k| {
            crate::numeric::func::select(y.lane(k), XS[k], y.lane(k))
        });
        // Several angles at once, as the scalar programs take them: each
        // lane's angles through the scalar call give that lane's bits.
        let (s, c) = func::sin_cos_many([x, y, x * y]);
        for (k, &xk) in XS.iter().enumerate() {
            let angles = [xk, y.lane(k), xk * y.lane(k)];
            let (s1, c1) = crate::numeric::func::sin_cos_many(angles);
            for j in 0..3 {
                assert_eq!(s[j].lane(k).to_bits(), s1[j].to_bits(), "sin, lane {k}");
                assert_eq!(c[j].lane(k).to_bits(), c1[j].to_bits(), "cos, lane {k}");
            }
        }
    }

    #[test]
    fn a_nan_test_selects_the_other_value_and_pivots_are_per_lane() {
        let nan = F64x4::from_array([f64::NAN, 1.0, -1.0, 0.0]);
        let picked = func::select(nan, F64x4::splat(1.0), F64x4::splat(2.0));
        assert_eq!(picked.to_array(), [2.0, 1.0, 2.0, 2.0]);
        let pivots = [
            F64x4::from_array([2.0, 1.0, f64::NAN, -1.0]),
            F64x4::from_array([0.5, 1.0, 1.0, -2.0]),
        ];
        assert_eq!(
            func::pivot_ratio(&pivots).to_array(),
            [0.25, 1.0, -1.0, -1.0]
        );
    }
}
