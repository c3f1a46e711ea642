//! Sine and cosine for generated code: one range reduction for both, straight-line and
//! inlined, so that a joint's `sin q` and `cos q` cost one short polynomial evaluation each
//! instead of two library calls (on the 8-link chain the sixteen calls were most of the
//! right-hand side's time).
//!
//! Method (Cody & Waite's reduction, the kernels of FreeBSD's `k_sin.c` / `k_cos.c`): `x =
//! k pi/2 + r`, `|r| <= pi/4`, with `pi/2` split into three 33-bit parts and a tail so that `k P1`,
//! `k P2` and `k P3` are exact for `|k| < 2^20` and `r` is carried as a head and a tail; then the
//! minimax polynomials of `sin r` and `cos r` on `[-pi/4, pi/4]` (errors below 2^-58), and
//! the quadrant's swap and signs. Measured against the platform's `sin`/`cos` (test
//! `within_one_ulp`): at most one unit in the last place apart. Arguments beyond
//! [`REDUCED_BELOW`] (and non-finite ones) go to the platform's functions.

#![allow(
    clippy::excessive_precision,
    reason = "the published digits of the kernels and of pi/2's parts, rounded by the compiler"
)]

/// `|x|` below which the three-part reduction is exact enough (`|k| < 2^19`).
pub const REDUCED_BELOW: f64 = 4.0e5;

// pi/2 = P1 + P2 + P3 + P3_TAIL, the first three of 33 significant bits.
const P1: f64 = 1.570_796_326_734_125_614_17e+00;
const P2: f64 = 6.077_100_506_303_965_976_60e-11;
const P3: f64 = 2.022_266_248_711_166_455_80e-21;
const P3_TAIL: f64 = 8.478_427_660_368_899_569_97e-32;
const TWO_OVER_PI: f64 = std::f64::consts::FRAC_2_PI;
/// `1.5 * 2^52`: adding it rounds to an integer, kept in the low bits of the sum.
const ROUND: f64 = 6_755_399_441_055_744.0;

const S1: f64 = -1.666_666_666_666_663_243_48e-01;
const S2: f64 = 8.333_333_333_322_489_461_24e-03;
const S3: f64 = -1.984_126_982_985_794_931_34e-04;
const S4: f64 = 2.755_731_370_707_006_767_89e-06;
const S5: f64 = -2.505_076_025_340_686_341_95e-08;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;

const C1: f64 = 4.166_666_666_666_660_190_37e-02;
const C2: f64 = -1.388_888_888_887_410_957_49e-03;
const C3: f64 = 2.480_158_728_947_672_941_78e-05;
const C4: f64 = -2.755_731_435_139_066_330_35e-07;
const C5: f64 = 2.087_572_321_298_174_827_90e-09;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;

/// `(sin x, cos x)`.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    // NaN fails the comparison too.
    if x.abs() >= REDUCED_BELOW || x.is_nan() {
        return (x.sin(), x.cos());
    }
    let shifted = x * TWO_OVER_PI + ROUND;
    let quadrant = shifted.to_bits();
    let k = shifted - ROUND;
    // x - k P1 is exact (Sterbenz); k P2 and k P3 are exact products.
    let t1 = x - k * P1;
    let w2 = k * P2;
    let t2 = t1 - w2;
    let e2 = (t1 - t2) - w2;
    let w3 = k * P3;
    let r = t2 - w3;
    let y = (((t2 - r) - w3) + e2) - k * P3_TAIL;
    let (s, c) = (kernel_sin(r, y), kernel_cos(r, y));
    // Quadrant k mod 4: (s, c), (c, -s), (-s, -c), (-c, s).
    let (s, c) = if quadrant & 1 == 0 { (s, c) } else { (c, -s) };
    if quadrant & 2 == 0 { (s, c) } else { (-s, -c) }
}

/// `(sin x_i, cos x_i)` for every `x_i`: the same operations as [`sin_cos`] (the same
/// values, bit for bit), with the quadrant's swap and signs chosen by bit masks instead of
/// branches, so that the compiler evaluates several arguments per vector instruction. A
/// joint tree's right-hand side takes all its joint angles' sines and cosines in one
/// call: on the 8-link chain they were a third of its time one at a time. Any argument
/// outside the reduced range sends the whole batch through [`sin_cos`].
#[inline(always)]
pub fn sin_cos_array<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
    // NaN fails the comparison too.
    if !x.iter().all(|v| v.abs() < REDUCED_BELOW) {
        let both = x.map(sin_cos);
        return (both.map(|p| p.0), both.map(|p| p.1));
    }
    let (mut sines, mut cosines) = ([0.0; N], [0.0; N]);
    for ((&x, s_out), c_out) in x.iter().zip(&mut sines).zip(&mut cosines) {
        let shifted = x * TWO_OVER_PI + ROUND;
        let quadrant = shifted.to_bits();
        let k = shifted - ROUND;
        let t1 = x - k * P1;
        let w2 = k * P2;
        let t2 = t1 - w2;
        let e2 = (t1 - t2) - w2;
        let w3 = k * P3;
        let r = t2 - w3;
        let y = (((t2 - r) - w3) + e2) - k * P3_TAIL;
        let (s, c) = (kernel_sin(r, y).to_bits(), kernel_cos(r, y).to_bits());
        // Odd quadrant: (c, -s); then quadrants 2 and 3 flip both signs.
        let odd = (quadrant & 1).wrapping_neg();
        let flip = (quadrant & 2) << 62;
        let minus_s = s ^ (1 << 63);
        *s_out = f64::from_bits(((s & !odd) | (c & odd)) ^ flip);
        *c_out = f64::from_bits(((c & !odd) | (minus_s & odd)) ^ flip);
    }
    (sines, cosines)
}

/// `sin x`; [`sin_cos`]'s first half (a `cos` of the same argument shares the reduction
/// once both are inlined).
#[inline(always)]
pub fn sin(x: f64) -> f64 {
    sin_cos(x).0
}

/// `cos x`; [`sin_cos`]'s second half.
#[inline(always)]
pub fn cos(x: f64) -> f64 {
    sin_cos(x).1
}

/// `sin(x + y)`, `|x| <= pi/4`, `y` the tail of `x` (`k_sin.c`).
#[inline(always)]
fn kernel_sin(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let v = z * x;
    x - ((z * (0.5 * y - v * r) - y) - v * S1)
}

/// `cos(x + y)`, `|x| <= pi/4`, `y` the tail of `x` (`k_cos.c`).
#[inline(always)]
fn kernel_cos(x: f64, y: f64) -> f64 {
    let z = x * x;
    let w = z * z;
    let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    let hz = 0.5 * z;
    let one_minus = 1.0 - hz;
    one_minus + (((1.0 - one_minus) - hz) + (z * r - x * y))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Units in the last place between `a` and the reference `b`.
    fn ulps(a: f64, b: f64) -> f64 {
        if a == b {
            return 0.0;
        }
        let ulp = f64::from_bits(b.abs().to_bits() + 1) - b.abs();
        (a - b).abs() / ulp
    }

    /// Against the platform's `sin` and `cos` over 2e6 arguments spread over
    /// `|x| < 1e-3 .. 4e5` (uniform in each decade, both signs), the multiples of
    /// `pi/4` near which the reduction cancels most, and exact zero: never more than one
    /// unit in the last place apart.
    #[test]
    fn within_one_ulp() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut args = vec![0.0, -0.0, 1e-300, 3.9e5];
        for decade in -3..6 {
            for _ in 0..200_000 {
                let x = 10f64.powi(decade) * 10.0 * next();
                args.push(if next() < 0.5 { x } else { -x });
            }
        }
        for k in 1..20_000 {
            let m = f64::from(k) * std::f64::consts::FRAC_PI_4;
            args.extend([
                m,
                f64::from_bits(m.to_bits() + 1),
                f64::from_bits(m.to_bits() - 1),
            ]);
        }
        let (mut worst_s, mut worst_c) = (0.0f64, 0.0f64);
        for &x in args.iter().filter(|x| x.abs() < REDUCED_BELOW) {
            let (s, c) = sin_cos(x);
            worst_s = worst_s.max(ulps(s, x.sin()));
            worst_c = worst_c.max(ulps(c, x.cos()));
        }
        assert!(
            worst_s <= 1.0 && worst_c <= 1.0,
            "sin {worst_s} ulp, cos {worst_c} ulp"
        );
    }

    /// The batch gives the scalar function's values bit for bit, in every quadrant, at the
    /// multiples of `pi/4`, and through the fallback (a large or NaN argument in the batch).
    #[test]
    fn batch_equals_scalar() {
        let mut x = [0.0f64; 64];
        for (i, v) in x.iter_mut().enumerate() {
            let k = i as f64 - 32.0;
            *v = k * 0.41
                + if i % 3 == 0 {
                    k * std::f64::consts::FRAC_PI_4
                } else {
                    0.0
                };
        }
        x[5] = -0.0;
        x[7] = 3.0e5;
        let same = |x: &[f64], s: &[f64], c: &[f64]| {
            x.iter().zip(s).zip(c).all(|((&x, &s), &c)| {
                let (s0, c0) = sin_cos(x);
                s.to_bits() == s0.to_bits() && c.to_bits() == c0.to_bits()
            })
        };
        let (s, c) = sin_cos_array(x);
        assert!(same(&x, &s, &c));
        for bad in [f64::NAN, 1e9, f64::NEG_INFINITY] {
            let mut y = [0.3, -2.0, 7.5];
            y[1] = bad;
            let (s, c) = sin_cos_array(y);
            assert_eq!(s[0], sin_cos(0.3).0);
            assert_eq!(c[2], sin_cos(7.5).1);
            let (s1, c1) = sin_cos(bad);
            assert!(s[1].to_bits() == s1.to_bits() || (s[1].is_nan() && s1.is_nan()));
            assert!(c[1].to_bits() == c1.to_bits() || (c[1].is_nan() && c1.is_nan()));
        }
    }

    /// Outside the reduced range and for non-finite arguments: the platform's values.
    #[test]
    fn large_and_non_finite_arguments() {
        for x in [4.0e5, -1e9, 1e300] {
            assert_eq!(sin_cos(x), (x.sin(), x.cos()));
        }
        let (s, c) = sin_cos(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
        let (s, c) = sin_cos(f64::INFINITY);
        assert!(s.is_nan() && c.is_nan());
        assert_eq!(sin(0.5), sin_cos(0.5).0);
        assert_eq!(cos(0.5), sin_cos(0.5).1);
    }
}
