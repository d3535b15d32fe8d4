//! Closest hits for rays that start inside a sphere: what a ray refracted into a glass ball, or
//! reflected inside one, can meet before it leaves the ball is known once for the scene, so its
//! query tests those few primitives instead of walking the tree.
//!
//! For each sphere a ray may start inside of, [`Interiors`] keeps the *neighbours*: every bounded
//! primitive whose box meets the sphere's box grown by a margin (a sphere resting on a floor has
//! the floor's triangles; a lone ball in the air has none), and every unbounded one. Then for a
//! ray whose origin lies in the ball, with `t_S` the sphere's own answer, no other primitive can
//! answer with `t ≤ t_S`:
//! - the ray's points up to `t_S` lie in the ball, as both ends do (the origin, and the sphere's
//!   computed hit, on the sphere up to the rounding of its quadratic) and the ball is convex;
//! - a primitive's hit lies in its own box up to the rounding of the slab test that clamps every
//!   bounded shape's `t` to its box ([`crate::geometry::Shape::intersect_prepared`]);
//! - the two roundings are a few ulps of the coordinates involved (pbrt-v4 §6.8 bounds them by
//!   small multiples of γ(n)), and the margin, 2⁻¹² of the sphere's reach from the origin of
//!   coordinates, is far above that: a box that stays clear of the grown box is never hit first.
//!
//! So testing the sphere and its neighbours in index order, each under the best `t` so far, gives
//! exactly what every accelerator gives (least `t`, ties to the least index; see
//! [`crate::accel`]). A ray that does not hit its sphere before `t_max` (the sphere's quadratic
//! missing from a point rounded onto its surface, or a shadow ray's bound ending inside) falls
//! back to the whole accelerator. `tests/accel.rs` holds the two to the same bits.

use glam::Vec3A;

use crate::accel::aabb::{slab, Aabb};
use crate::accel::leaves::Best;
use crate::accel::Accel;
use crate::geometry::{Candidate, Primitive, Primitives, Shape};
use crate::math::Vec3;
use crate::ray::{PreparedRay, Ray};

/// Most neighbours a sphere may have for its rays to be answered here; past this many the tree
/// is about as quick.
const MAX_NEIGHBOURS: usize = 8;

/// The grown box's margin as a fraction of the sphere's reach (`max |centre| + radius`).
const MARGIN: f32 = 1.0 / 4096.0;

/// A sphere that [`Interiors`] answers rays from inside of: an index into its table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Inside(u32);

/// The spheres whose inside rays are answered from their neighbours, and those neighbours.
#[derive(Debug, Clone, Default)]
pub struct Interiors {
    /// Per sphere, sorted by primitive: the sphere and its span of `tested`.
    spheres: Vec<(u32, u32, u32)>,
    /// Per sphere, the sphere itself and its neighbours, in increasing primitive index.
    tested: Vec<Neighbour>,
}

/// A primitive a ray from inside a sphere may meet, with its box (the whole space for an
/// unbounded one).
#[derive(Debug, Clone, Copy)]
struct Neighbour {
    prim: u32,
    lo: Vec3A,
    hi: Vec3A,
}

impl Interiors {
    /// The table for the spheres among `prims` for which `wanted` holds (those a ray can start
    /// inside of: the transmissive ones), found through `accel`. Empty for the plain list, which
    /// stays the reference that tests everything.
    pub fn new(prims: &Primitives, accel: &Accel, wanted: impl Fn(&Primitive) -> bool) -> Self {
        // Spheres are records: the triangles of large meshes are not read.
        let unbounded = prims.unbounded();
        let mut table = Interiors::default();
        let mut near = Vec::new();
        for (p, prim) in prims.records() {
            let Shape::Sphere(s) = &prim.shape else {
                continue;
            };
            let usable = s.radius > 0.0 && s.center.is_finite() && s.radius.is_finite();
            if !usable || !wanted(prim) {
                continue;
            }
            let reach = s.center.abs().max_element() + s.radius;
            let margin = Vec3::splat(reach * MARGIN);
            let b = s.bounds();
            let region = Aabb::new(b.min - margin, b.max + margin);
            if !accel.meeting_box(prims, &region, MAX_NEIGHBOURS + 1, &mut near) {
                continue;
            }
            // The sphere is among them (its box meets its grown box), each bounded primitive once.
            let start = table.tested.len() as u32;
            near.extend(&unbounded);
            near.sort_unstable();
            table.tested.extend(near.iter().map(|&p| {
                let b = prims.shape(p).bounds();
                Neighbour {
                    prim: p,
                    lo: b.min.into(),
                    hi: b.max.into(),
                }
            }));
            table.spheres.push((p, start, table.tested.len() as u32));
        }
        table
    }

    /// The entry of primitive `p`, if rays from inside it are answered here.
    #[inline]
    pub fn of(&self, p: u32) -> Option<Inside> {
        self.spheres
            .binary_search_by_key(&p, |e| e.0)
            .ok()
            .map(|i| Inside(i as u32))
    }

    /// Whether no sphere has an entry.
    pub fn is_empty(&self) -> bool {
        self.spheres.is_empty()
    }

    /// [`Accel::closest`] for a ray whose origin lies in the ball of `inside`'s sphere (a ray
    /// spawned below its surface): the same answer, from the sphere and its neighbours.
    #[inline]
    pub fn closest(
        &self,
        accel: &Accel,
        prims: &Primitives,
        inside: Inside,
        ray: &Ray,
        t_max: f32,
    ) -> Option<(u32, Candidate)> {
        let (sphere, start, end) = self.spheres[inside.0 as usize];
        let r = PreparedRay::new(ray);
        // (None too for a `t_max` that is not positive, as the tree would answer.)
        let Some(own) = prims.shape(sphere).intersect_prepared(&r, t_max) else {
            return accel.closest(prims, ray, t_max);
        };
        let mut best = Best::new(t_max);
        for n in &self.tested[start as usize..end as usize] {
            let p = n.prim;
            let c = if p == sphere {
                // Its `t` does not depend on the bound it is tested under.
                (own.t < best.t).then_some(own)
            } else if slab(n.lo, n.hi, &r, own.t).0 {
                // A hit at `t ≤ own.t` passes its box's slab test under that bound (see
                // `Shape::intersect_prepared`); a box that fails it cannot beat the sphere.
                prims.shape(p).intersect_prepared(&r, best.t)
            } else {
                None
            };
            if let Some(c) = c {
                best.take(p, c);
            }
        }
        best.hit()
    }
}
