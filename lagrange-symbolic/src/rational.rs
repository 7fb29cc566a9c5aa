//! Exact rational constants, and the numeric coefficient type used while
//! canonicalising (a rational that degrades to a float on overflow).

use std::fmt;
use std::hash::{Hash, Hasher};

/// An exact rational number `num / den`, always normalised: `den > 0` and
/// `gcd(|num|, den) == 1`.
///
/// All arithmetic is checked; an operation that would overflow `i64` returns
/// `None`, and the callers in this crate then fall back to a float constant,
/// so nothing panics on large coefficients.
#[derive(Copy, Clone, PartialEq, Eq, Hash, Debug)]
pub struct Rational {
    /// Numerator (carries the sign).
    pub num: i64,
    /// Denominator, strictly positive.
    pub den: i64,
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    a = a.abs();
    b = b.abs();
    while b != 0 {
        let r = a % b;
        a = b;
        b = r;
    }
    a
}

impl Rational {
    /// Zero.
    pub const ZERO: Rational = Rational { num: 0, den: 1 };
    /// One.
    pub const ONE: Rational = Rational { num: 1, den: 1 };
    /// Minus one.
    pub const MINUS_ONE: Rational = Rational { num: -1, den: 1 };

    /// The normalised `num / den`; `None` if `den == 0` or the normalised
    /// value does not fit in `i64`.
    pub fn new(num: i64, den: i64) -> Option<Rational> {
        Self::from_i128(num as i128, den as i128)
    }

    /// The integer `v`.
    pub fn integer(v: i64) -> Rational {
        Rational { num: v, den: 1 }
    }

    // Arithmetic is done in i128 (products of two i64 always fit) and only the
    // normalised result has to fit back into i64.
    fn from_i128(num: i128, den: i128) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        let g = gcd(num, den).max(1);
        let mut n = num / g;
        let mut d = den / g;
        if d < 0 {
            n = -n;
            d = -d;
        }
        Some(Rational {
            num: i64::try_from(n).ok()?,
            den: i64::try_from(d).ok()?,
        })
    }

    /// `self + o`, `None` on overflow.
    pub fn checked_add(self, o: Rational) -> Option<Rational> {
        let (a, b, c, d) = (
            self.num as i128,
            self.den as i128,
            o.num as i128,
            o.den as i128,
        );
        Self::from_i128(a * d + c * b, b * d)
    }

    /// `self - o`, `None` on overflow.
    pub fn checked_sub(self, o: Rational) -> Option<Rational> {
        self.checked_add(o.checked_neg()?)
    }

    /// `self * o`, `None` on overflow.
    pub fn checked_mul(self, o: Rational) -> Option<Rational> {
        let (a, b, c, d) = (
            self.num as i128,
            self.den as i128,
            o.num as i128,
            o.den as i128,
        );
        Self::from_i128(a * c, b * d)
    }

    /// `self / o`, `None` on overflow or division by zero.
    pub fn checked_div(self, o: Rational) -> Option<Rational> {
        self.checked_mul(o.checked_recip()?)
    }

    /// `-self`, `None` only for `i64::MIN`.
    pub fn checked_neg(self) -> Option<Rational> {
        Some(Rational {
            num: self.num.checked_neg()?,
            den: self.den,
        })
    }

    /// `1 / self`, `None` for zero.
    pub fn checked_recip(self) -> Option<Rational> {
        Self::from_i128(self.den as i128, self.num as i128)
    }

    /// `self^n` by repeated squaring, `None` on overflow or `0^-n`.
    pub fn checked_pow(self, n: i64) -> Option<Rational> {
        let base = if n < 0 { self.checked_recip()? } else { self };
        let mut e = n.unsigned_abs();
        let mut acc = Rational::ONE;
        let mut sq = base;
        while e > 0 {
            if e & 1 == 1 {
                acc = acc.checked_mul(sq)?;
            }
            e >>= 1;
            if e > 0 {
                sq = sq.checked_mul(sq)?;
            }
        }
        Some(acc)
    }

    /// The exact square root, if `self` is the square of a rational.
    pub fn checked_sqrt(self) -> Option<Rational> {
        fn isqrt(v: i64) -> Option<i64> {
            if v < 0 {
                return None;
            }
            let mut r = (v as f64).sqrt() as i64;
            while r > 0 && r.checked_mul(r).is_none_or(|s| s > v) {
                r -= 1;
            }
            while (r + 1).checked_mul(r + 1).is_some_and(|s| s <= v) {
                r += 1;
            }
            (r * r == v).then_some(r)
        }
        Some(Rational {
            num: isqrt(self.num)?,
            den: isqrt(self.den)?,
        })
    }

    /// Whether the denominator is one.
    pub fn is_integer(self) -> bool {
        self.den == 1
    }

    /// The value as an `f64` (rounded).
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// The exact rational value of `v` if it is a "small" dyadic rational:
    /// `|v|·2^k` an integer below 2^53 for some `k <= 32`. Floats such as
    /// `0.1` (whose exact value has a huge power-of-two denominator) stay
    /// floats, which is what a reader of the generated code expects.
    pub fn from_f64(v: f64) -> Option<Rational> {
        if !v.is_finite() {
            return None;
        }
        let mut scaled = v;
        for k in 0..=32u32 {
            if scaled.fract() == 0.0 && scaled.abs() < 9_007_199_254_740_992.0 {
                return Rational::new(scaled as i64, 1i64 << k);
            }
            scaled *= 2.0;
        }
        None
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

/// A numeric coefficient during canonicalisation: exact while it can be,
/// a float once an operation overflows or a float constant is involved.
#[derive(Copy, Clone, Debug)]
pub(crate) enum Num {
    Rat(Rational),
    Float(f64),
}

impl PartialEq for Num {
    fn eq(&self, other: &Num) -> bool {
        match (self, other) {
            (Num::Rat(a), Num::Rat(b)) => a == b,
            (Num::Float(a), Num::Float(b)) => a.to_bits() == b.to_bits(),
            _ => false,
        }
    }
}

impl Eq for Num {}

impl Hash for Num {
    fn hash<H: Hasher>(&self, state: &mut H) {
        match self {
            Num::Rat(r) => r.hash(state),
            Num::Float(v) => v.to_bits().hash(state),
        }
    }
}

impl Num {
    pub(crate) const ZERO: Num = Num::Rat(Rational::ZERO);
    pub(crate) const ONE: Num = Num::Rat(Rational::ONE);
    pub(crate) const MINUS_ONE: Num = Num::Rat(Rational::MINUS_ONE);

    /// A float result, turned back into an exact rational when it is one.
    pub(crate) fn float(v: f64) -> Num {
        match Rational::from_f64(v) {
            Some(r) => Num::Rat(r),
            None => Num::Float(v),
        }
    }

    pub(crate) fn to_f64(self) -> f64 {
        match self {
            Num::Rat(r) => r.to_f64(),
            Num::Float(v) => v,
        }
    }

    fn exact_or(
        self,
        o: Num,
        exact: impl Fn(Rational, Rational) -> Option<Rational>,
        float: impl Fn(f64, f64) -> f64,
    ) -> Num {
        if let (Num::Rat(a), Num::Rat(b)) = (self, o)
            && let Some(r) = exact(a, b)
        {
            return Num::Rat(r);
        }
        Num::float(float(self.to_f64(), o.to_f64()))
    }

    pub(crate) fn add(self, o: Num) -> Num {
        self.exact_or(o, Rational::checked_add, |a, b| a + b)
    }

    pub(crate) fn mul(self, o: Num) -> Num {
        self.exact_or(o, Rational::checked_mul, |a, b| a * b)
    }

    pub(crate) fn neg(self) -> Num {
        self.mul(Num::MINUS_ONE)
    }

    pub(crate) fn is_zero(self) -> bool {
        self == Num::ZERO
    }

    pub(crate) fn is_one(self) -> bool {
        self == Num::ONE
    }

    pub(crate) fn is_negative(self) -> bool {
        self.to_f64() < 0.0
    }

    pub(crate) fn abs(self) -> Num {
        if self.is_negative() { self.neg() } else { self }
    }

    /// The exact integer value, if this is an integral rational.
    pub(crate) fn as_integer(self) -> Option<i64> {
        match self {
            Num::Rat(r) if r.is_integer() => Some(r.num),
            _ => None,
        }
    }

    /// `self^e` when the result is a number: exact for integral exponents
    /// and perfect squares, float whenever a float is involved; `None` when
    /// the power has to stay symbolic (e.g. `2^(1/2)`).
    pub(crate) fn pow(self, e: Num) -> Option<Num> {
        match (self, e) {
            (Num::Rat(b), Num::Rat(x)) => {
                if x.is_integer() {
                    return Some(match b.checked_pow(x.num) {
                        Some(r) => Num::Rat(r),
                        None => Num::float(b.to_f64().powf(x.to_f64())),
                    });
                }
                if x.den == 2 {
                    let root = b.checked_sqrt()?;
                    return Num::Rat(root).pow(Num::Rat(Rational::integer(x.num)));
                }
                None
            }
            _ => Some(Num::float(self.to_f64().powf(e.to_f64()))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalises() {
        assert_eq!(Rational::new(4, -6), Some(Rational { num: -2, den: 3 }));
        assert_eq!(Rational::new(0, -5), Some(Rational::ZERO));
        assert_eq!(Rational::new(1, 0), None);
    }

    #[test]
    fn arithmetic() {
        let a = Rational::new(1, 2).unwrap();
        let b = Rational::new(1, 3).unwrap();
        assert_eq!(a.checked_add(b), Rational::new(5, 6));
        assert_eq!(a.checked_sub(b), Rational::new(1, 6));
        assert_eq!(a.checked_mul(b), Rational::new(1, 6));
        assert_eq!(a.checked_div(b), Rational::new(3, 2));
        assert_eq!(b.checked_pow(-2), Rational::new(9, 1));
        assert_eq!(
            Rational::new(9, 4).unwrap().checked_sqrt(),
            Rational::new(3, 2)
        );
        assert_eq!(Rational::new(2, 1).unwrap().checked_sqrt(), None);
        assert_eq!(Rational::ZERO.checked_recip(), None);
    }

    #[test]
    fn overflow_is_none_and_num_falls_back_to_float() {
        let big = Rational::integer(i64::MAX);
        assert_eq!(big.checked_add(Rational::ONE), None);
        assert_eq!(Rational::integer(i64::MIN).checked_neg(), None);
        assert_eq!(Rational::integer(3).checked_pow(100), None);
        let n = Num::Rat(big).add(Num::ONE);
        assert!(matches!(n, Num::Float(_)));
        assert!((n.to_f64() - 9.223_372_036_854_776e18).abs() < 1e4);
    }

    #[test]
    fn from_f64_is_exact_for_small_dyadics_only() {
        assert_eq!(Rational::from_f64(0.5), Rational::new(1, 2));
        assert_eq!(Rational::from_f64(-3.0), Some(Rational::integer(-3)));
        assert_eq!(Rational::from_f64(0.1), None);
        assert_eq!(Rational::from_f64(f64::NAN), None);
    }
}
