//! Capped cylinders (the CGR variant).
//!
//! ```json
//! { "type": "cylinder", "center": [-0.3, 0.19, 1], "axis": [0, 1, 0], "radius": 0.15, "height": 0.2,
//!   "material": { … } }
//! ```
//! `height` is the **half**-height: the cylinder spans `center ± height·axis`. Texture coordinates:
//! on the side `u` is the angle around the axis / 2π and `v` runs from 0 at the top rim to 1 at
//! the bottom; on the caps `(u, v)` is the planar projection of the disc onto the unit square.

use super::Candidate;
use crate::accel::aabb::Aabb;
use crate::math::{gamma, orthonormal_basis, Vec2, Vec3};
use crate::ray::{Hit, Ray};

const SIDE: f32 = 0.0;
const TOP: f32 = 1.0;
const BOTTOM: f32 = 2.0;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    pub center: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    pub radius: f32,
    pub half_height: f32,
}

impl Cylinder {
    pub fn new(center: Vec3, axis: Vec3, radius: f32, half_height: f32) -> Cylinder {
        let axis = axis.normalize();
        Cylinder {
            center,
            axis,
            radius,
            half_height,
        }
    }

    /// `(tangent, bitangent)` completing `axis` to an orthonormal frame. Recomputed on use rather
    /// than stored: it keeps every primitive record at 52 bytes (a triangle's size), which matters
    /// more on big meshes than the few operations it costs a cylinder test.
    #[inline]
    fn frame(&self) -> (Vec3, Vec3) {
        orthonormal_basis(self.axis)
    }

    #[inline]
    fn in_frame(&self, frame: (Vec3, Vec3), v: Vec3) -> Vec3 {
        Vec3::new(v.dot(frame.0), v.dot(frame.1), v.dot(self.axis))
    }

    pub fn bounds(&self) -> Aabb {
        // Extent of a disc of radius r with normal a along axis i: r·sqrt(1 − a_i²).
        let a = self.axis;
        let s = (Vec3::ONE - a * a).max(Vec3::ZERO);
        let disc = self.radius * Vec3::new(s.x.sqrt(), s.y.sqrt(), s.z.sqrt());
        let ends = (a * self.half_height).abs();
        Aabb::new(self.center - ends - disc, self.center + ends + disc)
    }

    /// Closest hit on the side or either cap. The side's quadratic uses the cancellation-free
    /// discriminant `A·r² − (o × d)_z²` and Vieta's formula for the second root.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Candidate> {
        let frame = self.frame();
        let o = self.in_frame(frame, ray.origin - self.center);
        let d = self.in_frame(frame, ray.dir);
        let (r, h) = (self.radius, self.half_height);
        let mut best: Option<Candidate> = None;
        let mut consider = |t: f32, part: f32| {
            if t > 0.0 && t < best.map_or(t_max, |b| b.t) {
                best = Some(Candidate {
                    t,
                    aux: [part, 0.0],
                });
            }
        };
        let a = d.x * d.x + d.y * d.y;
        if a > 0.0 {
            let b = -(o.x * d.x + o.y * d.y);
            let cross = o.x * d.y - o.y * d.x;
            let disc = a * r * r - cross * cross;
            if disc >= 0.0 {
                let c = o.x * o.x + o.y * o.y - r * r;
                let q = b + disc.sqrt().copysign(b);
                if q != 0.0 {
                    for t in [c / q, q / a] {
                        if (o.z + t * d.z).abs() <= h {
                            consider(t, SIDE);
                        }
                    }
                }
            }
        }
        if d.z != 0.0 {
            for (z, part) in [(h, TOP), (-h, BOTTOM)] {
                let t = (z - o.z) / d.z;
                let (x, y) = (o.x + t * d.x, o.y + t * d.y);
                if x * x + y * y <= r * r {
                    consider(t, part);
                }
            }
        }
        best
    }

    pub fn hit(&self, ray: &Ray, c: Candidate, prim: u32) -> Hit {
        self.hit_with(ray, c, prim, true)
    }

    /// The hit record; the side's texture coordinates (an arctangent) are worked out only when
    /// `want_uv` is set, and are zero otherwise.
    #[inline]
    pub fn hit_with(&self, ray: &Ray, c: Candidate, prim: u32, want_uv: bool) -> Hit {
        let p = ray.at(c.t);
        let frame = self.frame();
        let local = self.in_frame(frame, p - self.center);
        let (r, h) = (self.radius, self.half_height);
        let (normal, point, uv);
        if c.aux[0] == SIDE {
            // Re-project onto the side surface.
            let radial = Vec2::new(local.x, local.y).normalize_or(Vec2::X);
            normal = (radial.x * frame.0 + radial.y * frame.1).normalize();
            let z = local.z.clamp(-h, h);
            point = self.center + normal * r + self.axis * z;
            uv = if want_uv {
                let phi = radial.y.atan2(radial.x) / std::f32::consts::TAU;
                Vec2::new(phi - crate::math::floor_f32(phi), (h - z) / (2.0 * h))
            } else {
                Vec2::ZERO
            };
        } else {
            let sign = if c.aux[0] == TOP { 1.0 } else { -1.0 };
            normal = self.axis * sign;
            point = self.center + local.x * frame.0 + local.y * frame.1 + self.axis * (sign * h);
            uv = Vec2::new(0.5 + 0.5 * local.x / r, 0.5 - 0.5 * local.y / r);
        }
        // The local frame costs a dot product (3 roundings) each way; bound generously.
        let error =
            gamma(9) * (self.center.abs() + (point - self.center).abs() + Vec3::splat(r + h));
        Hit {
            t: c.t,
            point,
            error,
            normal,
            shading_normal: normal,
            uv,
            prim,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn side_and_caps_hit_where_computed_by_hand() {
        let cy = Cylinder::new(Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 0.5, 1.0);
        // Side, from +x.
        let ray = Ray::new(Vec3::new(5.0, 1.5, 0.0), -Vec3::X);
        let c = cy.intersect(&ray, f32::INFINITY).unwrap();
        assert!((c.t - 4.5).abs() < 1e-5);
        let h = cy.hit(&ray, c, 0);
        assert!(h.normal.distance(Vec3::X) < 1e-5);
        // Top cap, from above: the top is at y = 1 + 1 (half-height reading).
        let ray = Ray::new(Vec3::new(0.1, 5.0, 0.1), -Vec3::Y);
        let c = cy.intersect(&ray, f32::INFINITY).unwrap();
        assert!((c.t - 3.0).abs() < 1e-5);
        assert_eq!(cy.hit(&ray, c, 0).normal, Vec3::Y);
        // Just past the top rim: the side is not hit there.
        let ray = Ray::new(Vec3::new(5.0, 2.01, 0.0), -Vec3::X);
        assert!(cy.intersect(&ray, f32::INFINITY).is_none());
        // From inside, the far wall.
        let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::X);
        assert!((cy.intersect(&ray, f32::INFINITY).unwrap().t - 0.5).abs() < 1e-6);
    }

    #[test]
    fn bounds_contain_a_tilted_cylinder() {
        let cy = Cylinder::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), 0.3, 2.0);
        let b = cy.bounds();
        for i in 0..64 {
            let phi = i as f32 / 64.0 * std::f32::consts::TAU;
            for z in [-2.0, 0.0, 2.0] {
                let p = cy.center
                    + cy.axis * z
                    + 0.3 * (phi.cos() * cy.frame().0 + phi.sin() * cy.frame().1);
                assert!(b.contains(p, 1e-5), "{p}");
            }
        }
    }
}
