//! The primitives the shadow rays of one area light may meet from one shading point: a beam's
//! candidates ([`crate::accel::Accel::beam_candidates`]) less those a ray leaving from a given
//! origin leaves behind, each with its shape copied out. The light's samples test the list
//! over and over (every sample, or every four), so the shapes are read in order without looking
//! them up: a triangle of a large mesh is made from the mesh once per list, not once per test.

use super::aabb::Aabb;
use super::Beam;
use crate::geometry::{Primitives, Shape};
use crate::math::Vec3;
use crate::ray::{PreparedRay, Ray};

/// Primitive numbers with their shapes, in the order of the candidates they came from.
#[derive(Debug, Clone, Default)]
pub struct Reachable {
    numbers: Vec<u32>,
    shapes: Vec<Shape>,
}

impl Reachable {
    /// Of `candidates` (gathered for `beam`), those a ray of the beam leaving from `origin` may
    /// still hit, in place of what the list held: all but the bounded primitives it leaves
    /// behind ([`Beam::leaves_behind`]) and the axis-aligned triangles it leaves behind
    /// ([`Beam::leaves_plane_behind`]). Testing only these answers every such ray as testing all
    /// the candidates does.
    pub fn fill(&mut self, prims: &Primitives, beam: &Beam, candidates: &[u32], origin: Vec3) {
        self.numbers.clear();
        self.shapes.clear();
        for &p in candidates {
            let shape = prims.shape(p);
            let behind = |b: &Aabb| beam.leaves_behind(origin, b);
            let left_behind = match &*shape {
                Shape::Plane(_) => false,
                Shape::Triangle(t) => {
                    let b = t.bounds();
                    behind(&b) || beam.leaves_plane_behind(origin, &b)
                }
                Shape::Sphere(_) | Shape::Cylinder(_) => behind(&shape.bounds()),
            };
            if !left_behind {
                self.numbers.push(p);
                self.shapes.push(shape.into_owned());
            }
        }
    }

    /// Every one of `candidates`, none set aside.
    pub fn all(prims: &Primitives, candidates: &[u32]) -> Reachable {
        Reachable {
            numbers: candidates.to_vec(),
            shapes: candidates
                .iter()
                .map(|&p| prims.shape(p).into_owned())
                .collect(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.numbers.is_empty()
    }

    /// The primitive numbers, in order.
    pub fn numbers(&self) -> &[u32] {
        &self.numbers
    }

    /// Each primitive's number and shape, in order.
    #[inline]
    pub fn iter(&self) -> impl Iterator<Item = (u32, &Shape)> {
        self.numbers.iter().copied().zip(&self.shapes)
    }

    /// [`crate::accel::Accel::any`] over these primitives only, for a ray of the beam they were
    /// gathered for, leaving from their origin, up to `t_max`: then the answer is the one over
    /// every primitive.
    #[inline]
    pub fn any(&self, ray: &Ray, t_max: f32, mut blocks: impl FnMut(u32) -> bool) -> bool {
        if t_max.is_nan() || t_max <= 0.0 {
            return false;
        }
        let r = PreparedRay::new(ray);
        self.iter()
            .any(|(p, shape)| shape.intersect_prepared(&r, t_max).is_some() && blocks(p))
    }
}
