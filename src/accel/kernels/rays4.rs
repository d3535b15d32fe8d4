//! Four rays against one shape: the other way round from [`super::Sphere4`] and
//! [`super::Triangle4`], for rays that share their shapes rather than shapes that share a ray —
//! the shadow rays from one shading point towards the samples of one area light, which test the
//! same few candidates ([`crate::accel::Beam`]). Lane `l` holds ray `l`, and answers what
//! [`Shape::intersect_prepared`](crate::geometry::Shape::intersect_prepared) answers for it, bit
//! for bit (see [`super`] for why the bits agree).

use glam::{BVec4A, Vec4};

use super::ray4::{mask, sphere_root};
use crate::accel::aabb::SLAB_WIDEN;
use crate::geometry::Sphere;

/// Four rays in structure-of-arrays form, with what [`crate::ray::PreparedRay`] works out for
/// each: the values are those of `PreparedRay::new(&Ray::new(origin, dir))`, lane by lane.
#[derive(Debug, Clone, Copy)]
pub struct Rays4 {
    origin: [Vec4; 3],
    dir: [Vec4; 3],
    dir_length2: Vec4,
    inv_dir: [Vec4; 3],
    inv_dir_far: [Vec4; 3],
    negative: [BVec4A; 3],
}

impl Rays4 {
    /// The rays `origin + t·dir`, per world axis one lane per ray.
    #[inline(always)]
    pub fn new(origin: [Vec4; 3], dir: [Vec4; 3]) -> Rays4 {
        let inv_dir = dir.map(|d| Vec4::ONE / d);
        Rays4 {
            origin,
            dir,
            dir_length2: dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2],
            inv_dir,
            inv_dir_far: inv_dir.map(|i| i * SLAB_WIDEN),
            negative: inv_dir.map(|i| i.cmplt(Vec4::ZERO)),
        }
    }

    /// The lanes whose ray hits the sphere `s` with `0 < t < t_max` (lane by lane): bit `l` is
    /// set where `Shape::Sphere(s).intersect_prepared` finds a hit on ray `l` under `t_max[l]`.
    #[inline(always)]
    pub fn hit_sphere(&self, s: &Sphere, t_max: Vec4) -> u32 {
        let zero = Vec4::ZERO;
        if s.radius.is_nan() || s.radius <= 0.0 {
            return 0;
        }
        let center = s.center.to_array().map(Vec4::splat);
        let f = [0, 1, 2].map(|a| self.origin[a] - center[a]);
        let [dx, dy, dz] = self.dir;
        let a = self.dir_length2;
        let b = -(f[0] * dx + f[1] * dy + f[2] * dz);
        let r2 = Vec4::splat(s.radius * s.radius);
        let q = b / a;
        let perp = [f[0] + q * dx, f[1] + q * dy, f[2] + q * dz];
        let disc = a * (r2 - (perp[0] * perp[0] + perp[1] * perp[1] + perp[2] * perp[2]));
        // `disc < 0` and NaN both fail `disc >= 0`.
        let mut live = mask(disc.cmpge(zero));
        if live == 0 {
            return 0;
        }
        let c = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) - r2;
        let t = sphere_root(a, b, c, disc);
        live &= mask(t.cmpgt(zero) & t.cmplt(t_max));
        if live == 0 {
            return 0;
        }
        let r = Vec4::splat(s.radius);
        let lo = center.map(|c| c - r);
        let hi = center.map(|c| c + r);
        live & self.clamp_to_box(lo, hi, t, t_max)
    }

    /// The box clamp of [`Shape::intersect_prepared`](crate::geometry::Shape::intersect_prepared)
    /// for hits at `t` on a shape with bounds `[lo, hi]`: the robust slab test of
    /// [`crate::accel::aabb::slab`] with no bound, then `t` raised to the entry distance. Returns
    /// the lanes that pass the box and stay below `t_max`.
    #[inline(always)]
    fn clamp_to_box(&self, lo: [Vec4; 3], hi: [Vec4; 3], t: Vec4, t_max: Vec4) -> u32 {
        let mut near = Vec4::ZERO;
        let mut far = Vec4::INFINITY;
        for a in 0..3 {
            let near_plane = Vec4::select(self.negative[a], hi[a], lo[a]);
            let far_plane = Vec4::select(self.negative[a], lo[a], hi[a]);
            let t_near = (near_plane - self.origin[a]) * self.inv_dir[a];
            let t_far = (far_plane - self.origin[a]) * self.inv_dir_far[a];
            // `max`/`min` return their second operand for NaN: a ray in a slab's plane ignores it.
            near = near.max(t_near.max(Vec4::ZERO));
            far = far.min(t_far.min(Vec4::INFINITY));
        }
        let t = t.max(near);
        mask(near.cmple(far) & t.cmplt(t_max))
    }
}

#[cfg(test)]
mod tests {
    use super::super::twin::Rng;
    use super::*;
    use crate::geometry::Shape;
    use crate::math::Vec3;
    use crate::ray::{PreparedRay, Ray};

    /// Every lane against the scalar test; returns how many lanes were hit.
    fn agree(sphere: &Sphere, rays: &[Ray; 4], t_max: [f32; 4]) -> u32 {
        let lanes = |f: &dyn Fn(&Ray) -> Vec3| {
            [0, 1, 2].map(|a| Vec4::from_array(rays.each_ref().map(|r| f(r)[a])))
        };
        let r4 = Rays4::new(lanes(&|r| r.origin), lanes(&|r| r.dir));
        let got = r4.hit_sphere(sphere, Vec4::from_array(t_max));
        let shape = Shape::Sphere(*sphere);
        for (l, ray) in rays.iter().enumerate() {
            let want = shape
                .intersect_prepared(&PreparedRay::new(ray), t_max[l])
                .is_some();
            assert_eq!(
                got & (1 << l) != 0,
                want,
                "lane {l}: {sphere:?}, {ray:?}, t_max {}",
                t_max[l]
            );
        }
        got.count_ones()
    }

    #[test]
    fn lanes_equal_the_scalar_test() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut hits = 0;
        for i in 0..20_000 {
            let radius = match i % 11 {
                0 => 0.0,
                1 => -1.0,
                2 => 1e-6,
                3 => f32::NAN,
                _ => rng.next() * 3.0,
            };
            let sphere = Sphere::new(rng.vec(10.0), radius, Vec3::Y, Vec3::X);
            // Rays from one point (a shading point's) or from anywhere, towards the sphere's
            // rim, its centre, or anywhere.
            let apex = rng.vec(30.0);
            let rays: [Ray; 4] = std::array::from_fn(|l| {
                let origin = if i % 2 == 0 { apex } else { rng.vec(30.0) };
                let target = match (i + l) % 4 {
                    0 => {
                        sphere.center
                            + sphere.radius * rng.vec(1.0).cross(Vec3::Y).normalize_or(Vec3::X)
                    }
                    1 => sphere.center,
                    _ => rng.vec(10.0),
                };
                let mut dir = (target - origin).normalize_or_zero();
                if (i + l) % 7 == 0 {
                    dir[(i + l) / 7 % 3] = 0.0;
                }
                if (i + l) % 13 == 0 {
                    dir = -dir;
                }
                Ray::new(origin, dir)
            });
            let t_max = std::array::from_fn(|l| match (i + l) % 5 {
                0 => rng.next() * 40.0,
                1 => 0.0,
                _ => f32::INFINITY,
            });
            hits += agree(&sphere, &rays, t_max);
        }
        assert!(hits > 10_000, "{hits} hits");
    }

    #[test]
    fn bad_rays_hit_nothing() {
        let s = Sphere::new(Vec3::ZERO, 1.0, Vec3::Y, Vec3::X);
        let o = Vec4::splat(-5.0);
        let origin = [Vec4::ZERO, Vec4::ZERO, o];
        let dir = [
            Vec4::ZERO,
            Vec4::new(0.0, f32::NAN, 0.0, 0.0),
            Vec4::new(1.0, 1.0, 0.0, 0.0),
        ];
        let got = Rays4::new(origin, dir).hit_sphere(&s, Vec4::INFINITY);
        assert_eq!(got, 1, "only lane 0 (along +z) hits");
    }
}
