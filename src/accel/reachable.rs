//! The primitives the shadow rays of one area light may meet from one shading point: a beam's
//! candidates ([`crate::accel::Accel::beam_candidates`]) less those a ray leaving from a given
//! origin leaves behind, each with its shape copied out. The light's samples test the list
//! over and over (every sample, or every four), so the shapes are read in order without looking
//! them up: a triangle of a large mesh is made from the mesh once per list, not once per test.

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
        Reachable::fill_each(
            std::slice::from_mut(self),
            prims,
            beam,
            candidates,
            &[origin],
        );
    }

    /// [`Reachable::fill`] of each of `lists` with the ray origin of the same place in
    /// `origins`, looking each candidate up once for all of them.
    pub fn fill_each(
        lists: &mut [Reachable],
        prims: &Primitives,
        beam: &Beam,
        candidates: &[u32],
        origins: &[Vec3],
    ) {
        debug_assert_eq!(lists.len(), origins.len());
        for list in lists.iter_mut() {
            list.numbers.clear();
            list.shapes.clear();
        }
        for &p in candidates {
            let shape = prims.shape(p);
            // The box a leaving ray may leave behind, and whether the shape lies in its plane.
            let bounds = match &*shape {
                Shape::Plane(_) => None,
                Shape::Triangle(t) => Some((t.bounds(), true)),
                Shape::Sphere(_) | Shape::Cylinder(_) => Some((shape.bounds(), false)),
            };
            for (list, &origin) in lists.iter_mut().zip(origins) {
                let left_behind = bounds.is_some_and(|(b, flat)| {
                    beam.leaves_behind(origin, &b) || flat && beam.leaves_plane_behind(origin, &b)
                });
                if !left_behind {
                    list.numbers.push(p);
                    list.shapes.push(*shape);
                }
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
