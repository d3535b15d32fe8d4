//! The leaves of the BVHs ([`super::Bvh`], [`super::Bvh4`]): primitive indices laid out leaf by
//! leaf (`order`), each leaf's triangles, then its spheres, then its other primitives, each kind
//! starting at a multiple of four. Every four entries of `order` are one [`Block`]: triangles and
//! spheres copied into structure-of-arrays blocks ([`Triangle4`], [`Sphere4`]) and tested four at
//! a time in SIMD lanes, with the bits of the scalar tests, and other shapes tested one by one.
//!
//! A leaf is a span of entries `start..start + count` with `start` a multiple of four. The trees
//! differ only in their nodes; how a leaf answers a query is here, once.

use super::kernels::{Hits4, Ray4, Sphere4, Triangle4};
use crate::geometry::{Candidate, Primitive, Shape};
use crate::math::next_float_up;
use crate::ray::PreparedRay;

/// The entries of `order` that hold no primitive.
pub(super) const PAD: u32 = u32::MAX;

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
    pub fn among(&mut self, prims: &[Primitive], indices: &[u32], r: &PreparedRay) {
        for &p in indices {
            if let Some(c) = prims[p as usize].shape.intersect_prepared(r, self.t) {
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

/// Four entries of `order`, as a leaf tests them.
#[derive(Debug, Clone, Copy)]
enum Block {
    Triangles(Triangle4),
    Spheres(Sphere4),
    /// Other shapes, tested one by one: bit `l` of `lanes` is set where entry `l` holds one.
    Scalar {
        lanes: u32,
    },
}

impl Block {
    /// What the lanes hit with `t < t_max`; [`Hits4::scalar`] also holds every lane the scalar
    /// test must decide.
    #[inline(always)]
    fn intersect(&self, r4: &Ray4, t_max: f32) -> Hits4 {
        match self {
            Block::Triangles(b) => b.intersect(r4, t_max),
            Block::Spheres(b) => b.intersect(r4, t_max),
            Block::Scalar { lanes } => Hits4 {
                scalar: *lanes,
                ..Hits4::NONE
            },
        }
    }
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
enum Kind {
    Triangle,
    Sphere,
    Other,
}

fn kind(p: &Primitive) -> Kind {
    match p.shape {
        Shape::Triangle(_) => Kind::Triangle,
        Shape::Sphere(_) => Kind::Sphere,
        _ => Kind::Other,
    }
}

/// Every leaf of a tree, in blocks.
#[derive(Debug, Clone)]
pub(super) struct Leaves {
    /// Primitive indices, leaf by leaf; the entries that pad a kind to a multiple of four are
    /// [`PAD`].
    pub order: Vec<u32>,
    /// Block `j` holds the primitives of entries `4j..4j + 4` of `order`.
    blocks: Vec<Block>,
}

impl Leaves {
    /// Lays out the leaves `spans` (each a `(start, count)` of entries of `order`) in blocks, and
    /// updates each span to its new place (padding included).
    pub fn pack<'a>(
        prims: &[Primitive],
        order: &[u32],
        spans: impl Iterator<Item = (&'a mut u32, &'a mut u32)>,
    ) -> Leaves {
        let mut packed = Vec::with_capacity(order.len());
        for (start, count) in spans {
            // `packed` stays a multiple of four long between kinds and between leaves.
            let leaf = &order[*start as usize..][..*count as usize];
            *start = packed.len() as u32;
            for k in [Kind::Triangle, Kind::Sphere, Kind::Other] {
                packed.extend(leaf.iter().filter(|&&p| kind(&prims[p as usize]) == k));
                packed.resize(packed.len().next_multiple_of(4), PAD);
            }
            *count = packed.len() as u32 - *start;
        }
        let blocks = packed
            .chunks_exact(4)
            .map(|c| {
                let shape = |l: usize| (c[l] != PAD).then(|| &prims[c[l] as usize].shape);
                let lanes = [0, 1, 2, 3].map(shape);
                if lanes.iter().any(|s| matches!(s, Some(Shape::Triangle(_)))) {
                    Block::Triangles(Triangle4::new(lanes.map(|s| match s {
                        Some(Shape::Triangle(t)) => Some(t),
                        _ => None,
                    })))
                } else if lanes.iter().any(|s| matches!(s, Some(Shape::Sphere(_)))) {
                    Block::Spheres(Sphere4::new(lanes.map(|s| match s {
                        Some(Shape::Sphere(s)) => Some(s),
                        _ => None,
                    })))
                } else {
                    let lanes = (0..4).filter(|&l| c[l] != PAD).fold(0, |m, l| m | 1 << l);
                    Block::Scalar { lanes }
                }
            })
            .collect();
        Leaves {
            order: packed,
            blocks,
        }
    }

    /// Appends a leaf of one block that holds nothing and returns its span: what a tree points an
    /// unused child slot at, so that even a ray whose box tests all pass (a NaN direction) finds
    /// a valid, empty leaf there.
    pub fn push_empty(&mut self) -> (u32, u32) {
        let start = self.order.len() as u32;
        self.order.reserve_exact(4);
        self.order.extend([PAD; 4]);
        self.blocks.reserve_exact(1);
        self.blocks.push(Block::Scalar { lanes: 0 });
        (start, 4)
    }

    /// Bytes held: the primitive order and the blocks.
    pub fn bytes(&self) -> usize {
        self.blocks.capacity() * std::mem::size_of::<Block>()
            + self.order.capacity() * std::mem::size_of::<u32>()
    }

    /// The blocks of the leaf at `start..start + count` (`start` a multiple of four).
    #[inline(always)]
    fn blocks(&self, start: u32, count: u32) -> &[Block] {
        let start = start as usize;
        &self.blocks[start / 4..(start + count as usize).div_ceil(4)]
    }

    /// The primitives of the leaf at `start..start + count`.
    pub fn primitives(&self, start: u32, count: u32) -> impl Iterator<Item = u32> + '_ {
        let start = start as usize;
        self.order[start..start + count as usize]
            .iter()
            .copied()
            .filter(|&p| p != PAD)
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
        prims: &[Primitive],
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
        for (j, block) in self.blocks(start, count).iter().enumerate() {
            let base = start as usize + 4 * j;
            let h = block.intersect(r4, next_float_up(best.t));
            let scalar = h.scalar;
            for l in lanes(h.hit | scalar) {
                let p = self.order[base + l];
                let b = bound(p, best);
                let c = if scalar & (1 << l) != 0 {
                    prims[p as usize].shape.intersect_prepared(r, b)
                } else {
                    (h.t[l] < b).then(|| Candidate {
                        t: h.t[l],
                        aux: [h.b1[l], h.b2[l]],
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
        prims: &[Primitive],
        r: &PreparedRay,
        r4: &Ray4,
        (start, count): (u32, u32),
        t_max: f32,
        blocks: &mut impl FnMut(u32) -> bool,
    ) -> bool {
        for (j, block) in self.blocks(start, count).iter().enumerate() {
            let base = start as usize + 4 * j;
            let h = block.intersect(r4, t_max);
            let scalar = h.scalar;
            for l in lanes(h.hit | scalar) {
                let p = self.order[base + l];
                let hit = scalar & (1 << l) == 0
                    || prims[p as usize]
                        .shape
                        .intersect_prepared(r, t_max)
                        .is_some();
                if hit && blocks(p) {
                    return true;
                }
            }
        }
        false
    }
}
