//! The hash every random number comes from: SplitMix64's finaliser over a sequence of words.

/// A 64-bit mixing function with full avalanche (the finaliser of SplitMix64, Steele et al.,
/// "Fast Splittable Pseudorandom Number Generators", OOPSLA 2014).
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hashes a sequence of words into one.
#[inline]
pub fn hash(words: &[u64]) -> u64 {
    hash_on(0x9e37_79b9_7f4a_7c15, words)
}

/// [`hash`] continued from state `h`: `hash_on(hash(a), b)` is `hash` of `a` then `b`.
#[inline]
pub(super) fn hash_on(mut h: u64, words: &[u64]) -> u64 {
    for &w in words {
        h = mix64(h ^ w.wrapping_add(0x9e37_79b9_7f4a_7c15));
    }
    h
}

/// A uniform `f32` in `[0, 1)` from the top 24 bits of a hash.
#[inline]
pub fn to_unit(h: u64) -> f32 {
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}
