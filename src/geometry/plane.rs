//! Infinite planes: every point `x` with `n · x = d`, for a unit normal `n`.
//!
//! ```json
//! { "type": "plane", "normal": [0, 1, 0], "distance": -1, "material": "mat1" }
//! ```
//! is the floor `y = −1`. A plane is unbounded: it has no box, so the accelerators keep it out of
//! their trees and test it against every ray (see [`crate::accel`]).
//!
//! Texture coordinates are the hit point's coordinates along two unit axes of the plane, one
//! repeat of the image per unit of length: `u` runs along the world axis most nearly parallel to
//! the plane (the first of x, y, z with the least `|n · axis|`), projected into the plane, and
//! `v` along `u × n`. Seen from the side `n` points to, `u` then runs to the right and `v`
//! downwards, so an image lies upright: on the floor above, `u` is +x and `v` is +z; on a wall
//! facing +z, `u` is +x and `v` is −y.

use super::Candidate;
use crate::math::{gamma, Vec2, Vec3};
use crate::ray::{Hit, Ray};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Unit normal.
    pub normal: Vec3,
    /// Signed distance of the plane from the origin along `normal`: the plane is `normal · x = d`.
    pub distance: f32,
    /// Unit texture axes in the plane (see the module documentation).
    pub u_axis: Vec3,
    pub v_axis: Vec3,
}

impl Plane {
    /// The plane `normal · x = distance · |normal|`, i.e. `distance` is measured along the unit
    /// normal. `normal` must be nonzero and finite (the loader checks).
    pub fn new(normal: Vec3, distance: f32) -> Plane {
        let n = normal.normalize();
        let axes = [Vec3::X, Vec3::Y, Vec3::Z];
        let mut best = axes[0];
        for a in &axes[1..] {
            if n.dot(*a).abs() < n.dot(best).abs() {
                best = *a;
            }
        }
        let u_axis = (best - n.dot(best) * n).normalize();
        let v_axis = u_axis.cross(n).normalize();
        Plane {
            normal: n,
            distance,
            u_axis,
            v_axis,
        }
    }

    /// The intersection with `0 < t < t_max`. A ray parallel to the plane (or lying in it) never
    /// hits; the sign of the numerator decides which side the origin is on, so a ray spawned off
    /// the plane by [`Plane::hit`]'s error bound and leaving it is never counted as a hit (see
    /// there).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Candidate> {
        let denom = self.normal.dot(ray.dir);
        if denom == 0.0 {
            return None;
        }
        let t = (self.distance - self.normal.dot(ray.origin)) / denom;
        (t > 0.0 && t < t_max).then_some(Candidate { t, aux: [0.0; 2] })
    }

    /// The hit record. The point on the ray is projected back onto the plane (`p + (d − n·p)·n`),
    /// which removes the error of `t` along the ray; what is left is the plane's residual at the
    /// projected point, bounded below.
    pub fn hit(&self, ray: &Ray, c: Candidate, prim: u32) -> Hit {
        let n = self.normal;
        let p = ray.at(c.t);
        let s = self.distance - n.dot(p);
        let point = p + s * n;
        // Residual n·point − d in exact arithmetic on the stored values (Higham §3.1 rules):
        // - the computed s differs from d − n·p by at most γ(4)·(Σ|nᵢpᵢ| + |d|) (a three-term
        //   dot product, then a subtraction);
        // - each coordinate pᵢ + s·nᵢ rounds twice, γ(2)·(|pᵢ| + |s·nᵢ|), weighted by |nᵢ|;
        // - the stored normal is unit only to within a few ulps (normalisation: γ(4) on |n|²), an
        //   error of |s|·γ(4).
        // γ(8) over the sum of all these magnitudes covers the three. The bound is doubled
        // because a ray spawned from the hit re-evaluates the plane at its offset origin, with a
        // rounding of the same size: the offset must clear both for the sign of the new
        // origin's side to be computed correctly.
        let magnitude = n.abs().dot(p.abs() + point.abs()) + self.distance.abs() + 3.0 * s.abs();
        let residual = 2.0 * gamma(8) * magnitude;
        // `offset_ray_origin` moves by `|n| · error` along n, at least `residual` since Σ|nᵢ| ≥ 1.
        let error = Vec3::splat(residual);
        Hit {
            t: c.t,
            point,
            error,
            normal: n,
            shading_normal: n,
            uv: Vec2::new(point.dot(self.u_axis), point.dot(self.v_axis)),
            prim,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{hash, to_unit, uniform_sphere};

    #[test]
    fn the_floor_under_the_spheres_is_hit_where_expected() {
        let floor = Plane::new(Vec3::new(0.0, 2.0, 0.0), -1.0);
        assert_eq!(floor.normal, Vec3::Y);
        let ray = Ray::new(Vec3::new(3.0, 4.0, -2.0), -Vec3::Y);
        let c = floor.intersect(&ray, f32::INFINITY).unwrap();
        assert_eq!(c.t, 5.0);
        let h = floor.hit(&ray, c, 7);
        assert_eq!(h.point, Vec3::new(3.0, -1.0, -2.0));
        assert_eq!(h.normal, Vec3::Y);
        assert_eq!(h.prim, 7);
        // u along +x, v along +z (u × n with n = +y).
        assert_eq!(h.uv, Vec2::new(3.0, -2.0));
        // Parallel rays, rays going away and t_max all miss.
        assert!(floor
            .intersect(&Ray::new(Vec3::ZERO, Vec3::X), f32::INFINITY)
            .is_none());
        assert!(floor
            .intersect(&Ray::new(Vec3::ZERO, Vec3::Y), f32::INFINITY)
            .is_none());
        assert!(floor.intersect(&ray, 5.0).is_none());
    }

    #[test]
    fn uv_axes_read_an_image_upright_on_a_wall() {
        let wall = Plane::new(Vec3::Z, -3.0);
        assert_eq!(wall.u_axis, Vec3::X);
        assert_eq!(wall.v_axis, -Vec3::Y);
        let tilted = Plane::new(Vec3::new(1.0, 2.0, 3.0), 0.5);
        for a in [tilted.u_axis, tilted.v_axis] {
            assert!((a.length() - 1.0).abs() < 1e-6);
            assert!(a.dot(tilted.normal).abs() < 1e-6);
        }
        assert!(tilted.u_axis.dot(tilted.v_axis).abs() < 1e-6);
    }

    #[test]
    fn a_hit_far_from_the_origin_lies_within_its_bound_and_spawned_rays_leave_cleanly() {
        let mut k = 0u64;
        let mut next = || {
            k += 1;
            to_unit(hash(&[k, 0x9_1a9e]))
        };
        for i in 0..4000 {
            let n = uniform_sphere(Vec2::new(next(), next()));
            let d = (next() - 0.5) * 2.0e4;
            let plane = Plane::new(n, d);
            // Origins up to 1e5 away, directions at any angle to the plane.
            let o = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * 2.0e5;
            let dir = uniform_sphere(Vec2::new(next(), next()));
            let ray = Ray::new(o, dir);
            let Some(c) = plane.intersect(&ray, f32::INFINITY) else {
                continue;
            };
            let h = plane.hit(&ray, c, 0);
            // The residual, in f64, is within the bound.
            let pn = h.point.as_dvec3().dot(plane.normal.as_dvec3()) - plane.distance as f64;
            assert!(
                pn.abs() <= h.error.x as f64 / 2.0,
                "case {i}: {pn} > {}",
                h.error.x
            );
            // Rays leaving to either side never hit the plane they leave.
            for w in [
                dir,
                -dir,
                n,
                -n,
                (dir + n).normalize(),
                (dir - n).normalize(),
            ] {
                if w.dot(n).abs() < 1e-3 {
                    continue;
                }
                let spawned = h.spawn(w);
                assert!(
                    plane.intersect(&spawned, f32::INFINITY).is_none(),
                    "case {i}: a ray leaving the plane hit it again"
                );
            }
        }
    }
}
