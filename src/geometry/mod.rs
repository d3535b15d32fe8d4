//! The shapes the renderer intersects. Every shape is a [`Primitive`] of one numbered list,
//! [`Primitives`] (meshes are split into their triangles, a planar quad into two), so the
//! accelerator sees one kind of thing; the triangles of large meshes are made from the mesh when
//! asked for rather than stored.
//!
//! Intersection is two-phase: [`Shape::intersect`] finds only the ray parameter and a few
//! shape-specific numbers (barycentrics, which part of a cylinder), cheap enough to run on every
//! candidate; [`Primitive::hit`] turns the closest one into a full [`Hit`] with point, error bound,
//! normals and texture coordinates.
//!
//! Every shape but the infinite [`Plane`] is bounded; [`Shape::is_bounded`] tells the
//! accelerators which primitives their trees may hold.

pub mod cylinder;
pub mod mesh;
pub mod plane;
pub mod primitives;
pub mod sphere;
pub mod triangle;

pub use cylinder::Cylinder;
pub use mesh::{Mesh, MeshUv};
pub use plane::Plane;
pub use primitives::Primitives;
pub use sphere::Sphere;
pub use triangle::Triangle;

use crate::accel::aabb::{slab, Aabb};
use crate::math::Vec3;
use crate::ray::{Hit, PreparedRay, Ray};

/// A candidate intersection: the ray parameter and two shape-specific values (triangle
/// barycentrics `b1, b2`; for cylinders which part was hit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    pub t: f32,
    pub aux: [f32; 2],
}

/// One intersectable shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Triangle(Triangle),
    Cylinder(Cylinder),
    /// Unbounded: never in a BVH (see [`Shape::is_bounded`]).
    Plane(Plane),
}

impl Shape {
    /// The closest intersection with `0 < t < t_max`, if any. See
    /// [`Shape::intersect_prepared`].
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Candidate> {
        self.intersect_prepared(&PreparedRay::new(ray), t_max)
    }

    /// The closest intersection with `0 < t < t_max` for a ray prepared once per traversal (what
    /// the accelerators call).
    ///
    /// A bounded shape's hit is kept only if the ray passes the robust slab test on the shape's
    /// bounds ([`crate::accel::aabb::slab`]), its `t` raised to the box's entry distance where
    /// rounding left it below (by a few ulps: grazing rays, hits on a flat box's face). As the
    /// computed entry and exit distances are monotone in the box, every box holding the shape then
    /// passes for any bound `≥ t`, so a BVH culling boxes against the best `t` so far reports what
    /// testing every primitive reports, bit for bit. The result depends on `t_max` only through
    /// the final `t < t_max`. An infinite plane is never in a tree: its own test is the answer.
    #[inline(always)]
    pub fn intersect_prepared(&self, r: &PreparedRay, t_max: f32) -> Option<Candidate> {
        let c = match self {
            Shape::Triangle(t) => t.intersect_prepared(r, t_max),
            Shape::Sphere(s) => s.intersect(&r.ray, t_max),
            Shape::Cylinder(c) => c.intersect(&r.ray, t_max),
            Shape::Plane(p) => return p.intersect(&r.ray, t_max),
        }?;
        let b = self.bounds();
        let (inside, entry) = slab(b.min.into(), b.max.into(), r, f32::INFINITY);
        let t = c.t.max(entry);
        (inside && t < t_max).then_some(Candidate { t, aux: c.aux })
    }

    /// Axis-aligned bounds; for an unbounded shape, the whole space (`±∞` on every axis).
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Triangle(t) => t.bounds(),
            Shape::Cylinder(c) => c.bounds(),
            Shape::Plane(_) => Aabb::new(Vec3::NEG_INFINITY, Vec3::INFINITY),
        }
    }

    /// Whether the shape fits in a finite box. Unbounded shapes are kept out of BVHs and tested
    /// against every ray.
    #[inline]
    pub fn is_bounded(&self) -> bool {
        !matches!(self, Shape::Plane(_))
    }
}

/// A shape with its material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Primitive {
    pub shape: Shape,
    /// Index into the scene's materials.
    pub material: u32,
}

impl Primitive {
    /// The full hit record of a candidate found by [`Shape::intersect`] on this primitive.
    pub fn hit(&self, ray: &Ray, c: Candidate, prim: u32, meshes: &[Mesh]) -> Hit {
        self.hit_with(ray, c, prim, meshes, true)
    }

    /// The hit record, with texture coordinates only where `uv` is set: without them
    /// [`Hit::uv`] is zero for spheres and cylinders, whose coordinates cost inverse
    /// trigonometric functions (triangles and planes fill them in either way: they are a few
    /// multiplications).
    #[inline]
    pub fn hit_with(&self, ray: &Ray, c: Candidate, prim: u32, meshes: &[Mesh], uv: bool) -> Hit {
        match &self.shape {
            Shape::Sphere(s) => s.hit_with(ray, c, prim, uv),
            Shape::Triangle(t) => t.hit(c, prim, &meshes[t.mesh as usize]),
            Shape::Cylinder(cy) => cy.hit_with(ray, c, prim, uv),
            Shape::Plane(p) => p.hit(ray, c, prim),
        }
    }

    /// Centre of the bounds (what the BVH builders sort by).
    pub fn centroid(&self) -> Vec3 {
        self.shape.bounds().center()
    }
}
