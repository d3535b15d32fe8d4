//! Axis-aligned bounding boxes and the robust ray/box slab test.

use crate::math::{gamma, Vec3};

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

    /// Slab test: whether the ray `origin + t·dir` (with `inv_dir = 1/dir`) meets the box for some
    /// `t` in `[0, t_max]`. The far distances are widened by `1 + 2γ(3)` so rounding never culls a
    /// box the ray touches (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013), and the min/max
    /// ordering is written so that a NaN from `0 · ∞` (a ray in a slab's plane) never widens the
    /// interval: NaN comparisons are false, so such slabs leave it as it was.
    #[inline]
    pub fn hit(&self, origin: Vec3, inv_dir: Vec3, t_max: f32) -> bool {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let mut near = 0.0f32;
        let mut far = t_max;
        let widen = 1.0 + 2.0 * gamma(3);
        for i in 0..3 {
            // Swap only on a true comparison, so a NaN stays where it is and is ignored below.
            let (a, b) = if t0[i] > t1[i] {
                (t1[i], t0[i])
            } else {
                (t0[i], t1[i])
            };
            let b = b * widen;
            if a > near {
                near = a;
            }
            if b < far {
                far = b;
            }
            if near > far {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_test_hits_misses_and_grazes() {
        let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let inv = |d: Vec3| Vec3::ONE / d;
        assert!(b.hit(Vec3::new(0.5, 0.5, -1.0), inv(Vec3::Z), f32::INFINITY));
        assert!(!b.hit(Vec3::new(1.5, 0.5, -1.0), inv(Vec3::Z), f32::INFINITY));
        assert!(!b.hit(Vec3::new(0.5, 0.5, -1.0), inv(Vec3::Z), 0.5));
        assert!(!b.hit(Vec3::new(0.5, 0.5, 2.0), inv(Vec3::Z), f32::INFINITY));
        // Axis-parallel ray exactly in the plane of a face: 0·∞ = NaN must not cull it.
        assert!(b.hit(Vec3::new(0.0, 0.5, -1.0), inv(Vec3::Z), f32::INFINITY));
        // Origin inside.
        assert!(b.hit(
            Vec3::splat(0.5),
            inv(Vec3::new(1.0, 2.0, 3.0)),
            f32::INFINITY
        ));
    }

    #[test]
    fn flat_box_is_hit() {
        let b = Aabb::new(Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 1.0, 1.0));
        assert!(b.hit(Vec3::new(0.5, 0.5, 0.0), Vec3::ONE / Vec3::Z, f32::INFINITY));
    }
}
