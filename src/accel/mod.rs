//! Ray queries over all primitives of a scene: closest hit for camera, reflection and refraction
//! rays, and any hit for shadow rays. [`Accel`] hides whether a BVH is used.

pub mod aabb;
pub mod bvh;

pub use bvh::{Bvh, BvhOptions};

use crate::geometry::{Candidate, Primitive};
use crate::ray::Ray;

/// Which accelerator to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AccelKind {
    /// A BVH, except for scenes so small that testing every primitive is as fast.
    #[default]
    Auto,
    /// Test every primitive.
    None,
    /// The median-split BVH (axis cycling per level).
    Median,
}

impl std::str::FromStr for AccelKind {
    type Err = String;
    fn from_str(s: &str) -> Result<AccelKind, String> {
        match s {
            "auto" => Ok(AccelKind::Auto),
            "none" => Ok(AccelKind::None),
            "median" => Ok(AccelKind::Median),
            other => Err(format!(
                "unknown accelerator '{other}' (expected auto, none or median)"
            )),
        }
    }
}

/// Below this many primitives `auto` tests them all: a BVH's node tests cost more than they save.
pub const AUTO_MIN_PRIMITIVES: usize = 8;

/// The built accelerator.
#[derive(Debug, Clone)]
pub enum Accel {
    List,
    Bvh(Bvh),
}

impl Accel {
    pub fn build(prims: &[Primitive], kind: AccelKind, leaf_size: usize) -> Accel {
        match kind {
            AccelKind::None => Accel::List,
            AccelKind::Auto if prims.len() < AUTO_MIN_PRIMITIVES => Accel::List,
            AccelKind::Auto | AccelKind::Median => {
                Accel::Bvh(Bvh::build_median(prims, BvhOptions { leaf_size }))
            }
        }
    }

    /// The closest hit with `0 < t < t_max`: the primitive index and its candidate.
    #[inline]
    pub fn closest(&self, prims: &[Primitive], ray: &Ray, t_max: f32) -> Option<(u32, Candidate)> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        match self {
            Accel::List => {
                let mut best = None;
                let mut t_max = t_max;
                for (i, p) in prims.iter().enumerate() {
                    if let Some(c) = p.shape.intersect(ray, t_max) {
                        t_max = c.t;
                        best = Some((i as u32, c));
                    }
                }
                best
            }
            Accel::Bvh(b) => b.closest(prims, ray, t_max),
        }
    }

    /// Whether anything is hit with `0 < t < t_max` for which `blocks(primitive)` holds. Stops at
    /// the first such hit.
    #[inline]
    pub fn any(
        &self,
        prims: &[Primitive],
        ray: &Ray,
        t_max: f32,
        blocks: impl Fn(u32) -> bool,
    ) -> bool {
        if t_max.is_nan() || t_max <= 0.0 {
            return false;
        }
        match self {
            Accel::List => prims
                .iter()
                .enumerate()
                .any(|(i, p)| blocks(i as u32) && p.shape.intersect(ray, t_max).is_some()),
            Accel::Bvh(b) => b.any(prims, ray, t_max, blocks),
        }
    }
}
