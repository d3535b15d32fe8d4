//! Tests of the binary BVH: its builds, its queries against every primitive, its limits.

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
