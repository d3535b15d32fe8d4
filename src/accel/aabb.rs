//! Axis-aligned bounding boxes and the robust ray/box slab test.

use glam::Vec3A;

use crate::math::{Vec3, MACHINE_EPSILON};
use crate::ray::PreparedRay;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (the identity of [`Aabb::union`]).
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn new(min: Vec3, max: Vec3) -> Aabb {
        Aabb { min, max }
    }

    pub fn union(self, o: Aabb) -> Aabb {
        Aabb::new(self.min.min(o.min), self.max.max(o.max))
    }

    pub fn grow(self, p: Vec3) -> Aabb {
        Aabb::new(self.min.min(p), self.max.max(p))
    }

    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Corner `i` (0–7): bit 0 picks the maximum in x, bit 1 in y, bit 2 in z.
    #[inline]
    pub fn corner(&self, i: usize) -> Vec3 {
        let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
        Vec3::new(
            pick(1, self.min.x, self.max.x),
            pick(2, self.min.y, self.max.y),
            pick(4, self.min.z, self.max.z),
        )
    }

    /// The ball around the box: its centre, and half its diagonal.
    #[inline]
    pub fn ball(&self) -> (Vec3, f32) {
        (self.center(), 0.5 * (self.max - self.min).length())
    }

    pub fn extent(&self) -> Vec3 {
        (self.max - self.min).max(Vec3::ZERO)
    }

    pub fn surface_area(&self) -> f32 {
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Whether `p` lies inside, with slack `tol`.
    pub fn contains(&self, p: Vec3, tol: f32) -> bool {
        p.cmpge(self.min - Vec3::splat(tol)).all() && p.cmple(self.max + Vec3::splat(tol)).all()
    }

    /// Slab test: whether the ray `origin + t·dir` meets the box for some `t` in `[0, t_max]`.
    /// See [`slab`].
    #[inline]
    pub fn hit(&self, ray: &PreparedRay, t_max: f32) -> bool {
        slab(self.min.into(), self.max.into(), ray, t_max).0
    }
}

/// The widening factor `1 + 2γ(3)` of the slab test's far distances (Ize 2013, §3.2).
pub const SLAB_WIDEN: f32 = 1.0 + 2.0 * (3.0 * MACHINE_EPSILON / (1.0 - 3.0 * MACHINE_EPSILON));

/// Slab test of the box `[lo, hi]` against a prepared ray: whether the ray meets the box for some
/// `t` in `[0, t_max]`, and the entry distance (at least 0). All three slabs at once in SIMD lanes
/// (the fourth lane of `lo` and `hi` is ignored).
///
/// Robustness (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013): the far distances are widened by
/// `1 + 2γ(3)`, so rounding never culls a box the ray touches. They are computed as
/// `(b − o) · (inv · (1 + 2γ(3)))`: the same four roundings as `((b − o) · inv) · (1 + 2γ(3))`, so
/// the same error bound holds. The near plane of each slab is chosen by the sign of `inv_dir` (a
/// direction component of `-0.0` counts as negative, as its reciprocal `-∞` is). A ray lying in a
/// slab's plane gives `0 · ∞ = NaN` there; `max`/`min` below return their second operand when
/// the first is NaN, so such a plane is ignored and the ray counts as inside that slab.
#[inline(always)]
pub fn slab(lo: Vec3A, hi: Vec3A, r: &PreparedRay, t_max: f32) -> (bool, f32) {
    let near_plane = Vec3A::select(r.negative, hi, lo);
    let far_plane = Vec3A::select(r.negative, lo, hi);
    let t_near = (near_plane - r.origin) * r.inv_dir;
    let t_far = (far_plane - r.origin) * r.inv_dir_far;
    // SSE `max(a, b)`/`min(a, b)` return `b` when either is NaN: NaN slabs give 0 and t_max.
    let near = t_near.max(Vec3A::ZERO).max_element();
    let far = t_far.min(Vec3A::splat(t_max)).min_element();
    (near <= far, near)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::Ray;

    fn hit(b: &Aabb, o: Vec3, d: Vec3, t_max: f32) -> bool {
        b.hit(&PreparedRay::new(&Ray::new(o, d)), t_max)
    }

    #[test]
    fn slab_test_hits_misses_and_grazes() {
        let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let inf = f32::INFINITY;
        assert!(hit(&b, Vec3::new(0.5, 0.5, -1.0), Vec3::Z, inf));
        assert!(!hit(&b, Vec3::new(1.5, 0.5, -1.0), Vec3::Z, inf));
        assert!(!hit(&b, Vec3::new(0.5, 0.5, -1.0), Vec3::Z, 0.5));
        assert!(!hit(&b, Vec3::new(0.5, 0.5, 2.0), Vec3::Z, inf));
        // Axis-parallel rays exactly in the plane of a face: 0·∞ = NaN must not cull them.
        assert!(hit(&b, Vec3::new(0.0, 0.5, -1.0), Vec3::Z, inf));
        assert!(hit(&b, Vec3::new(1.0, 1.0, -1.0), Vec3::Z, inf));
        // The same with direction components of -0.0, on either face plane.
        let d = Vec3::new(-0.0, -0.0, 1.0);
        for o in [
            Vec3::new(0.0, 0.5, -1.0),
            Vec3::new(1.0, 0.5, -1.0),
            Vec3::new(0.5, 1.0, -1.0),
            Vec3::new(1.0, 0.0, -1.0),
        ] {
            assert!(hit(&b, o, d, inf), "{o}");
        }
        assert!(!hit(&b, Vec3::new(1.5, 0.5, -1.0), d, inf));
        assert!(!hit(&b, Vec3::new(-0.5, 0.5, -1.0), d, inf));
        // Origin inside.
        assert!(hit(&b, Vec3::splat(0.5), Vec3::new(1.0, 2.0, 3.0), inf));
        // A NaN direction or bound never passes.
        assert!(!hit(&b, Vec3::splat(0.5), Vec3::Z, f32::NAN));
    }

    #[test]
    fn widening_is_two_gamma_three() {
        assert_eq!(SLAB_WIDEN, 1.0 + 2.0 * crate::math::gamma(3));
    }

    #[test]
    fn flat_box_is_hit() {
        let b = Aabb::new(Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 1.0, 1.0));
        assert!(hit(&b, Vec3::new(0.5, 0.5, 0.0), Vec3::Z, f32::INFINITY));
        // Grazing the flat box along its plane's edge, and at the far end of a long ray.
        assert!(hit(&b, Vec3::new(0.0, 0.0, 0.0), Vec3::Z, f32::INFINITY));
        let far = Vec3::new(0.3, 0.7, -1.0e6);
        assert!(hit(&b, far, Vec3::new(0.0, 0.0, 1.0), 1.0e6 + 1.0));
    }
}
