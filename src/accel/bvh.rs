//! A bounding volume hierarchy over primitives, flattened into an array of nodes in depth-first
//! order (a node's first child follows it directly; the second child's index is stored).
//!
//! Builder: median split, the axis cycling x, y, z with depth, leaves of at most `leaf_size`
//! primitives. Primitives are reordered so each leaf's are contiguous.

use super::aabb::Aabb;
use crate::geometry::{Candidate, Primitive};
use crate::ray::Ray;

/// Traversal stack size. Median splits halve the primitive count per level, so a tree over at most
/// 2³² primitives is at most 33 levels deep.
const MAX_DEPTH: usize = 64;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BvhOptions {
    /// Most primitives in a leaf (at least 1).
    pub leaf_size: usize,
}

impl Default for BvhOptions {
    fn default() -> Self {
        BvhOptions { leaf_size: 4 }
    }
}

/// A flat node: 32 bytes. For a leaf `count > 0` and `index` is the first entry of `order`; for an
/// interior node `count == 0`, the first child is the next node and `index` is the second child.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    bounds_min: [f32; 3],
    index: u32,
    bounds_max: [f32; 3],
    count: u32,
}

#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Primitive indices, leaf by leaf.
    order: Vec<u32>,
    /// Split axis of each interior node (for near-child-first traversal).
    axis: Vec<u8>,
}

impl Bvh {
    /// Builds with the median split.
    pub fn build_median(prims: &[Primitive], options: BvhOptions) -> Bvh {
        let bounds: Vec<Aabb> = prims.iter().map(|p| p.shape.bounds()).collect();
        let centroids: Vec<_> = bounds.iter().map(|b| b.center()).collect();
        let mut order: Vec<u32> = (0..prims.len() as u32).collect();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * prims.len() / options.leaf_size.max(1) + 1),
            order: Vec::new(),
            axis: Vec::new(),
        };
        if !prims.is_empty() {
            bvh.build_node(
                &bounds,
                &centroids,
                &mut order,
                0,
                0,
                options.leaf_size.max(1),
            );
        }
        bvh.order = order;
        bvh
    }

    fn build_node(
        &mut self,
        bounds: &[Aabb],
        centroids: &[glam::Vec3],
        order: &mut [u32],
        first: usize,
        depth: usize,
        leaf_size: usize,
    ) -> usize {
        let b = order
            .iter()
            .fold(Aabb::EMPTY, |acc, &i| acc.union(bounds[i as usize]));
        let me = self.nodes.len();
        self.nodes.push(Node {
            bounds_min: b.min.into(),
            index: first as u32,
            bounds_max: b.max.into(),
            count: order.len() as u32,
        });
        self.axis.push(0);
        if order.len() <= leaf_size {
            return me;
        }
        let axis = depth % 3;
        let mid = order.len() / 2;
        order.select_nth_unstable_by(mid, |&a, &b| {
            centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
        });
        let (left, right) = order.split_at_mut(mid);
        self.build_node(bounds, centroids, left, first, depth + 1, leaf_size);
        let second = self.build_node(bounds, centroids, right, first + mid, depth + 1, leaf_size);
        self.nodes[me].count = 0;
        self.nodes[me].index = second as u32;
        self.axis[me] = axis as u8;
        me
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    #[inline]
    fn node_hit(n: &Node, ray: &Ray, inv: glam::Vec3, t_max: f32) -> bool {
        Aabb::new(n.bounds_min.into(), n.bounds_max.into()).hit(ray.origin, inv, t_max)
    }

    /// Closest hit, visiting the nearer child first.
    pub fn closest(&self, prims: &[Primitive], ray: &Ray, t_max: f32) -> Option<(u32, Candidate)> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv = glam::Vec3::ONE / ray.dir;
        let negative = [ray.dir.x < 0.0, ray.dir.y < 0.0, ray.dir.z < 0.0];
        let mut t_max = t_max;
        let mut best = None;
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 0usize;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if Self::node_hit(n, ray, inv, t_max) {
                if n.count > 0 {
                    let start = n.index as usize;
                    for &p in &self.order[start..start + n.count as usize] {
                        if let Some(c) = prims[p as usize].shape.intersect(ray, t_max) {
                            t_max = c.t;
                            best = Some((p, c));
                        }
                    }
                } else {
                    // Near child first: along a negative direction the second child is nearer.
                    let (near, far) = if negative[self.axis[node] as usize] {
                        (n.index as usize, node + 1)
                    } else {
                        (node + 1, n.index as usize)
                    };
                    stack[top] = far as u32;
                    top += 1;
                    node = near;
                    continue;
                }
            }
            if top == 0 {
                break;
            }
            top -= 1;
            node = stack[top] as usize;
        }
        best
    }

    /// Whether any primitive for which `blocks` holds is hit with `0 < t < t_max`.
    pub fn any(
        &self,
        prims: &[Primitive],
        ray: &Ray,
        t_max: f32,
        blocks: impl Fn(u32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inv = glam::Vec3::ONE / ray.dir;
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 0usize;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if Self::node_hit(n, ray, inv, t_max) {
                if n.count > 0 {
                    let start = n.index as usize;
                    for &p in &self.order[start..start + n.count as usize] {
                        if blocks(p) && prims[p as usize].shape.intersect(ray, t_max).is_some() {
                            return true;
                        }
                    }
                } else {
                    stack[top] = n.index;
                    top += 1;
                    node += 1;
                    continue;
                }
            }
            if top == 0 {
                return false;
            }
            top -= 1;
            node = stack[top] as usize;
        }
    }
}
