//! What the kernels share: the per-ray values ([`Ray4`]), what they return ([`Hits4`]), and the
//! box clamp every bounded shape's hit goes through (see
//! [`Shape::intersect_prepared`](crate::geometry::Shape::intersect_prepared)).

use glam::{BVec4A, Vec3, Vec4};

use crate::ray::PreparedRay;

/// The per-ray values of the four-lane kernels, worked out once per ray from a [`PreparedRay`].
#[derive(Debug, Clone, Copy)]
pub struct Ray4 {
    /// The watertight triangle test's axis permutation `(kx, ky, kz)`.
    pub(super) axes: [usize; 3],
    /// The origin in the permuted axes.
    pub(super) origin_k: [Vec4; 3],
    /// The triangle test's shear `(sx, sy, sz)`.
    pub(super) shear: [Vec4; 3],
    /// Whether the triangle test can run at all ([`PreparedRay::shear_ok`]).
    pub(super) shear_ok: bool,
    /// The origin and direction per world axis, and the direction's squared length.
    pub(in crate::accel) origin: [Vec4; 3],
    pub(super) dir: [Vec4; 3],
    pub(super) dir_length2: Vec4,
    /// `1/dir` and the widened `1/dir` per world axis, and their signs, for the box clamp.
    pub(in crate::accel) inv_dir: [Vec4; 3],
    pub(in crate::accel) inv_dir_far: [Vec4; 3],
    negative: [bool; 3],
}

impl Ray4 {
    #[inline(always)]
    pub fn new(r: &PreparedRay) -> Ray4 {
        let axes = crate::ray::axis_permutation(r.kz);
        let o = r.ray.origin.to_array();
        let d: Vec3 = r.ray.dir;
        Ray4 {
            axes,
            origin_k: axes.map(|k| Vec4::splat(o[k])),
            shear: [r.shear.x, r.shear.y, r.shear.z].map(Vec4::splat),
            shear_ok: r.shear_ok,
            origin: o.map(Vec4::splat),
            dir: d.to_array().map(Vec4::splat),
            dir_length2: Vec4::splat(d.length_squared()),
            inv_dir: r.inv_dir.to_array().map(Vec4::splat),
            inv_dir_far: r.inv_dir_far.to_array().map(Vec4::splat),
            negative: [0, 1, 2].map(|a| r.negative.test(a)),
        }
    }

    /// The box clamp of four hits at `t` on shapes with bounds `[lo, hi]` (per axis, one lane per
    /// shape): the robust slab test of [`crate::accel::aabb::slab`] with no bound, then `t`
    /// raised to the entry distance. Returns the lanes that pass the box and stay below `t_max`,
    /// and the raised `t`.
    #[inline(always)]
    pub(super) fn clamp_to_boxes(
        &self,
        lo: [Vec4; 3],
        hi: [Vec4; 3],
        t: Vec4,
        t_max: f32,
    ) -> (u32, Vec4) {
        let mut near = Vec4::ZERO;
        let mut far = Vec4::INFINITY;
        for a in 0..3 {
            let (near_plane, far_plane) = if self.negative[a] {
                (hi[a], lo[a])
            } else {
                (lo[a], hi[a])
            };
            let t_near = (near_plane - self.origin[a]) * self.inv_dir[a];
            let t_far = (far_plane - self.origin[a]) * self.inv_dir_far[a];
            // `max`/`min` return their second operand for NaN: a ray in a slab's plane ignores it.
            near = near.max(t_near.max(Vec4::ZERO));
            far = far.min(t_far.min(Vec4::INFINITY));
        }
        let t = t.max(near);
        (mask(near.cmple(far) & t.cmplt(Vec4::splat(t_max))), t)
    }
}

/// What a four-lane kernel found.
#[derive(Debug, Clone, Copy)]
pub struct Hits4 {
    /// Lanes hit with `t < t_max`: for each, `t` and `b1, b2` are the `t` and `aux` that
    /// `Shape::intersect_prepared` returns for that shape.
    pub hit: u32,
    /// Lanes the kernel leaves undecided (see each kernel): the caller asks the scalar test.
    pub scalar: u32,
    pub t: Vec4,
    pub b1: Vec4,
    pub b2: Vec4,
}

impl Hits4 {
    pub const NONE: Hits4 = Hits4 {
        hit: 0,
        scalar: 0,
        t: Vec4::ZERO,
        b1: Vec4::ZERO,
        b2: Vec4::ZERO,
    };
}

/// The ray parameter [`crate::geometry::Sphere::intersect`] takes, lane by lane: of the roots
/// `c/q` and `q/a` of the quadratic (`q = b + sign(b)·√disc`, both 0 where `q` is), the nearer
/// one if it is positive, else the farther. The caller keeps lanes with `disc ≥ 0` and a positive
/// result.
#[inline(always)]
pub(super) fn sphere_root(a: Vec4, b: Vec4, c: Vec4, disc: Vec4) -> Vec4 {
    let zero = Vec4::ZERO;
    let q = b + crate::math::sqrt4(disc).copysign(b);
    let q_zero = q.cmpeq(zero);
    let t0 = Vec4::select(q_zero, zero, c / q);
    let t1 = Vec4::select(q_zero, zero, q / a);
    let swap = t0.cmpgt(t1);
    let (t0, t1) = (Vec4::select(swap, t1, t0), Vec4::select(swap, t0, t1));
    Vec4::select(t0.cmpgt(zero), t0, t1)
}

/// The lanes of `b` as bits.
#[inline(always)]
pub(super) fn mask(b: BVec4A) -> u32 {
    b.bitmask()
}
