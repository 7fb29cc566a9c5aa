//! Sines and cosines of several angles at once, four to a SIMD register.
//!
//! The emitted programs need sin and cos of the joint angles, and the C
//! library's `sincos` is a call per angle, with every value live across it
//! spilled and reloaded (the calls clobber every vector register), and a
//! cost that depends on the angle (glibc's has a short path below about
//! 0.86 rad and longer ones beyond). Here the angles of a program go through one
//! straight-line kernel in lanes of `wide::f64x4`: fdlibm's reduction by
//! π/2 (π/2 in three parts of 33 bits and a tail, the remainder kept to
//! first order in a tail of its own) and its kernels `__kernel_sin` and
//! `__kernel_cos`. The result is within an ulp of the C library's (the
//! tests below check that; measured, it equals glibc's on 97 % of 2 million
//! angles in |x| < 10), costs the same at every angle, and
//! does not depend on the lane an angle sits in, so the batched programs
//! (`lanes`) and the scalar ones agree to the bit. Products fuse where the
//! build targets FMA, as [`crate::numeric::func::mul_add`] does.
//!
//! Beyond |x| = [`REDUCED_BELOW`] (where n·π/2's parts stop being exact) an
//! angle is handed to the C library's `sin` and `cos`, lane by lane.

use wide::{f64x4, u64x4};

/// Angles up to this size are reduced here; larger finite ones go to the C
/// library's `sin` and `cos`. n = round(x · 2/π) then stays below 2¹⁹, so
/// n times each 33-bit part of π/2 is exact.
pub const REDUCED_BELOW: f64 = 8.0e5;

// fdlibm's (and musl's) constants, by their bits: π/2 in three 33-bit parts
// and a tail (p1 + p2 + p3 + p3t = π/2 to 151 bits), and the minimax
// coefficients of sin and cos on [−π/4, π/4].
const INV_PIO2: f64 = core::f64::consts::FRAC_2_PI;
const PIO2_1: f64 = f64::from_bits(0x3ff921fb54400000); // 1.5707963267341256
const PIO2_2: f64 = f64::from_bits(0x3dd0b4611a600000); // 6.077100506303966e-11
const PIO2_3: f64 = f64::from_bits(0x3ba3198a2e000000); // 2.0222662487111665e-21
const PIO2_3T: f64 = f64::from_bits(0x397b839a252049c1); // 8.4784276603689e-32
/// 1.5 · 2⁵²: x · 2/π + this rounds to the nearest integer, held in the low
/// bits of the sum.
const TO_INT: f64 = 6_755_399_441_055_744.0;
const S1: f64 = f64::from_bits(0xbfc5555555555549); // -0.16666666666666632
const S2: f64 = f64::from_bits(0x3f8111111110f8a6); // 0.00833333333332249
const S3: f64 = f64::from_bits(0xbf2a01a019c161d5); // -0.0001984126982985795
const S4: f64 = f64::from_bits(0x3ec71de357b1fe7d); // 2.7557313707070068e-06
const S5: f64 = f64::from_bits(0xbe5ae5e68a2b9ceb); // -2.5050760253406863e-08
const S6: f64 = f64::from_bits(0x3de5d93a5acfd57c); // 1.58969099521155e-10
const C1: f64 = f64::from_bits(0x3fa555555555554c); // 0.0416666666666666
const C2: f64 = f64::from_bits(0xbf56c16c16c15177); // -0.001388888888887411
const C3: f64 = f64::from_bits(0x3efa01a019cb1590); // 2.480158728947673e-05
const C4: f64 = f64::from_bits(0xbe927e4f809c52ad); // -2.7557314351390663e-07
const C5: f64 = f64::from_bits(0x3e21ee9ebdb4b1c4); // 2.087572321298175e-09
const C6: f64 = f64::from_bits(0xbda8fae9be8838d4); // -1.1359647557788195e-11

/// (sin xₖ, cos xₖ) for every angle, four at a time (one AVX register, or
/// two SSE2 or NEON ones). Not wider: on this project's AVX-512 machine,
/// eight lanes (one 512-bit register) made the whole program around the
/// call about twice as slow, since 512-bit instructions take over a port
/// the scalar code runs on.
///
/// ```
/// use lagrange_runtime::numeric::sincos::sin_cos_many;
/// let x = [0.3, -2.0, 7.5, 1e6];
/// let (s, c) = sin_cos_many(x);
/// for k in 0..4 {
///     // Within an ulp of the C library's values (1e6 is handed to it).
///     assert!((s[k] - x[k].sin()).abs() <= f64::EPSILON);
///     assert!((c[k] - x[k].cos()).abs() <= f64::EPSILON);
/// }
/// ```
#[inline(always)]
pub fn sin_cos_many<const K: usize>(x: [f64; K]) -> ([f64; K], [f64; K]) {
    let (mut s, mut c) = ([0.0; K], [0.0; K]);
    // Written out for up to four registers (the conditions are constants,
    // so each block is there or not), a loop beyond.
    let mut four = |at: usize| {
        if at < K {
            four_at(&x, at, (&mut s, &mut c));
        }
    };
    four(0);
    four(4);
    four(8);
    four(12);
    for at in (16..K).step_by(4) {
        four_at(&x, at, (&mut s, &mut c));
    }
    (s, c)
}

/// sin and cos of `x[at..at + 4]` (those of them there are) into `s` and
/// `c`, each angle read on its own: a load of four angles at once from
/// where they were just stored one by one (a state the runtime has just
/// written) waits until the stores reach the cache, which held the UR5's
/// q̈ up by a fifth.
#[inline(always)]
fn four_at<const K: usize>(x: &[f64; K], at: usize, (s, c): (&mut [f64; K], &mut [f64; K])) {
    let lane = |j: usize| if at + j < K { apart(x[at + j]) } else { 0.0 };
    let (sv, cv) = sin_cos_lanes(f64x4::new([lane(0), lane(1), lane(2), lane(3)]));
    let (sv, cv) = (sv.to_array(), cv.to_array());
    for j in 0..4 {
        if at + j < K {
            (s[at + j], c[at + j]) = (sv[j], cv[j]);
        }
    }
}

/// `x`, unchanged, through a register the compiler cannot see into, so
/// that angles read from neighbouring places stay separate loads: left to
/// itself, LLVM merges them into one load of a whole register, which waits
/// for the stores it overlaps to reach the cache when they were written
/// one by one just before (a failed store-to-load forward). Elsewhere than
/// on x86-64 the value is passed on as is.
#[inline(always)]
#[cfg_attr(not(target_arch = "x86_64"), allow(unused_mut))]
pub(crate) fn apart(mut x: f64) -> f64 {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: the template is empty (a comment naming the register): no
    // instruction runs, no memory is touched, and the register holds `x`
    // before and after.
    unsafe {
        core::arch::asm!(
            "/* {0} */",
            inout(xmm_reg) x,
            options(pure, nomem, nostack, preserves_flags)
        );
    }
    x
}

/// (sin x, cos x) in each of four lanes: the kernel where
/// |x| ≤ [`REDUCED_BELOW`] (or x is not finite, which gives NaN as the C
/// library does), the C library elsewhere.
#[inline(always)]
pub(crate) fn sin_cos_lanes(x: f64x4) -> (f64x4, f64x4) {
    let (s, c) = reduced(x);
    let big = x.abs().simd_gt(f64x4::splat(REDUCED_BELOW)) & x.is_finite();
    if !big.any() {
        return (s, c);
    }
    let (xs, mut s, mut c) = (x.to_array(), s.to_array(), c.to_array());
    for (k, big) in big.to_array().into_iter().enumerate() {
        if big != 0.0 {
            (s[k], c[k]) = xs[k].sin_cos();
        }
    }
    (f64x4::new(s), f64x4::new(c))
}

/// a b + c, fused where the build targets FMA.
#[inline(always)]
fn fma(a: f64x4, b: f64x4, c: f64x4) -> f64x4 {
    if cfg!(target_feature = "fma") {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// The reduction to [−π/4, π/4] and the quadrant, valid for
/// |x| ≤ [`REDUCED_BELOW`].
#[inline(always)]
fn reduced(x: f64x4) -> (f64x4, f64x4) {
    let splat = f64x4::splat;
    let shifted = fma(x, splat(INV_PIO2), splat(TO_INT));
    let n = shifted - splat(TO_INT);
    // x − n p1 is exact (Sterbenz), and so is the rounding error of its
    // difference with n p2 (Dekker's: n p2 has 53 bits at most, below
    // x − n p1's lowest where it is the larger); the rest of n π/2 joins
    // that error in the tail, which the kernels take to first order.
    let r1 = fma(-n, splat(PIO2_1), x);
    let np2 = n * splat(PIO2_2);
    let r = r1 - np2;
    let y = ((r1 - r) - np2) - n * splat(PIO2_3) - n * splat(PIO2_3T);
    let (s, c) = (kernel_sin(r, y), kernel_cos(r, y));
    // The quadrant n mod 4, in the low bits of `shifted`: odd swaps sin and
    // cos; sin changes sign in quadrants 2 and 3, cos in 1 and 2.
    let bits = shifted.to_bits();
    let (one, two, sign) = (u64x4::ONE, u64x4::splat(2), u64x4::splat(1 << 63));
    let odd = f64x4::from_bits((bits & one).simd_eq(one));
    let sin_sign = (bits & two).simd_eq(two) & sign;
    let cos_sign = ((bits + one) & two).simd_eq(two) & sign;
    let sin = f64x4::from_bits(odd.select(c, s).to_bits() ^ sin_sign);
    let cos = f64x4::from_bits(odd.select(s, c).to_bits() ^ cos_sign);
    (sin, cos)
}

/// sin(r + y) for |r + y| ≤ π/4, y the tail of r (fdlibm's `__kernel_sin`).
#[inline(always)]
fn kernel_sin(r: f64x4, y: f64x4) -> f64x4 {
    let splat = f64x4::splat;
    let z = r * r;
    let (w, v) = (z * z, z * r);
    let tail = fma(z, fma(z, splat(S4), splat(S3)), splat(S2));
    let p = fma(z * w, fma(z, splat(S6), splat(S5)), tail);
    r - (fma(z, fma(splat(0.5), y, -(v * p)), -y) - v * splat(S1))
}

/// cos(r + y) for |r + y| ≤ π/4, y the tail of r (fdlibm's `__kernel_cos`).
#[inline(always)]
fn kernel_cos(r: f64x4, y: f64x4) -> f64x4 {
    let splat = f64x4::splat;
    let z = r * r;
    let w = z * z;
    let head = fma(z, fma(z, splat(C3), splat(C2)), splat(C1));
    let p = fma(
        z,
        head,
        w * w * fma(z, fma(z, splat(C6), splat(C5)), splat(C4)),
    );
    let hz = splat(0.5) * z;
    let one_minus = splat(1.0) - hz;
    one_minus + (((splat(1.0) - one_minus) - hz) + (z * p - r * y))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place (of the larger of the two).
    fn ulps(a: f64, b: f64) -> f64 {
        if a == b {
            return 0.0;
        }
        let scale = a.abs().max(b.abs());
        let ulp = f64::from_bits(scale.to_bits() + 1) - scale;
        (a - b).abs() / ulp
    }

    fn worst(angles: impl Iterator<Item = f64>) -> (f64, f64) {
        let (mut worst, mut at) = (0.0f64, 0.0);
        let angles: Vec<f64> = angles.collect();
        for chunk in angles.chunks(4) {
            let mut lanes = [0.0; 4];
            lanes[..chunk.len()].copy_from_slice(chunk);
            let (s, c) = sin_cos_lanes(f64x4::new(lanes));
            for (k, &x) in chunk.iter().enumerate() {
                let e = ulps(s.to_array()[k], x.sin()).max(ulps(c.to_array()[k], x.cos()));
                if e > worst {
                    (worst, at) = (e, x);
                }
            }
        }
        (worst, at)
    }

    #[test]
    fn within_an_ulp_of_the_c_library_on_a_wide_range() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (e, at) = worst((0..200_000).map(|_| (next() - 0.5) * 20.0));
        assert!(e <= 1.0, "{e} ulp at {at}");
        let (e, at) = worst((0..200_000).map(|_| (next() - 0.5) * 2.0 * REDUCED_BELOW));
        assert!(e <= 1.0, "{e} ulp at {at}");
    }

    #[test]
    fn within_an_ulp_beside_multiples_of_a_quarter_turn() {
        // Where the reduction cancels most: n π/2 rounded, and its neighbours.
        let angles = (1..=4000i64).flat_map(|n| {
            let m = (n * n * 37) % 500_000 + n;
            let x = m as f64 * std::f64::consts::FRAC_PI_2;
            let up = |x: f64, k: u64| f64::from_bits(x.to_bits() + k);
            [x, up(x, 1), up(x, 2), f64::from_bits(x.to_bits() - 1), -x]
        });
        let (e, at) = worst(angles);
        assert!(e <= 1.0, "{e} ulp at {at}");
    }

    #[test]
    fn exact_where_the_c_library_is_and_nan_where_it_is() {
        let (s, c) = sin_cos_many([0.0, -0.0, 1e-300, f64::NAN, f64::INFINITY, 1e6, -3e9]);
        assert_eq!((s[0], c[0]), (0.0, 1.0));
        assert!(s[1] == 0.0 && c[1] == 1.0);
        assert_eq!((s[2], c[2]), (1e-300, 1.0));
        assert!(s[3].is_nan() && c[3].is_nan() && s[4].is_nan() && c[4].is_nan());
        assert_eq!((s[5], c[5]), 1e6f64.sin_cos());
        assert_eq!((s[6], c[6]), (-3e9f64).sin_cos());
    }

    #[test]
    fn every_lane_gives_the_same_bits() {
        let x = [0.3, -2.1, 7.9, std::f64::consts::FRAC_PI_2];
        let (s, c) = sin_cos_many(x);
        for k in 0..4 {
            let mut lanes = [0.0; 4];
            lanes[3 - k] = x[k];
            let (sv, cv) = sin_cos_lanes(f64x4::new(lanes));
            assert_eq!((sv.to_array()[3 - k], cv.to_array()[3 - k]), (s[k], c[k]));
        }
    }

    /// Each count of angles, through the blocks written out (up to 16) and
    /// the loop beyond, gives every angle its own lane's result.
    fn each_angle_its_own<const K: usize>() {
        let x: [f64; K] = core::array::from_fn(|k| 0.7 - 0.37 * k as f64);
        let (s, c) = sin_cos_many(x);
        for k in 0..K {
            let (sv, cv) = sin_cos_lanes(f64x4::splat(x[k]));
            assert_eq!(
                (s[k], c[k]),
                (sv.to_array()[0], cv.to_array()[0]),
                "{k} of {K}"
            );
        }
    }

    #[test]
    fn every_count_of_angles_gives_each_its_own() {
        each_angle_its_own::<1>();
        each_angle_its_own::<3>();
        each_angle_its_own::<4>();
        each_angle_its_own::<5>();
        each_angle_its_own::<12>();
        each_angle_its_own::<16>();
        each_angle_its_own::<17>();
        each_angle_its_own::<23>();
    }
}
