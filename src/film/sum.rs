//! Exact sums of a pixel's samples, so that a render split into sample ranges and merged gives
//! the same bytes as the render done whole.
//!
//! Floating-point addition is not associative: `(a + b) + c` and `a + (b + c)` can differ in the
//! last bit, so summing samples 0..8 and 8..16 apart and adding the two sums would not equal the
//! sum of 0..16 taken in order. Here every sample's channel is rounded once to a multiple of
//! 2⁻⁴⁸ (about 3.6·10⁻¹⁵, twelve orders of magnitude below one 8-bit step) and added as an
//! integer, which is exact and so independent of order and grouping. The mean divides the exact
//! sum by the sample count and rounds once to `f32`.
//!
//! Non-finite samples keep their IEEE meaning: a NaN sample makes the channel NaN, as it would
//! in a float sum; an infinite one makes it infinite (NaN if both signs occur). A finite sample
//! beyond ±[`FINITE_LIMIT`] is clamped to it: it saturates any display a hundred million billion
//! times over, stays finite as it came, and keeps the integer sum of at most 2²⁰ samples below
//! 2¹²⁴, so that it never overflows its 128 bits.

use glam::Vec3;

/// Samples are rounded to integer multiples of `2^-FRACTION_BITS`.
const FRACTION_BITS: i32 = 48;

/// The largest sample value summed as it is: 2⁵⁶ (about 7.2·10¹⁶); finite samples beyond are
/// clamped to it.
pub const FINITE_LIMIT: f32 = (1u64 << 56) as f32;

/// `x + 1.5·2⁵² − 1.5·2⁵²` is `x` rounded to the nearest integer, ties to even, for
/// `|x| < 2⁵¹`: the sum lands where the doubles are spaced one apart, and the current rounding
/// mode (to nearest, ties to even: Rust never changes it) does the rounding.
const ROUNDER: f64 = 6_755_399_441_055_744.0;
const ROUNDS_BY_ADDING: f64 = 2_251_799_813_685_248.0;

/// The most samples one pixel may sum (the integer sum's headroom): 2²⁰.
pub const MAX_SAMPLES: u32 = 1 << 20;

/// `x` rounded to an integer, ties to even, for `x` up to 2¹⁰⁴. Kept out of line so that the
/// compiler does not compute its software conversion on every sample, the fast path's too.
#[cold]
#[inline(never)]
fn wide_round(x: f64) -> i128 {
    x.round_ties_even() as i128
}

/// `x` rounded to the nearest `f64`; out of line for the same reason as [`wide_round`].
#[cold]
#[inline(never)]
fn wide_to_f64(x: i128) -> f64 {
    x as f64
}

/// The exact sum of one colour channel's samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ChannelSum {
    /// The finite samples, in units of 2⁻⁴⁸.
    pub fixed: i128,
    /// Some sample was NaN.
    pub nan: bool,
    /// Some sample was +∞.
    pub pos_inf: bool,
    /// Some sample was −∞.
    pub neg_inf: bool,
}

impl ChannelSum {
    /// Adds one sample.
    #[inline]
    pub fn add(&mut self, v: f32) {
        if v.is_nan() {
            self.nan = true;
        } else if v == f32::INFINITY {
            self.pos_inf = true;
        } else if v == f32::NEG_INFINITY {
            self.neg_inf = true;
        } else {
            // v·2⁴⁸ is exact in f64 (a 24-bit mantissa times a power of two), and so is its
            // rounding to an integer below 2¹⁰⁴.
            let v = v.clamp(-FINITE_LIMIT, FINITE_LIMIT);
            let scaled = f64::from(v) * f64::from(FRACTION_BITS).exp2();
            self.fixed += if scaled.abs() < ROUNDS_BY_ADDING {
                // The same integer, without the software rounding and 128-bit conversion.
                ((scaled + ROUNDER) - ROUNDER) as i64 as i128
            } else {
                wide_round(scaled)
            };
        }
    }

    /// What [`ChannelSum::mean`] gives for the sum of the one sample `v`, without the sum.
    ///
    /// A finite `v` with `2⁻²⁵ ≤ |v| ≤` [`FINITE_LIMIT`] is a whole number of units of 2⁻⁴⁸
    /// (its 24-bit significand's last place is at least 2⁻⁴⁸), so its rounding keeps it, and the
    /// mean of one is `v` itself. Anything else (zeros, whose sign the sum drops, tiny values,
    /// non-finite and clamped ones) goes through the sum.
    #[inline]
    pub fn mean_of_one(v: f32) -> f32 {
        const SMALLEST_WHOLE: f32 = 1.0 / (1u64 << 25) as f32;
        if (SMALLEST_WHOLE..=FINITE_LIMIT).contains(&v.abs()) {
            v
        } else {
            let mut s = ChannelSum::default();
            s.add(v);
            s.mean(1)
        }
    }

    /// Adds another sum (of other samples of the same pixel).
    pub fn merge(&mut self, other: &ChannelSum) {
        self.fixed += other.fixed;
        self.nan |= other.nan;
        self.pos_inf |= other.pos_inf;
        self.neg_inf |= other.neg_inf;
    }

    /// The mean of `count` samples summed here, rounded to `f32`; NaN for no samples.
    pub fn mean(&self, count: u32) -> f32 {
        if self.nan || (self.pos_inf && self.neg_inf) || count == 0 {
            f32::NAN
        } else if self.pos_inf {
            f32::INFINITY
        } else if self.neg_inf {
            f32::NEG_INFINITY
        } else {
            // One rounding to f64 (exact below 2⁵³ units), one exact scaling, one division,
            // one rounding to f32: a fixed sequence, so equal sums give equal means.
            // A sum that fits in 64 bits converts as one (the same correctly rounded value).
            let fixed = match i64::try_from(self.fixed) {
                Ok(small) => small as f64,
                Err(_) => wide_to_f64(self.fixed),
            };
            let sum = fixed * f64::from(-FRACTION_BITS).exp2();
            (sum / f64::from(count)) as f32
        }
    }
}

/// The exact sums of a pixel's red, green and blue samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PixelSum(pub [ChannelSum; 3]);

impl PixelSum {
    /// Adds one sample's radiance.
    #[inline]
    pub fn add(&mut self, c: Vec3) {
        self.0[0].add(c.x);
        self.0[1].add(c.y);
        self.0[2].add(c.z);
    }

    /// Adds the sums of other samples of the same pixel.
    pub fn merge(&mut self, other: &PixelSum) {
        for (a, b) in self.0.iter_mut().zip(&other.0) {
            a.merge(b);
        }
    }

    /// The mean a pixel of the one sample `c` has: [`ChannelSum::mean_of_one`] per channel.
    #[inline]
    pub fn mean_of_one(c: Vec3) -> Vec3 {
        c.to_array().map(ChannelSum::mean_of_one).into()
    }

    /// The mean radiance of `count` samples summed here.
    pub fn mean(&self, count: u32) -> Vec3 {
        Vec3::new(
            self.0[0].mean(count),
            self.0[1].mean(count),
            self.0[2].mean(count),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum_of(values: &[f32]) -> ChannelSum {
        let mut s = ChannelSum::default();
        for &v in values {
            s.add(v);
        }
        s
    }

    #[test]
    fn rounding_by_adding_is_round_ties_even() {
        assert_eq!(ROUNDER, 1.5 * 2f64.powi(52));
        assert_eq!(ROUNDS_BY_ADDING, 2f64.powi(51));
        let mut values = vec![
            0.5,
            1.5,
            2.5,
            -0.5,
            -1.5,
            -2.5,
            0.49999999999999994,
            1e-300,
            -0.0,
        ];
        for k in 0..52 {
            let x = 2f64.powi(k);
            values.extend([x - 0.5, x + 0.5, -x - 0.5, x * 1.2345, -x * 0.987, x * 0.75]);
        }
        values.push(ROUNDS_BY_ADDING - 0.5);
        values.push(-(ROUNDS_BY_ADDING - 0.5));
        for x in values.into_iter().filter(|x| x.abs() < ROUNDS_BY_ADDING) {
            assert_eq!((x + ROUNDER) - ROUNDER, x.round_ties_even(), "{x}");
        }
        // Both paths of `add`, and both of `mean`, agree with the 128-bit arithmetic.
        for v in [0.1f32, 7.99, 8.0, 8.01, 1e3, -3.3, 1e10, FINITE_LIMIT] {
            let mut s = ChannelSum::default();
            s.add(v);
            let want = (f64::from(v) * 2f64.powi(48)).round_ties_even() as i128;
            assert_eq!(s.fixed, want, "{v}");
            assert_eq!(s.mean(1), (want as f64 * 2f64.powi(-48)) as f32, "{v}");
        }
    }

    #[test]
    fn any_split_and_order_gives_the_same_sum() {
        // Values whose float sum depends on the order: large and small mixed.
        let values: Vec<f32> = (0..97)
            .map(|i| ((i * 7919) % 1000) as f32 * 1.37e-3 + if i % 5 == 0 { 3.0e4 } else { 0.0 })
            .collect();
        let whole = sum_of(&values);
        for cut in [0, 1, 13, 50, 96, 97] {
            let mut a = sum_of(&values[..cut]);
            a.merge(&sum_of(&values[cut..]));
            assert_eq!(a, whole, "cut at {cut}");
        }
        let mut reversed: Vec<f32> = values.clone();
        reversed.reverse();
        assert_eq!(sum_of(&reversed), whole);
        // Float sums do depend on the order, which is why this module exists.
        let (forward, backward) = ((1.0f32 + 1e8) - 1e8, (-1e8f32 + 1e8) + 1.0);
        assert_ne!(forward, backward);
        assert_eq!(sum_of(&[1.0, 1e8, -1e8]), sum_of(&[-1e8, 1e8, 1.0]));
        assert_eq!(sum_of(&[1.0, 1e8, -1e8]).mean(1), 1.0);
    }

    #[test]
    fn mean_is_within_one_rounding_of_the_true_mean() {
        let values = [0.1f32, 0.2, 0.3, 1.0e-3, 7.5];
        let exact: f64 = values.iter().map(|&v| f64::from(v)).sum::<f64>() / 5.0;
        let mean = sum_of(&values).mean(5);
        assert!(
            (f64::from(mean) - exact).abs() <= exact * 1e-7,
            "{mean} vs {exact}"
        );
        // One sample of a representable value comes back exactly.
        for v in [0.0f32, 1.0, 0.5, 0.123_456_79, 1.0e-6, 3.0e9, -2.5] {
            assert_eq!(sum_of(&[v]).mean(1), v);
        }
    }

    /// The shortcut for one sample gives the sum's mean bit for bit: on every power of two and
    /// its neighbours, the ends of the shortcut's range, zeros, subnormals, non-finite values
    /// and a spread of bit patterns.
    #[test]
    fn the_mean_of_one_sample_is_the_sums() {
        let mut bits: Vec<u32> = (0..=255u32)
            .flat_map(|e| {
                [
                    e << 23,
                    (e << 23) | 1,
                    (e << 23) | 0x7f_ffff,
                    (e << 23) | 0x40_0000,
                ]
            })
            .collect();
        bits.extend((0..200_000u32).map(|i| i.wrapping_mul(0x9e37_79b9) ^ (i >> 3)));
        let limits = [2f32.powi(-25), FINITE_LIMIT];
        bits.extend(
            limits
                .iter()
                .flat_map(|l| [l.to_bits() - 1, l.to_bits(), l.to_bits() + 1]),
        );
        for b in bits {
            for v in [f32::from_bits(b), -f32::from_bits(b)] {
                let want = sum_of(&[v]).mean(1);
                let got = ChannelSum::mean_of_one(v);
                assert_eq!(got.to_bits(), want.to_bits(), "{v:e} ({b:#x})");
            }
        }
        // The range's lower end matters: below it the sum rounds the sample.
        let below = f32::from_bits(2f32.powi(-25).to_bits() - 1);
        assert_ne!(sum_of(&[below]).mean(1), below);
        let c = Vec3::new(0.25, -0.0, 1e-30);
        let mut p = PixelSum::default();
        p.add(c);
        assert_eq!(
            PixelSum::mean_of_one(c).to_array().map(f32::to_bits),
            p.mean(1).to_array().map(f32::to_bits)
        );
    }

    #[test]
    fn non_finite_samples_keep_their_meaning() {
        assert!(sum_of(&[1.0, f32::NAN, 2.0]).mean(3).is_nan());
        assert_eq!(sum_of(&[1.0, f32::INFINITY]).mean(2), f32::INFINITY);
        assert_eq!(sum_of(&[f32::NEG_INFINITY, 1.0]).mean(2), f32::NEG_INFINITY);
        assert!(sum_of(&[f32::INFINITY, f32::NEG_INFINITY]).mean(2).is_nan());
        assert_eq!(sum_of(&[3.0e38]).mean(1), FINITE_LIMIT);
        assert_eq!(sum_of(&[-f32::MAX, 1.0]).mean(2), -FINITE_LIMIT / 2.0);
        assert_eq!(sum_of(&[FINITE_LIMIT]).mean(1), FINITE_LIMIT);
        // Infinities from different parts combine as in one sum.
        let mut a = sum_of(&[f32::INFINITY]);
        a.merge(&sum_of(&[f32::NEG_INFINITY]));
        assert!(a.mean(2).is_nan());
        assert!(ChannelSum::default().mean(0).is_nan());
    }

    #[test]
    fn the_largest_sums_do_not_overflow() {
        let mut s = ChannelSum::default();
        let mut big = ChannelSum::default();
        big.add(FINITE_LIMIT);
        big.fixed *= i128::from(MAX_SAMPLES);
        s.merge(&big);
        assert_eq!(s.mean(MAX_SAMPLES), FINITE_LIMIT);
    }

    #[test]
    fn pixel_sum_sums_each_channel() {
        let mut p = PixelSum::default();
        p.add(Vec3::new(1.0, 2.0, 3.0));
        p.add(Vec3::new(3.0, 2.0, 1.0));
        assert_eq!(p.mean(2), Vec3::splat(2.0));
    }
}
