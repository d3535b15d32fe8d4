//! Jittered strata: square grids, N-rooks, and the lens's orthogonal array against the film.

use crate::math::Vec2;

use super::*;

/// The lens stratum, on the `k×k` grid of a pixel of `k²` jittered samples, of the camera
/// sample `key` whose film stratum is `film`: the film cell `(i, j)` and the lens cell are one run of a strength-2
/// orthogonal array of four factors (Bose's construction; Jarosz et al., "Orthogonal Array
/// Sampling for Monte Carlo Rendering", EGSR 2019), `(i + j, i + 2j)` over the integers mod `k`
/// for odd `k` and `(i ⊕ j, i ⊕ x·j)` over polynomials mod `x^m + x + 1` for `k = 2^m ≥ 4`.
/// Each lens axis's levels are then shuffled per pixel. Every pair of the four coordinates (film
/// x, film y, lens x, lens y) then puts one sample in each cell of its `k×k` grid: the film
/// against the lens as the film against itself. Two forms `a·i + b·j` and `c·i + d·j` pair
/// that way when `ad − bc` is invertible, as every pair of `i`, `j`, `i + j` and `i + 2j` is
/// for odd `k` (and of `i`, `j`, `i ⊕ j`, `i ⊕ x·j`, where `x` and `x + 1` are invertible mod
/// `x^m + x + 1`, for `k = 2^m`). `None` where no such array is built here: a count that is
/// not a square, `k = 2`, or `k` twice an odd number (the lens then pairs with the film at
/// random, as it did).
pub(super) fn lens_stratum(key: &SampleKey, film: u32) -> Option<u32> {
    let k = square_side(key.spp);
    if k < 3 {
        return None;
    }
    let (i, j) = (film % k, film / k);
    let (a, b) = if k % 2 == 1 {
        ((i + j) % k, (i + 2 * j) % k)
    } else if k.is_power_of_two() {
        // Multiplying by x mod x^m + x + 1: shift, and fold the overflow back in.
        let mut xj = j << 1;
        if xj >= k {
            xj ^= k | 0b11;
        }
        (i ^ j, i ^ xj)
    } else {
        return None;
    };
    let shuffle = (key.pixel_hash(&[1, 0x0a]) & 0xffff_ffff) as u32;
    // Stratum `x + k·y`, as `stratum_point` lays out a square grid.
    Some(permute(a, k, shuffle) + k * permute(b, k, shuffle.rotate_left(16)))
}

/// The side `k` of the `k×k` grid of strata when `count` is a perfect square, else 0.
pub(super) fn square_side(count: u32) -> u32 {
    let k = (count as f64).sqrt() as u32;
    if k * k == count {
        k
    } else {
        0
    }
}

/// The point of stratum `index` out of `count` (at least 1), offset by `jitter ∈ [0,1)²` inside
/// its stratum. Perfect squares (`side` = [`square_side`] of `count`, nonzero) use a `k×k` grid;
/// other counts use N-rooks with columns shuffled by `shuffle`.
pub(super) fn stratum_point(index: u32, count: u32, side: u32, jitter: Vec2, shuffle: u32) -> Vec2 {
    let k = side;
    if k > 0 {
        let (i, j) = (index % k, index / k);
        Vec2::new(
            (i as f32 + jitter.x) / k as f32,
            (j as f32 + jitter.y) / k as f32,
        )
    } else {
        let column = permute(index, count, shuffle);
        Vec2::new(
            (index as f32 + jitter.x) / count as f32,
            (column as f32 + jitter.y) / count as f32,
        )
        .min(Vec2::splat(1.0 - f32::EPSILON / 2.0))
    }
}

/// A pseudo-random permutation of `0..len` evaluated at `i`, keyed by `key`: Kensler's hash-based
/// permutation with cycle walking ("Correlated Multi-Jittered Sampling", Pixar Technical Memo
/// 13-01, 2013, listing 3).
pub fn permute(mut i: u32, len: u32, key: u32) -> u32 {
    if len <= 1 {
        return 0;
    }
    let mut w = len - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= key;
        i = i.wrapping_mul(0xe170893d);
        i ^= key >> 16;
        i ^= (i & w) >> 4;
        i ^= key >> 8;
        i = i.wrapping_mul(0x0929eb3f);
        i ^= key >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | key >> 27);
        i = i.wrapping_mul(0x6935fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dcb303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e501cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860a3df);
        i &= w;
        i ^= i >> 5;
        if i < len {
            break;
        }
    }
    (i.wrapping_add(key)) % len
}
