//! Four triangles against one ray: the watertight test of [`crate::geometry::triangle`] followed
//! by the box clamp of [`Shape::intersect_prepared`](crate::geometry::Shape::intersect_prepared).
//!
//! A lane reaches the `min`/`max` steps only with a finite, nonzero determinant, which any
//! non-finite corner or shear value would have spoilt, so they see no NaN. The one step that is
//! not lane-wise `f32` arithmetic, the scalar test's `f64` recomputation of an edge function that
//! is exactly zero (a ray through an edge or a vertex), is left to the scalar test: such lanes
//! come back in [`Hits4::scalar`].
//!
//! An empty lane holds NaN corners: its edge functions are NaN, never zero, so it is neither hit
//! nor handed to the scalar test, and no lane mask is kept.
//!
//! The unit tests compare every lane with [`Triangle::intersect_prepared`] bit for bit on random,
//! edge-aimed, vertex-aimed, axis-parallel and degenerate cases.

use glam::Vec4;

use super::ray4::{mask, Hits4, Ray4};
use super::Rows;
use crate::geometry::Triangle;
use crate::math::gamma;

/// Up to four triangles in structure-of-arrays form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle4 {
    /// `p[corner][axis]`: one lane per triangle, NaN in an empty lane.
    p: Rows,
}

impl Triangle4 {
    /// The block holding `tris` in their lanes (`None` lanes are empty).
    pub fn new(tris: [Option<&Triangle>; 4]) -> Triangle4 {
        let mut p = [[Vec4::NAN; 3]; 3];
        for (l, t) in tris.iter().enumerate() {
            let Some(t) = t else { continue };
            for (c, corner) in t.p.iter().enumerate() {
                for a in 0..3 {
                    p[c][a][l] = corner[a];
                }
            }
        }
        Triangle4 { p }
    }

    /// The block as a leaf stores it.
    #[inline(always)]
    pub fn rows(&self) -> Rows {
        self.p
    }

    /// Bit `l` set where lane `l` holds a triangle.
    pub fn lanes(&self) -> u32 {
        mask(self.p[0][0].is_nan_mask()) ^ 0b1111
    }

    /// Every lane's [`Shape::intersect_prepared`](crate::geometry::Shape::intersect_prepared)
    /// with bound `t_max`, but for the lanes returned in [`Hits4::scalar`].
    #[inline(always)]
    pub fn intersect(&self, r: &Ray4, t_max: f32) -> Hits4 {
        intersect_rows(&self.p, r, t_max)
    }
}

/// [`Triangle4::intersect`] of the block a leaf stored with [`Triangle4::rows`], read where it
/// lies, so that a leaf's block is not copied out first.
#[inline(always)]
pub fn intersect_rows(p: &Rows, r: &Ray4, t_max: f32) -> Hits4 {
    if !r.shear_ok {
        return Hits4::NONE;
    }
    let [kx, ky, kz] = r.axes;
    // Translate to the origin, permute, shear (`watertight` in triangle.rs).
    let corner = |c: usize| {
        let x = p[c][kx] - r.origin_k[0];
        let y = p[c][ky] - r.origin_k[1];
        let z = p[c][kz] - r.origin_k[2];
        (x + r.shear[0] * z, y + r.shear[1] * z, z)
    };
    let (x0, y0, z0) = corner(0);
    let (x1, y1, z1) = corner(1);
    let (x2, y2, z2) = corner(2);
    let e0 = x1 * y2 - y1 * x2;
    let e1 = x2 * y0 - y2 * x0;
    let e2 = x0 * y1 - y0 * x1;
    let zero = Vec4::ZERO;
    let scalar = mask(e0.cmpeq(zero) | e1.cmpeq(zero) | e2.cmpeq(zero));
    let negative = e0.cmplt(zero) | e1.cmplt(zero) | e2.cmplt(zero);
    let positive = e0.cmpgt(zero) | e1.cmpgt(zero) | e2.cmpgt(zero);
    let mut live = !scalar & !mask(negative & positive) & 0b1111;
    let det = e0 + e1 + e2;
    live &= mask(det.cmpne(zero) & det.abs().cmplt(Vec4::INFINITY));
    if live == 0 {
        return Hits4 {
            scalar,
            ..Hits4::NONE
        };
    }
    let max_z = z0.abs().max(z1.abs()).max(z2.abs());
    let (z0, z1, z2) = (z0 * r.shear[2], z1 * r.shear[2], z2 * r.shear[2]);
    let t_scaled = e0 * z0 + e1 * z1 + e2 * z2;
    let behind =
        (det.cmplt(zero) & t_scaled.cmpge(zero)) | (det.cmpgt(zero) & t_scaled.cmple(zero));
    live &= !mask(behind);
    let inv_det = Vec4::ONE / det;
    let t = t_scaled * inv_det;
    // The conservative lower bound on t of pbrt-v4 §6.8.4, as in `watertight`.
    let max_zt = z0.abs().max(z1.abs()).max(z2.abs());
    let delta_z = gamma(3) * max_zt;
    let max_xt = x0.abs().max(x1.abs()).max(x2.abs());
    let max_yt = y0.abs().max(y1.abs()).max(y2.abs());
    let delta_x = gamma(5) * (max_xt + max_z);
    let delta_y = gamma(5) * (max_yt + max_z);
    let delta_e = 2.0 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    let max_e = e0.abs().max(e1.abs()).max(e2.abs());
    let delta_t =
        3.0 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * inv_det.abs();
    live &= mask(t.cmpgt(delta_t));
    if live == 0 {
        return Hits4 {
            scalar,
            ..Hits4::NONE
        };
    }
    // The box clamp, on each triangle's own bounds.
    let lo = [0, 1, 2].map(|a| p[0][a].min(p[1][a]).min(p[2][a]));
    let hi = [0, 1, 2].map(|a| p[0][a].max(p[1][a]).max(p[2][a]));
    let (inside, t) = r.clamp_to_boxes(lo, hi, t, t_max);
    live &= inside;
    Hits4 {
        hit: live,
        scalar,
        t,
        b1: e1 * inv_det,
        b2: e2 * inv_det,
    }
}

#[cfg(test)]
mod tests {
    use super::super::twin::{assert_twin, Rng};
    use super::*;
    use crate::geometry::Shape;
    use crate::math::Vec3;
    use crate::ray::{PreparedRay, Ray};

    fn tri(p: [Vec3; 3]) -> Triangle {
        Triangle {
            p,
            mesh: 0,
            face: 0,
        }
    }

    /// Every lane against the scalar test, bit for bit; returns how many lanes were hit and how
    /// many left to the scalar test.
    fn agree(tris: &[Triangle; 4], ray: &Ray, t_max: f32) -> (u32, u32) {
        let block = Triangle4::new([0, 1, 2, 3].map(|l| Some(&tris[l])));
        let pr = PreparedRay::new(ray);
        let h = block.intersect(&Ray4::new(&pr), t_max);
        assert_twin(&h, &tris.map(Shape::Triangle), &pr, t_max);
        (h.hit.count_ones(), h.scalar.count_ones())
    }

    #[test]
    fn lanes_equal_the_scalar_test_bit_for_bit() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut hits, mut scalar) = (0, 0);
        for i in 0..20_000 {
            let tris: [Triangle; 4] = std::array::from_fn(|_| {
                let c = rng.vec(4.0);
                tri([c + rng.vec(2.0), c + rng.vec(2.0), c + rng.vec(2.0)])
            });
            let origin = rng.vec(12.0);
            let target = match i % 4 {
                // At a random point of lane 0's triangle, on one of its edges, at a vertex.
                0 => {
                    let (a, b) = (rng.next(), rng.next());
                    let (a, b) = if a + b > 1.0 {
                        (1.0 - a, 1.0 - b)
                    } else {
                        (a, b)
                    };
                    let p = tris[0].p;
                    p[0] + a * (p[1] - p[0]) + b * (p[2] - p[0])
                }
                1 => {
                    let p = tris[0].p;
                    p[1] + rng.next() * (p[2] - p[1])
                }
                2 => tris[0].p[i / 4 % 3],
                _ => rng.vec(8.0),
            };
            let mut dir = target - origin;
            if i % 7 == 0 {
                // Axis-parallel and zero components.
                dir[i / 7 % 3] = 0.0;
            }
            let t_max = if i % 5 == 0 {
                rng.next() * 10.0
            } else {
                f32::INFINITY
            };
            let (h, s) = agree(&tris, &Ray::new(origin, dir), t_max);
            hits += h;
            scalar += s;
        }
        // The cases are not vacuous: many lanes hit, and edge-aimed rays reach the scalar path.
        assert!(hits > 5_000, "{hits} hits");
        assert!(scalar > 0);
    }

    #[test]
    fn degenerate_huge_tiny_and_flat_triangles_agree() {
        let mut rng = Rng(42);
        for _ in 0..5_000 {
            let c = rng.vec(2.0);
            let tris = [
                // A line (zero area), a point, a huge one and a tiny one.
                tri([c, c + Vec3::X, c + 2.0 * Vec3::X]),
                tri([c, c, c]),
                tri([c + rng.vec(1e30), c + rng.vec(1e30), c + rng.vec(1e30)]),
                tri([c, c + rng.vec(1e-6), c + rng.vec(1e-6)]),
            ];
            let ray = Ray::new(rng.vec(10.0), c - rng.vec(10.0));
            agree(&tris, &ray, f32::INFINITY);
            // Axis-aligned triangles seen along and across their plane.
            let flat = [0, 1, 2, 3].map(|_| {
                let z = rng.next();
                tri([
                    Vec3::new(0.0, 0.0, z),
                    Vec3::new(1.0, 0.0, z),
                    Vec3::new(0.0, 1.0, z),
                ])
            });
            agree(
                &flat,
                &Ray::new(Vec3::new(rng.next(), rng.next(), -1.0), Vec3::Z),
                5.0,
            );
            agree(
                &flat,
                &Ray::new(Vec3::new(-1.0, rng.next(), 0.5), Vec3::X),
                5.0,
            );
        }
    }

    #[test]
    fn bad_rays_and_empty_lanes_hit_nothing() {
        let t = tri([Vec3::ZERO, Vec3::X, Vec3::Y]);
        let block = Triangle4::new([Some(&t), None, None, None]);
        assert_eq!(block.lanes(), 1);
        let o = Vec3::new(0.2, 0.2, -1.0);
        for d in [
            Vec3::ZERO,
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(0.0, f32::INFINITY, 1.0),
        ] {
            let h = block.intersect(
                &Ray4::new(&PreparedRay::new(&Ray::new(o, d))),
                f32::INFINITY,
            );
            assert_eq!((h.hit, h.scalar), (0, 0));
        }
        let h = block.intersect(
            &Ray4::new(&PreparedRay::new(&Ray::new(o, Vec3::Z))),
            f32::INFINITY,
        );
        assert_eq!((h.hit, h.scalar), (1, 0));
        assert_eq!(h.t[0], 1.0);
    }
}
