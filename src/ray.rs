//! Rays, surface hits, and the robust origin offset that keeps spawned rays from re-hitting the
//! surface they leave.

use crate::math::{dot4, splat4, Vec2, Vec3};
use glam::{BVec3A, Vec3A, Vec4};

/// A ray `origin + t·dir`. `dir` need not be unit length for intersection, but every ray the
/// renderer spawns has a unit direction so that `t` is a distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
}

impl Ray {
    pub fn new(origin: Vec3, dir: Vec3) -> Ray {
        Ray { origin, dir }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

/// A ray with the values every box and triangle test of one traversal shares, computed once per
/// ray instead of once per test: the reciprocal direction and its signs for the slab test, and
/// the axis permutation and shear of the watertight triangle test (Woop et al. 2013, §3). The
/// values are computed exactly as the per-test code would, so a test gives the same bits either
/// way.
#[derive(Debug, Clone, Copy)]
pub struct PreparedRay {
    pub ray: Ray,
    /// The origin, in SIMD form for the slab test.
    pub origin: Vec3A,
    /// `1 / dir` (±∞ for zero components, with the sign of the zero).
    pub inv_dir: Vec3A,
    /// `inv_dir · (1 + 2γ(3))`: far slab distances are computed with it, which widens them as
    /// Ize's robust slab test requires (see [`crate::accel::aabb::slab`]).
    pub inv_dir_far: Vec3A,
    /// Per axis, whether `inv_dir` is negative (the ray meets the slab's upper plane first).
    pub negative: BVec3A,
    /// The axis of the largest `|dir|` component; the triangle test maps it to z.
    pub kz: usize,
    /// Shear `(-d_x/d_z, -d_y/d_z, 1/d_z)` of the permuted direction.
    pub shear: Vec3,
    /// Whether the triangle test can run at all (`d_z` nonzero and finite).
    pub shear_ok: bool,
}

impl PreparedRay {
    #[inline]
    pub fn new(ray: &Ray) -> PreparedRay {
        let d = ray.dir;
        let inv_dir = Vec3A::ONE / Vec3A::from(d);
        let kz = crate::math::max_dimension(d.abs());
        let [kx, ky, _] = axis_permutation(kz);
        let (dx, dy, dz) = (d[kx], d[ky], d[kz]);
        PreparedRay {
            ray: *ray,
            origin: ray.origin.into(),
            inv_dir,
            inv_dir_far: inv_dir * crate::accel::aabb::SLAB_WIDEN,
            negative: inv_dir.cmplt(Vec3A::ZERO),
            kz,
            shear: Vec3::new(-dx / dz, -dy / dz, 1.0 / dz),
            shear_ok: dz != 0.0 && dz.is_finite(),
        }
    }
}

/// The watertight triangle test's axis permutation `[kx, ky, kz]` for the ray's largest direction
/// axis `kz`: the other two in cyclic order, so that the permutation keeps the winding.
#[inline]
pub fn axis_permutation(kz: usize) -> [usize; 3] {
    let kx = if kz == 2 { 0 } else { kz + 1 };
    let ky = if kx == 2 { 0 } else { kx + 1 };
    [kx, ky, kz]
}

/// Where a ray meets a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// The hit point.
    pub point: Vec3,
    /// Per-axis bound on the absolute floating-point error of `point`.
    pub error: Vec3,
    /// Unit geometric normal. Spheres and cylinders: outward; triangles: by winding (v1−v0)×(v2−v0).
    pub normal: Vec3,
    /// Unit shading normal (interpolated vertex normals where a mesh has them), same side as `normal`.
    pub shading_normal: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Index of the primitive that was hit.
    pub prim: u32,
}

/// Origin for a ray leaving a surface point `p` (with error bound `error`) with geometric normal `n`
/// in direction `w`: `p` pushed along `±n` just past its error box, on the side `w` points to, then
/// rounded away from `p` (pbrt-v4 §6.8.6 "Robust Spawned Ray Origins").
#[inline]
pub fn offset_ray_origin(p: Vec3, error: Vec3, n: Vec3, w: Vec3) -> Vec3 {
    let offset = surface_offset(error, n);
    if w.dot(n) < 0.0 {
        rounded_away(p - offset, -offset)
    } else {
        rounded_away(p + offset, offset)
    }
}

/// How far along `n` a point with error bound `error` must move to leave the surface's error box.
#[inline]
fn surface_offset(error: Vec3, n: Vec3) -> Vec3 {
    n.abs().dot(error) * n
}

/// `po` (a point moved by `offset`) rounded one step further in each component `offset` moves:
/// [`rounded_away_scalar`]'s bits, in SIMD lanes and without a branch where the CPU has SSE2.
/// The offset points along the surface normal, whose signs change from one hit to the next, so
/// the scalar form's per-component branches predict poorly.
#[inline]
fn rounded_away(po: Vec3, offset: Vec3) -> Vec3 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        use std::arch::x86_64::*;
        // SAFETY: SSE2 is enabled for this target (checked at compile time above), and these
        // intrinsics only compute on their register operands.
        unsafe {
            let x: __m128 = po.extend(0.0).into();
            let d: __m128 = offset.extend(0.0).into();
            let zero = _mm_setzero_ps();
            let pick = |m: __m128i, a: __m128i, b: __m128i| {
                _mm_or_si128(_mm_and_si128(m, a), _mm_andnot_si128(m, b))
            };
            let bits = _mm_castps_si128(x);
            let one = _mm_set1_epi32(1);
            // A step up or down moves a float's bits one away from zero where its sign (a NaN
            // counts as negative, as `x >= 0` fails) is the step's, one towards zero where not.
            let negative = _mm_castps_si128(_mm_cmpnge_ps(x, zero));
            let down = _mm_castps_si128(_mm_cmplt_ps(d, zero));
            let up = _mm_castps_si128(_mm_cmpgt_ps(d, zero));
            let towards_zero = _mm_xor_si128(negative, down);
            let moved = _mm_add_epi32(bits, _mm_or_si128(towards_zero, one));
            // From ±0 the step is to the least float of the step's sign.
            let from_zero = _mm_or_si128(_mm_and_si128(down, _mm_set1_epi32(i32::MIN)), one);
            let moved = pick(_mm_castps_si128(_mm_cmpeq_ps(x, zero)), from_zero, moved);
            // An infinity stepped away from zero stays; a zero or NaN offset moves nothing.
            let magnitude = _mm_and_ps(x, _mm_castsi128_ps(_mm_set1_epi32(i32::MAX)));
            let infinite = _mm_castps_si128(_mm_cmpeq_ps(magnitude, _mm_set1_ps(f32::INFINITY)));
            let stays = _mm_andnot_si128(towards_zero, infinite);
            let moving = _mm_andnot_si128(stays, _mm_or_si128(down, up));
            let moved = pick(moving, moved, bits);
            Vec4::from(_mm_castsi128_ps(moved)).truncate()
        }
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        rounded_away_scalar(po, offset)
    }
}

/// The scalar twin of [`rounded_away`]: each component of `po` one float up where `offset` is
/// positive, one down where it is negative, as it is elsewhere (zero or NaN).
#[cfg_attr(all(target_arch = "x86_64", target_feature = "sse2"), allow(dead_code))]
#[inline]
fn rounded_away_scalar(mut po: Vec3, offset: Vec3) -> Vec3 {
    for i in 0..3 {
        if offset[i] > 0.0 {
            po[i] = crate::math::next_float_up(po[i]);
        } else if offset[i] < 0.0 {
            po[i] = crate::math::next_float_down(po[i]);
        }
    }
    po
}

impl Hit {
    /// A ray leaving this hit in direction `w` (unit), from a robustly offset origin.
    #[inline]
    pub fn spawn(&self, w: Vec3) -> Ray {
        Ray::new(offset_ray_origin(self.point, self.error, self.normal, w), w)
    }

    /// A ray from this hit towards `target`, returning the ray (unit direction) and the distance
    /// from the offset origin to the target.
    #[inline]
    pub fn spawn_to(&self, target: Vec3) -> (Ray, f32) {
        let w = (target - self.point).normalize_or_zero();
        let origin = offset_ray_origin(self.point, self.error, self.normal, w);
        let to = target - origin;
        let dist = to.length();
        (Ray::new(origin, to / dist.max(f32::MIN_POSITIVE)), dist)
    }
}

/// The two origins rays leave a hit from (just above and just below the surface), worked out once
/// for a shading point that spawns many rays, such as the shadow rays towards an area light.
/// [`SpawnPoints::ray_to`] gives exactly what [`Hit::spawn_to`] gives.
#[derive(Debug, Clone, Copy)]
pub struct SpawnPoints {
    point: Vec3,
    normal: Vec3,
    /// The origin for directions with `w · normal ≥ 0`.
    above: Vec3,
    /// The origin for directions with `w · normal < 0`.
    below: Vec3,
}

/// Which of a hit's two spawn origins a ray leaves from (see [`SpawnPoints`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Just above the surface, for directions with `w · normal ≥ 0`.
    Above = 0,
    /// Just below it, for directions with `w · normal < 0`.
    Below = 1,
}

impl SpawnPoints {
    /// The side a ray leaving in direction `w` starts on: `offset_ray_origin` depends on the
    /// direction only through the sign of `w · normal`.
    #[inline]
    pub fn side(&self, w: Vec3) -> Side {
        if w.dot(self.normal) < 0.0 {
            Side::Below
        } else {
            Side::Above
        }
    }

    /// The origin on `side`.
    #[inline]
    pub fn origin_on(&self, side: Side) -> Vec3 {
        match side {
            Side::Above => self.above,
            Side::Below => self.below,
        }
    }

    /// The origin of a ray leaving in direction `w`.
    #[inline]
    fn origin(&self, w: Vec3) -> Vec3 {
        self.origin_on(self.side(w))
    }

    /// The side the ray of [`SpawnPoints::ray_to`] `target` starts on: the sign of
    /// `normalize_or_zero(v) · normal` for `v = target − point`.
    ///
    /// Where `v · normal` is far from zero against its rounding, that sign is the sign of `v ·
    /// normal` itself, and the normalisation (a square root and a division) is skipped. With
    /// `S = Σ|vᵢ·nᵢ|`, the computed `v · n` is within γ(3)·S of the exact one, and the computed
    /// `w · n` of the normalised `w` within γ(4)·S·(1/|v|) of `(1/|v|)·(v · n)` (each `wᵢ`
    /// rounds once more): beyond γ(8)·S both have the exact product's sign. The bounds on `|v|`
    /// and `S` keep every product and `1/|v|` far from underflow and overflow; outside them (and
    /// for NaN) the side comes from the normalised direction.
    #[inline]
    pub fn side_to(&self, target: Vec3) -> Side {
        const SMALLEST: f32 = 1.0 / (1u64 << 60) as f32;
        const LARGEST: f32 = (1u64 << 60) as f32;
        let v = target - self.point;
        let dot = v.dot(self.normal);
        let spread = v.abs().dot(self.normal.abs());
        let length2 = v.length_squared();
        if (SMALLEST..=LARGEST).contains(&length2)
            && spread >= SMALLEST
            && dot.abs() > crate::math::gamma(8) * spread
        {
            return if dot < 0.0 { Side::Below } else { Side::Above };
        }
        self.side(v.normalize_or_zero())
    }

    /// [`Hit::spawn`] from the hit these points were made for.
    #[inline]
    pub fn ray(&self, w: Vec3) -> Ray {
        Ray::new(self.origin(w), w)
    }

    /// How far the origins are from the hit point.
    #[inline]
    pub fn offset(&self) -> f32 {
        (self.above - self.point)
            .length()
            .max((self.below - self.point).length())
    }

    /// [`Hit::spawn_to`] from the hit these points were made for.
    #[inline]
    pub fn ray_to(&self, target: Vec3) -> (Ray, f32) {
        self.ray_from(self.side_to(target), target)
    }

    /// The ray of [`SpawnPoints::ray_to`] `target`, whose side `side` the caller has found with
    /// [`SpawnPoints::side_to`].
    #[inline]
    pub fn ray_from(&self, side: Side, target: Vec3) -> (Ray, f32) {
        let origin = self.origin_on(side);
        let to = target - origin;
        let dist = to.length();
        (Ray::new(origin, to / dist.max(f32::MIN_POSITIVE)), dist)
    }
}

/// Four rays of [`SpawnPoints::rays_to4`], per world axis one lane per ray.
#[derive(Debug, Clone, Copy)]
pub struct RaysTo4 {
    pub origin: [Vec4; 3],
    pub dir: [Vec4; 3],
    /// The distance from each origin to its target.
    pub dist: Vec4,
    /// Bit `l` is set where ray `l` leaves from [`Side::Below`].
    pub below: u32,
}

impl SpawnPoints {
    /// [`SpawnPoints::ray_to`] for four targets at once (per world axis one lane per target):
    /// lane by lane the same operations in the same order, so the same bits, with the side each
    /// ray leaves from.
    #[inline(always)]
    pub fn rays_to4(&self, target: [Vec4; 3]) -> RaysTo4 {
        let zero = Vec4::ZERO;
        let [point, normal, above, below] =
            [self.point, self.normal, self.above, self.below].map(splat4);
        // `side_to`: the sign of `normalize_or_zero(target − point) · normal`.
        let w = [0, 1, 2].map(|a| target[a] - point[a]);
        let rcp = Vec4::ONE / crate::math::sqrt4(dot4(&w, &w));
        let normalized = rcp.abs().cmplt(Vec4::INFINITY) & rcp.cmpgt(zero);
        let w = w.map(|c| Vec4::select(normalized, c * rcp, zero));
        let leaves_below = dot4(&w, &normal).cmplt(zero);
        // `ray_from`.
        let origin = [0, 1, 2].map(|a| Vec4::select(leaves_below, below[a], above[a]));
        let to = [0, 1, 2].map(|a| target[a] - origin[a]);
        let dist = crate::math::sqrt4(dot4(&to, &to));
        // `max` returns its second operand for NaN, as `f32::max` returns the number.
        let len = dist.max(Vec4::splat(f32::MIN_POSITIVE));
        RaysTo4 {
            origin,
            dir: to.map(|c| c / len),
            dist,
            below: leaves_below.bitmask(),
        }
    }
}

impl Hit {
    /// The origins of every ray this hit may spawn (see [`SpawnPoints`]).
    #[inline]
    pub fn spawn_points(&self) -> SpawnPoints {
        let offset = surface_offset(self.error, self.normal);
        SpawnPoints {
            point: self.point,
            normal: self.normal,
            above: rounded_away(self.point + offset, offset),
            below: rounded_away(self.point - offset, -offset),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `side_to` gives the side of the normalised direction's dot product, whether or not it
    /// takes the short way: on random directions, directions within a few units of the last
    /// place of the surface's plane, tiny and huge distances and non-finite targets; and the
    /// short way decides most rays that are not grazing.
    #[test]
    fn the_side_without_the_normalisation_is_the_normalised_side() {
        let mut rng = crate::accel::kernels::twin::Rng(0x2545_f491_4f6c_dd1d);
        let mut unit = || {
            rng.next();
            ((rng.0 >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
        };
        let (mut cases, mut decided) = (0usize, 0usize);
        for i in 0..40_000 {
            let normal = Vec3::new(unit(), unit(), unit()).normalize_or(Vec3::Z);
            let point = Vec3::new(unit(), unit(), unit()) * 10.0;
            let points = SpawnPoints {
                point,
                normal,
                above: point,
                below: point,
            };
            let mut dir = Vec3::new(unit(), unit(), unit());
            if i % 3 == 0 {
                // Nearly in the plane: the component along the normal removed, then a hair back.
                dir -= dir.dot(normal) * normal;
                dir += normal * unit() * 1e-6;
            }
            let scale = [1.0, 1e-12, 1e12, 1e-20, 1e20, 3.0e-3][(i / 3) % 6];
            for target in [
                point + dir * scale,
                point,
                Vec3::new(f32::NAN, 0.0, 0.0),
                Vec3::splat(f32::INFINITY),
            ] {
                let want = points.side((target - point).normalize_or_zero());
                assert_eq!(
                    points.side_to(target),
                    want,
                    "{target} from {point}, n {normal}"
                );
                cases += 1;
            }
            let v = dir * scale;
            let (d, s) = (v.dot(normal), v.abs().dot(normal.abs()));
            if (i / 3) % 6 == 0 && i % 3 != 0 && d.abs() > crate::math::gamma(8) * s {
                decided += 1;
            }
        }
        assert!(cases > 100_000);
        // Of the rays at scale 1 that are not made grazing (about 4,400), nearly all are
        // decided without the normalisation.
        assert!(decided > 4_000, "{decided}");
    }

    #[test]
    fn rounding_away_in_lanes_gives_the_scalar_bits() {
        let mut values = vec![
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            f32::from_bits(1),
            f32::from_bits(0x8000_0001),
            f32::EPSILON,
            3.5e-7,
            -1234.567,
        ];
        // Any bit pattern: the generator's state, stepped.
        let mut rng = crate::accel::kernels::twin::Rng(0x9e37_79b9_7f4a_7c15);
        for _ in 0..200 {
            rng.next();
            values.push(f32::from_bits((rng.0 >> 32) as u32));
        }
        let offsets = [
            0.0f32,
            -0.0,
            1e-6,
            -1e-6,
            f32::NAN,
            f32::INFINITY,
            -f32::INFINITY,
        ];
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        for (i, &x) in values.iter().enumerate() {
            for &d in &offsets {
                // Each value in each lane, beside other values and offsets.
                let y = values[(i * 7 + 3) % values.len()];
                let z = values[(i * 13 + 5) % values.len()];
                for (po, off) in [
                    (Vec3::new(x, y, z), Vec3::new(d, -d, 1.0)),
                    (Vec3::new(y, x, z), Vec3::new(-1.0, d, -d)),
                    (Vec3::new(z, y, x), Vec3::new(0.0, 1.0, d)),
                ] {
                    assert_eq!(
                        bits(rounded_away(po, off)),
                        bits(rounded_away_scalar(po, off)),
                        "{po:?} moved along {off:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn offset_moves_to_the_side_of_the_outgoing_direction() {
        let p = Vec3::new(1.0, 2.0, 3.0);
        let err = Vec3::splat(1e-6);
        let up = offset_ray_origin(p, err, Vec3::Z, Vec3::new(0.0, 0.3, 1.0));
        let down = offset_ray_origin(p, err, Vec3::Z, Vec3::new(0.0, 0.3, -1.0));
        assert!(up.z > p.z + 1e-6 * 0.99);
        assert!(down.z < p.z - 1e-6 * 0.99);
        assert_eq!(up.x, p.x);
    }

    /// [`SpawnPoints::rays_to4`] against [`SpawnPoints::ray_to`], lane by lane, bit for bit.
    fn lanes_give_ray_to(points: &SpawnPoints, targets: [Vec3; 4]) {
        let lanes = [0, 1, 2].map(|a| Vec4::from_array(targets.map(|t| t[a])));
        let r4 = points.rays_to4(lanes);
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        for (l, &target) in targets.iter().enumerate() {
            let (ray, dist) = points.ray_to(target);
            let lane = |v: [Vec4; 3]| Vec3::new(v[0][l], v[1][l], v[2][l]);
            assert_eq!(bits(lane(r4.origin)), bits(ray.origin), "{target}");
            assert_eq!(bits(lane(r4.dir)), bits(ray.dir), "{target}");
            assert_eq!(r4.dist[l].to_bits(), dist.to_bits(), "{target}");
            let side = if r4.below & (1 << l) != 0 {
                Side::Below
            } else {
                Side::Above
            };
            assert_eq!(side, points.side_to(target));
        }
    }

    #[test]
    fn spawn_points_give_the_rays_of_spawn_and_spawn_to() {
        let mut rng = 0x1234_5678u32;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 17;
            rng ^= rng << 5;
            rng as f32 / u32::MAX as f32 * 2.0 - 1.0
        };
        for _ in 0..2000 {
            let normal = Vec3::new(next(), next(), next()).normalize_or(Vec3::Y);
            let hit = Hit {
                t: 1.0,
                point: Vec3::new(next(), next(), next()) * 10.0,
                error: Vec3::new(next().abs(), next().abs(), next().abs()) * 1e-5,
                normal,
                shading_normal: normal,
                uv: Vec2::ZERO,
                prim: 0,
            };
            let points = hit.spawn_points();
            // Targets on both sides, and ones almost in the tangent plane.
            let dir = Vec3::new(next(), next(), next());
            let tangent = dir - dir.dot(normal) * normal;
            for target in [
                hit.point + dir * 5.0,
                hit.point + tangent + normal * 1e-7,
                hit.point + tangent - normal * 1e-7,
                hit.point,
            ] {
                assert_eq!(points.ray_to(target), hit.spawn_to(target));
                lanes_give_ray_to(&points, [target, hit.point + dir, target, hit.point]);
                let w = (target - hit.point).normalize_or(normal);
                assert_eq!(points.ray(w), hit.spawn(w));
            }
        }
    }

    #[test]
    fn zero_error_still_rounds_away() {
        let p = Vec3::new(0.5, 0.5, 0.5);
        let o = offset_ray_origin(p, Vec3::ZERO, Vec3::Z, Vec3::Z);
        assert_eq!(o, p); // zero offset: no rounding step taken
        let o = offset_ray_origin(p, Vec3::splat(1e-9), Vec3::Z, Vec3::Z);
        assert!(o.z > p.z);
    }
}
