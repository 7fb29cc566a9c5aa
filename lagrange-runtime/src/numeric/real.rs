//! The scalar the runtime computes in.

use nalgebra::RealField;

/// A real scalar: `f64`, `f32`, or any `nalgebra::RealField` that is `Copy`.
///
/// `RealField` alone admits arbitrary-precision types that are only `Clone`; the
/// runtime keeps states on the stack and passes scalars by value, hence `Copy`.
pub trait Real: RealField + Copy {
    /// Converts an `f64` constant into this scalar (exact for f64, rounded for f32).
    #[inline(always)]
    fn lit(x: f64) -> Self {
        nalgebra::convert(x)
    }
    /// Converts this scalar to `f64`, for reports and error messages.
    #[inline(always)]
    fn to_f64(self) -> f64 {
        nalgebra::try_convert(self).unwrap_or(f64::NAN)
    }
}

impl<T: RealField + Copy> Real for T {}
