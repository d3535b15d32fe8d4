//! Wide BVHs: the binned-SAH binary tree of [`super::bvh`] collapsed so that each node holds up
//! to four ([`Bvh4`]) or eight ([`Bvh8`]) children, whose boxes one traversal step tests together,
//! four at a time in the SIMD lanes of a `glam::Vec4` (SSE on x86-64, so every 64-bit x86 CPU
//! runs it as it is), or, for the eight-wide tree on a CPU with AVX2, all eight in one AVX
//! register ([`super::kernels::isa`]: the queries then run in a copy of their loops compiled for
//! AVX2, with the same answers).
//!
//! Collapsing (as Embree's and tinybvh's wide BVHs are made from a binary tree): a node starts
//! with its two binary children; while it has fewer than its width and one of them is interior,
//! the interior child of largest surface area is replaced by its own two children. A tree of `L`
//! leaves then has about `L/3` four-wide nodes (`L/7` eight-wide) instead of `L − 1`, each 128
//! bytes (256 eight-wide: the planes of the boxes in structure-of-arrays form, then the
//! children's references), and a ray takes about a half (a third) as many dependent steps from
//! the root to a leaf.
//!
//! A closest-hit query visits the nearest hit child first and keeps the others on a stack with
//! their entry distances, in slot order (a full sort by distance costs more in branches than the
//! order saves); an any-hit query does not order them at all.
//!
//! The leaves are the binary tree's, unchanged (`accel/leaves.rs`), and every box test makes the
//! decisions of [`super::aabb::slab`] lane for lane, so the answers are exactly those of every
//! other accelerator (`tests/accel.rs`).

use glam::{Vec3A, Vec4};

use super::aabb::Aabb;
use super::beam::Beam;
use super::bvh::{BinaryTree, BvhOptions, BvhStats, Node as BinaryNode, NodeRef, Split};
#[cfg(target_arch = "x86_64")]
use super::kernels::boxes8::Planes8;
use super::kernels::{Isa, Ray4};
use super::leaves::{lanes, Best, Leaves};
use super::stack::Stack;
use super::traverse::{self, next_within, Tree, MAX_WIDTH, TRAVERSAL_STACK_SIZE};
use crate::geometry::{Candidate, Primitives};
use crate::math::Vec3;
use crate::ray::PreparedRay;

/// The four-wide BVH.
pub type Bvh4 = WideBvh<1>;

/// The eight-wide BVH.
pub type Bvh8 = WideBvh<2>;

/// `4·C` children (`C` groups of four, each one SIMD test): per axis, the lower and the upper
/// bounds, then each child's reference (`count == 0`: node `index`; else the leaf
/// `index..index + count` of the entries). Slot `l` is lane `l % 4` of group `l / 4`. An unused
/// slot has an empty box (`+∞` to `−∞`, missed by every ray) and points at an empty leaf, so even
/// a ray that passes every box test (a NaN direction) finds nothing there.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
struct Node<const C: usize> {
    lo: [[[f32; 4]; C]; 3],
    hi: [[[f32; 4]; C]; 3],
    index: [[u32; 4]; C],
    count: [[u32; 4]; C],
}

const _: () = assert!(std::mem::size_of::<Node<1>>() == 128);
const _: () = assert!(std::mem::size_of::<Node<2>>() == 256);

impl<const C: usize> Node<C> {
    const WIDTH: usize = {
        assert!(4 * C <= MAX_WIDTH, "wider than the traversal stack allows");
        4 * C
    };

    fn empty((index, count): (u32, u32)) -> Node<C> {
        Node {
            lo: [[[f32::INFINITY; 4]; C]; 3],
            hi: [[[f32::NEG_INFINITY; 4]; C]; 3],
            index: [[index; 4]; C],
            count: [[count; 4]; C],
        }
    }

    fn set(&mut self, slot: usize, lo: Vec3A, hi: Vec3A, child: NodeRef) {
        let (g, l) = (slot / 4, slot % 4);
        for a in 0..3 {
            self.lo[a][g][l] = lo[a];
            self.hi[a][g][l] = hi[a];
        }
        self.index[g][l] = child.index;
        self.count[g][l] = child.count;
    }

    #[inline(always)]
    fn child(&self, slot: usize) -> NodeRef {
        NodeRef {
            index: self.index[slot / 4][slot % 4],
            count: self.count[slot / 4][slot % 4],
        }
    }

    /// The lower and upper planes per axis as rows of eight slots, for an eight-wide node.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn rows8(&self) -> Option<(&Planes8, &Planes8)> {
        let rows = |b: &[[[f32; 4]; C]; 3]| -> Option<&Planes8> {
            // SAFETY: for `C == 2`, `[[f32; 4]; 2]` and `[f32; 8]` are the same eight `f32`s in
            // the same order, with the same alignment.
            (C == 2).then(|| unsafe { &*(b as *const [[[f32; 4]; C]; 3]).cast::<Planes8>() })
        };
        Some((rows(&self.lo)?, rows(&self.hi)?))
    }

    fn boxes(&self) -> impl Iterator<Item = (Aabb, NodeRef)> + '_ {
        (0..Self::WIDTH).map(|s| {
            let (g, l) = (s / 4, s % 4);
            let corner = |b: &[[[f32; 4]; C]; 3]| Vec3::new(b[0][g][l], b[1][g][l], b[2][g][l]);
            (Aabb::new(corner(&self.lo), corner(&self.hi)), self.child(s))
        })
    }
}

/// Slab test of the boxes of `node` (the decisions of [`slab`](super::aabb::slab) on each, for a
/// ray whose direction has the signs `NX`, `NY`, `NZ`: `true` for negative), four at a time, or
/// eight at a time where `isa` has AVX2 ([`super::kernels::boxes8`]): a mask of the boxes hit
/// (bit `l`: slot `l`) and their entry distances.
#[inline(always)]
fn hit<const C: usize, const NX: bool, const NY: bool, const NZ: bool>(
    node: &Node<C>,
    r: &Ray4,
    t_max: f32,
    isa: Isa,
) -> (u32, [Vec4; C]) {
    #[cfg(target_arch = "x86_64")]
    if let (Some((lo, hi)), true) = (node.rows8(), isa.avx2()) {
        // SAFETY: an `Isa` says AVX2 only where the CPU has it.
        let (mask, entry8) =
            unsafe { super::kernels::boxes8::hit8::<NX, NY, NZ>(lo, hi, r, t_max) };
        let mut entry = [Vec4::ZERO; C];
        entry.copy_from_slice(&entry8[..C]);
        return (mask, entry);
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = isa;
    hit4::<C, NX, NY, NZ>(node, r, t_max)
}

/// [`hit`] four boxes at a time, in SSE lanes.
#[inline(always)]
fn hit4<const C: usize, const NX: bool, const NY: bool, const NZ: bool>(
    node: &Node<C>,
    r: &Ray4,
    t_max: f32,
) -> (u32, [Vec4; C]) {
    let mut mask = 0;
    let mut entry = [Vec4::ZERO; C];
    for (g, entry) in entry.iter_mut().enumerate() {
        // As in `slab`: `max(t, acc)` and `min(t, acc)` return `acc` where `t` is NaN (a ray in
        // a slab's plane), so such a plane is ignored.
        let mut near = Vec4::ZERO;
        let mut far = Vec4::splat(t_max);
        for (a, negative) in [NX, NY, NZ].into_iter().enumerate() {
            let lo = Vec4::from_array(node.lo[a][g]);
            let hi = Vec4::from_array(node.hi[a][g]);
            let (near_plane, far_plane) = if negative { (hi, lo) } else { (lo, hi) };
            near = ((near_plane - r.origin[a]) * r.inv_dir[a]).max(near);
            far = ((far_plane - r.origin[a]) * r.inv_dir_far[a]).min(far);
        }
        mask |= near.cmple(far).bitmask() << (4 * g);
        *entry = near;
    }
    (mask, entry)
}

/// The slot of `mask` (not empty) of least entry distance `near[slot]` (the lowest such slot).
#[inline(always)]
fn nearest(mask: u32, near: &[f32]) -> usize {
    let mut first = mask.trailing_zeros() as usize;
    for l in lanes(mask & (mask - 1)) {
        if near[l] < near[first] {
            first = l;
        }
    }
    first
}

/// A BVH of `4·C` children a node.
#[derive(Debug, Clone)]
pub struct WideBvh<const C: usize> {
    /// The root's box and reference (a node, or a leaf when the whole tree is one); `None` for no
    /// primitives.
    root: Option<(Vec3A, Vec3A, NodeRef)>,
    /// The nodes, depth first from the root.
    nodes: Vec<Node<C>>,
    leaves: Leaves,
    /// The unbounded primitives, in index order: outside the tree, tested by every query.
    unbounded: Vec<u32>,
    /// What the queries run with (see [`WideBvh::build`] and [`WideBvh::with_isa`]).
    isa: Isa,
}

/// Collapses the binary subtree at `slot` (interior) into `out`; returns its node's index.
fn collapse<const C: usize>(
    binary: &[BinaryNode],
    slot: usize,
    empty: (u32, u32),
    out: &mut Vec<Node<C>>,
) -> u32 {
    let children = |s: usize| {
        let k = binary[s].index as usize;
        [1 + 2 * k, 2 + 2 * k]
    };
    let area = |s: usize| {
        let e = (binary[s].hi - binary[s].lo).max(Vec3A::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    };
    let mut kids = children(slot).to_vec();
    while kids.len() < Node::<C>::WIDTH {
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
    out.push(Node::empty(empty));
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

impl<const C: usize> WideBvh<C> {
    /// Builds the binary SAH tree over `prims` with leaves of at most `leaf_size` primitives and
    /// collapses it. At most `leaves::MAX_PRIMITIVES` primitives (the caller checks).
    pub fn build(prims: &Primitives, leaf_size: usize) -> WideBvh<C> {
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
        WideBvh {
            root,
            nodes,
            leaves,
            unbounded,
            // The eight-wide node test takes one AVX register instead of two SSE ones; the
            // four-wide tree's queries gain nothing from the VEX encoding, so they keep the
            // baseline.
            isa: if C == 2 { Isa::detect() } else { Isa::BASELINE },
        }
    }

    /// The tree with queries that run with `isa` in place of the one chosen at the build (the
    /// best the CPU has for the eight-wide tree, the baseline for the four-wide one). Their
    /// answers are the same bits either way.
    pub fn with_isa(self, isa: Isa) -> WideBvh<C> {
        WideBvh { isa, ..self }
    }

    /// What the queries run with.
    pub fn isa(&self) -> Isa {
        self.isa
    }

    /// Bytes held: the nodes, the leaves' blocks and the unbounded list.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<WideBvh<C>>()
            + self.node_bytes()
            + self.leaf_bytes()
            + self.unbounded.capacity() * std::mem::size_of::<u32>()
    }

    /// Bytes of the interior nodes.
    pub fn node_bytes(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node<C>>()
    }

    /// Bytes of the leaves: their SIMD blocks (primitive indices included).
    pub fn leaf_bytes(&self) -> usize {
        self.leaves.bytes()
    }

    /// Node count, leaf count, depth (in wide levels) and largest leaf. Unused slots are not
    /// counted.
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
    /// unbounded primitives first, in index order, then the tree, visiting the hit children
    /// nearest first and skipping subtrees that start beyond the best hit so far.
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

impl<const C: usize> Tree for WideBvh<C> {
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
        self.nodes.len()
    }

    fn children(&self, n: NodeRef) -> impl Iterator<Item = (Aabb, NodeRef)> + '_ {
        self.nodes[n.index as usize].boxes()
    }

    /// The children's boxes four at a time ([`Beam::may_hit_boxes4`]).
    #[inline]
    fn beam_children(&self, n: NodeRef, beam: &Beam, mut visit: impl FnMut(NodeRef)) {
        let node = &self.nodes[n.index as usize];
        for g in 0..C {
            let lo = [0, 1, 2].map(|a| Vec4::from_array(node.lo[a][g]));
            let hi = [0, 1, 2].map(|a| Vec4::from_array(node.hi[a][g]));
            for l in lanes(beam.may_hit_boxes4(lo, hi)) {
                visit(node.child(4 * g + l));
            }
        }
    }

    /// Visits the nearest hit child first and skips subtrees that start beyond the best hit so
    /// far. Runs the copy compiled for the tree's [`Isa`].
    fn closest_below<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        best: Best,
    ) -> Option<(u32, Candidate)> {
        #[cfg(target_arch = "x86_64")]
        if self.isa.avx2() {
            // SAFETY: an `Isa` says AVX2 only where the CPU has it.
            return unsafe {
                super::kernels::isa::in_avx2(|isa| {
                    self.closest_in::<NX, NY, NZ>(prims, r, root, best, isa)
                })
            };
        }
        self.closest_in::<NX, NY, NZ>(prims, r, root, best, Isa::BASELINE)
    }

    /// Visits the hit children in slot order (see the module docs). Runs the copy compiled for
    /// the tree's [`Isa`].
    fn any_below<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        t_max: f32,
        blocks: &mut impl FnMut(u32) -> bool,
    ) -> bool {
        #[cfg(target_arch = "x86_64")]
        if self.isa.avx2() {
            // SAFETY: an `Isa` says AVX2 only where the CPU has it.
            return unsafe {
                super::kernels::isa::in_avx2(|isa| {
                    self.any_in::<NX, NY, NZ>(prims, r, root, t_max, blocks, isa)
                })
            };
        }
        self.any_in::<NX, NY, NZ>(prims, r, root, t_max, blocks, Isa::BASELINE)
    }
}

/// The queries' loops, compiled once per [`Isa`].
impl<const C: usize> WideBvh<C> {
    /// [`Tree::closest_below`] with the instructions of `isa`: inlined into the copy for each.
    #[inline(always)]
    fn closest_in<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        mut best: Best,
        isa: Isa,
    ) -> Option<(u32, Candidate)> {
        let r4 = Ray4::new(r);
        // Entries: a child and its entry distance.
        let mut stack: Stack<(NodeRef, f32), TRAVERSAL_STACK_SIZE> = Stack::new();
        let mut n = root;
        loop {
            if n.count == 0 {
                let node = &self.nodes[n.index as usize];
                let (mask, entry) = hit::<C, NX, NY, NZ>(node, &r4, best.t, isa);
                if mask != 0 {
                    if mask & (mask - 1) == 0 {
                        n = node.child(mask.trailing_zeros() as usize);
                        continue;
                    }
                    // Two or more: the nearest is visited now and the others wait on the
                    // stack, in slot order (see the module docs). The entry distances are only
                    // the node's own `4·C`, so that no padded `MAX_WIDTH` array is copied.
                    let near = entry.map(|e| e.to_array());
                    let near = near.as_flattened();
                    let first = nearest(mask, near);
                    for l in lanes(mask & !(1 << first)) {
                        stack.push((node.child(l), near[l]));
                    }
                    n = node.child(first);
                    continue;
                }
            } else {
                self.leaves
                    .closest(prims, r, &r4, (n.index, n.count), &mut best);
            }
            let Some(child) = next_within(&mut stack, best.t) else {
                return best.hit();
            };
            n = child;
        }
    }

    /// [`Tree::any_below`] with the instructions of `isa`.
    #[inline(always)]
    fn any_in<const NX: bool, const NY: bool, const NZ: bool>(
        &self,
        prims: &Primitives,
        r: &PreparedRay,
        root: NodeRef,
        t_max: f32,
        blocks: &mut impl FnMut(u32) -> bool,
        isa: Isa,
    ) -> bool {
        let r4 = Ray4::new(r);
        let mut stack: Stack<NodeRef, TRAVERSAL_STACK_SIZE> = Stack::new();
        let mut n = root;
        loop {
            if n.count == 0 {
                let node = &self.nodes[n.index as usize];
                let (mask, _) = hit::<C, NX, NY, NZ>(node, &r4, t_max, isa);
                if mask != 0 {
                    // The first hit child now, the others (in slot order) on the stack: for
                    // shadow rays, visiting the nearest first does not pay, nor does a sort.
                    for l in lanes(mask & (mask - 1)) {
                        stack.push(node.child(l));
                    }
                    n = node.child(mask.trailing_zeros() as usize);
                    continue;
                }
            } else if self
                .leaves
                .any(prims, r, &r4, (n.index, n.count), t_max, blocks)
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
    use crate::geometry::{Plane, Primitive, Shape, Sphere, Triangle};

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
    fn check<const C: usize>(tree: &WideBvh<C>, prims: &Primitives) {
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
                    let pb = prims.get(p).shape.bounds();
                    assert!(b.contains(pb.min, 0.0) && b.contains(pb.max, 0.0));
                }
                continue;
            }
            let mut used = 0;
            for (cb, child) in tree.nodes[n.index as usize].boxes() {
                if cb.min.x == f32::INFINITY {
                    assert_eq!(tree.leaves.primitives(child.index, child.count).count(), 0);
                    continue;
                }
                used += 1;
                assert!(b.contains(cb.min, 0.0) && b.contains(cb.max, 0.0));
                stack.push((cb, child));
            }
            assert!(used >= 2, "a node of fewer than two children");
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
                let prims = Primitives::from(prims);
                check(&Bvh4::build(&prims, leaf), &prims);
                check(&Bvh8::build(&prims, leaf), &prims);
            }
        }
    }

    /// `hit` with `isa` and the four-lane test of the same node, for the ray's octant.
    #[cfg(target_arch = "x86_64")]
    fn both_node_tests(
        node: &Node<2>,
        r: &PreparedRay,
        t_max: f32,
        isa: Isa,
    ) -> [(u32, [Vec4; 2]); 2] {
        fn pair<const NX: bool, const NY: bool, const NZ: bool>(
            node: &Node<2>,
            r4: &Ray4,
            t_max: f32,
            isa: Isa,
        ) -> [(u32, [Vec4; 2]); 2] {
            [
                hit::<2, NX, NY, NZ>(node, r4, t_max, isa),
                hit4::<2, NX, NY, NZ>(node, r4, t_max),
            ]
        }
        let r4 = Ray4::new(r);
        match r.negative.bitmask() {
            0 => pair::<false, false, false>(node, &r4, t_max, isa),
            1 => pair::<true, false, false>(node, &r4, t_max, isa),
            2 => pair::<false, true, false>(node, &r4, t_max, isa),
            3 => pair::<true, true, false>(node, &r4, t_max, isa),
            4 => pair::<false, false, true>(node, &r4, t_max, isa),
            5 => pair::<true, false, true>(node, &r4, t_max, isa),
            6 => pair::<false, true, true>(node, &r4, t_max, isa),
            _ => pair::<true, true, true>(node, &r4, t_max, isa),
        }
    }

    /// The eight-lane AVX node test gives, bit for bit, the mask and entry distances of the
    /// four-lane SSE one: on empty, point, flat, unbounded and random boxes, for rays in every
    /// octant, along the axes, and lying in a box's planes (where `0·∞` makes NaN distances that
    /// both must ignore alike).
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_avx_node_test_is_its_sse_twin() {
        use crate::accel::kernels::twin::Rng;
        use crate::ray::Ray;
        let isa = Isa::detect();
        if !isa.avx2() {
            eprintln!("this CPU has no AVX2: the eight-lane node test never runs here");
            return;
        }
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut hits, mut nan_planes) = (0, 0);
        for i in 0..20_000usize {
            let mut node = Node::<2>::empty((0, 0));
            let leaf = NodeRef { index: 0, count: 1 };
            let mut corners = Vec::new();
            for slot in 0..8 {
                let p = rng.vec(4.0);
                let size = rng.vec(3.0).abs();
                let (lo, hi) = match (i + slot) % 7 {
                    0 => continue,
                    1 => (p, p),
                    2 => (p, p + size * Vec3::new(1.0, 0.0, 1.0)),
                    3 => (Vec3::NEG_INFINITY, Vec3::INFINITY),
                    _ => (p, p + size),
                };
                node.set(slot, lo.into(), hi.into(), leaf);
                corners.push(lo);
            }
            let mut origin = rng.vec(12.0);
            let mut dir = rng.vec(2.0);
            match i % 5 {
                // Along an axis, the other components zero.
                0 => dir = Vec3::AXES[i / 5 % 3] * if i % 2 == 0 { 1.0 } else { -1.0 },
                // In the planes of a box: `plane − origin` is zero where `1/dir` is infinite.
                1 if !corners.is_empty() => {
                    let c = corners[i / 5 % corners.len()];
                    let a = i / 5 % 3;
                    origin[a] = c[a];
                    dir[a] = 0.0;
                    nan_planes += 1;
                }
                _ => {}
            }
            let r = PreparedRay::new(&Ray::new(origin, dir));
            let t_max = if i % 3 == 0 {
                f32::INFINITY
            } else {
                rng.next() * 10.0
            };
            let [(got, got_entry), (want, want_entry)] = both_node_tests(&node, &r, t_max, isa);
            assert_eq!(got, want, "node {node:?}, ray {:?}, t_max {t_max}", r.ray);
            for l in lanes(want) {
                assert_eq!(
                    got_entry[l / 4][l % 4].to_bits(),
                    want_entry[l / 4][l % 4].to_bits(),
                    "slot {l} of {node:?}, ray {:?}",
                    r.ray
                );
            }
            hits += want.count_ones();
        }
        assert!(
            hits > 20_000 && nan_planes > 3_000,
            "{hits} hits, {nan_planes} rays in planes"
        );
    }

    #[test]
    fn collapsing_fills_nodes_and_cuts_the_depth() {
        let prims = Primitives::from(grid(4000));
        let binary = Bvh::build_sah(&prims, 4).stats();
        let four = Bvh4::build(&prims, 4).stats();
        let eight = Bvh8::build(&prims, 4).stats();
        for wide in [four, eight] {
            assert_eq!(wide.leaves, binary.leaves);
            assert_eq!(wide.max_leaf, binary.max_leaf);
        }
        // `L` leaves in binary nodes of two children: `L − 1` nodes; full nodes of four would be
        // `(L − 1)/3`. A node stops growing when all its children are leaves, so nodes hold
        // fewer, and eight-wide ones far fewer than eight (3.8 on average on this grid).
        assert!(
            four.nodes * 2 < binary.leaves,
            "{four:?} against {binary:?}"
        );
        assert!(eight.nodes < four.nodes, "{eight:?} against {four:?}");
        assert!(
            2 * four.depth <= binary.depth + 1,
            "{four:?} against {binary:?}"
        );
        assert!(eight.depth < four.depth, "{eight:?} against {four:?}");
    }
}
