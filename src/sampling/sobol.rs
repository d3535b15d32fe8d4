//! Owen-scrambled Sobol points (Burley 2020), the `sobol_burley` crate's points from byte tables.

use crate::math::Vec2;

use super::*;

/// Point `index` of the 2D Owen-scrambled Sobol set keyed by `seed`: dimensions 0 and 1 of the
/// sequence, both scrambled and shuffled with `seed` so that they stay paired. The crate supports
/// indices below 2^16; later points continue in a fresh, independently seeded copy of the sequence
/// (still well spread, though the set is then no longer one net).
#[inline]
pub fn sobol2(index: u32, seed: u32) -> Vec2 {
    let [x, y, _, _] = sobol4(index, seed);
    Vec2::new(x, y)
}

/// Point `index` of the 4D Owen-scrambled Sobol set keyed by `seed`: dimensions 0 to 3 of the
/// sequence, continued past 2^16 points as [`sobol2`] is (the crate computes the four at once, in
/// SIMD lanes where the CPU has them, with the same integer arithmetic as one at a time).
#[inline]
pub fn sobol4(index: u32, seed: u32) -> [f32; 4] {
    const LEN: u32 = 1 << 16;
    let (block, i) = (index / LEN, index % LEN);
    let seed = if block == 0 {
        seed
    } else {
        (hash(&[seed as u64, block as u64]) >> 32) as u32
    };
    sobol_set0(i, seed)
}

/// The first 16 direction numbers of Sobol dimensions 0 to 3 (Joe and Kuo, "Constructing Sobol
/// sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30(5), 2008; their
/// `new-joe-kuo-6` set, which `sobol_burley` uses), one row per bit of the index from its most
/// significant, each number with its bits reversed as `sobol_burley` stores them. A test checks
/// them against the crate.
pub(super) const SOBOL_REV_VECTORS: [[u32; 4]; 16] = [
    [0x0000_0001, 0x0000_0001, 0x0000_0001, 0x0000_0001],
    [0x0000_0002, 0x0000_0003, 0x0000_0003, 0x0000_0003],
    [0x0000_0004, 0x0000_0005, 0x0000_0006, 0x0000_0004],
    [0x0000_0008, 0x0000_000f, 0x0000_0009, 0x0000_000a],
    [0x0000_0010, 0x0000_0011, 0x0000_0017, 0x0000_001f],
    [0x0000_0020, 0x0000_0033, 0x0000_003a, 0x0000_002e],
    [0x0000_0040, 0x0000_0055, 0x0000_0071, 0x0000_0045],
    [0x0000_0080, 0x0000_00ff, 0x0000_00a3, 0x0000_00c9],
    [0x0000_0100, 0x0000_0101, 0x0000_0116, 0x0000_011b],
    [0x0000_0200, 0x0000_0303, 0x0000_0339, 0x0000_02a4],
    [0x0000_0400, 0x0000_0505, 0x0000_0677, 0x0000_079a],
    [0x0000_0800, 0x0000_0f0f, 0x0000_09aa, 0x0000_0b67],
    [0x0000_1000, 0x0000_1111, 0x0000_1601, 0x0000_101e],
    [0x0000_2000, 0x0000_3333, 0x0000_3903, 0x0000_302d],
    [0x0000_4000, 0x0000_5555, 0x0000_7706, 0x0000_4041],
    [0x0000_8000, 0x0000_ffff, 0x0000_aa09, 0x0000_a0c3],
];

/// The Sobol matrices of dimensions 0 to 3 applied to every value of one byte of the
/// bit-reversed index: entry `[k][b]` is the XOR of the direction numbers of the bits set in `b`
/// when `b` is byte `k` (0 the most significant) of the index's top 16 bits. The matrices are
/// linear over GF(2), so two lookups give what a walk over the index's set bits gives.
pub(super) const SOBOL_BYTE_TABLES: [[[u32; 4]; 256]; 2] = {
    let mut tables = [[[0u32; 4]; 256]; 2];
    let mut k = 0;
    while k < 2 {
        let mut b = 0;
        while b < 256 {
            let mut bit = 0;
            while bit < 8 {
                if b & (0x80 >> bit) != 0 {
                    let row = SOBOL_REV_VECTORS[8 * k + bit];
                    let mut lane = 0;
                    while lane < 4 {
                        tables[k][b][lane] ^= row[lane];
                        lane += 1;
                    }
                }
                bit += 1;
            }
            b += 1;
        }
        k += 1;
    }
    tables
};

/// `sobol_burley::sample_4d(index, 0, seed)` bit for bit (`index` < 2^16), with the crate's
/// walk over the index's set bits (one data-dependent step per bit) replaced by two lookups in
/// [`SOBOL_BYTE_TABLES`]; the
/// index shuffle and the Owen scrambling are the crate's own.
#[inline]
pub(super) fn sobol_set0(index: u32, seed: u32) -> [f32; 4] {
    use sobol_burley::parts::{hash, hash_int4, owen_scramble_int4_rev, owen_scramble_rev, Int4};
    // Burley's nested uniform shuffle of the index, as the crate seeds it.
    let shuffled = owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c6_8e4a));
    let hi = SOBOL_BYTE_TABLES[0][(shuffled >> 24) as usize];
    let lo = SOBOL_BYTE_TABLES[1][((shuffled >> 16) & 0xff) as usize];
    let sobol = Int4::from([0, 1, 2, 3].map(|d| hi[d] ^ lo[d]));
    // The crate's per-dimension scramble keys for dimension set 0.
    let keys = Int4::from([seed.wrapping_mul(0x9c8f_2d3b); 4])
        ^ Int4::from([0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8]);
    owen_scramble_int4_rev(sobol, hash_int4(keys))
        .reverse_bits()
        .to_f32_norm()
}
