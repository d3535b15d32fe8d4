//! Spheres.
//!
//! ```json
//! { "type": "sphere", "center": [0, 2.7, 0.15], "radius": 0.5, "material": { … } }
//! ```
//! Texture coordinates are longitude/latitude about `pole` (world +y for loaded scenes, see
//! `docs/scene-format.md`):
//! `u = φ / 2π` (φ measured from the sphere's reference direction, counter-clockwise seen from
//! above), `v = θ / π` with `v = 0` at the top pole, so an equirectangular image wraps the sphere
//! upright.

use super::Candidate;
use crate::accel::aabb::Aabb;
use crate::math::{floor_f32, gamma, Vec2, Vec3};
use crate::ray::{Hit, Ray};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
    /// Unit vector towards the top pole (`v = 0`).
    pub pole: Vec3,
    /// Unit vector perpendicular to `pole` where `u = 0`.
    pub meridian: Vec3,
}

impl Sphere {
    pub fn new(center: Vec3, radius: f32, pole: Vec3, meridian: Vec3) -> Sphere {
        Sphere {
            center,
            radius,
            pole,
            meridian,
        }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            self.center - Vec3::splat(self.radius),
            self.center + Vec3::splat(self.radius),
        )
    }

    /// Closest root in `(0, t_max)`. The quadratic is solved in the form that avoids catastrophic
    /// cancellation for small or distant spheres: the discriminant from the distance of the centre
    /// to the ray line, and the second root from Vieta's formula (Haines et al., "Precision
    /// Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Candidate> {
        let f = ray.origin - self.center;
        let a = ray.dir.length_squared();
        let b = -f.dot(ray.dir); // −b/2 of the usual a t² + b t + c
        let r2 = self.radius * self.radius;
        // Perpendicular offset of the centre from the ray line: f + (b/a)·d.
        let perp = f + (b / a) * ray.dir;
        let disc = a * (r2 - perp.length_squared());
        if disc.is_nan() || disc < 0.0 || self.radius <= 0.0 {
            return None;
        }
        let c = f.length_squared() - r2;
        let q = b + disc.sqrt().copysign(b);
        let (mut t0, mut t1) = if q == 0.0 { (0.0, 0.0) } else { (c / q, q / a) };
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        let t = if t0 > 0.0 { t0 } else { t1 };
        if t > 0.0 && t < t_max {
            Some(Candidate { t, aux: [0.0; 2] })
        } else {
            None
        }
    }

    pub fn hit(&self, ray: &Ray, c: Candidate, prim: u32) -> Hit {
        self.hit_with(ray, c, prim, true)
    }

    /// The hit record; its texture coordinates (two inverse trigonometric functions) are worked
    /// out only when `uv` is set, and are zero otherwise.
    #[inline]
    pub fn hit_with(&self, ray: &Ray, c: Candidate, prim: u32, uv: bool) -> Hit {
        let local = ray.at(c.t) - self.center;
        // Re-project onto the surface to remove the error accumulated along the ray.
        let n = local.normalize_or(self.pole);
        let local = n * self.radius;
        let point = self.center + local;
        // |local| error of the re-projection (pbrt-v4 §6.8.5: γ(5)), plus the rounding of the
        // addition of the centre.
        let error = local.abs() * gamma(5) + (self.center.abs() + local.abs()) * gamma(1);
        let uv = if uv { self.uv(n) } else { Vec2::ZERO };
        Hit {
            t: c.t,
            point,
            error,
            normal: n,
            shading_normal: n,
            uv,
            prim,
        }
    }

    /// Texture coordinates of the point with outward unit normal `n`.
    #[inline]
    pub fn uv(&self, n: Vec3) -> Vec2 {
        let cos_theta = n.dot(self.pole).clamp(-1.0, 1.0);
        let east = self.pole.cross(self.meridian);
        let phi = n.dot(east).atan2(n.dot(self.meridian));
        let u = phi / std::f32::consts::TAU;
        Vec2::new(u - floor_f32(u), cos_theta.acos() / std::f32::consts::PI)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_sphere_at(c: Vec3, r: f32) -> Sphere {
        Sphere::new(c, r, Vec3::Z, Vec3::X)
    }

    #[test]
    fn hits_front_and_back_as_computed_by_hand() {
        let s = unit_sphere_at(Vec3::new(0.0, 5.0, 0.0), 1.0);
        let ray = Ray::new(Vec3::ZERO, Vec3::Y);
        assert_eq!(s.intersect(&ray, f32::INFINITY).unwrap().t, 4.0);
        // From inside, the far side.
        let inside = Ray::new(Vec3::new(0.0, 5.0, 0.0), Vec3::Y);
        assert_eq!(s.intersect(&inside, f32::INFINITY).unwrap().t, 1.0);
        // t_max excludes.
        assert!(s.intersect(&ray, 3.9).is_none());
        // Misses by a hair.
        let miss = Ray::new(Vec3::new(1.0001, 0.0, 0.0), Vec3::Y);
        assert!(s.intersect(&miss, f32::INFINITY).is_none());
        // Behind the ray.
        assert!(s
            .intersect(&Ray::new(Vec3::ZERO, -Vec3::Y), f32::INFINITY)
            .is_none());
    }

    #[test]
    fn hit_record_has_outward_normal_and_lat_long_uv() {
        let s = unit_sphere_at(Vec3::ZERO, 2.0);
        let ray = Ray::new(Vec3::new(0.0, 0.0, 10.0), -Vec3::Z);
        let c = s.intersect(&ray, f32::INFINITY).unwrap();
        let h = s.hit(&ray, c, 0);
        assert_eq!(h.point, Vec3::new(0.0, 0.0, 2.0));
        assert_eq!(h.normal, Vec3::Z);
        assert!(h.uv.y.abs() < 1e-6); // top pole
        let ray = Ray::new(Vec3::new(10.0, 0.0, 0.0), -Vec3::X);
        let h = s.hit(&ray, s.intersect(&ray, f32::INFINITY).unwrap(), 0);
        assert!((h.uv - Vec2::new(0.0, 0.5)).length() < 1e-6); // on the meridian, at the equator
        let ray = Ray::new(Vec3::new(0.0, 10.0, 0.0), -Vec3::Y);
        let h = s.hit(&ray, s.intersect(&ray, f32::INFINITY).unwrap(), 0);
        assert!((h.uv - Vec2::new(0.25, 0.5)).length() < 1e-6); // a quarter turn east
    }

    #[test]
    fn small_sphere_far_away_is_hit_accurately() {
        let c = Vec3::new(0.0, 0.0, 1.0e5);
        let s = unit_sphere_at(c, 1.0e-2);
        let ray = Ray::new(Vec3::ZERO, Vec3::Z);
        let t = s.intersect(&ray, f32::INFINITY).unwrap().t;
        assert!((t - (1.0e5 - 1.0e-2)).abs() <= 1.0e5 * 4.0 * f32::EPSILON);
    }

    #[test]
    fn zero_radius_is_never_hit() {
        let s = unit_sphere_at(Vec3::new(0.0, 0.0, 5.0), 0.0);
        assert!(s
            .intersect(&Ray::new(Vec3::ZERO, Vec3::Z), f32::INFINITY)
            .is_none());
    }

    #[test]
    fn nan_ray_reports_no_hit() {
        let s = unit_sphere_at(Vec3::ZERO, 1.0);
        let ray = Ray::new(Vec3::new(f32::NAN, 0.0, 5.0), -Vec3::Z);
        assert!(s.intersect(&ray, f32::INFINITY).is_none());
    }
}
