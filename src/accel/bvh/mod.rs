//! A bounding volume hierarchy over primitives, flattened into an array of 32-byte nodes. The two
//! children of an interior node are stored together, interleaved in one 64-byte cache line
//! (`NodePair`), so a traversal step tests both boxes at once in SIMD lanes and visits the nearer
//! first; pairs are laid out depth-first.
//!
//! Two builders, both over individual primitives (a mesh is already one primitive per triangle):
//! - **median**: the primitives' centroids split at the median, the axis cycling x, y, z with
//!   depth, leaves of at most `leaf_size` primitives;
//! - **SAH**: binned surface area heuristic (Wald, "On fast Construction of SAH-based Bounding
//!   Volume Hierarchies", IEEE Symposium on Interactive Ray Tracing 2007): the centroid bounds of a
//!   node are cut into [`SAH_BINS`] equal bins on each of the three axes, and of the `3·(BINS − 1)`
//!   planes between bins the one of least expected cost is taken, or a leaf is made if that is
//!   cheaper (MacDonald and Booth, "Heuristics for ray tracing using space subdivision", The Visual
//!   Computer 6(3), 1990, give the cost model). When all centroids coincide, no plane separates
//!   them and the node is split at the middle of its list instead.
//!
//! Primitive indices are reordered so that each leaf's are contiguous, in blocks of four tested in
//! SIMD lanes (`accel/leaves.rs`).
//!
//! Both builders split the nodes of at least `PARALLEL_MIN` primitives and build their two
//! subtrees as two `rayon` tasks, then lay the parts out where the one-thread recursion puts
//! them: the tree is the same, node for node, on any number of threads.
//!
//! Unbounded primitives (infinite planes, see [`crate::geometry::Shape::is_bounded`]) have no box
//! to put in a node: they are kept out of the tree in a list of their own (`unbounded`), which
//! every query tests first. A closest-hit query then starts from their best hit, so the tree is
//! culled by it (a floor plane hides everything below it).
//!
//! Queries return exactly what testing every primitive returns: the hit of least `t`, and among
//! equal `t` the one of least primitive index (see [`crate::accel`]).

use glam::{Vec3A, Vec4, Vec4Swizzles};

use super::aabb::Aabb;
use super::beam::Beam;
use super::kernels::Ray4;
use super::leaves::{Best, Leaves};
use super::stack::Stack;
use super::traverse::{self, next_within, Tree};
use crate::geometry::{Candidate, Primitives};
use crate::math::Vec3;
use crate::ray::PreparedRay;

mod build;
#[cfg(test)]
mod tests;

pub(in crate::accel) use build::BinaryTree;
use build::*;

/// Traversal stack entries. The builders keep every tree at most `MAX_SAH_DEPTH + 33` levels deep
/// (see `MAX_SAH_DEPTH`), and a traversal holds at most one entry per level.
pub const STACK_SIZE: usize = 128;

/// Depth below which the SAH builder switches to median splits. A median split halves a node, so
/// fewer than 2³² primitives need at most 32 more levels: trees stay within [`STACK_SIZE`].
/// SAH trees of ordinary scenes are far shallower, so this only bounds pathological inputs (a
/// long run of ever larger primitives, where SAH peels one per level).
const MAX_SAH_DEPTH: usize = 90;

/// Bins per axis of the SAH builder: Wald (2007) found 16 bins within a few percent of the full
/// sweep's tree quality.
pub const SAH_BINS: usize = 16;
const _: () = assert!(SAH_BINS.is_power_of_two() && SAH_BINS >= 12);

/// Cost of one traversal step (testing the two children's boxes and choosing the next node),
/// relative to [`INTERSECTION_COST`], chosen by measurement (`docs/performance.md`, "Building
/// the tree"). A step costs more than its arithmetic because its next node depends on a
/// comparison: the traversal waits on latency.
pub const TRAVERSAL_COST: f32 = 2.0;

/// Cost of testing one block of up to four primitives in SIMD lanes (see `accel/leaves.rs`): a
/// leaf of `n` primitives costs `⌈n/4⌉` of these, so the builder fills blocks rather than
/// splitting a leaf of four that costs what a leaf of one costs.
pub const INTERSECTION_COST: f32 = 1.0;

/// Which builder.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Split {
    /// Median split, axis cycling with depth.
    Median,
    /// Binned SAH.
    Sah,
    /// No split: every bounded primitive in the root, one leaf tested block by block (what
    /// tiny scenes want: no traversal at all).
    None,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BvhOptions {
    /// Most primitives in a leaf (at least 1). The SAH builder makes smaller leaves where its cost
    /// model says so.
    pub leaf_size: usize,
    pub split: Split,
}

impl Default for BvhOptions {
    fn default() -> Self {
        BvhOptions {
            leaf_size: 4,
            split: Split::Sah,
        }
    }
}

/// A node as the builder makes it. For a leaf `count > 0` and `index` is its first entry in
/// `order`; for an interior node `count == 0` and its children are the two nodes of pair `index`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Node {
    pub lo: Vec3A,
    pub hi: Vec3A,
    pub index: u32,
    pub count: u32,
}

impl Node {
    /// The leaf over entries `first..first + count` of the order, with bounds `b`.
    fn leaf(b: &Bounds, first: usize, count: usize) -> Node {
        Node {
            lo: b.lo,
            hi: b.hi,
            index: first as u32,
            count: count as u32,
        }
    }

    /// The node with its children, if it has any, `pairs` sibling pairs further on.
    fn shifted(&self, pairs: u32) -> Node {
        Node {
            index: self.index + if self.count == 0 { pairs } else { 0 },
            ..*self
        }
    }

    pub fn reference(&self) -> NodeRef {
        NodeRef {
            index: self.index,
            count: self.count,
        }
    }
}

/// The two children of an interior node: 32 bytes each (a box and two counts), stored interleaved
/// in one 64-byte cache line so that both boxes are tested together. Per axis the four lanes are
/// `[lo of child 0, lo of child 1, hi of child 0, hi of child 1]`; `meta` is
/// `[index 0, index 1, count 0, count 1]`. The root, which has no sibling, is kept apart.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(64))]
struct NodePair {
    axes: [[f32; 4]; 3],
    meta: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<NodePair>() == 64);

impl NodePair {
    fn new(a: &Node, b: &Node) -> NodePair {
        let axis = |i: usize| [a.lo[i], b.lo[i], a.hi[i], b.hi[i]];
        NodePair {
            axes: [axis(0), axis(1), axis(2)],
            meta: [a.index, b.index, a.count, b.count],
        }
    }

    #[inline(always)]
    fn index(&self, side: usize) -> u32 {
        self.meta[side & 1]
    }

    #[inline(always)]
    fn count(&self, side: usize) -> u32 {
        self.meta[2 + (side & 1)]
    }
}

/// A node reference in traversal: `(index, count)` as in [`Node`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct NodeRef {
    pub index: u32,
    pub count: u32,
}

/// The per-ray constants of the two-box test [`Bvh::pair_hit`].
struct PairRay {
    origin: [Vec4; 3],
    /// Per axis, the multipliers of the four lanes: `inv_dir` for the near planes, and
    /// `-inv_dir · (1 + 2γ(3))` for the far planes (negated, so one `max` gathers both).
    scale: [Vec4; 3],
}

impl PairRay {
    #[inline(always)]
    fn new(r: &PreparedRay) -> PairRay {
        let o = r.origin.to_array();
        let inv = r.inv_dir.to_array();
        let far = r.inv_dir_far.to_array();
        let neg = [r.negative.test(0), r.negative.test(1), r.negative.test(2)];
        PairRay {
            origin: [0, 1, 2].map(|a| Vec4::splat(o[a])),
            scale: [0, 1, 2].map(|a| {
                if neg[a] {
                    Vec4::new(-far[a], -far[a], inv[a], inv[a])
                } else {
                    Vec4::new(inv[a], inv[a], -far[a], -far[a])
                }
            }),
        }
    }
}

/// Shape of a built tree, for benchmarks and tests.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BvhStats {
    pub nodes: usize,
    pub leaves: usize,
    /// Levels below the root of the deepest leaf.
    pub depth: usize,
    /// Most primitives in one leaf.
    pub max_leaf: usize,
}

#[derive(Debug, Clone)]
pub struct Bvh {
    /// The root's box and reference; `None` for no primitives.
    root: Option<(Vec3A, Vec3A, NodeRef)>,
    /// Every other node, in sibling pairs.
    pairs: Vec<NodePair>,
    /// The leaves' primitives, in blocks.
    leaves: Leaves,
    /// The unbounded primitives, in index order: outside the tree, tested by every query.
    unbounded: Vec<u32>,
}

impl Bvh {
    /// Builds a tree over `prims`. At most `leaves::MAX_PRIMITIVES` primitives (the caller checks).
    pub fn build(prims: &Primitives, options: BvhOptions) -> Bvh {
        let BinaryTree {
            nodes,
            leaves,
            unbounded,
        } = BinaryTree::build(prims, options);
        let pairs = nodes
            .get(1..)
            .unwrap_or_default()
            .chunks_exact(2)
            .map(|c| NodePair::new(&c[0], &c[1]))
            .collect();
        Bvh {
            root: nodes.first().map(|n| (n.lo, n.hi, n.reference())),
            pairs,
            leaves,
            unbounded,
        }
    }

    /// Builds with the median split (the axis cycling per level).
    pub fn build_median(prims: &Primitives, leaf_size: usize) -> Bvh {
        Bvh::build(
            prims,
            BvhOptions {
                leaf_size,
                split: Split::Median,
            },
        )
    }

    /// Builds the one-leaf tree ([`Split::None`]).
    pub fn build_flat(prims: &Primitives) -> Bvh {
        Bvh::build(
            prims,
            BvhOptions {
                leaf_size: usize::MAX,
                split: Split::None,
            },
        )
    }

    /// Builds with the binned SAH.
    pub fn build_sah(prims: &Primitives, leaf_size: usize) -> Bvh {
        Bvh::build(
            prims,
            BvhOptions {
                leaf_size,
                split: Split::Sah,
            },
        )
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        usize::from(self.root.is_some()) + 2 * self.pairs.len()
    }

    /// Bytes held: the nodes, the leaves' blocks and the unbounded list.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Bvh>()
            + self.node_bytes()
            + self.leaf_bytes()
            + self.unbounded.capacity() * std::mem::size_of::<u32>()
    }

    /// Bytes of the interior nodes.
    pub fn node_bytes(&self) -> usize {
        self.pairs.capacity() * std::mem::size_of::<NodePair>()
    }

    /// Bytes of the leaves: their SIMD blocks (primitive indices included).
    pub fn leaf_bytes(&self) -> usize {
        self.leaves.bytes()
    }

    /// The node with identifier `id`: side `id & 1` of pair `id >> 1`.
    #[inline(always)]
    fn node(&self, id: u32) -> NodeRef {
        let pair = &self.pairs[id as usize >> 1];
        NodeRef {
            index: pair.index(id as usize),
            count: pair.count(id as usize),
        }
    }

    /// Slab test of both boxes of a pair at once (the same decisions as [`super::aabb::slab`] on
    /// each): a bit mask of the boxes hit (bit 0: child 0) and their entry distances.
    #[inline(always)]
    fn pair_hit<const NX: bool, const NY: bool, const NZ: bool>(
        pair: &NodePair,
        pr: &PairRay,
        t_max: f32,
    ) -> (u32, f32, f32) {
        // Lanes 0 and 1 gather the entry distances (at least 0), lanes 2 and 3 minus the exit
        // distances (at least −t_max). `max(t, acc)` returns `acc` where `t` is NaN: a ray in a
        // slab's plane ignores that plane, as in `slab`.
        let mut acc = Vec4::new(0.0, 0.0, -t_max, -t_max);
        for (a, swap) in [NX, NY, NZ].into_iter().enumerate() {
            let t = (Vec4::from_array(pair.axes[a]) - pr.origin[a]) * pr.scale[a];
            let t = if swap { t.zwxy() } else { t };
            acc = t.max(acc);
        }
        let exit = -acc.zwxy();
        (acc.cmple(exit).bitmask() & 3, acc.x, acc.y)
    }

    /// Node count, leaf count, depth and largest leaf.
    pub fn stats(&self) -> BvhStats {
        traverse::stats(self)
    }

    /// See [`crate::accel::Accel::beam_candidates`].
    pub fn beam_candidates(
        &self,
        prims: &Primitives,
        beam: &Beam,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        traverse::beam_candidates(self, prims, beam, limit, out)
    }

    /// The closest hit with `0 < t < t_max` (least `t`, then least primitive index): the
    /// unbounded primitives first, in index order, then the tree, visiting the nearer child first
    /// and skipping subtrees that start beyond the best hit so far.
    pub fn closest(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        t_max: f32,
    ) -> Option<(u32, Candidate)> {
        traverse::closest(self, prims, r, t_max)
    }

    /// Whether any primitive for which `blocks` holds is hit with `0 < t < t_max`; stops at the
    /// first. The unbounded primitives are tested first.
    pub fn any(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        t_max: f32,
        blocks: impl FnMut(u32) -> bool,
    ) -> bool {
        traverse::any(self, prims, r, t_max, blocks)
    }
}

impl Tree for Bvh {
    fn unbounded(&self) -> &[u32] {
        &self.unbounded
    }

    fn root(&self) -> Option<(Vec3A, Vec3A, NodeRef)> {
        self.root
    }

    fn leaves(&self) -> &Leaves {
        &self.leaves
    }

    fn node_count(&self) -> usize {
        Bvh::node_count(self)
    }

    fn children(&self, n: NodeRef) -> impl Iterator<Item = (Aabb, NodeRef)> + '_ {
        let pair = &self.pairs[n.index as usize];
        let a = &pair.axes;
        (0..2).map(move |side| {
            let lo = Vec3::new(a[0][side], a[1][side], a[2][side]);
            let hi = Vec3::new(a[0][2 + side], a[1][2 + side], a[2][2 + side]);
            let child = NodeRef {
                index: pair.index(side),
                count: pair.count(side),
            };
            (Aabb::new(lo, hi), child)
        })
    }

    /// Visits the nearer child of a pair first and skips subtrees that start beyond the best hit
    /// so far.
    fn closest_below<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        mut best: Best,
    ) -> Option<(u32, Candidate)> {
        let pr = PairRay::new(r);
        let r4 = Ray4::new(r);
        // Entries: node identifier and entry distance.
        let mut stack: Stack<(u32, f32), STACK_SIZE> = Stack::new();
        let mut n = root;
        loop {
            if n.count == 0 {
                let k = n.index;
                let pair = &self.pairs[k as usize];
                let (hits, near0, near1) = Self::pair_hit::<NX, NY, NZ>(pair, &pr, best.t);
                let c0 = NodeRef {
                    index: pair.meta[0],
                    count: pair.meta[2],
                };
                let c1 = NodeRef {
                    index: pair.meta[1],
                    count: pair.meta[3],
                };
                if hits == 3 {
                    if near1 < near0 {
                        stack.push((k << 1, near0));
                        n = c1;
                    } else {
                        stack.push(((k << 1) | 1, near1));
                        n = c0;
                    }
                    continue;
                } else if hits == 1 {
                    n = c0;
                    continue;
                } else if hits == 2 {
                    n = c1;
                    continue;
                }
            } else {
                self.leaves
                    .closest(prims, r, &r4, (n.index, n.count), &mut best);
            }
            let Some(id) = next_within(&mut stack, best.t) else {
                return best.hit();
            };
            n = self.node(id);
        }
    }

    fn any_below<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        t_max: f32,
        blocks: &mut impl FnMut(u32) -> bool,
    ) -> bool {
        let pr = PairRay::new(r);
        let r4 = Ray4::new(r);
        let mut stack: Stack<u32, STACK_SIZE> = Stack::new();
        let mut n = root;
        loop {
            if n.count == 0 {
                let k = n.index;
                let pair = &self.pairs[k as usize];
                let (hits, near0, near1) = Self::pair_hit::<NX, NY, NZ>(pair, &pr, t_max);
                let c0 = NodeRef {
                    index: pair.meta[0],
                    count: pair.meta[2],
                };
                let c1 = NodeRef {
                    index: pair.meta[1],
                    count: pair.meta[3],
                };
                if hits == 3 {
                    if near1 < near0 {
                        stack.push(k << 1);
                        n = c1;
                    } else {
                        stack.push((k << 1) | 1);
                        n = c0;
                    }
                    continue;
                } else if hits == 1 {
                    n = c0;
                    continue;
                } else if hits == 2 {
                    n = c1;
                    continue;
                }
            } else if self
                .leaves
                .any(prims, r, &r4, (n.index, n.count), t_max, blocks)
            {
                return true;
            }
            let Some(id) = stack.pop() else {
                return false;
            };
            n = self.node(id);
        }
    }
}
