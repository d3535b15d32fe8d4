//! The leaves of the BVHs ([`super::Bvh`], [`super::Bvh4`]): blocks of four entries, leaf by
//! leaf, each leaf's triangles, then its spheres, then its other primitives, each kind starting
//! a new [`Block`]. A block holds its primitives' indices and, for triangles and spheres, their
//! shapes in structure-of-arrays form ([`Triangle4`], [`Sphere4`]), tested four at a time in SIMD
//! lanes with the bits of the scalar tests; other shapes are tested one by one.
//!
//! A leaf is a span of entries `start..start + count` with `start` a multiple of four. The trees
//! differ only in their nodes; how a leaf answers a query is here, once.

use super::kernels::{triangle4, Hits4, Ray4, Rows, Sphere4, Triangle4};
use crate::geometry::{Candidate, Primitives, Shape};
use crate::math::next_float_up;
use crate::ray::PreparedRay;

/// An entry that holds no primitive.
pub(super) const PAD: u32 = u32::MAX;

/// Where an entry keeps its block's kind: the bits from here up. Primitive indices are below
/// [`MAX_PRIMITIVES`].
const KIND_SHIFT: u32 = 30;

/// The most primitives a tree can hold (the bits above them name their block's kind).
pub(super) const MAX_PRIMITIVES: usize = 1 << KIND_SHIFT;

/// The closest hit so far.
pub(super) struct Best {
    /// Its `t` (the query's `t_max` before any hit).
    pub t: f32,
    /// Its primitive, or [`Best::NONE`].
    pub index: u32,
    pub candidate: Candidate,
}

impl Best {
    pub const NONE: u32 = u32::MAX;

    #[inline(always)]
    pub fn new(t_max: f32) -> Best {
        Best {
            t: t_max,
            index: Best::NONE,
            candidate: Candidate {
                t: t_max,
                aux: [0.0; 2],
            },
        }
    }

    #[inline(always)]
    pub fn hit(&self) -> Option<(u32, Candidate)> {
        (self.index != Best::NONE).then_some((self.index, self.candidate))
    }

    /// Tests the primitives `indices` (in increasing order) one by one: with a strict bound, the
    /// first of equal-`t` hits stays, and a primitive of lower index at the same `t` met later
    /// in a leaf still wins there ([`Leaves::closest`]).
    #[inline(always)]
    pub fn among(&mut self, prims: &Primitives, indices: &[u32], r: &PreparedRay) {
        for &p in indices {
            if let Some(c) = prims.shape(p).intersect_prepared(r, self.t) {
                self.take(p, c);
            }
        }
    }

    /// Takes `c` on primitive `p` as the best hit.
    #[inline(always)]
    pub fn take(&mut self, p: u32, c: Candidate) {
        self.t = c.t;
        self.index = p;
        self.candidate = c;
    }
}

/// Four entries of a leaf, 160 bytes: their primitives, each tagged with the block's [`BlockKind`],
/// and their shapes as the block's kernel reads them (unused in a [`BlockKind::Other`] block).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(16))]
struct Block {
    /// `index | kind << KIND_SHIFT` for each lane, or [`PAD`] (always after the lanes in use).
    entries: [u32; 4],
    shapes: Rows,
}

const _: () = assert!(std::mem::size_of::<Block>() == 160);

impl Block {
    /// A block with no entry.
    const EMPTY: Block = Block {
        entries: [PAD; 4],
        shapes: [[glam::Vec4::ZERO; 3]; 3],
    };

    fn new(kind: BlockKind, shapes: Rows, indices: &[u32]) -> Block {
        let entries = std::array::from_fn(|l| match indices[l] {
            PAD => PAD,
            p => p | (kind as u32) << KIND_SHIFT,
        });
        Block { entries, shapes }
    }

    /// The primitive of lane `l` (a lane in use).
    #[inline(always)]
    fn primitive(&self, l: usize) -> u32 {
        self.entries[l] & ((1 << KIND_SHIFT) - 1)
    }

    /// The primitives of the block.
    fn primitives(&self) -> impl Iterator<Item = u32> + '_ {
        (0..4)
            .filter(|&l| self.entries[l] != PAD)
            .map(|l| self.primitive(l))
    }

    /// What the lanes hit with `t < t_max`; [`Hits4::scalar`] also holds every lane the scalar
    /// test must decide.
    #[inline(always)]
    fn intersect(&self, r4: &Ray4, t_max: f32) -> Hits4 {
        const TRIANGLE: u32 = BlockKind::Triangle as u32;
        const SPHERE: u32 = BlockKind::Sphere as u32;
        const OTHER: u32 = BlockKind::Other as u32;
        match self.entries[0] >> KIND_SHIFT {
            TRIANGLE => triangle4::intersect_rows(&self.shapes, r4, t_max),
            SPHERE => Sphere4::from_rows(&self.shapes).intersect(r4, t_max),
            OTHER => Hits4 {
                scalar: (0..4).fold(0, |m, l| m | ((self.entries[l] != PAD) as u32) << l),
                ..Hits4::NONE
            },
            _ => Hits4::NONE,
        }
    }
}

/// The scalar test of primitive `p`, for the lanes a block's kernel leaves to it: out of line,
/// so that the rarely taken test of every shape is not copied into each traversal loop.
#[inline(never)]
fn scalar_test(prims: &Primitives, p: u32, r: &PreparedRay, t_max: f32) -> Option<Candidate> {
    prims.shape(p).intersect_prepared(r, t_max)
}

/// The set bits of `mask`, lowest first.
#[inline(always)]
pub(super) fn lanes(mut mask: u32) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let l = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            l
        })
    })
}

/// The kinds of primitive a leaf keeps apart, in their order there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum BlockKind {
    Triangle = 0,
    Sphere = 1,
    Other = 2,
}

fn kind(shape: &Shape) -> BlockKind {
    match shape {
        Shape::Triangle(_) => BlockKind::Triangle,
        Shape::Sphere(_) => BlockKind::Sphere,
        _ => BlockKind::Other,
    }
}

/// Every leaf of a tree, in blocks.
#[derive(Debug, Clone)]
pub(super) struct Leaves {
    /// Entries `4j..4j + 4` are block `j`.
    blocks: Vec<Block>,
}

impl Leaves {
    /// Lays out the leaves `spans` (each a `(start, count)` of entries of `order`) in blocks, and
    /// updates each span to its new place (padding included).
    pub fn pack<'a>(
        prims: &Primitives,
        order: &[u32],
        spans: impl Iterator<Item = (&'a mut u32, &'a mut u32)>,
    ) -> Leaves {
        debug_assert!(prims.len() <= MAX_PRIMITIVES);
        let spans: Vec<_> = spans.collect();
        // Each primitive's kind, found once (a primitive with no record is a mesh's triangle).
        let kind_at: Vec<BlockKind> = order
            .iter()
            .map(|&p| {
                prims
                    .record(p)
                    .map_or(BlockKind::Triangle, |r| kind(&r.shape))
            })
            .collect();
        let kinds = [BlockKind::Triangle, BlockKind::Sphere, BlockKind::Other];
        // The positions in `order` of a leaf's primitives of kind `k`, in their order there.
        let of_kind = |start: u32, count: u32, k: BlockKind| {
            let kind_at = &kind_at;
            (start..start + count).filter(move |&j| kind_at[j as usize] == k)
        };
        let total = spans
            .iter()
            .map(|(start, count)| {
                kinds
                    .map(|k| of_kind(**start, **count, k).count().div_ceil(4))
                    .iter()
                    .sum::<usize>()
            })
            .sum();
        let mut blocks = Vec::with_capacity(total);
        let mut lanes = Vec::with_capacity(4);
        for (start, count) in spans {
            let leaf = (*start, *count);
            *start = 4 * blocks.len() as u32;
            for k in kinds {
                let mut of_kind = of_kind(leaf.0, leaf.1, k);
                loop {
                    lanes.clear();
                    lanes.extend(of_kind.by_ref().take(4));
                    if lanes.is_empty() {
                        break;
                    }
                    for j in lanes.iter_mut() {
                        *j = order[*j as usize];
                    }
                    let lane: [Option<Shape>; 4] =
                        std::array::from_fn(|l| lanes.get(l).map(|&p| prims.shape(p).into_owned()));
                    let rows = match k {
                        BlockKind::Triangle => Triangle4::new(lane.each_ref().map(|s| match s {
                            Some(Shape::Triangle(t)) => Some(t),
                            _ => None,
                        }))
                        .rows(),
                        BlockKind::Sphere => Sphere4::new(lane.each_ref().map(|s| match s {
                            Some(Shape::Sphere(s)) => Some(s),
                            _ => None,
                        }))
                        .rows(),
                        BlockKind::Other => Block::EMPTY.shapes,
                    };
                    lanes.resize(4, PAD);
                    blocks.push(Block::new(k, rows, &lanes));
                }
            }
            *count = 4 * blocks.len() as u32 - *start;
        }
        debug_assert_eq!(blocks.len(), total);
        Leaves { blocks }
    }

    /// Appends a leaf of one block that holds nothing and returns its span: what a tree points an
    /// unused child slot at, so that even a ray whose box tests all pass (a NaN direction) finds
    /// a valid, empty leaf there.
    pub fn push_empty(&mut self) -> (u32, u32) {
        let start = 4 * self.blocks.len() as u32;
        self.blocks.reserve_exact(1);
        self.blocks.push(Block::EMPTY);
        (start, 4)
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.blocks.capacity() * std::mem::size_of::<Block>()
    }

    /// The blocks of the leaf at `start..start + count` (`start` a multiple of four).
    #[inline(always)]
    fn blocks(&self, start: u32, count: u32) -> &[Block] {
        let start = start as usize;
        &self.blocks[start / 4..(start + count as usize).div_ceil(4)]
    }

    /// The primitives of the leaf at `start..start + count`.
    pub fn primitives(&self, start: u32, count: u32) -> impl Iterator<Item = u32> + '_ {
        self.blocks(start, count).iter().flat_map(Block::primitives)
    }

    /// Every primitive of every leaf, leaf by leaf.
    #[cfg(test)]
    pub fn all(&self) -> impl Iterator<Item = u32> + '_ {
        self.blocks.iter().flat_map(Block::primitives)
    }

    /// Tests the primitives of the leaf at `start..start + count` for a closer hit than `best`. A
    /// tie in `t` goes to the lower index: such a primitive may also hit at exactly `best.t`, so
    /// its bound is the next float up.
    ///
    /// Blocks are tested four lanes at a time under the loosest bound, `next_float_up(best.t)`;
    /// each lane hit is then held to its own bound, as the scalar test would have been (a lane's
    /// `t` does not depend on the bound it was tested under).
    #[inline(always)]
    pub fn closest(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        r4: &Ray4,
        (start, count): (u32, u32),
        best: &mut Best,
    ) {
        let bound = |p: u32, best: &Best| {
            if p < best.index && best.index != Best::NONE {
                next_float_up(best.t)
            } else {
                best.t
            }
        };
        for block in self.blocks(start, count) {
            let h = block.intersect(r4, next_float_up(best.t));
            let scalar = h.scalar;
            if h.hit | scalar == 0 {
                continue;
            }
            // Lanes by index from arrays: `Vec4`'s own indexing is a jump table over the lane.
            let (t, b1, b2) = (h.t.to_array(), h.b1.to_array(), h.b2.to_array());
            for l in lanes(h.hit | scalar) {
                let p = block.primitive(l);
                let b = bound(p, best);
                let c = if scalar & (1 << l) != 0 {
                    scalar_test(prims, p, r, b)
                } else {
                    (t[l] < b).then(|| Candidate {
                        t: t[l],
                        aux: [b1[l], b2[l]],
                    })
                };
                if let Some(c) = c {
                    best.take(p, c);
                }
            }
        }
    }

    /// Whether a primitive of the leaf at `start..start + count` accepted by `blocks` is hit
    /// before `t_max`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn any(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        r4: &Ray4,
        (start, count): (u32, u32),
        t_max: f32,
        blocks: &mut impl FnMut(u32) -> bool,
    ) -> bool {
        for block in self.blocks(start, count) {
            let h = block.intersect(r4, t_max);
            let scalar = h.scalar;
            for l in lanes(h.hit | scalar) {
                let p = block.primitive(l);
                let hit = scalar & (1 << l) == 0 || scalar_test(prims, p, r, t_max).is_some();
                if hit && blocks(p) {
                    return true;
                }
            }
        }
        false
    }
}
