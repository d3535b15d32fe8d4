//! The shapes the renderer intersects. Every shape is a [`Primitive`] in one flat list (meshes are
//! split into their triangles, a planar quad into two), so the accelerator sees one kind of thing.
//!
//! Intersection is two-phase: [`Shape::intersect`] finds only the ray parameter and a few
//! shape-specific numbers (barycentrics, which part of a cylinder), cheap enough to run on every
//! candidate; [`Primitive::hit`] turns the closest one into a full [`Hit`] with point, error bound,
//! normals and texture coordinates.

pub mod cylinder;
pub mod mesh;
pub mod sphere;
pub mod triangle;

pub use cylinder::Cylinder;
pub use mesh::{Mesh, MeshUv};
pub use sphere::Sphere;
pub use triangle::Triangle;

use crate::accel::aabb::Aabb;
use crate::math::Vec3;
use crate::ray::{Hit, Ray};

/// A candidate intersection: the ray parameter and two shape-specific values (triangle
/// barycentrics `b1, b2`; for cylinders which part was hit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    pub t: f32,
    pub aux: [f32; 2],
}

/// One intersectable shape.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Triangle(Triangle),
    Cylinder(Cylinder),
}

impl Shape {
    /// The closest intersection with `0 < t < t_max`, if any.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Candidate> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_max),
            Shape::Triangle(t) => t.intersect(ray, t_max),
            Shape::Cylinder(c) => c.intersect(ray, t_max),
        }
    }

    /// Axis-aligned bounds.
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Triangle(t) => t.bounds(),
            Shape::Cylinder(c) => c.bounds(),
        }
    }
}

/// A shape with its material.
#[derive(Debug, Clone, PartialEq)]
pub struct Primitive {
    pub shape: Shape,
    /// Index into the scene's materials.
    pub material: u32,
}

impl Primitive {
    /// The full hit record of a candidate found by [`Shape::intersect`] on this primitive.
    pub fn hit(&self, ray: &Ray, c: Candidate, prim: u32, meshes: &[Mesh]) -> Hit {
        match &self.shape {
            Shape::Sphere(s) => s.hit(ray, c, prim),
            Shape::Triangle(t) => t.hit(c, prim, &meshes[t.mesh as usize]),
            Shape::Cylinder(cy) => cy.hit(ray, c, prim),
        }
    }

    /// Centre of the bounds (what the BVH builders sort by).
    pub fn centroid(&self) -> Vec3 {
        self.shape.bounds().center()
    }
}
