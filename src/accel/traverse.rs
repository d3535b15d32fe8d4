//! What the queries of every tree ([`super::Bvh`], [`super::wide::WideBvh`]) share around their
//! own node loops: the unbounded primitives first, the root's box, a root that is itself a leaf,
//! and one copy of the node loop per octant of the ray's direction, so that the box tests' choice
//! of near and far planes is fixed at compile time; and the walks that need no speed (a beam's
//! candidates, the tree's shape), which see a node only through its children's boxes.

use glam::Vec3A;

use super::aabb::{slab, Aabb};
use super::beam::Beam;
use super::bvh::{BvhStats, NodeRef, STACK_SIZE};
use super::kernels::Ray4;
use super::leaves::{Best, Leaves};
use super::stack::Stack;
use super::{any_among, gather};
use crate::geometry::{Candidate, Primitives};
use crate::ray::PreparedRay;

/// A tree as its queries see it. `NX`, `NY`, `NZ` are the signs of the ray's direction (`true`
/// for negative).
pub(super) trait Tree {
    /// The primitives kept outside the tree, in index order.
    fn unbounded(&self) -> &[u32];

    /// The root's box and reference; `None` for a tree of no primitives.
    fn root(&self) -> Option<(Vec3A, Vec3A, NodeRef)>;

    fn leaves(&self) -> &Leaves;

    /// Interior nodes.
    fn node_count(&self) -> usize;

    /// The box and reference of each child of the interior node `n` (unused slots too, with
    /// their empty boxes and empty leaves).
    fn children(&self, n: NodeRef) -> impl Iterator<Item = (Aabb, NodeRef)> + '_;

    /// Calls `visit` on each child of the interior node `n` whose box `beam` may meet
    /// ([`Beam::may_hit_box`]), in slot order.
    #[inline]
    fn beam_children(&self, n: NodeRef, beam: &Beam, mut visit: impl FnMut(NodeRef)) {
        for (b, child) in self.children(n) {
            if beam.may_hit_box(&b) {
                visit(child);
            }
        }
    }

    /// The closest hit below the interior node `root`, starting from `best`. The root's own box
    /// has not been tested (see [`closest`]).
    fn closest_below<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        best: Best,
    ) -> Option<(u32, Candidate)>;

    /// Whether a primitive accepted by `blocks` below the interior node `root` is hit before
    /// `t_max`. The root's own box has not been tested.
    fn any_below<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        t_max: f32,
        blocks: &mut impl FnMut(u32) -> bool,
    ) -> bool;
}

/// The closest hit with `0 < t < t_max` (least `t`, then least primitive index): the unbounded
/// primitives first, in index order, then the tree.
///
/// The root's box is tested only where the root is a leaf. Above an interior root the node loop
/// tests the root's children's boxes anyway, and the answer is the primitives' own tests' with or
/// without it (boxes only prune). Rays that start inside the scene (every secondary ray) always
/// pass it, so testing it would be work for nothing on most rays.
pub(super) fn closest(
    tree: &impl Tree,
    prims: &Primitives,
    r: &PreparedRay,
    t_max: f32,
) -> Option<(u32, Candidate)> {
    let mut best = Best::new(t_max);
    best.among(prims, tree.unbounded(), r);
    let Some((lo, hi, root)) = tree.root() else {
        return best.hit();
    };
    if root.count > 0 {
        if !slab(lo, hi, r, best.t).0 {
            return best.hit();
        }
        // A single leaf: no traversal.
        let span = (root.index, root.count);
        tree.leaves()
            .closest(prims, r, &Ray4::new(r), span, &mut best);
        return best.hit();
    }
    match r.negative.bitmask() {
        0 => tree.closest_below::<false, false, false>(prims, r, root, best),
        1 => tree.closest_below::<true, false, false>(prims, r, root, best),
        2 => tree.closest_below::<false, true, false>(prims, r, root, best),
        3 => tree.closest_below::<true, true, false>(prims, r, root, best),
        4 => tree.closest_below::<false, false, true>(prims, r, root, best),
        5 => tree.closest_below::<true, false, true>(prims, r, root, best),
        6 => tree.closest_below::<false, true, true>(prims, r, root, best),
        _ => tree.closest_below::<true, true, true>(prims, r, root, best),
    }
}

/// Whether any primitive for which `blocks` holds is hit with `0 < t < t_max`; stops at the
/// first. The unbounded primitives are tested first.
pub(super) fn any(
    tree: &impl Tree,
    prims: &Primitives,
    r: &PreparedRay,
    t_max: f32,
    mut blocks: impl FnMut(u32) -> bool,
) -> bool {
    // Most trees have no unbounded primitive: no call for them.
    let unbounded = tree.unbounded();
    if !unbounded.is_empty() && any_among(prims, unbounded, r, t_max, &mut blocks) {
        return true;
    }
    let Some((lo, hi, root)) = tree.root() else {
        return false;
    };
    if root.count > 0 {
        if !slab(lo, hi, r, t_max).0 {
            return false;
        }
        let span = (root.index, root.count);
        return tree
            .leaves()
            .any(prims, r, &Ray4::new(r), span, t_max, &mut blocks);
    }
    let b = &mut blocks;
    match r.negative.bitmask() {
        0 => tree.any_below::<false, false, false>(prims, r, root, t_max, b),
        1 => tree.any_below::<true, false, false>(prims, r, root, t_max, b),
        2 => tree.any_below::<false, true, false>(prims, r, root, t_max, b),
        3 => tree.any_below::<true, true, false>(prims, r, root, t_max, b),
        4 => tree.any_below::<false, false, true>(prims, r, root, t_max, b),
        5 => tree.any_below::<true, false, true>(prims, r, root, t_max, b),
        6 => tree.any_below::<false, true, true>(prims, r, root, t_max, b),
        _ => tree.any_below::<true, true, true>(prims, r, root, t_max, b),
    }
}

/// Most children of a node of any tree here.
pub(super) const MAX_WIDTH: usize = 8;

/// Entries of a traversal stack: enough for any tree here (a tree is at most [`STACK_SIZE`]
/// levels deep, and a step pushes all but one of a node's children). A stack's slots are not
/// initialised until pushed, so a narrower tree pays nothing for the ones it never reaches.
pub(super) const TRAVERSAL_STACK_SIZE: usize = (MAX_WIDTH - 1) * STACK_SIZE;

/// See [`crate::accel::Accel::beam_candidates`]: the unbounded primitives, then the primitives
/// of every leaf whose box and own bounds meet the beam.
pub(super) fn beam_candidates(
    tree: &impl Tree,
    prims: &Primitives,
    beam: &Beam,
    limit: usize,
    out: &mut Vec<u32>,
) -> bool {
    out.clear();
    if !gather(beam, prims, tree.unbounded().iter().copied(), limit, out) {
        return false;
    }
    let Some((lo, hi, root)) = tree.root() else {
        return true;
    };
    if !beam.may_hit_box(&Aabb::new(lo.into(), hi.into())) {
        return true;
    }
    let mut stack: Stack<NodeRef, TRAVERSAL_STACK_SIZE> = Stack::new();
    stack.push(root);
    while let Some(n) = stack.pop() {
        if n.count > 0 {
            let leaf = tree.leaves().primitives(n.index, n.count);
            if !gather(beam, prims, leaf, limit, out) {
                return false;
            }
            continue;
        }
        tree.beam_children(n, beam, |child| stack.push(child));
    }
    true
}

/// The bounded primitives whose boxes meet `region` (closed boxes: touching counts), written
/// to `out` in no particular order; `false`, with `out` of no use, as soon as there would be more
/// than `limit`.
pub(super) fn meeting_box(
    tree: &impl Tree,
    prims: &Primitives,
    region: &Aabb,
    limit: usize,
    out: &mut Vec<u32>,
) -> bool {
    out.clear();
    let meets = |b: &Aabb| b.min.cmple(region.max).all() && region.min.cmple(b.max).all();
    let Some((lo, hi, root)) = tree.root() else {
        return true;
    };
    if !meets(&Aabb::new(lo.into(), hi.into())) {
        return true;
    }
    let mut stack: Stack<NodeRef, TRAVERSAL_STACK_SIZE> = Stack::new();
    stack.push(root);
    while let Some(n) = stack.pop() {
        if n.count > 0 {
            for p in tree.leaves().primitives(n.index, n.count) {
                if meets(&prims.shape(p).bounds()) {
                    if out.len() >= limit {
                        return false;
                    }
                    out.push(p);
                }
            }
            continue;
        }
        for (b, child) in tree.children(n) {
            if meets(&b) {
                stack.push(child);
            }
        }
    }
    true
}

/// Node count, leaf count, depth and largest leaf. The empty leaves unused slots point at are
/// not counted.
pub(super) fn stats(tree: &impl Tree) -> BvhStats {
    let mut s = BvhStats {
        nodes: tree.node_count(),
        ..BvhStats::default()
    };
    let Some((_, _, root)) = tree.root() else {
        return s;
    };
    let mut stack = vec![(root, 0usize)];
    while let Some((n, d)) = stack.pop() {
        if n.count > 0 {
            let size = tree.leaves().primitives(n.index, n.count).count();
            if size > 0 || n == root {
                s.leaves += 1;
                s.depth = s.depth.max(d);
                s.max_leaf = s.max_leaf.max(size);
            }
        } else {
            stack.extend(tree.children(n).map(|(_, child)| (child, d + 1)));
        }
    }
    s
}

/// The next deferred subtree of a closest-hit traversal whose entry distance is not beyond
/// `t_best`: the answer the box test would give now, as the box's exit side passed when it was
/// pushed. `None` when none is left.
#[inline(always)]
pub(super) fn next_within<T: Copy, const N: usize>(
    stack: &mut Stack<(T, f32), N>,
    t_best: f32,
) -> Option<T> {
    while let Some((node, near)) = stack.pop() {
        if near <= t_best {
            return Some(node);
        }
    }
    None
}
