//! Four spheres against one ray: [`Sphere::intersect`] and the box clamp of
//! [`Shape::intersect_prepared`](crate::geometry::Shape::intersect_prepared), operation for
//! operation (see [`super`] for why the bits agree). No lane is left to the scalar test. An empty
//! lane has a NaN radius, which no test accepts.

use glam::Vec4;

use super::ray4::{mask, sphere_root, Hits4, Ray4};
use super::Rows;
use crate::geometry::Sphere;

/// Up to four spheres in structure-of-arrays form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere4 {
    center: [Vec4; 3],
    /// NaN in an empty lane.
    radius: Vec4,
}

impl Sphere4 {
    /// The block holding `spheres` in their lanes (`None` lanes are empty).
    pub fn new(spheres: [Option<&Sphere>; 4]) -> Sphere4 {
        let mut center = [Vec4::ZERO; 3];
        let mut radius = Vec4::NAN;
        for (l, s) in spheres.iter().enumerate() {
            let Some(s) = s else { continue };
            for (a, c) in center.iter_mut().enumerate() {
                c[l] = s.center[a];
            }
            radius[l] = s.radius;
        }
        Sphere4 { center, radius }
    }

    /// The block as a leaf stores it: the centres in the first row, the radii first in the
    /// second.
    #[inline(always)]
    pub fn rows(&self) -> Rows {
        [
            self.center,
            [self.radius, Vec4::ZERO, Vec4::ZERO],
            [Vec4::ZERO; 3],
        ]
    }

    /// The block a leaf stored with [`Sphere4::rows`].
    #[inline(always)]
    pub fn from_rows(rows: &Rows) -> Sphere4 {
        Sphere4 {
            center: rows[0],
            radius: rows[1][0],
        }
    }

    /// Bit `l` set where lane `l` holds a sphere.
    pub fn lanes(&self) -> u32 {
        mask(self.radius.is_nan_mask()) ^ 0b1111
    }

    /// Every lane's `Shape::intersect_prepared` with bound `t_max` (`scalar` is always empty).
    #[inline(always)]
    pub fn intersect(&self, r: &Ray4, t_max: f32) -> Hits4 {
        let zero = Vec4::ZERO;
        let f = [0, 1, 2].map(|a| r.origin[a] - self.center[a]);
        let [dx, dy, dz] = r.dir;
        let a = r.dir_length2;
        let b = -(f[0] * dx + f[1] * dy + f[2] * dz);
        let r2 = self.radius * self.radius;
        let s = b / a;
        let perp = [f[0] + s * dx, f[1] + s * dy, f[2] + s * dz];
        let disc = a * (r2 - (perp[0] * perp[0] + perp[1] * perp[1] + perp[2] * perp[2]));
        // `disc < 0` and NaN both fail `disc >= 0`.
        let mut live = mask(disc.cmpge(zero) & self.radius.cmpgt(zero));
        if live == 0 {
            return Hits4::NONE;
        }
        let c = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) - r2;
        let t = sphere_root(a, b, c, disc);
        live &= mask(t.cmpgt(zero) & t.cmplt(Vec4::splat(t_max)));
        if live == 0 {
            return Hits4::NONE;
        }
        let lo = [0, 1, 2].map(|a| self.center[a] - self.radius);
        let hi = [0, 1, 2].map(|a| self.center[a] + self.radius);
        let (inside, t) = r.clamp_to_boxes(lo, hi, t, t_max);
        Hits4 {
            hit: live & inside,
            scalar: 0,
            t,
            b1: zero,
            b2: zero,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::twin::{assert_twin, Rng};
    use super::*;
    use crate::geometry::Shape;
    use crate::math::Vec3;
    use crate::ray::{PreparedRay, Ray};

    /// Every lane against the scalar test, bit for bit; returns how many lanes were hit.
    fn agree(spheres: &[Sphere; 4], ray: &Ray, t_max: f32) -> u32 {
        let block = Sphere4::new([0, 1, 2, 3].map(|l| Some(&spheres[l])));
        let pr = PreparedRay::new(ray);
        let h = block.intersect(&Ray4::new(&pr), t_max);
        assert_eq!(h.scalar, 0);
        assert_twin(&h, &spheres.map(Shape::Sphere), &pr, t_max);
        h.hit.count_ones()
    }

    #[test]
    fn lanes_equal_the_scalar_test_bit_for_bit() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut hits = 0;
        for i in 0..20_000 {
            let spheres: [Sphere; 4] = std::array::from_fn(|k| {
                let radius = match (i + k) % 9 {
                    0 => 0.0,
                    1 => -1.0,
                    2 => 1e-6,
                    3 => 1e6,
                    _ => rng.next() * 3.0,
                };
                Sphere::new(rng.vec(10.0), radius, Vec3::Y, Vec3::X)
            });
            let origin = match i % 3 {
                0 => spheres[0].center, // from the centre
                _ => rng.vec(30.0),
            };
            let target = match i % 4 {
                // Tangent to lane 0, through its centre, at random.
                0 => {
                    spheres[0].center
                        + spheres[0].radius * rng.vec(1.0).cross(Vec3::Y).normalize_or(Vec3::X)
                }
                1 => spheres[0].center,
                _ => rng.vec(10.0),
            };
            let mut dir = (target - origin) * if i % 5 == 0 { 1e-3 } else { 1.0 };
            if i % 7 == 0 {
                dir[i / 7 % 3] = 0.0;
            }
            let t_max = if i % 6 == 0 {
                rng.next() * 20.0
            } else {
                f32::INFINITY
            };
            hits += agree(&spheres, &Ray::new(origin, dir), t_max);
        }
        assert!(hits > 5_000, "{hits} hits");
    }

    #[test]
    fn empty_lanes_and_bad_rays_hit_nothing() {
        let s = Sphere::new(Vec3::ZERO, 1.0, Vec3::Y, Vec3::X);
        let block = Sphere4::new([None, Some(&s), None, None]);
        assert_eq!(block.lanes(), 2);
        let o = Vec3::new(0.0, 0.0, -5.0);
        let h = block.intersect(
            &Ray4::new(&PreparedRay::new(&Ray::new(o, Vec3::Z))),
            f32::INFINITY,
        );
        assert_eq!(h.hit, 2);
        assert_eq!(h.t[1], 4.0);
        for d in [Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 1.0)] {
            let h = block.intersect(
                &Ray4::new(&PreparedRay::new(&Ray::new(o, d))),
                f32::INFINITY,
            );
            assert_eq!(h.hit, 0);
        }
    }
}
