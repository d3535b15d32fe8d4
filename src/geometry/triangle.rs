//! Triangles: the watertight ray/triangle test.
//!
//! ```json
//! { "type": "triangle", "v0": [-2, 8, 0], "v1": [-2, 8, 5], "v2": [-2, 0, 0], "material": { … } }
//! ```
//! A lone triangle, a planar quad and every mesh face are all this primitive; the vertex data for
//! normals and texture coordinates lives in the owning [`Mesh`].

use super::{Candidate, Mesh};
use crate::accel::aabb::Aabb;
use crate::math::{gamma, Vec3};
use crate::ray::{Hit, PreparedRay, Ray};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle {
    /// The corner positions (copied from the mesh for locality).
    pub p: [Vec3; 3],
    /// Index of the owning mesh in the scene.
    pub mesh: u32,
    /// Index of this face in the mesh.
    pub face: u32,
}

/// Edge functions of the sheared, translated corners. An edge function that is exactly 0 in
/// `f32` (a ray through an edge or a vertex) is recomputed in `f64`, as Woop et al. do — but edge
/// by edge: recomputing all three when one is zero (as pbrt-v4 does) changes a *shared* edge's
/// value in one triangle and not in its neighbour, which opens a gap along that edge.
#[inline]
fn edge_functions(p0: Vec3, p1: Vec3, p2: Vec3) -> [f32; 3] {
    let edge = |a: Vec3, b: Vec3| {
        let e = a.x * b.y - a.y * b.x;
        if e == 0.0 {
            (a.x as f64 * b.y as f64 - a.y as f64 * b.x as f64) as f32
        } else {
            e
        }
    };
    [edge(p1, p2), edge(p2, p0), edge(p0, p1)]
}

/// The body of the watertight test with the axis permutation `(KX, KY, KZ)`.
#[inline(always)]
fn watertight<const KX: usize, const KY: usize, const KZ: usize>(
    p: &[Vec3; 3],
    r: &PreparedRay,
    t_max: f32,
) -> Option<Candidate> {
    let o = r.ray.origin.to_array();
    let (sx, sy, sz) = (r.shear.x, r.shear.y, r.shear.z);
    let shear = |v: Vec3| {
        let v = v.to_array();
        let (x, y, z) = (v[KX] - o[KX], v[KY] - o[KY], v[KZ] - o[KZ]);
        Vec3::new(x + sx * z, y + sy * z, z)
    };
    let (mut p0, mut p1, mut p2) = (shear(p[0]), shear(p[1]), shear(p[2]));
    let [e0, e1, e2] = edge_functions(p0, p1, p2);
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return None;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    // Largest |z| before scaling: |Sx·z| and |Sy·z| are at most this (|d.z| is the largest
    // component), which bounds the shear's error in x and y below.
    let max_z = p0.z.abs().max(p1.z.abs()).max(p2.z.abs());
    p0.z *= sz;
    p1.z *= sz;
    p2.z *= sz;
    let t_scaled = e0 * p0.z + e1 * p1.z + e2 * p2.z;
    // A hit behind the origin (t_scaled and det of opposite signs) is rejected early; the
    // comparison with t_max is made on the final t below (see `intersect_prepared`).
    if (det < 0.0 && t_scaled >= 0.0) || (det > 0.0 && t_scaled <= 0.0) {
        return None;
    }
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    let below = t < t_max; // false for NaN
    if !below {
        return None;
    }
    // Conservative lower bound on t (pbrt-v4 §6.8.4): reject hits that rounding could have
    // placed on the wrong side of the origin. pbrt bounds the error of the sheared x and y
    // with the *scaled* z (≈ t), which is only comparable to x and y for unit directions;
    // the unscaled |z| bounds |Sx·z| for any direction length, so short directions do not
    // reject true hits on small triangles.
    let max_zt = p0.z.abs().max(p1.z.abs()).max(p2.z.abs());
    let delta_z = gamma(3) * max_zt;
    let max_xt = p0.x.abs().max(p1.x.abs()).max(p2.x.abs());
    let max_yt = p0.y.abs().max(p1.y.abs()).max(p2.y.abs());
    let delta_x = gamma(5) * (max_xt + max_z);
    let delta_y = gamma(5) * (max_yt + max_z);
    let delta_e = 2.0 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    let max_e = e0.abs().max(e1.abs()).max(e2.abs());
    let delta_t =
        3.0 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * inv_det.abs();
    if t.is_nan() || t <= delta_t {
        return None;
    }
    Some(Candidate {
        t,
        aux: [e1 * inv_det, e2 * inv_det],
    })
}

impl Triangle {
    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            self.p[0].min(self.p[1]).min(self.p[2]),
            self.p[0].max(self.p[1]).max(self.p[2]),
        )
    }

    /// The watertight test of Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection",
    /// JCGT 2(1), 2013: translate to the ray origin, permute so the ray's largest direction component
    /// is z, shear the ray onto +z, and decide inside/outside by the signs of three 2D edge
    /// functions, so that a ray through a shared edge hits exactly one of its triangles. `t` is
    /// accepted only when it is provably positive under the error bounds of pbrt-v4 §6.8.4.
    /// Degenerate (zero-area) triangles are never hit. `aux` holds the barycentrics of `p1`, `p2`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Candidate> {
        self.intersect_prepared(&PreparedRay::new(ray), t_max)
    }

    /// [`Triangle::intersect`] with the per-ray permutation and shear computed once per ray.
    ///
    /// The result depends on `t_max` only through the final comparison `t < t_max` on the
    /// computed `t`, so a hit found under one bound is found, with the same bits, under any larger
    /// bound: every accelerator then agrees with testing all primitives, whatever order it visits
    /// them in.
    #[inline(always)]
    pub fn intersect_prepared(&self, r: &PreparedRay, t_max: f32) -> Option<Candidate> {
        if !r.shear_ok {
            return None;
        }
        // The permutation is a per-ray constant: one predictable branch selects a copy of the test
        // with the axes fixed at compile time.
        match r.kz {
            0 => watertight::<1, 2, 0>(&self.p, r, t_max),
            1 => watertight::<2, 0, 1>(&self.p, r, t_max),
            _ => watertight::<0, 1, 2>(&self.p, r, t_max),
        }
    }

    pub fn hit(&self, c: Candidate, prim: u32, mesh: &Mesh) -> Hit {
        let [b1, b2] = c.aux;
        let b0 = (1.0 - b1 - b2).max(0.0);
        let [p0, p1, p2] = self.p;
        let point = b0 * p0 + b1 * p1 + b2 * p2;
        let error = gamma(7) * ((b0 * p0).abs() + (b1 * p1).abs() + (b2 * p2).abs());
        let geometric = (p1 - p0).cross(p2 - p0);
        let normal = geometric.normalize_or(Vec3::Z);
        let face = self.face as usize;
        let shading_normal = match mesh.vertex_normals(face) {
            Some([n0, n1, n2]) => {
                let n = (b0 * n0 + b1 * n1 + b2 * n2).normalize_or(normal);
                if n.dot(normal) < 0.0 {
                    -n
                } else {
                    n
                }
            }
            None => normal,
        };
        let [t0, t1, t2] = mesh.face_uvs(face);
        Hit {
            t: c.t,
            point,
            error,
            normal,
            shading_normal,
            uv: b0 * t0 + b1 * t1 + b2 * t2,
            prim,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
        Triangle {
            p: [Vec3::from(a), Vec3::from(b), Vec3::from(c)],
            mesh: 0,
            face: 0,
        }
    }

    #[test]
    fn hit_matches_hand_computation() {
        let t = tri([0.0, 0.0, 5.0], [2.0, 0.0, 5.0], [0.0, 2.0, 5.0]);
        let ray = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::Z);
        let c = t.intersect(&ray, f32::INFINITY).unwrap();
        assert_eq!(c.t, 5.0);
        assert!((c.aux[0] - 0.25).abs() < 1e-6 && (c.aux[1] - 0.25).abs() < 1e-6);
        // Both windings are hit (two-sided).
        let back = tri([0.0, 0.0, 5.0], [0.0, 2.0, 5.0], [2.0, 0.0, 5.0]);
        assert_eq!(back.intersect(&ray, f32::INFINITY).unwrap().t, 5.0);
        // Outside, behind, beyond t_max.
        assert!(t
            .intersect(&Ray::new(Vec3::new(1.5, 1.5, 0.0), Vec3::Z), f32::INFINITY)
            .is_none());
        assert!(t
            .intersect(&Ray::new(Vec3::new(0.5, 0.5, 6.0), Vec3::Z), f32::INFINITY)
            .is_none());
        assert!(t.intersect(&ray, 4.99).is_none());
    }

    #[test]
    fn shared_edge_is_hit_by_exactly_one_triangle() {
        let a = tri([0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]);
        let b = tri([1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]);
        let mut misses = 0;
        for i in 0..=1000 {
            let s = i as f32 / 1000.0;
            // Points on the diagonal edge, from a skewed origin.
            let target = Vec3::new(s, 1.0 - s, 1.0);
            let origin = Vec3::new(0.3, -0.7, -2.0);
            let ray = Ray::new(origin, target - origin);
            let hits = [
                a.intersect(&ray, f32::INFINITY),
                b.intersect(&ray, f32::INFINITY),
            ]
            .iter()
            .filter(|h| h.is_some())
            .count();
            if hits == 0 {
                misses += 1;
            }
        }
        assert_eq!(misses, 0);
    }

    #[test]
    fn degenerate_triangle_is_never_hit() {
        let t = tri([0.0, 0.0, 1.0], [1.0, 1.0, 1.0], [2.0, 2.0, 1.0]);
        for i in 0..100 {
            let x = i as f32 / 50.0;
            assert!(t
                .intersect(&Ray::new(Vec3::new(x, x, 0.0), Vec3::Z), f32::INFINITY)
                .is_none());
        }
    }

    #[test]
    fn nan_and_zero_directions_report_no_hit() {
        let t = tri([0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]);
        for d in [
            Vec3::ZERO,
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(0.0, f32::INFINITY, 1.0),
        ] {
            assert!(t
                .intersect(&Ray::new(Vec3::new(0.1, 0.1, 0.0), d), f32::INFINITY)
                .is_none());
        }
    }
}
