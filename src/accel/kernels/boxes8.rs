//! Eight boxes against one ray in the lanes of one AVX register: the slab test of an eight-wide
//! node ([`crate::accel::Bvh8`]) where the CPU has AVX2 ([`super::Isa`]). Its twin is the node
//! test of `accel/wide.rs`, which makes the same test four boxes at a time in SSE lanes; lane
//! for lane the two do the same operations on the same values (`(plane − origin) · 1/dir`, then
//! `max` into the entry and `min` into the exit distance, with the operands in the same order,
//! so that a NaN from a ray lying in a slab's plane is ignored alike), and the tests of
//! `accel/wide.rs` compare their masks and entry distances bit for bit.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::{
    __m256, _mm256_castps256_ps128, _mm256_cmp_ps, _mm256_extractf128_ps, _mm256_loadu_ps,
    _mm256_max_ps, _mm256_min_ps, _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps,
    _mm256_setzero_ps, _mm256_sub_ps, _CMP_LE_OQ,
};

#[cfg(target_arch = "x86_64")]
use glam::Vec4;

#[cfg(target_arch = "x86_64")]
use super::Ray4;

/// The lower or the upper planes of eight boxes: a row of eight slots per axis.
#[cfg(target_arch = "x86_64")]
pub(in crate::accel) type Planes8 = [[f32; 8]; 3];

/// The boxes `lo[a][l]..hi[a][l]` (axis `a`, slot `l`) against the ray `r` whose direction has
/// the signs `NX`, `NY`, `NZ` (`true` for negative): bit `l` of the mask is set where the ray
/// meets box `l` between 0 and `t_max`, and lane `l % 4` of entry `l / 4` holds its entry
/// distance.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(in crate::accel) fn hit8<const NX: bool, const NY: bool, const NZ: bool>(
    lo: &Planes8,
    hi: &Planes8,
    r: &Ray4,
    t_max: f32,
) -> (u32, [Vec4; 2]) {
    // SAFETY: each row is eight `f32`s, read unaligned.
    let load = |row: &[f32; 8]| -> __m256 { unsafe { _mm256_loadu_ps(row.as_ptr()) } };
    let mut near = _mm256_setzero_ps();
    let mut far = _mm256_set1_ps(t_max);
    for (a, negative) in [NX, NY, NZ].into_iter().enumerate() {
        let (near_plane, far_plane) = if negative {
            (load(&hi[a]), load(&lo[a]))
        } else {
            (load(&lo[a]), load(&hi[a]))
        };
        let origin = _mm256_set1_ps(r.origin[a].x);
        let t_near = _mm256_mul_ps(
            _mm256_sub_ps(near_plane, origin),
            _mm256_set1_ps(r.inv_dir[a].x),
        );
        let t_far = _mm256_mul_ps(
            _mm256_sub_ps(far_plane, origin),
            _mm256_set1_ps(r.inv_dir_far[a].x),
        );
        // `max(t, acc)`: the second operand where either is NaN, as `Vec4::max` gives.
        near = _mm256_max_ps(t_near, near);
        far = _mm256_min_ps(t_far, far);
    }
    // Ordered `≤`: false where either side is NaN, as `Vec4::cmple`.
    let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
    let entry = [
        Vec4::from(_mm256_castps256_ps128(near)),
        Vec4::from(_mm256_extractf128_ps::<1>(near)),
    ];
    (mask, entry)
}
