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
use rayon::prelude::*;

use super::aabb::Aabb;
use super::beam::Beam;
use super::kernels::Ray4;
use super::leaves::{Best, Leaves};
use super::stack::Stack;
use super::traverse::{self, next_within, Tree};
use crate::geometry::{Candidate, Primitives};
use crate::math::Vec3;
use crate::ray::PreparedRay;

/// Traversal stack entries. The builders keep every tree at most `MAX_SAH_DEPTH + 33` levels deep
/// (see `MAX_SAH_DEPTH`), and a traversal holds at most one entry per level.
pub const STACK_SIZE: usize = 128;

/// Depth below which the SAH builder switches to median splits. A median split halves a node, so
/// fewer than 2³² primitives need at most 32 more levels: trees stay within [`STACK_SIZE`].
/// The benchmark scenes' SAH trees are about 20 levels deep, so this only bounds pathological
/// inputs (a long run of ever larger primitives, where SAH peels one per level).
const MAX_SAH_DEPTH: usize = 90;

/// Bins per axis of the SAH builder. Wald (2007) found 16 bins within a few percent of the full
/// sweep's tree quality; 32 made no difference above the noise on `raytracer bench --rays`.
pub const SAH_BINS: usize = 16;
const _: () = assert!(SAH_BINS.is_power_of_two() && SAH_BINS >= 12);

/// Cost of one traversal step (testing the two children's boxes and choosing the next node),
/// relative to [`INTERSECTION_COST`]. Chosen by measurement on the 524,290-triangle grid of
/// `raytracer bench --rays` (with one scalar test per primitive): ratios from 1 to 3 traced all
/// three ray sets at the same speed within 4%, and 4 or more was slower; 2 builds a third fewer
/// nodes than 1. A step costs more than one might think because its next node depends on a
/// comparison: it is latency, not arithmetic, that the traversal waits on.
pub const TRAVERSAL_COST: f32 = 2.0;

/// Cost of testing one block of up to four primitives in SIMD lanes (see `accel/leaves.rs`): a
/// leaf of `n` primitives costs `⌈n/4⌉` of these, so the builder fills blocks rather than
/// splitting a leaf of four that costs what a leaf of one costs. Against counting every primitive, this
/// traced the 524,290-triangle grid's primary, shadow and incoherent rays 1.2×, 1.2× and 1.2×
/// as fast and took 123 instead of 142 bytes per triangle (`raytracer bench --rays`, one thread,
/// two runs each, interleaved).
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

/// A primitive's bounds during the build, with its index.
#[derive(Debug, Clone, Copy)]
struct Ref {
    /// The box's lower corner, and in `w` the primitive's index (as bits, see [`Ref::new`]): 32
    /// bytes a primitive, not 48, for the passes over every primitive at each level.
    lo_index: Vec4,
    hi: Vec4,
}

const _: () = assert!(std::mem::size_of::<Ref>() == 32);

impl Ref {
    /// Bit 30 of the `w` lane's bits is set above the index (below `leaves::MAX_PRIMITIVES`, 2³⁰),
    /// so the lane is never a subnormal float: the box arithmetic, which carries `w` along
    /// unread, would slow down on one.
    const INDEX_TAG: u32 = 1 << 30;

    fn new(lo: Vec3A, hi: Vec3A, index: u32) -> Ref {
        debug_assert!(index < Ref::INDEX_TAG);
        Ref {
            lo_index: lo.extend(f32::from_bits(index | Ref::INDEX_TAG)),
            hi: hi.extend(0.0),
        }
    }

    /// The bounded primitives of `prims`, in index order (whatever the threads: rayon's
    /// `collect` keeps it).
    fn bounded(prims: &Primitives) -> Vec<Ref> {
        (0..prims.len() as u32)
            .into_par_iter()
            .filter_map(|i| {
                let shape = prims.shape(i);
                let b = shape.is_bounded().then(|| shape.bounds())?;
                Some(Ref::new(b.min.into(), b.max.into(), i))
            })
            .collect()
    }

    #[inline(always)]
    fn lo(&self) -> Vec3A {
        Vec3A::from_vec4(self.lo_index)
    }

    #[inline(always)]
    fn hi(&self) -> Vec3A {
        Vec3A::from_vec4(self.hi)
    }

    #[inline(always)]
    fn index(&self) -> u32 {
        self.lo_index.w.to_bits() & !Ref::INDEX_TAG
    }

    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        0.5 * (self.lo() + self.hi())
    }
}

#[derive(Debug, Clone, Copy)]
struct Bin {
    lo: Vec3A,
    hi: Vec3A,
    count: u32,
}

impl Bin {
    const EMPTY: Bin = Bin {
        lo: Vec3A::splat(f32::INFINITY),
        hi: Vec3A::splat(f32::NEG_INFINITY),
        count: 0,
    };
}

/// Half the surface area of a box (the SAH needs only ratios); 0 for an empty box.
#[inline]
fn half_area(lo: Vec3A, hi: Vec3A) -> f32 {
    let e = (hi - lo).max(Vec3A::ZERO);
    e.x * e.y + e.y * e.z + e.z * e.x
}

/// Bounds and centroid bounds of a set of [`Ref`]s.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    lo: Vec3A,
    hi: Vec3A,
    clo: Vec3A,
    chi: Vec3A,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
        clo: Vec3A::INFINITY,
        chi: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    fn add(&mut self, r: &Ref) {
        self.lo = self.lo.min(r.lo());
        self.hi = self.hi.max(r.hi());
        let c = r.centroid();
        self.clo = self.clo.min(c);
        self.chi = self.chi.max(c);
    }

    fn of(refs: &[Ref]) -> Bounds {
        let mut b = Bounds::EMPTY;
        for r in refs {
            b.add(r);
        }
        b
    }
}

/// Subtrees over at least this many primitives are built as two tasks (`rayon::join`), below it
/// by one recursive call. The tree does not depend on it (nor on the thread count): it only
/// decides which parts of the same recursion run side by side. At about 2,500 instructions a
/// primitive (callgrind, the 524,290-triangle grid of `raytracer bench --rays`), a task of
/// 4,096 primitives is about 10 million instructions, far above what a join costs.
const PARALLEL_MIN: usize = 4096;

struct Builder {
    nodes: Vec<Node>,
    leaf_size: usize,
    split: Split,
    /// Empty between nodes (each node's evaluation empties the bins it filled).
    bins: [[Bin; SAH_BINS]; 3],
}

/// Makes the node at `slot` interior: appends its sibling pair (slot 0 is the root; pair `k` is
/// slots `1 + 2k` and `2 + 2k`) and points the node at it. Returns the pair's first slot.
fn push_pair(nodes: &mut Vec<Node>, slot: usize) -> usize {
    let child = nodes.len();
    nodes.push(Node::default());
    nodes.push(Node::default());
    nodes[slot].index = (child as u32 - 1) / 2;
    nodes[slot].count = 0;
    child
}

/// A subtree built by [`Builder::part`]: split at its root into two parts built side by side, or
/// built whole by [`Builder::node`] (its root first, then its sibling pairs in the order the
/// serial build appends them).
enum Part {
    Split {
        lo: Vec3A,
        hi: Vec3A,
        left: Box<Part>,
        right: Box<Part>,
    },
    Whole(Vec<Node>),
}

impl Part {
    /// Writes the part's root into `nodes[slot]` and appends the rest of it, renumbered, where
    /// the serial build would have: a split's sibling pair, then its left part, then its right.
    fn place(self, slot: usize, nodes: &mut Vec<Node>) {
        match self {
            Part::Split {
                lo,
                hi,
                left,
                right,
            } => {
                nodes[slot].lo = lo;
                nodes[slot].hi = hi;
                let child = push_pair(nodes, slot);
                left.place(child, nodes);
                right.place(child + 1, nodes);
            }
            Part::Whole(part) => {
                // The part's pairs start at its index 1 and go to `nodes.len()`, a shift of
                // `shift` pairs.
                let shift = (nodes.len() as u32 - 1) / 2;
                nodes[slot] = part[0].shifted(shift);
                nodes.extend(part[1..].iter().map(|n| n.shifted(shift)));
            }
        }
    }
}

impl Builder {
    fn new(leaf_size: usize, split: Split) -> Builder {
        Builder {
            nodes: Vec::new(),
            leaf_size,
            split,
            bins: [[Bin::EMPTY; SAH_BINS]; 3],
        }
    }

    /// The subtree over `refs` (whose first entry is entry `first` of the final order, and whose
    /// bounds are `b`), its large parts built side by side.
    fn part(&mut self, refs: &mut [Ref], first: usize, depth: usize, b: Bounds) -> Part {
        if refs.len() < PARALLEL_MIN {
            self.nodes = vec![Node::default()];
            self.node(0, refs, first, depth, b);
            return Part::Whole(std::mem::take(&mut self.nodes));
        }
        let Some((mid, left_bounds, right_bounds)) = self.split(refs, depth, &b) else {
            return Part::Whole(vec![Node::leaf(&b, first, refs.len())]);
        };
        let (left, right) = refs.split_at_mut(mid);
        let (leaf_size, split) = (self.leaf_size, self.split);
        let (left, right) = rayon::join(
            || Builder::new(leaf_size, split).part(left, first, depth + 1, left_bounds),
            || Builder::new(leaf_size, split).part(right, first + mid, depth + 1, right_bounds),
        );
        Part::Split {
            lo: b.lo,
            hi: b.hi,
            left: Box::new(left),
            right: Box::new(right),
        }
    }

    /// Builds the subtree over `refs` (whose first entry is entry `first` of the final order, and
    /// whose bounds are `b`) into the node at `slot`.
    fn node(&mut self, slot: usize, refs: &mut [Ref], first: usize, depth: usize, b: Bounds) {
        self.nodes[slot] = Node::leaf(&b, first, refs.len());
        let Some((mid, left_bounds, right_bounds)) = self.split(refs, depth, &b) else {
            return;
        };
        let child = push_pair(&mut self.nodes, slot);
        let (left, right) = refs.split_at_mut(mid);
        self.node(child, left, first, depth + 1, left_bounds);
        self.node(child + 1, right, first + mid, depth + 1, right_bounds);
    }

    /// Whether the node over `refs` (at `depth`, with bounds `b`) is split, and where: `refs`
    /// is then partitioned, and the size of the left part and both parts' bounds are returned;
    /// `None` makes it a leaf.
    fn split(
        &mut self,
        refs: &mut [Ref],
        depth: usize,
        b: &Bounds,
    ) -> Option<(usize, Bounds, Bounds)> {
        let n = refs.len();
        if n <= 1 {
            return None;
        }
        let halves = |refs: &mut [Ref], mid: usize| {
            Some((mid, Bounds::of(&refs[..mid]), Bounds::of(&refs[mid..])))
        };
        match self.split {
            Split::None => None,
            Split::Median => {
                if n <= self.leaf_size {
                    return None;
                }
                let mid = median_split(refs, depth % 3);
                halves(refs, mid)
            }
            Split::Sah if depth >= MAX_SAH_DEPTH => {
                if n <= self.leaf_size {
                    return None;
                }
                let e = b.chi - b.clo;
                let axis = if e.x >= e.y && e.x >= e.z {
                    0
                } else if e.y >= e.z {
                    1
                } else {
                    2
                };
                let mid = median_split(refs, axis);
                halves(refs, mid)
            }
            Split::Sah => match self.sah_split(refs, b) {
                SahChoice::Leaf => None,
                SahChoice::Split(mid, l, r) => Some((mid, l, r)),
                // All centroids coincide (or no plane separates them): the middle of the list.
                SahChoice::None if n <= self.leaf_size => None,
                SahChoice::None => halves(refs, n / 2),
            },
        }
    }

    /// The binned SAH decision for a node of `refs` with bounds `b`. On a split, `refs` is
    /// partitioned; the size of the left part and both parts' bounds are returned.
    fn sah_split(&mut self, refs: &mut [Ref], b: &Bounds) -> SahChoice {
        let n = refs.len();
        let extent = (b.chi - b.clo).to_array();
        let valid = extent.map(|e| e > 0.0 && e.is_finite());
        if !valid.contains(&true) {
            return SahChoice::None;
        }
        let clo = b.clo;
        let scale = Vec3A::from(extent.map(|e| SAH_BINS as f32 / e));
        let last = Vec3A::splat((SAH_BINS - 1) as f32);
        // Bin index per axis: bin k holds the centroids at k to k + 1 bin widths from `clo`,
        // saturating (NaN and below to bin 0, beyond to the last). `x` in [0, 15] is rounded to
        // an integer by adding 2²³ (where the float spacing is 1), whose bits then hold it: three
        // integer subtractions instead of three saturating float conversions, the build's
        // costliest step otherwise.
        let magic = Vec3A::splat(8_388_608.0);
        let bin = |r: &Ref| {
            let x = ((r.centroid() - clo) * scale - Vec3A::splat(0.5))
                .max(Vec3A::ZERO)
                .min(last);
            (x + magic)
                .to_array()
                .map(|v| (v.to_bits().wrapping_sub(0x4b00_0000) as usize) & (SAH_BINS - 1))
        };
        for r in refs.iter() {
            let idx = bin(r);
            for (a, &i) in idx.iter().enumerate() {
                let bin = &mut self.bins[a][i & (SAH_BINS - 1)];
                bin.lo = bin.lo.min(r.lo());
                bin.hi = bin.hi.max(r.hi());
                bin.count += 1;
            }
        }
        // Least cost Σ area·count over both sides, over the planes between non-empty bins of
        // every valid axis (planes next to empty bins repeat a partition). Ties go to the first
        // axis and plane, so the tree is a function of the input alone; a NaN cost (overflowing
        // coordinates) is never taken. The bins are emptied for the next node on the way.
        let mut best: Option<(f32, usize, usize)> = None;
        for (a, bins) in self.bins.iter_mut().enumerate() {
            let mut used = [0u8; SAH_BINS];
            let mut k = 0;
            for (i, bin) in bins.iter().enumerate() {
                if bin.count > 0 {
                    used[k] = i as u8;
                    k += 1;
                }
            }
            let used = &used[..k];
            if valid[a] && k > 1 {
                let mut right_cost = [0.0f32; SAH_BINS];
                let mut acc = Bin::EMPTY;
                for j in (1..k).rev() {
                    let bin = &bins[used[j] as usize];
                    acc.lo = acc.lo.min(bin.lo);
                    acc.hi = acc.hi.max(bin.hi);
                    acc.count += bin.count;
                    right_cost[j] = half_area(acc.lo, acc.hi) * blocks(acc.count as usize);
                }
                let mut acc = Bin::EMPTY;
                for j in 1..k {
                    let bin = &bins[used[j - 1] as usize];
                    acc.lo = acc.lo.min(bin.lo);
                    acc.hi = acc.hi.max(bin.hi);
                    acc.count += bin.count;
                    let cost =
                        half_area(acc.lo, acc.hi) * blocks(acc.count as usize) + right_cost[j];
                    if best.is_none_or(|(c, _, _)| cost < c) {
                        best = Some((cost, a, used[j] as usize));
                    }
                }
            }
            for &i in used {
                bins[i as usize] = Bin::EMPTY;
            }
        }
        let Some((cost, axis, plane)) = best else {
            return SahChoice::None;
        };
        let leaf_cost = INTERSECTION_COST * blocks(n);
        let split_cost = TRAVERSAL_COST + INTERSECTION_COST * cost / half_area(b.lo, b.hi);
        // A zero-area node (all primitives on one line or point) has no meaningful SAH cost:
        // it is a leaf if it fits and split otherwise.
        let split_pays = split_cost < leaf_cost; // false for NaN
        if n <= self.leaf_size && !split_pays {
            return SahChoice::Leaf;
        }
        // Partition by the same bin computation, gathering both sides' bounds.
        let is_left = |r: &Ref| bin(r)[axis] < plane;
        let (mut left, mut right) = (Bounds::EMPTY, Bounds::EMPTY);
        let (mut i, mut j) = (0, n);
        loop {
            while i < j && is_left(&refs[i]) {
                left.add(&refs[i]);
                i += 1;
            }
            while i < j && !is_left(&refs[j - 1]) {
                right.add(&refs[j - 1]);
                j -= 1;
            }
            if i >= j {
                break;
            }
            refs.swap(i, j - 1);
            left.add(&refs[i]);
            right.add(&refs[j - 1]);
            i += 1;
            j -= 1;
        }
        debug_assert!(i > 0 && i < n);
        SahChoice::Split(i, left, right)
    }
}

enum SahChoice {
    Leaf,
    Split(usize, Bounds, Bounds),
    /// No plane between bins separates the centroids.
    None,
}

/// Blocks of four a leaf of `n` primitives takes: its cost in units of [`INTERSECTION_COST`].
fn blocks(n: usize) -> f32 {
    n.div_ceil(4) as f32
}

/// Puts the lower half of `refs` by centroid on `axis` first; returns the split position.
fn median_split(refs: &mut [Ref], axis: usize) -> usize {
    let mid = refs.len() / 2;
    refs.select_nth_unstable_by(mid, |a, b| {
        a.centroid()[axis]
            .total_cmp(&b.centroid()[axis])
            .then(a.index().cmp(&b.index()))
    });
    mid
}

/// The binary tree as the builders make it, before its nodes are laid out for traversal: node 0
/// is the root, and the children of an interior node with `index` k are nodes `1 + 2k` and
/// `2 + 2k`. Leaves are already packed into blocks.
pub(super) struct BinaryTree {
    pub nodes: Vec<Node>,
    pub leaves: Leaves,
    /// The unbounded primitives, in index order.
    pub unbounded: Vec<u32>,
}

impl BinaryTree {
    pub fn build(prims: &Primitives, options: BvhOptions) -> BinaryTree {
        let unbounded = prims.unbounded();
        let mut refs = Ref::bounded(prims);
        let leaf_size = options.leaf_size.max(1);
        let mut nodes = Vec::with_capacity(2 * prims.len() / leaf_size.min(4) + 1);
        if !refs.is_empty() {
            let b = Bounds::of(&refs);
            let root = Builder::new(leaf_size, options.split).part(&mut refs, 0, 0, b);
            nodes.push(Node::default());
            root.place(0, &mut nodes);
        }
        let order: Vec<u32> = refs.iter().map(Ref::index).collect();
        let leaves = Leaves::pack(
            prims,
            &order,
            nodes
                .iter_mut()
                .filter(|n| n.count > 0)
                .map(|n| (&mut n.index, &mut n.count)),
        );
        BinaryTree {
            nodes,
            leaves,
            unbounded,
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Primitive, Shape, Sphere, Triangle};
    use crate::math::Vec3;

    fn tri(p: [Vec3; 3]) -> Primitive {
        Primitive {
            shape: Shape::Triangle(Triangle {
                p,
                mesh: 0,
                face: 0,
            }),
            material: 0,
        }
    }

    fn sphere(c: Vec3, r: f32) -> Primitive {
        Primitive {
            shape: Shape::Sphere(Sphere::new(c, r, Vec3::Y, Vec3::X)),
            material: 0,
        }
    }

    /// Every node with its box.
    fn all_nodes(bvh: &Bvh) -> Vec<([f32; 3], [f32; 3], NodeRef)> {
        let Some((lo, hi, root)) = bvh.root else {
            return Vec::new();
        };
        let mut out = vec![(lo.to_array(), hi.to_array(), root)];
        for (k, pair) in bvh.pairs.iter().enumerate() {
            for side in 0..2 {
                let a = pair.axes;
                out.push((
                    [a[0][side], a[1][side], a[2][side]],
                    [a[0][2 + side], a[1][2 + side], a[2][2 + side]],
                    bvh.node((k as u32) << 1 | side as u32),
                ));
            }
        }
        out
    }

    /// Every primitive once (the bounded ones in the tree, the others in the unbounded list),
    /// every box containing its contents, depth within the stack.
    fn check(bvh: &Bvh, prims: &Primitives, leaf_size: usize) {
        let mut seen = vec![false; prims.len()];
        for p in bvh.leaves.all() {
            assert!(!seen[p as usize], "primitive {p} twice");
            assert!(prims.get(p).shape.is_bounded());
            seen[p as usize] = true;
        }
        for &p in &bvh.unbounded {
            assert!(!seen[p as usize], "primitive {p} twice");
            assert!(!prims.get(p).shape.is_bounded());
            seen[p as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
        let contains = |lo: &[f32; 3], hi: &[f32; 3], ilo: &[f32; 3], ihi: &[f32; 3]| {
            (0..3).all(|i| lo[i] <= ilo[i] && ihi[i] <= hi[i])
        };
        let nodes = all_nodes(bvh);
        for (lo, hi, n) in &nodes {
            if n.count > 0 {
                assert!(bvh.leaves.primitives(n.index, n.count).count() <= leaf_size);
                for p in bvh.leaves.primitives(n.index, n.count) {
                    let b = prims.get(p).shape.bounds();
                    assert!(contains(lo, hi, &b.min.to_array(), &b.max.to_array()));
                }
            } else {
                for side in 0..2 {
                    let (clo, chi, _) = &nodes[1 + 2 * n.index as usize + side];
                    assert!(contains(lo, hi, clo, chi));
                }
            }
        }
        assert!(bvh.stats().depth < STACK_SIZE);
    }

    fn grid(n: usize) -> Vec<Primitive> {
        (0..n)
            .map(|i| {
                let x = (i % 37) as f32;
                let y = (i / 37) as f32 * 0.5;
                tri([
                    Vec3::new(x, y, 0.0),
                    Vec3::new(x + 1.0, y, 0.3),
                    Vec3::new(x, y + 1.0, 0.1),
                ])
            })
            .collect()
    }

    /// The tree the plain recursion builds over `prims`, with no part built side by side: its
    /// nodes and the primitives' order.
    fn serial_tree(prims: &Primitives, leaf_size: usize, split: Split) -> (Vec<Node>, Vec<u32>) {
        let mut refs = Ref::bounded(prims);
        let mut builder = Builder::new(leaf_size, split);
        builder.nodes.push(Node::default());
        let b = Bounds::of(&refs);
        builder.node(0, &mut refs, 0, 0, b);
        (builder.nodes, refs.iter().map(Ref::index).collect())
    }

    #[test]
    fn the_tree_built_side_by_side_is_the_serial_one_on_any_thread_count() {
        // Random triangles, some coincident, in clusters: large enough for several levels of
        // parts (`PARALLEL_MIN`), with leaves below them built whole.
        let mut rng = crate::accel::kernels::twin::Rng(7);
        let mut prims: Vec<Primitive> = (0..40_000)
            .map(|i| {
                let c = rng.vec(100.0) * if i % 3 == 0 { 0.05 } else { 1.0 };
                tri([c, c + rng.vec(1.0), c + rng.vec(1.0)])
            })
            .collect();
        prims.extend_from_within(..500);
        let prims = Primitives::from(prims);
        for split in [Split::Sah, Split::Median] {
            let (want_nodes, want_order) = serial_tree(&prims, 4, split);
            for threads in [1, 2, 5] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let tree = pool.install(|| {
                    BinaryTree::build(
                        &prims,
                        BvhOptions {
                            leaf_size: 4,
                            split,
                        },
                    )
                });
                // Leaf spans are renumbered by the packing: compare interior nodes whole, and
                // leaves by their boxes and primitives.
                assert_eq!(
                    tree.nodes.len(),
                    want_nodes.len(),
                    "{split:?}, {threads} threads"
                );
                for (got, want) in tree.nodes.iter().zip(&want_nodes) {
                    assert_eq!((got.lo, got.hi), (want.lo, want.hi));
                    if want.count == 0 {
                        assert_eq!((got.index, got.count), (want.index, 0));
                    } else {
                        let got: Vec<u32> = tree.leaves.primitives(got.index, got.count).collect();
                        let want = &want_order[want.index as usize..][..want.count as usize];
                        let mut want = want.to_vec();
                        want.sort_unstable();
                        let mut got = got;
                        got.sort_unstable();
                        assert_eq!(got, want);
                    }
                }
            }
        }
    }

    #[test]
    fn both_builders_make_valid_trees() {
        for n in [1, 2, 3, 5, 17, 100, 1000] {
            let prims = Primitives::from(grid(n));
            for leaf in [1, 2, 4, 8] {
                check(&Bvh::build_median(&prims, leaf), &prims, leaf);
                check(&Bvh::build_sah(&prims, leaf), &prims, leaf);
            }
        }
    }

    #[test]
    fn planes_stay_out_of_the_tree_and_are_hit_far_outside_it() {
        use crate::geometry::Plane;
        let mut prims = grid(100);
        let plane = |n: Vec3, d: f32| Primitive {
            shape: Shape::Plane(Plane::new(n, d)),
            material: 0,
        };
        prims.insert(3, plane(Vec3::Z, -5.0));
        prims.push(plane(Vec3::Z, -5.0)); // a duplicate: the lower index wins the tie
        let prims = Primitives::from(prims);
        for bvh in [Bvh::build_sah(&prims, 4), Bvh::build_median(&prims, 2)] {
            check(&bvh, &prims, 4);
            assert_eq!(bvh.unbounded(), &[3, 101]);
            // Far outside the grid's box, straight down onto the plane z = −5.
            let r = PreparedRay::new(&crate::ray::Ray::new(
                Vec3::new(1.0e4, -3.0e4, 10.0),
                -Vec3::Z,
            ));
            let (i, c) = bvh.closest(&prims, &r, f32::INFINITY).unwrap();
            assert_eq!((i, c.t), (3, 15.0));
            assert!(bvh.any(&prims, &r, 15.5, |_| true));
            assert!(!bvh.any(&prims, &r, 15.0, |_| true));
            assert!(bvh.any(&prims, &r, 15.5, |p| p == 101));
            // Through the grid (z from 0 to 0.3 at these points): a triangle is nearer.
            let r = PreparedRay::new(&crate::ray::Ray::new(Vec3::new(5.2, 0.2, 10.0), -Vec3::Z));
            let (i, c) = bvh.closest(&prims, &r, f32::INFINITY).unwrap();
            assert!(prims.get(i).shape.is_bounded() && c.t < 10.5, "{i} {c:?}");
        }
    }

    #[test]
    fn coincident_centroids_split_at_the_middle() {
        let prims = Primitives::from(vec![sphere(Vec3::ONE, 1.0); 100]);
        let bvh = Bvh::build_sah(&prims, 4);
        check(&bvh, &prims, 4);
        let s = bvh.stats();
        assert!(s.depth <= 6, "{s:?}");
    }

    #[test]
    fn pathological_inputs_stay_within_the_stack() {
        // Sizes doubling along x: SAH peels one primitive per level; the depth cap takes over.
        let prims: Vec<_> = (0..400)
            .map(|i| sphere(Vec3::new(1.5f32.powi(i / 4), 0.0, 0.0), 1.0))
            .collect();
        let prims = Primitives::from(prims);
        let bvh = Bvh::build_sah(&prims, 1);
        check(&bvh, &prims, 1);
        // Huge and non-finite coordinates must not panic.
        let prims = vec![
            sphere(Vec3::splat(3e38), 1e38),
            sphere(Vec3::splat(-3e38), 1e38),
            tri([Vec3::splat(f32::NAN), Vec3::ZERO, Vec3::ONE]),
            tri([Vec3::ZERO; 3]),
            tri([Vec3::ZERO; 3]),
        ];
        let prims = Primitives::from(prims);
        for leaf in [1, 4] {
            check(&Bvh::build_sah(&prims, leaf), &prims, leaf);
        }
    }

    #[test]
    fn sah_beats_median_on_clustered_input() {
        // Two dense clusters far apart plus a few scattered primitives: SAH cuts between the
        // clusters; the tree has fewer expected node visits than the median tree.
        let mut prims = grid(500);
        for i in 0..20 {
            let x = 1000.0 + i as f32 * 50.0;
            prims.push(tri([
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x + 1.0, 0.0, 0.0),
                Vec3::new(x, 1.0, 0.0),
            ]));
        }
        let prims = Primitives::from(prims);
        let sah = Bvh::build_sah(&prims, 4);
        let median = Bvh::build_median(&prims, 4);
        let cost = |b: &Bvh| {
            let area = |lo: [f32; 3], hi: [f32; 3]| half_area(lo.into(), hi.into());
            let nodes = all_nodes(b);
            let root = area(nodes[0].0, nodes[0].1);
            nodes
                .into_iter()
                .map(|(lo, hi, n)| {
                    let a = area(lo, hi) / root;
                    if n.count > 0 {
                        a * b.leaves.primitives(n.index, n.count).count() as f32
                    } else {
                        a * TRAVERSAL_COST
                    }
                })
                .sum::<f32>()
        };
        assert!(
            cost(&sah) < cost(&median),
            "{} {}",
            cost(&sah),
            cost(&median)
        );
    }
}
