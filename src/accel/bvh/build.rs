//! The builders of the binary BVH: binned SAH and median splits over primitive references, in
//! parallel above `PARALLEL_MIN` primitives with the same tree on any thread count.

use glam::{Vec3A, Vec4};
use rayon::prelude::*;

use crate::geometry::Primitives;

use super::*;

/// A primitive's bounds during the build, with its index.
#[derive(Debug, Clone, Copy)]
pub(super) struct Ref {
    /// The box's lower corner, and in `w` the primitive's index (as bits, see [`Ref::new`]): 32
    /// bytes a primitive, not 48, for the passes over every primitive at each level.
    pub(super) lo_index: Vec4,
    pub(super) hi: Vec4,
}

const _: () = assert!(std::mem::size_of::<Ref>() == 32);

impl Ref {
    /// Bit 30 of the `w` lane's bits is set above the index (below `leaves::MAX_PRIMITIVES`, 2³⁰),
    /// so the lane is never a subnormal float: the box arithmetic, which carries `w` along
    /// unread, would slow down on one.
    const INDEX_TAG: u32 = 1 << 30;

    pub(super) fn new(lo: Vec3A, hi: Vec3A, index: u32) -> Ref {
        debug_assert!(index < Ref::INDEX_TAG);
        Ref {
            lo_index: lo.extend(f32::from_bits(index | Ref::INDEX_TAG)),
            hi: hi.extend(0.0),
        }
    }

    /// The bounded primitives of `prims`, in index order (whatever the threads: rayon's
    /// `collect` keeps it).
    pub(super) fn bounded(prims: &Primitives) -> Vec<Ref> {
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
    pub(super) fn index(&self) -> u32 {
        self.lo_index.w.to_bits() & !Ref::INDEX_TAG
    }

    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        0.5 * (self.lo() + self.hi())
    }
}

#[derive(Debug, Clone, Copy)]
pub(super) struct Bin {
    pub(super) lo: Vec3A,
    pub(super) hi: Vec3A,
    pub(super) count: u32,
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
pub(super) fn half_area(lo: Vec3A, hi: Vec3A) -> f32 {
    let e = (hi - lo).max(Vec3A::ZERO);
    e.x * e.y + e.y * e.z + e.z * e.x
}

/// Bounds and centroid bounds of a set of [`Ref`]s.
#[derive(Debug, Clone, Copy)]
pub(super) struct Bounds {
    pub(super) lo: Vec3A,
    pub(super) hi: Vec3A,
    pub(super) clo: Vec3A,
    pub(super) chi: Vec3A,
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

    pub(super) fn of(refs: &[Ref]) -> Bounds {
        let mut b = Bounds::EMPTY;
        for r in refs {
            b.add(r);
        }
        b
    }
}

/// Subtrees over at least this many primitives are built as two tasks (`rayon::join`), below it
/// by one recursive call. The tree does not depend on it (nor on the thread count): it only
/// decides which parts of the same recursion run side by side; a task this large costs far more
/// than a join.
pub(super) const PARALLEL_MIN: usize = 4096;

pub(super) struct Builder {
    pub(super) nodes: Vec<Node>,
    pub(super) leaf_size: usize,
    pub(super) split: Split,
    /// Empty between nodes (each node's evaluation empties the bins it filled).
    pub(super) bins: [[Bin; SAH_BINS]; 3],
}

/// Makes the node at `slot` interior: appends its sibling pair (slot 0 is the root; pair `k` is
/// slots `1 + 2k` and `2 + 2k`) and points the node at it. Returns the pair's first slot.
pub(super) fn push_pair(nodes: &mut Vec<Node>, slot: usize) -> usize {
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
pub(super) enum Part {
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
    pub(super) fn new(leaf_size: usize, split: Split) -> Builder {
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
    pub(super) fn node(
        &mut self,
        slot: usize,
        refs: &mut [Ref],
        first: usize,
        depth: usize,
        b: Bounds,
    ) {
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
        let binning = Binning::new(b.clo, extent);
        for r in refs.iter() {
            let idx = binning.of(r);
            for (a, &i) in idx.iter().enumerate() {
                let bin = &mut self.bins[a][i & (SAH_BINS - 1)];
                bin.lo = bin.lo.min(r.lo());
                bin.hi = bin.hi.max(r.hi());
                bin.count += 1;
            }
        }
        let Some((cost, axis, plane)) = self.best_plane(valid) else {
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
        let (i, left, right) = partition(refs, |r| binning.of(r)[axis] < plane);
        debug_assert!(i > 0 && i < n);
        SahChoice::Split(i, left, right)
    }

    /// The plane of least cost Σ area·count over both sides, as (cost, axis, first bin on the
    /// right), over the planes between non-empty bins of every `valid` axis (planes next to empty
    /// bins repeat a partition). Ties go to the first axis and plane, so the tree is a function of
    /// the input alone; a NaN cost (overflowing coordinates) is never taken. The bins are emptied
    /// for the next node on the way.
    fn best_plane(&mut self, valid: [bool; 3]) -> Option<(f32, usize, usize)> {
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
        best
    }
}

/// Which bin a centroid falls in on each axis: bin k holds the centroids at k to k + 1 bin widths
/// from the node's lower centroid corner, saturating (NaN and below to bin 0, beyond to the last).
struct Binning {
    clo: Vec3A,
    scale: Vec3A,
    last: Vec3A,
}

impl Binning {
    fn new(clo: Vec3A, extent: [f32; 3]) -> Binning {
        Binning {
            clo,
            scale: Vec3A::from(extent.map(|e| SAH_BINS as f32 / e)),
            last: Vec3A::splat((SAH_BINS - 1) as f32),
        }
    }

    /// The bin of `r`'s centroid on each axis. `x` in [0, 15] is rounded to an integer by adding
    /// 2²³ (where the float spacing is 1), whose bits then hold it: three integer subtractions
    /// instead of three saturating float conversions.
    #[inline]
    fn of(&self, r: &Ref) -> [usize; 3] {
        let magic = Vec3A::splat(8_388_608.0);
        let x = ((r.centroid() - self.clo) * self.scale - Vec3A::splat(0.5))
            .max(Vec3A::ZERO)
            .min(self.last);
        (x + magic)
            .to_array()
            .map(|v| (v.to_bits().wrapping_sub(0x4b00_0000) as usize) & (SAH_BINS - 1))
    }
}

/// Partitions `refs` in place into those `is_left` and the rest, gathering both sides' bounds:
/// the size of the left part and the two bounds.
fn partition(refs: &mut [Ref], is_left: impl Fn(&Ref) -> bool) -> (usize, Bounds, Bounds) {
    let n = refs.len();
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
    (i, left, right)
}

pub(super) enum SahChoice {
    Leaf,
    Split(usize, Bounds, Bounds),
    /// No plane between bins separates the centroids.
    None,
}

/// Blocks of four a leaf of `n` primitives takes: its cost in units of [`INTERSECTION_COST`].
pub(super) fn blocks(n: usize) -> f32 {
    n.div_ceil(4) as f32
}

/// Puts the lower half of `refs` by centroid on `axis` first; returns the split position.
pub(super) fn median_split(refs: &mut [Ref], axis: usize) -> usize {
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
pub(in crate::accel) struct BinaryTree {
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
