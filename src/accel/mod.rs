//! Ray queries over all primitives of a scene: closest hit for camera, reflection and refraction
//! rays, and any hit for shadow rays. [`Accel`] hides whether a BVH is used.
//!
//! Every accelerator answers exactly as testing every primitive in index order would:
//! - `closest` returns the primitive hit with the least `t` in `(0, t_max)`; when several are hit
//!   at the same `t` (coincident or duplicated primitives, a ray through a shared vertex) the one
//!   with the **least primitive index** wins;
//! - `any` returns whether at least one primitive accepted by the filter is hit in `(0, t_max)`.
//!
//! This holds because each primitive test depends on `t_max` only through a final `t < t_max` on
//! its computed `t` (so visiting order cannot change a primitive's answer), and because the box
//! test is conservative (Ize 2013; see [`aabb::slab`]). Unbounded primitives (infinite planes)
//! are not in any tree: the BVH tests them against every ray before its traversal. `tests/accel.rs`
//! checks all of this bit for bit against [`Accel::List`] on adversarial rays.

pub mod aabb;
pub mod beam;
pub mod bvh;
pub mod interior;
pub mod kernels;
mod leaves;
pub mod light_buffer;
pub mod reachable;
pub mod stack;
mod traverse;
pub mod wide;

pub use beam::Beam;
pub use bvh::{Bvh, BvhOptions, BvhStats, Split};
pub use interior::{Inside, Interiors};
pub use kernels::Isa;
pub use light_buffer::LightBuffer;
pub use reachable::Reachable;
pub use wide::{Bvh4, Bvh8};

use crate::geometry::{Candidate, Primitives, Shape};
use crate::math::Vec3;
use crate::ray::{PreparedRay, Ray};
use aabb::Aabb;

/// Which accelerator to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AccelKind {
    /// The four-wide SAH BVH, whatever the scene's size: the SAH itself makes a tiny scene's root
    /// one leaf where splitting does not pay, so small scenes need no flat special case
    /// (`docs/performance.md`, "The `auto` choice").
    #[default]
    Auto,
    /// Test every primitive, one by one (the reference every other kind agrees with).
    None,
    /// Every primitive in one BVH leaf: no traversal, triangles and spheres tested four at a
    /// time.
    Flat,
    /// The median-split BVH (axis cycling per level).
    Median,
    /// The binned-SAH BVH.
    Sah,
    /// The binned-SAH BVH collapsed to four children a node, tested in SIMD lanes.
    Sah4,
    /// The binned-SAH BVH collapsed to eight children a node.
    Sah8,
}

impl AccelKind {
    /// Every kind, in the order the benchmark reports them.
    pub const ALL: [AccelKind; 7] = [
        AccelKind::Auto,
        AccelKind::None,
        AccelKind::Flat,
        AccelKind::Median,
        AccelKind::Sah,
        AccelKind::Sah4,
        AccelKind::Sah8,
    ];

    pub fn name(self) -> &'static str {
        match self {
            AccelKind::Auto => "auto",
            AccelKind::None => "none",
            AccelKind::Flat => "flat",
            AccelKind::Median => "median",
            AccelKind::Sah => "sah",
            AccelKind::Sah4 => "sah4",
            AccelKind::Sah8 => "sah8",
        }
    }
}

impl AccelKind {
    /// What this kind builds: `auto` resolved to `sah4`.
    pub fn resolved(self) -> AccelKind {
        match self {
            AccelKind::Auto => AccelKind::Sah4,
            kind => kind,
        }
    }
}

impl std::fmt::Display for AccelKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for AccelKind {
    type Err = String;
    fn from_str(s: &str) -> Result<AccelKind, String> {
        match s {
            "auto" => Ok(AccelKind::Auto),
            "none" => Ok(AccelKind::None),
            "flat" => Ok(AccelKind::Flat),
            "median" => Ok(AccelKind::Median),
            "sah" => Ok(AccelKind::Sah),
            "sah4" => Ok(AccelKind::Sah4),
            "sah8" => Ok(AccelKind::Sah8),
            other => Err(format!(
                "unknown accelerator '{other}' (expected auto, none, flat, median, sah, sah4 or \
                 sah8)"
            )),
        }
    }
}

/// The built accelerator.
#[derive(Debug, Clone)]
pub enum Accel {
    List,
    Bvh(Bvh),
    Bvh4(Bvh4),
    Bvh8(Bvh8),
}

impl Accel {
    /// Builds the accelerator `kind` over `prims`; `leaf_size` is the most primitives in a BVH
    /// leaf.
    pub fn build(prims: &Primitives, kind: AccelKind, leaf_size: usize) -> Accel {
        // A leaf entry keeps its block's kind above the primitive's index.
        if prims.len() > leaves::MAX_PRIMITIVES {
            return Accel::List;
        }
        match kind.resolved() {
            AccelKind::None => Accel::List,
            AccelKind::Flat => Accel::Bvh(Bvh::build_flat(prims)),
            AccelKind::Median => Accel::Bvh(Bvh::build_median(prims, leaf_size)),
            AccelKind::Sah => Accel::Bvh(Bvh::build_sah(prims, leaf_size)),
            AccelKind::Auto | AccelKind::Sah4 => Accel::Bvh4(Bvh4::build(prims, leaf_size)),
            AccelKind::Sah8 => Accel::Bvh8(Bvh8::build(prims, leaf_size)),
        }
    }

    /// The accelerator with queries that run with `isa` (a wide tree's; the others run with the
    /// baseline whatever `isa` says). The answers are the same bits for every `isa`
    /// ([`kernels::isa`]).
    pub fn with_isa(self, isa: Isa) -> Accel {
        match self {
            Accel::Bvh4(b) => Accel::Bvh4(b.with_isa(isa)),
            Accel::Bvh8(b) => Accel::Bvh8(b.with_isa(isa)),
            other => other,
        }
    }

    /// What the queries run with.
    pub fn isa(&self) -> Isa {
        match self {
            Accel::Bvh4(b) => b.isa(),
            Accel::Bvh8(b) => b.isa(),
            Accel::List | Accel::Bvh(_) => Isa::BASELINE,
        }
    }

    /// Bytes the accelerator holds beyond the primitives (nodes and leaf blocks).
    pub fn memory_bytes(&self) -> usize {
        match self {
            Accel::List => 0,
            Accel::Bvh(b) => b.memory_bytes(),
            Accel::Bvh4(b) => b.memory_bytes(),
            Accel::Bvh8(b) => b.memory_bytes(),
        }
    }

    /// Of [`Accel::memory_bytes`], the bytes of the leaves (their blocks).
    pub fn leaf_bytes(&self) -> usize {
        match self {
            Accel::List => 0,
            Accel::Bvh(b) => b.leaf_bytes(),
            Accel::Bvh4(b) => b.leaf_bytes(),
            Accel::Bvh8(b) => b.leaf_bytes(),
        }
    }

    /// The tree's shape, if there is one.
    pub fn stats(&self) -> Option<BvhStats> {
        match self {
            Accel::List => None,
            Accel::Bvh(b) => Some(b.stats()),
            Accel::Bvh4(b) => Some(b.stats()),
            Accel::Bvh8(b) => Some(b.stats()),
        }
    }

    /// The closest hit with `0 < t < t_max`: the primitive index and its candidate. Among hits at
    /// the same `t`, the least primitive index.
    #[inline]
    pub fn closest(&self, prims: &Primitives, ray: &Ray, t_max: f32) -> Option<(u32, Candidate)> {
        if t_max.is_nan() || t_max <= 0.0 {
            return None;
        }
        let r = PreparedRay::new(ray);
        match self {
            Accel::List => {
                // In index order with a strict bound: the first of equal-t hits stays.
                let mut best = None;
                let mut t_max = t_max;
                for i in 0..prims.len() as u32 {
                    if let Some(c) = prims.shape(i).intersect_prepared(&r, t_max) {
                        t_max = c.t;
                        best = Some((i, c));
                    }
                }
                best
            }
            Accel::Bvh(b) => b.closest(prims, &r, t_max),
            Accel::Bvh4(b) => b.closest(prims, &r, t_max),
            Accel::Bvh8(b) => b.closest(prims, &r, t_max),
        }
    }

    /// Whether anything is hit with `0 < t < t_max` for which `blocks(primitive)` holds. Stops at
    /// the first such hit. `blocks` is called only for primitives the ray hits, in no particular
    /// order, and may note what it is shown (a shadow ray notes the transmissive surfaces it
    /// passes).
    #[inline]
    pub fn any(
        &self,
        prims: &Primitives,
        ray: &Ray,
        t_max: f32,
        mut blocks: impl FnMut(u32) -> bool,
    ) -> bool {
        if t_max.is_nan() || t_max <= 0.0 {
            return false;
        }
        let r = PreparedRay::new(ray);
        match self {
            Accel::List => (0..prims.len() as u32)
                .any(|i| prims.shape(i).intersect_prepared(&r, t_max).is_some() && blocks(i)),
            Accel::Bvh(b) => b.any(prims, &r, t_max, blocks),
            Accel::Bvh4(b) => b.any(prims, &r, t_max, blocks),
            Accel::Bvh8(b) => b.any(prims, &r, t_max, blocks),
        }
    }

    /// The primitives some ray of `beam` may hit (see [`Beam`]), written to `out`: every
    /// unbounded primitive and every bounded one whose bounding ball meets the beam. Returns
    /// `false`, with `out` of no use, when there are more than `limit`: the caller then queries
    /// the whole accelerator, as cheap as a long list.
    pub fn beam_candidates(
        &self,
        prims: &Primitives,
        beam: &Beam,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        match self {
            Accel::List => gather(beam, prims, 0..prims.len() as u32, limit, out),
            Accel::Bvh(b) => b.beam_candidates(prims, beam, limit, out),
            Accel::Bvh4(b) => b.beam_candidates(prims, beam, limit, out),
            Accel::Bvh8(b) => b.beam_candidates(prims, beam, limit, out),
        }
    }

    /// The bounded primitives whose boxes meet `region` (touching counts), written to `out`;
    /// `false`, with `out` of no use, when there are more than `limit` or the accelerator is the
    /// plain list (which keeps no boxes to find them by).
    pub fn meeting_box(
        &self,
        prims: &Primitives,
        region: &Aabb,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        match self {
            Accel::List => false,
            Accel::Bvh(b) => traverse::meeting_box(b, prims, region, limit, out),
            Accel::Bvh4(b) => traverse::meeting_box(b, prims, region, limit, out),
            Accel::Bvh8(b) => traverse::meeting_box(b, prims, region, limit, out),
        }
    }
}

/// Whether one of the primitives `indices` accepted by `blocks` is hit with `0 < t < t_max`
/// (what [`Accel::any`] asks of a tree's unbounded primitives, where it has any). Kept out of line
/// so that it does not change how the tree's any-hit loops around it are compiled.
#[inline(never)]
pub(crate) fn any_among(
    prims: &Primitives,
    indices: &[u32],
    r: &PreparedRay,
    t_max: f32,
    blocks: &mut impl FnMut(u32) -> bool,
) -> bool {
    indices
        .iter()
        .any(|&i| prims.shape(i).intersect_prepared(r, t_max).is_some() && blocks(i))
}

/// Appends to `out` those of the primitives `indices` that some ray of `beam` may hit; `false`
/// as soon as that would make `out` longer than `limit`.
pub(crate) fn gather(
    beam: &Beam,
    prims: &Primitives,
    indices: impl IntoIterator<Item = u32>,
    limit: usize,
    out: &mut Vec<u32>,
) -> bool {
    for i in indices {
        if may_hit(beam, &prims.shape(i)) {
            if out.len() >= limit {
                return false;
            }
            out.push(i);
        }
    }
    true
}

/// Whether some ray of `beam` may hit `shape`: spheres by their own ball, other bounded shapes by
/// their box's, unbounded ones always.
#[inline]
pub(crate) fn may_hit(beam: &Beam, shape: &Shape) -> bool {
    ball_of(shape).is_none_or(|(center, radius)| beam.may_hit_ball(center, radius))
}

/// The ball [`may_hit`] tests `shape` by: a sphere's own, the bounding ball of another bounded
/// shape's box ([`Beam::may_hit_box`]'s); `None` for an unbounded shape.
#[inline]
pub(crate) fn ball_of(shape: &Shape) -> Option<(Vec3, f32)> {
    match shape {
        Shape::Sphere(s) => Some((s.center, s.radius.abs())),
        Shape::Plane(_) => None,
        Shape::Triangle(_) | Shape::Cylinder(_) => Some(shape.bounds().ball()),
    }
}
