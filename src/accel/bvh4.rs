//! A four-wide BVH: the binned-SAH binary tree of [`super::bvh`] collapsed so that each node holds
//! up to four children, whose boxes one traversal step tests together in the four SIMD lanes of a
//! `glam::Vec4` (SSE on x86-64, so every 64-bit x86 CPU runs it as it is).
//!
//! Collapsing (as Embree's and tinybvh's wide BVHs are made from a binary tree): a node starts
//! with its two binary children; while it has fewer than four and one of them is interior, the
//! interior child of largest surface area is replaced by its own two children. A tree of `L`
//! leaves then has about `L/3` nodes instead of `L − 1`, each 128 bytes (two cache lines: the
//! twelve planes of the four boxes in structure-of-arrays form, and the four children's
//! references), and a ray takes about half as many dependent steps from the root to a leaf.
//!
//! Traversal visits the hit children nearest first (a closest-hit query sorts the up to four
//! entry distances; an any-hit query does not order them) and keeps the far ones on a stack.
//! The leaves are the binary tree's, unchanged ([`super::leaves`]), and every box test makes the
//! decisions of [`super::aabb::slab`] lane for lane, so the answers are exactly those of every
//! other accelerator (`tests/accel.rs`).

use glam::{Vec3A, Vec4};

use super::aabb::{slab, Aabb};
use super::beam::Beam;
use super::bvh::{BinaryTree, BvhOptions, BvhStats, Node, NodeRef, Split, STACK_SIZE};
use super::kernels::Ray4;
use super::leaves::{lanes, Best, Leaves};
use super::stack::Stack;
use super::{any_among, gather};
use crate::geometry::{Candidate, Primitive};
use crate::math::Vec3;
use crate::ray::PreparedRay;

/// Children of a node.
const WIDTH: usize = 4;

/// Traversal stack entries. A collapsed tree is no deeper than the binary tree it came from (at
/// most [`STACK_SIZE`] levels), and a step pushes at most three children.
const STACK4_SIZE: usize = (WIDTH - 1) * STACK_SIZE;

/// Four children: per axis, the four lower and the four upper bounds, then each child's
/// reference (`count == 0`: node `index`; else the leaf `index..index + count` of the entries).
/// An unused slot has an empty box (`+∞` to `−∞`, missed by every ray) and points at an empty
/// leaf, so even a ray that passes every box test (a NaN direction) finds nothing there.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
struct Node4 {
    lo: [[f32; WIDTH]; 3],
    hi: [[f32; WIDTH]; 3],
    index: [u32; WIDTH],
    count: [u32; WIDTH],
}

const _: () = assert!(std::mem::size_of::<Node4>() == 128);

impl Node4 {
    fn empty((index, count): (u32, u32)) -> Node4 {
        Node4 {
            lo: [[f32::INFINITY; WIDTH]; 3],
            hi: [[f32::NEG_INFINITY; WIDTH]; 3],
            index: [index; WIDTH],
            count: [count; WIDTH],
        }
    }

    fn set(&mut self, slot: usize, lo: Vec3A, hi: Vec3A, child: NodeRef) {
        for a in 0..3 {
            self.lo[a][slot] = lo[a];
            self.hi[a][slot] = hi[a];
        }
        self.index[slot] = child.index;
        self.count[slot] = child.count;
    }

    #[inline(always)]
    fn child(&self, slot: usize) -> NodeRef {
        NodeRef {
            index: self.index[slot],
            count: self.count[slot],
        }
    }

    fn boxes(&self) -> impl Iterator<Item = (Aabb, NodeRef)> + '_ {
        (0..WIDTH).map(|l| {
            let corner = |b: &[[f32; WIDTH]; 3]| Vec3::new(b[0][l], b[1][l], b[2][l]);
            (Aabb::new(corner(&self.lo), corner(&self.hi)), self.child(l))
        })
    }
}

/// The per-ray constants of the four-box test, each splatted over the lanes.
struct BoxRay {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
    inv_dir_far: [Vec4; 3],
}

impl BoxRay {
    #[inline(always)]
    fn new(r: &PreparedRay) -> BoxRay {
        let splat = |v: Vec3A| [v.x, v.y, v.z].map(Vec4::splat);
        BoxRay {
            origin: splat(r.origin),
            inv_dir: splat(r.inv_dir),
            inv_dir_far: splat(r.inv_dir_far),
        }
    }
}

/// Slab test of the four boxes of `node` (the decisions of [`slab`] on each, for a ray whose
/// direction has the signs `NX`, `NY`, `NZ`: `true` for negative): a mask of the boxes hit (bit
/// `l`: slot `l`) and their entry distances.
#[inline(always)]
fn hit4<const NX: bool, const NY: bool, const NZ: bool>(
    node: &Node4,
    r: &BoxRay,
    t_max: f32,
) -> (u32, Vec4) {
    // As in `slab`: `max(t, acc)` and `min(t, acc)` return `acc` where `t` is NaN (a ray in a
    // slab's plane), so such a plane is ignored.
    let mut near = Vec4::ZERO;
    let mut far = Vec4::splat(t_max);
    for (a, negative) in [NX, NY, NZ].into_iter().enumerate() {
        let lo = Vec4::from_array(node.lo[a]);
        let hi = Vec4::from_array(node.hi[a]);
        let (near_plane, far_plane) = if negative { (hi, lo) } else { (lo, hi) };
        near = ((near_plane - r.origin[a]) * r.inv_dir[a]).max(near);
        far = ((far_plane - r.origin[a]) * r.inv_dir_far[a]).min(far);
    }
    (near.cmple(far).bitmask(), near)
}

/// The slots of `mask` (two or more set) sorted by entry distance `near`, farthest first, and
/// how many there are.
#[inline(always)]
fn far_to_near(mask: u32, near: Vec4) -> ([usize; WIDTH], usize) {
    let near = near.to_array();
    let mut sorted = [0usize; WIDTH];
    let mut k = 0;
    for l in lanes(mask) {
        let mut j = k;
        while j > 0 && near[sorted[j - 1]] < near[l] {
            sorted[j] = sorted[j - 1];
            j -= 1;
        }
        sorted[j] = l;
        k += 1;
    }
    (sorted, k)
}

/// The four-wide BVH.
#[derive(Debug, Clone)]
pub struct Bvh4 {
    /// The root's box and reference (a node, or a leaf when the whole tree is one); `None` for no
    /// primitives.
    root: Option<(Vec3A, Vec3A, NodeRef)>,
    /// The nodes, depth first from the root.
    nodes: Vec<Node4>,
    leaves: Leaves,
    /// The unbounded primitives, in index order: outside the tree, tested by every query.
    unbounded: Vec<u32>,
}

/// Collapses the binary subtree at `slot` (interior) into `out`; returns its node's index.
fn collapse(binary: &[Node], slot: usize, empty: (u32, u32), out: &mut Vec<Node4>) -> u32 {
    let children = |s: usize| {
        let k = binary[s].index as usize;
        [1 + 2 * k, 2 + 2 * k]
    };
    let area = |s: usize| {
        let e = (binary[s].hi - binary[s].lo).max(Vec3A::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    };
    let mut kids = children(slot).to_vec();
    while kids.len() < WIDTH {
        // The interior child of largest area (the first of equal ones) opens up.
        let Some(i) = (0..kids.len())
            .filter(|&i| binary[kids[i]].count == 0)
            .reduce(|a, b| if area(kids[b]) > area(kids[a]) { b } else { a })
        else {
            break;
        };
        let [l, r] = children(kids[i]);
        kids[i] = l;
        kids.insert(i + 1, r);
    }
    let me = out.len();
    out.push(Node4::empty(empty));
    for (l, &k) in kids.iter().enumerate() {
        let b = &binary[k];
        let child = if b.count == 0 {
            NodeRef {
                index: collapse(binary, k, empty, out),
                count: 0,
            }
        } else {
            b.reference()
        };
        out[me].set(l, b.lo, b.hi, child);
    }
    me as u32
}

impl Bvh4 {
    /// Builds the binary SAH tree over `prims` with leaves of at most `leaf_size` primitives and
    /// collapses it. Fewer than `u32::MAX` primitives (the caller checks).
    pub fn build(prims: &[Primitive], leaf_size: usize) -> Bvh4 {
        let BinaryTree {
            nodes: binary,
            mut leaves,
            unbounded,
        } = BinaryTree::build(
            prims,
            BvhOptions {
                leaf_size,
                split: Split::Sah,
            },
        );
        let mut nodes = Vec::new();
        let root = binary.first().map(|n| {
            let root = if n.count > 0 {
                n.reference()
            } else {
                let empty = leaves.push_empty();
                nodes.reserve(binary.len() / 3 + 1);
                NodeRef {
                    index: collapse(&binary, 0, empty, &mut nodes),
                    count: 0,
                }
            };
            (n.lo, n.hi, root)
        });
        nodes.shrink_to_fit();
        Bvh4 {
            root,
            nodes,
            leaves,
            unbounded,
        }
    }

    /// Bytes held: the nodes, the leaves (primitive order and blocks) and the unbounded list.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Bvh4>()
            + self.node_bytes()
            + self.leaf_bytes()
            + self.unbounded.capacity() * std::mem::size_of::<u32>()
    }

    /// Bytes of the interior nodes.
    pub fn node_bytes(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node4>()
    }

    /// Bytes of the leaves: the primitive order and the SIMD blocks.
    pub fn leaf_bytes(&self) -> usize {
        self.leaves.bytes()
    }

    /// The primitives kept outside the tree (unbounded shapes), in index order.
    pub fn unbounded(&self) -> &[u32] {
        &self.unbounded
    }

    /// Node count, leaf count, depth (in four-wide levels) and largest leaf. Unused slots are
    /// not counted.
    pub fn stats(&self) -> BvhStats {
        let mut s = BvhStats {
            nodes: self.nodes.len(),
            ..BvhStats::default()
        };
        let Some((_, _, root)) = self.root else {
            return s;
        };
        let mut stack = vec![(root, 0usize)];
        while let Some((n, d)) = stack.pop() {
            if n.count > 0 {
                let size = self.leaves.primitives(n.index, n.count).count();
                if size > 0 || n == root {
                    s.leaves += 1;
                    s.depth = s.depth.max(d);
                    s.max_leaf = s.max_leaf.max(size);
                }
            } else {
                let node = &self.nodes[n.index as usize];
                stack.extend((0..WIDTH).map(|l| (node.child(l), d + 1)));
            }
        }
        s
    }

    /// See [`crate::accel::Accel::beam_candidates`]: the unbounded primitives, then the
    /// primitives of every leaf whose box and own bounds meet the beam.
    pub fn beam_candidates(
        &self,
        prims: &[Primitive],
        beam: &Beam,
        limit: usize,
        out: &mut Vec<u32>,
    ) -> bool {
        out.clear();
        if !gather(beam, prims, self.unbounded.iter().copied(), limit, out) {
            return false;
        }
        let Some((lo, hi, root)) = self.root else {
            return true;
        };
        if !beam.may_hit_box(&Aabb::new(lo.into(), hi.into())) {
            return true;
        }
        let mut stack: Stack<NodeRef, STACK4_SIZE> = Stack::new();
        stack.push(root);
        while let Some(n) = stack.pop() {
            if n.count > 0 {
                let leaf = self.leaves.primitives(n.index, n.count);
                if !gather(beam, prims, leaf, limit, out) {
                    return false;
                }
                continue;
            }
            for (b, child) in self.nodes[n.index as usize].boxes() {
                if beam.may_hit_box(&b) {
                    stack.push(child);
                }
            }
        }
        true
    }

    /// The closest hit with `0 < t < t_max` (least `t`, then least primitive index): the
    /// unbounded primitives first, in index order, then the tree, visiting the hit children
    /// nearest first and skipping subtrees that start beyond the best hit so far.
    pub fn closest(
        &self,
        prims: &[Primitive],
        r: &PreparedRay,
        t_max: f32,
    ) -> Option<(u32, Candidate)> {
        let mut best = Best::new(t_max);
        best.among(prims, &self.unbounded, r);
        let Some((lo, hi, root)) = self.root else {
            return best.hit();
        };
        if !slab(lo, hi, r, best.t).0 {
            return best.hit();
        }
        if root.count > 0 {
            let r4 = Ray4::new(r);
            self.leaves
                .closest(prims, r, &r4, (root.index, root.count), &mut best);
            return best.hit();
        }
        // One copy of the loop per octant of the direction, so that the choice of near and far
        // planes is made at compile time.
        match r.negative.bitmask() {
            0 => self.closest_in::<false, false, false>(prims, r, root, best),
            1 => self.closest_in::<true, false, false>(prims, r, root, best),
            2 => self.closest_in::<false, true, false>(prims, r, root, best),
            3 => self.closest_in::<true, true, false>(prims, r, root, best),
            4 => self.closest_in::<false, false, true>(prims, r, root, best),
            5 => self.closest_in::<true, false, true>(prims, r, root, best),
            6 => self.closest_in::<false, true, true>(prims, r, root, best),
            _ => self.closest_in::<true, true, true>(prims, r, root, best),
        }
    }

    /// The tree's part of [`Bvh4::closest`] from the interior node `root`, starting from `best`.
    fn closest_in<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &[Primitive],
        r: &PreparedRay,
        root: NodeRef,
        mut best: Best,
    ) -> Option<(u32, Candidate)> {
        let br = BoxRay::new(r);
        let r4 = Ray4::new(r);
        // Entries: a child and its entry distance.
        let mut stack: Stack<(NodeRef, f32), STACK4_SIZE> = Stack::new();
        let mut n = root;
        loop {
            if n.count == 0 {
                let node = &self.nodes[n.index as usize];
                let (mask, near) = hit4::<NX, NY, NZ>(node, &br, best.t);
                if mask != 0 {
                    if mask & (mask - 1) == 0 {
                        n = node.child(mask.trailing_zeros() as usize);
                        continue;
                    }
                    // Two or more: the nearest is visited now and the others wait on the
                    // stack, nearer ones above.
                    let (sorted, k) = far_to_near(mask, near);
                    let near = near.to_array();
                    for &l in &sorted[..k - 1] {
                        stack.push((node.child(l), near[l]));
                    }
                    n = node.child(sorted[k - 1]);
                    continue;
                }
            } else {
                self.leaves
                    .closest(prims, r, &r4, (n.index, n.count), &mut best);
            }
            // Next subtree from the stack whose entry is not beyond the best hit: the same answer
            // the box test would give now, as its exit side passed when it was pushed.
            loop {
                let Some((child, near)) = stack.pop() else {
                    return best.hit();
                };
                if near <= best.t {
                    n = child;
                    break;
                }
            }
        }
    }

    /// Whether any primitive for which `blocks` holds is hit with `0 < t < t_max`; stops at the
    /// first. The unbounded primitives are tested first.
    pub fn any(
        &self,
        prims: &[Primitive],
        r: &PreparedRay,
        t_max: f32,
        mut blocks: impl FnMut(u32) -> bool,
    ) -> bool {
        if any_among(prims, &self.unbounded, r, t_max, &mut blocks) {
            return true;
        }
        let Some((lo, hi, root)) = self.root else {
            return false;
        };
        if !slab(lo, hi, r, t_max).0 {
            return false;
        }
        if root.count > 0 {
            let span = (root.index, root.count);
            return self
                .leaves
                .any(prims, r, &Ray4::new(r), span, t_max, &mut blocks);
        }
        match r.negative.bitmask() {
            0 => self.any_in::<false, false, false>(prims, r, root, t_max, blocks),
            1 => self.any_in::<true, false, false>(prims, r, root, t_max, blocks),
            2 => self.any_in::<false, true, false>(prims, r, root, t_max, blocks),
            3 => self.any_in::<true, true, false>(prims, r, root, t_max, blocks),
            4 => self.any_in::<false, false, true>(prims, r, root, t_max, blocks),
            5 => self.any_in::<true, false, true>(prims, r, root, t_max, blocks),
            6 => self.any_in::<false, true, true>(prims, r, root, t_max, blocks),
            _ => self.any_in::<true, true, true>(prims, r, root, t_max, blocks),
        }
    }

    /// The tree's part of [`Bvh4::any`] from the interior node `root`. The hit children are
    /// visited in slot order: any hit ends the query, so ordering them would buy nothing.
    fn any_in<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &[Primitive],
        r: &PreparedRay,
        root: NodeRef,
        t_max: f32,
        mut blocks: impl FnMut(u32) -> bool,
    ) -> bool {
        let br = BoxRay::new(r);
        let r4 = Ray4::new(r);
        let mut stack: Stack<NodeRef, STACK4_SIZE> = Stack::new();
        let mut n = root;
        loop {
            if n.count == 0 {
                let node = &self.nodes[n.index as usize];
                let (mask, near) = hit4::<NX, NY, NZ>(node, &br, t_max);
                if mask != 0 {
                    if mask & (mask - 1) == 0 {
                        n = node.child(mask.trailing_zeros() as usize);
                        continue;
                    }
                    let (sorted, k) = far_to_near(mask, near);
                    for &l in &sorted[..k - 1] {
                        stack.push(node.child(l));
                    }
                    n = node.child(sorted[k - 1]);
                    continue;
                }
            } else if self
                .leaves
                .any(prims, r, &r4, (n.index, n.count), t_max, &mut blocks)
            {
                return true;
            }
            let Some(child) = stack.pop() else {
                return false;
            };
            n = child;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::bvh::Bvh;
    use crate::geometry::{Plane, Shape, Sphere, Triangle};

    fn grid(n: usize) -> Vec<Primitive> {
        (0..n)
            .map(|i| {
                let (x, y) = ((i % 37) as f32, (i / 37) as f32 * 0.5);
                let shape = if i % 5 == 0 {
                    Shape::Sphere(Sphere::new(Vec3::new(x, y, 1.0), 0.4, Vec3::Y, Vec3::X))
                } else {
                    Shape::Triangle(Triangle {
                        p: [
                            Vec3::new(x, y, 0.0),
                            Vec3::new(x + 1.0, y, 0.3),
                            Vec3::new(x, y + 1.0, 0.1),
                        ],
                        mesh: 0,
                        face: 0,
                    })
                };
                Primitive { shape, material: 0 }
            })
            .collect()
    }

    /// Every bounded primitive in exactly one leaf, inside its slot's box; every unused slot
    /// empty, pointing at the empty leaf; every node's children inside its own slot's box.
    fn check(tree: &Bvh4, prims: &[Primitive]) {
        let mut seen = vec![0u32; prims.len()];
        let Some((lo, hi, root)) = tree.root else {
            assert!(prims.iter().all(|p| !p.shape.is_bounded()));
            return;
        };
        let mut stack = vec![(Aabb::new(lo.into(), hi.into()), root)];
        while let Some((b, n)) = stack.pop() {
            if n.count > 0 {
                for p in tree.leaves.primitives(n.index, n.count) {
                    seen[p as usize] += 1;
                    let pb = prims[p as usize].shape.bounds();
                    assert!(b.contains(pb.min, 0.0) && b.contains(pb.max, 0.0));
                }
                continue;
            }
            let node = &tree.nodes[n.index as usize];
            let used = node
                .count
                .iter()
                .zip(node.lo[0])
                .filter(|(_, l)| l.is_finite());
            assert!(used.count() >= 2, "a node of fewer than two children");
            for (cb, child) in node.boxes() {
                if cb.min.x == f32::INFINITY {
                    assert_eq!(tree.leaves.primitives(child.index, child.count).count(), 0);
                    continue;
                }
                assert!(b.contains(cb.min, 0.0) && b.contains(cb.max, 0.0));
                stack.push((cb, child));
            }
        }
        for (p, prim) in prims.iter().enumerate() {
            let want = u32::from(prim.shape.is_bounded());
            assert_eq!(seen[p], want, "primitive {p}");
            assert_eq!(tree.unbounded.contains(&(p as u32)), want == 0);
        }
    }

    #[test]
    fn collapsed_trees_hold_every_primitive_once() {
        for n in [0, 1, 2, 3, 5, 17, 100, 1000] {
            for leaf in [1, 4, 8] {
                let mut prims = grid(n);
                if n == 17 {
                    prims.push(Primitive {
                        shape: Shape::Plane(Plane::new(Vec3::Z, 0.0)),
                        material: 0,
                    });
                }
                check(&Bvh4::build(&prims, leaf), &prims);
            }
        }
    }

    #[test]
    fn collapsing_fills_nodes_and_halves_the_depth() {
        let prims = grid(4000);
        let binary = Bvh::build_sah(&prims, 4).stats();
        let wide = Bvh4::build(&prims, 4).stats();
        assert_eq!(wide.leaves, binary.leaves);
        assert_eq!(wide.max_leaf, binary.max_leaf);
        // `L` leaves in binary nodes of two children: `L − 1` nodes; four children: `(L − 1)/3`.
        // Nodes whose children are all leaves may hold fewer, so allow a little more.
        assert!(
            wide.nodes * 2 < binary.leaves,
            "{wide:?} against {binary:?}"
        );
        assert!(
            2 * wide.depth <= binary.depth + 1,
            "{wide:?} against {binary:?}"
        );
    }
}
