//! Differential test of the accelerators: every BVH builder (median, SAH, four-wide SAH, at
//! several leaf sizes,
//! and `auto`) must give exactly the answers of testing every primitive (`Accel::List`): the same
//! closest primitive with bit-identical `t` and barycentrics, and the same any-hit answer, on
//! random, grazing, axis-parallel and edge-aimed rays, over meshes and mixed scenes, including
//! empty scenes, single primitives, degenerate triangles and duplicated primitives (where the
//! lower primitive index wins a tie in `t`), and with infinite planes, which no tree holds.

use raytracer::accel::{Accel, AccelKind, Bvh, Bvh4, Isa, Reachable};
use raytracer::geometry::{
    Candidate, Cylinder, Mesh, MeshUv, Plane, Primitive, Primitives, Shape, Sphere, Triangle,
};
use raytracer::math::{next_float_up, Vec3};
use raytracer::ray::Ray;
use raytracer::sampling::{hash, to_unit, uniform_sphere};

/// Deterministic uniform numbers in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 += 1;
        to_unit(hash(&[self.0, 0xacce1]))
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
    fn index(&mut self, n: usize) -> usize {
        ((self.next() * n as f32) as usize).min(n.saturating_sub(1))
    }
    fn vec(&mut self, lo: Vec3, hi: Vec3) -> Vec3 {
        Vec3::new(
            self.range(lo.x, hi.x),
            self.range(lo.y, hi.y),
            self.range(lo.z, hi.z),
        )
    }
    fn dir(&mut self) -> Vec3 {
        uniform_sphere(raytracer::math::Vec2::new(self.next(), self.next()))
    }
}

fn tri(a: Vec3, b: Vec3, c: Vec3) -> Primitive {
    Primitive {
        shape: Shape::Triangle(Triangle {
            p: [a, b, c],
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

fn plane(n: Vec3, d: f32) -> Primitive {
    Primitive {
        shape: Shape::Plane(Plane::new(n, d)),
        material: 0,
    }
}

fn cylinder(c: Vec3, axis: Vec3, r: f32, h: f32) -> Primitive {
    Primitive {
        shape: Shape::Cylinder(Cylinder::new(c, axis, r, h)),
        material: 0,
    }
}

/// Spheres, cylinders and triangles at random, with degenerate triangles (a line, a point, a
/// repeated vertex), axis-aligned triangles sharing planes, and exact duplicates of earlier
/// primitives placed after them.
fn mixed_scene(n: usize, seed: u64) -> Vec<Primitive> {
    let mut rng = Rng(seed << 32);
    let mut prims = Vec::new();
    let (lo, hi) = (Vec3::splat(-4.0), Vec3::splat(4.0));
    for i in 0..n {
        let c = rng.vec(lo, hi);
        prims.push(match i % 7 {
            0 => sphere(c, rng.range(0.05, 0.8)),
            1 => cylinder(c, rng.dir(), rng.range(0.05, 0.5), rng.range(0.05, 0.7)),
            // Degenerate: collinear corners, one point, a repeated corner.
            2 => {
                let d = rng.dir();
                tri(c, c + d, c + 2.0 * d)
            }
            3 if i % 2 == 1 => tri(c, c, c),
            3 => tri(c, c, c + rng.dir()),
            // Axis-aligned, on a few shared planes (grazing and slab-plane cases).
            4 => {
                let y = (rng.index(5) as f32) - 2.0;
                let a = Vec3::new(c.x, y, c.z);
                tri(
                    a,
                    a + Vec3::new(rng.range(0.1, 1.5), 0.0, 0.0),
                    a + Vec3::new(0.0, 0.0, rng.range(0.1, 1.5)),
                )
            }
            _ => tri(c, c + rng.dir() * 1.2, c + rng.dir() * 1.2),
        });
    }
    // Duplicates of earlier primitives (the earlier, lower index must win every tie).
    for k in 0..n / 5 {
        let p = prims[(k * 37) % n];
        prims.push(p);
    }
    prims
}

/// A mesh whose faces are `corners` taken three at a time (no vertex shared).
fn soup(corners: Vec<Vec3>) -> Mesh {
    let faces = (0..corners.len() as u32 / 3)
        .map(|f| [3 * f, 3 * f + 1, 3 * f + 2])
        .collect();
    Mesh {
        positions: corners,
        normals: None,
        uv: MeshUv::Strip,
        faces,
    }
}

/// A `g×g` grid of UV spheres of `s×s` quads (two triangles each, degenerate at the poles) on a
/// ground quad: the benchmark scene's layout, small.
fn mesh_scene(g: u32, s: u32) -> Primitives {
    let gf = g as f32;
    let ground = [
        Vec3::new(-gf, 0.0, -gf),
        Vec3::new(gf, 0.0, -gf),
        Vec3::new(gf, 0.0, gf),
        Vec3::new(-gf, 0.0, gf),
    ];
    let point = |c: Vec3, a: u32, b: u32| {
        let theta = std::f32::consts::PI * a as f32 / s as f32;
        let phi = std::f32::consts::TAU * b as f32 / s as f32;
        c + 0.45
            * Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            )
    };
    let mut balls = Vec::new();
    for i in 0..g {
        for j in 0..g {
            let c = Vec3::new(i as f32 - gf / 2.0 + 0.5, 0.45, j as f32 - gf / 2.0 + 0.5);
            for a in 0..s {
                for b in 0..s {
                    let (p00, p10) = (point(c, a, b), point(c, a + 1, b));
                    let (p11, p01) = (point(c, a + 1, b + 1), point(c, a, b + 1));
                    balls.extend([p00, p10, p11, p00, p11, p01]);
                }
            }
        }
    }
    // Two meshes, stored both ways: the ground's two faces as records, the balls' faces as a
    // run (as a large mesh's are), whose triangles are made from the mesh when asked for.
    let mut prims = Primitives::default();
    let [a, b, c, d] = ground;
    prims.push_mesh(soup(vec![a, b, c, a, c, d]), 0);
    prims.push_faces(soup(balls), 0);
    prims
}

fn triangles(prims: &Primitives) -> Vec<[Vec3; 3]> {
    prims
        .iter()
        .filter_map(|p| match &p.shape {
            Shape::Triangle(t) => Some(t.p),
            _ => None,
        })
        .collect()
}

/// The bounded primitives' box, at least [−1, 1]³.
fn bounds(prims: &Primitives) -> (Vec3, Vec3) {
    prims.iter().filter(|p| p.shape.is_bounded()).fold(
        (Vec3::splat(-1.0), Vec3::splat(1.0)),
        |(lo, hi), p| {
            let b = p.shape.bounds();
            (lo.min(b.min), hi.max(b.max))
        },
    )
}

/// Rays of every kind for a scene.
fn rays(prims: &Primitives, count: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed << 40);
    let tris = triangles(prims);
    let (lo, hi) = bounds(prims);
    let (lo, hi) = (lo - 0.25 * (hi - lo), hi + 0.25 * (hi - lo));
    let axes = [Vec3::X, Vec3::Y, Vec3::Z];
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let kind = out.len() % 6;
        let ray = match kind {
            // Random origin and direction.
            0 => Ray::new(rng.vec(lo, hi), rng.dir()),
            // Aimed at a triangle's corner, edge or inside (watertightness, shared edges).
            1 if !tris.is_empty() => {
                let t = tris[rng.index(tris.len())];
                let target = match rng.index(4) {
                    0 => t[rng.index(3)],
                    1 => {
                        let i = rng.index(3);
                        0.5 * (t[i] + t[(i + 1) % 3])
                    }
                    _ => {
                        let (u, v) = (rng.next(), rng.next());
                        t[0] + u * (t[1] - t[0]) + v * (1.0 - u) * (t[2] - t[0])
                    }
                };
                let o = rng.vec(lo, hi);
                Ray::new(o, (target - o).normalize_or(Vec3::X))
            }
            // Grazing: the origin on (or next to) a triangle's plane, the direction in the plane
            // but for a tiny (or zero) normal component.
            2 if !tris.is_empty() => {
                let t = tris[rng.index(tris.len())];
                let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
                let n = e1.cross(e2).normalize_or(Vec3::Y);
                let (u, v) = (rng.range(-0.5, 1.5), rng.range(-0.5, 1.5));
                let o = t[0] + u * e1 + v * e2;
                let in_plane = (rng.range(-1.0, 1.0) * e1 + rng.range(-1.0, 1.0) * e2)
                    .normalize_or(e1.normalize_or(Vec3::X));
                let tilt = [0.0, 1e-7, -1e-7, 1e-4, -1e-3][rng.index(5)];
                let back = in_plane * rng.range(0.0, 3.0);
                Ray::new(o - back, (in_plane + tilt * n).normalize_or(in_plane))
            }
            // Axis-parallel: direction components exactly ±0, origins on vertex coordinates (so
            // rays run in slab planes and triangle planes).
            3 => {
                let a = axes[rng.index(3)];
                let sign = if rng.next() < 0.5 { -1.0 } else { 1.0 };
                let mut d = sign * a;
                // Zero components of either sign.
                for k in 0..3 {
                    if d[k] == 0.0 && rng.next() < 0.5 {
                        d[k] = -0.0;
                    }
                }
                let mut o = rng.vec(lo, hi);
                if !tris.is_empty() {
                    let v = tris[rng.index(tris.len())][rng.index(3)];
                    for k in 0..3 {
                        if a[k] == 0.0 && rng.next() < 0.7 {
                            o[k] = v[k];
                        }
                    }
                }
                Ray::new(o, d)
            }
            // Two axes: a diagonal in a coordinate plane, from a vertex's plane.
            4 => {
                let zero = rng.index(3);
                let mut d = rng.dir();
                d[zero] = if rng.next() < 0.5 { 0.0 } else { -0.0 };
                let mut o = rng.vec(lo, hi);
                if !tris.is_empty() {
                    o[zero] = tris[rng.index(tris.len())][rng.index(3)][zero];
                }
                Ray::new(o, d.normalize_or(Vec3::X))
            }
            // From inside the scene in a random direction, short or long.
            _ => Ray::new(rng.vec(lo, hi) * 0.5, rng.dir() * rng.range(0.5, 3.0)),
        };
        out.push(ray);
    }
    out
}

type Closest = Option<(u32, u32, [u32; 2])>;

fn key(h: Option<(u32, Candidate)>) -> Closest {
    h.map(|(p, c)| (p, c.t.to_bits(), c.aux.map(f32::to_bits)))
}

/// Every accelerator under test for `prims`.
fn accelerators(prims: &Primitives) -> Vec<(String, Accel)> {
    let mut v = vec![
        ("auto".to_string(), Accel::build(prims, AccelKind::Auto, 4)),
        (
            "median".to_string(),
            Accel::build(prims, AccelKind::Median, 4),
        ),
        ("sah".to_string(), Accel::build(prims, AccelKind::Sah, 4)),
        ("sah4".to_string(), Accel::build(prims, AccelKind::Sah4, 4)),
        ("sah8".to_string(), Accel::build(prims, AccelKind::Sah8, 4)),
        // Each wide tree with the other instruction set from the one it is built with: the
        // baseline and, where the CPU has it, AVX2 (`accel::kernels::isa`).
        (
            "sah4 avx2".to_string(),
            Accel::build(prims, AccelKind::Sah4, 4).with_isa(Isa::detect()),
        ),
        (
            "sah8 baseline".to_string(),
            Accel::build(prims, AccelKind::Sah8, 4).with_isa(Isa::BASELINE),
        ),
    ];
    for leaf in [1, 2, 8] {
        v.push((
            format!("median leaf {leaf}"),
            Accel::Bvh(Bvh::build_median(prims, leaf)),
        ));
        v.push((
            format!("sah leaf {leaf}"),
            Accel::Bvh(Bvh::build_sah(prims, leaf)),
        ));
        v.push((
            format!("sah4 leaf {leaf}"),
            Accel::Bvh4(Bvh4::build(prims, leaf)),
        ));
    }
    v
}

/// Checks every accelerator against the list on `rays` with several `t_max`; returns the number
/// of rays.
fn check_scene(name: &str, prims: &Primitives, rays: &[Ray]) -> usize {
    let list = Accel::List;
    let accels = accelerators(prims);
    let blocks_some = |p: u32| p % 3 != 1;
    let mut queries = 0;
    let mut hits = 0;
    for (i, ray) in rays.iter().enumerate() {
        let first = list.closest(prims, ray, f32::INFINITY);
        hits += first.is_some() as usize;
        let mut limits = vec![f32::INFINITY, 0.5 + 4.0 * (i % 7) as f32];
        if let Some((_, c)) = first {
            // Exactly at the hit (excluded: t < t_max) and just past it (included).
            limits.push(c.t);
            limits.push(next_float_up(c.t));
        }
        for &t_max in &limits {
            queries += 1;
            let want = key(list.closest(prims, ray, t_max));
            let want_any = list.any(prims, ray, t_max, |_| true);
            let want_some = list.any(prims, ray, t_max, blocks_some);
            assert_eq!(
                want_any,
                want.is_some(),
                "{name}: list any/closest disagree"
            );
            for (accel_name, accel) in &accels {
                let got = key(accel.closest(prims, ray, t_max));
                assert_eq!(
                    got, want,
                    "{name}, {accel_name}: closest differs for ray {i} {ray:?} t_max {t_max}"
                );
                assert_eq!(
                    accel.any(prims, ray, t_max, |_| true),
                    want_any,
                    "{name}, {accel_name}: any differs for ray {i} {ray:?} t_max {t_max}"
                );
                assert_eq!(
                    accel.any(prims, ray, t_max, blocks_some),
                    want_some,
                    "{name}, {accel_name}: filtered any differs for ray {i} {ray:?}"
                );
            }
        }
    }
    let hittable = prims.iter().any(|p| match p.shape {
        Shape::Triangle(t) => (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]) != Vec3::ZERO,
        _ => true,
    });
    assert_eq!(
        hits > 0,
        hittable,
        "{name}: {hits} of {queries} queries hit"
    );
    rays.len()
}

#[test]
fn every_builder_matches_brute_force() {
    let mut total = 0;
    // A small mesh (many shared edges and vertices, degenerate pole triangles) and a mixed scene
    // with degenerate and duplicated primitives.
    let mesh = mesh_scene(2, 8);
    assert_eq!(mesh.len(), 514);
    total += check_scene("sphere grid", &mesh, &rays(&mesh, 40_000, 1));
    let mixed = Primitives::from(mixed_scene(200, 2));
    total += check_scene("mixed", &mixed, &rays(&mixed, 40_000, 2));
    let mixed_small = Primitives::from(mixed_scene(20, 3));
    total += check_scene("mixed small", &mixed_small, &rays(&mixed_small, 8_000, 3));
    // Few primitives: nothing, one of each kind, two coincident.
    let empty = Primitives::default();
    total += check_scene("empty", &empty, &rays(&empty, 1_000, 4));
    let one_tri = Primitives::from(vec![tri(Vec3::ZERO, Vec3::X, Vec3::Y)]);
    total += check_scene("one triangle", &one_tri, &rays(&one_tri, 4_000, 5));
    let one_sphere = Primitives::from(vec![sphere(Vec3::ONE, 0.5)]);
    total += check_scene("one sphere", &one_sphere, &rays(&one_sphere, 1_000, 6));
    let one_cyl = Primitives::from(vec![cylinder(Vec3::ZERO, Vec3::Z, 0.5, 1.0)]);
    total += check_scene("one cylinder", &one_cyl, &rays(&one_cyl, 1_000, 7));
    let twins = Primitives::from(vec![
        tri(Vec3::ZERO, Vec3::X, Vec3::Y),
        tri(Vec3::ZERO, Vec3::X, Vec3::Y),
    ]);
    total += check_scene("two coincident", &twins, &rays(&twins, 4_000, 8));
    let points = Primitives::from(vec![tri(Vec3::ONE, Vec3::ONE, Vec3::ONE); 9]);
    total += check_scene("degenerate only", &points, &rays(&points, 1_000, 9));
    assert!(total >= 100_000, "only {total} rays");
}

#[test]
fn planes_outside_the_trees_keep_the_contract() {
    // Planes among mixed geometry: one through the axis-aligned triangles at y = 0 (ties in t),
    // a duplicate of it later (ties between planes), tilted and axis-aligned ones, one far away.
    let mut mixed = mixed_scene(200, 13);
    mixed.insert(0, plane(Vec3::Y, 0.0));
    mixed.insert(57, plane(Vec3::new(1.0, 2.0, -0.5), 1.5));
    mixed.insert(120, plane(Vec3::X, -3.0));
    mixed.push(plane(Vec3::Y, 0.0));
    mixed.push(plane(Vec3::new(0.0, -1.0, 1.0), 1.0e4));
    let mixed = Primitives::from(mixed);
    let n = check_scene("mixed with planes", &mixed, &rays(&mixed, 30_000, 14));
    // Planes alone (the tree is empty) and one plane under one sphere (a list under `auto`).
    let planes = Primitives::from(vec![
        plane(Vec3::Z, 1.0),
        plane(Vec3::Z, 1.0),
        plane(Vec3::ONE, -2.0),
    ]);
    let m = check_scene("planes only", &planes, &rays(&planes, 4_000, 15));
    let floor = Primitives::from(vec![
        sphere(Vec3::new(0.0, 1.0, 0.0), 1.0),
        plane(Vec3::Y, 0.0),
    ]);
    let k = check_scene("sphere on a floor", &floor, &rays(&floor, 4_000, 16));
    assert!(n + m + k >= 38_000);
    // A ray far outside every finite box still finds the floor, in every accelerator.
    let ray = Ray::new(Vec3::new(1.0e5, 50.0, -7.0e4), Vec3::new(0.0, -1.0, 0.0));
    for (name, accel) in accelerators(&mixed) {
        let (p, c) = accel.closest(&mixed, &ray, f32::INFINITY).expect("hit");
        assert_eq!((p, c.t), (0, 50.0), "{name}");
        assert!(
            accel.any(&mixed, &ray, 51.0, |p| p != 0),
            "{name}: the duplicate blocks"
        );
    }
}

#[test]
fn larger_mesh_matches_brute_force() {
    // The size of the smallest benchmark grid: deeper trees; fewer rays, as the list is slow here.
    let mesh = mesh_scene(4, 16);
    assert_eq!(mesh.len(), 8_194);
    check_scene("grid 4x16", &mesh, &rays(&mesh, 1_500, 10));
}

#[test]
fn ties_go_to_the_lowest_index_in_every_accelerator() {
    // Copies of one triangle at indices 3, 7 and 40, among other geometry far away; another
    // triangle sharing the copies' plane and an edge.
    let a = Vec3::new(0.0, 0.0, 5.0);
    let b = Vec3::new(2.0, 0.0, 5.0);
    let c = Vec3::new(0.0, 2.0, 5.0);
    let mut prims = mixed_scene(60, 11)
        .into_iter()
        .map(|p| match p.shape {
            // Move the random geometry out of the way.
            Shape::Sphere(s) => sphere(s.center + Vec3::splat(50.0), s.radius),
            _ => tri(
                Vec3::splat(50.0),
                Vec3::new(51.0, 50.0, 50.0),
                Vec3::splat(51.0),
            ),
        })
        .collect::<Vec<_>>();
    for i in [3, 7, 40] {
        prims[i] = tri(a, b, c);
    }
    prims[20] = tri(b, Vec3::new(2.0, 2.0, 5.0), c);
    let prims = Primitives::from(prims);
    let ray = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::Z);
    for (name, accel) in accelerators(&prims) {
        let (p, c) = accel.closest(&prims, &ray, f32::INFINITY).expect("hit");
        assert_eq!((p, c.t), (3, 5.0), "{name}");
        // With t_max at the hit, nothing; just past it, the same.
        assert!(accel.closest(&prims, &ray, 5.0).is_none(), "{name}");
        assert_eq!(
            accel.closest(&prims, &ray, next_float_up(5.0)).map(|h| h.0),
            Some(3),
            "{name}"
        );
        // Filtering out index 3 leaves 7 as the lowest blocker.
        assert!(accel.any(&prims, &ray, f32::INFINITY, |p| p == 7), "{name}");
        assert!(!accel.any(&prims, &ray, 5.0, |_| true), "{name}");
    }
    // Through the shared edge of two triangles in one plane: the watertight test hits at least
    // one; with equal t the lower index wins.
    let ray = Ray::new(Vec3::new(1.0, 1.0, 0.0), Vec3::Z);
    let want = Accel::List
        .closest(&prims, &ray, f32::INFINITY)
        .map(|h| h.0);
    assert_eq!(want, Some(3));
    for (name, accel) in accelerators(&prims) {
        assert_eq!(
            accel.closest(&prims, &ray, f32::INFINITY).map(|h| h.0),
            want,
            "{name}"
        );
    }
}

#[test]
fn nan_and_zero_directions_hit_nothing() {
    let prims = Primitives::from(mixed_scene(50, 12));
    for d in [
        Vec3::ZERO,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::splat(f32::NAN),
        Vec3::new(0.0, f32::INFINITY, 0.0),
    ] {
        let ray = Ray::new(Vec3::ZERO, d);
        for (name, accel) in accelerators(&prims) {
            assert_eq!(
                key(accel.closest(&prims, &ray, f32::INFINITY)),
                key(Accel::List.closest(&prims, &ray, f32::INFINITY)),
                "{name} {d}"
            );
            assert_eq!(
                accel.any(&prims, &ray, f32::INFINITY, |_| true),
                Accel::List.any(&prims, &ray, f32::INFINITY, |_| true),
                "{name} {d}"
            );
        }
    }
}

/// A light: a flat quad or a small box, somewhere above the middle of the scene.
fn light_box(rng: &mut Rng) -> raytracer::accel::aabb::Aabb {
    let c = rng.vec(Vec3::new(-3.0, 3.0, -3.0), Vec3::new(3.0, 6.0, 3.0));
    let half = Vec3::new(
        rng.range(0.1, 1.5),
        rng.range(0.0, 0.3),
        rng.range(0.1, 1.5),
    );
    raytracer::accel::aabb::Aabb::new(c - half, c + half)
}

/// The shadow ray from `origin` to `target`, and its bound: just short of the target.
fn shadow_ray(origin: Vec3, target: Vec3) -> (Ray, f32) {
    let to = target - origin;
    let dist = to.length();
    (Ray::new(origin, to / dist), dist * (1.0 - 1e-4))
}

/// `count` shadow rays from origins within `offset` of `point` to points of `light`, each
/// answered by `candidates` as testing every primitive answers it; how many were blocked.
fn assert_shadow_rays_answered(
    rng: &mut Rng,
    prims: &Primitives,
    candidates: &Reachable,
    (point, offset): (Vec3, f32),
    light: &raytracer::accel::aabb::Aabb,
    count: usize,
    name: &str,
) -> usize {
    let mut blocked = 0;
    for _ in 0..count {
        let origin = point + rng.dir() * offset * rng.next();
        let (ray, t_max) = shadow_ray(origin, rng.vec(light.min, light.max));
        let want = Accel::List.any(prims, &ray, t_max, |_| true);
        assert_eq!(
            candidates.any(&ray, t_max, |_| true),
            want,
            "{name}: {ray:?} to {t_max}"
        );
        blocked += want as usize;
    }
    blocked
}

/// Shadow rays from one point to the points of a light box, tested against only the candidates
/// of their beam, give the answer of testing every primitive, in every accelerator; and the
/// beam does set primitives aside.
#[test]
fn beam_candidates_answer_every_shadow_ray_of_the_beam() {
    use raytracer::accel::aabb::Aabb;
    use raytracer::accel::Beam;
    let mut prims = Primitives::from(mixed_scene(300, 11));
    prims.push(plane(Vec3::new(0.0, 1.0, 0.0), -4.5));
    let accels = accelerators(&prims);
    let mut rng = Rng(0xbea);
    let (mut rays, mut blocked, mut kept, mut beams) = (0usize, 0usize, 0usize, 0usize);
    let mut candidates = Vec::new();
    for _ in 0..150 {
        let light = light_box(&mut rng);
        let apex = rng.vec(Vec3::splat(-4.0), Vec3::new(4.0, 2.0, 4.0));
        // Origins within `offset` of the apex, as spawned shadow rays are.
        let offset = 1e-4;
        let Some(beam) = Beam::new(apex, &light, offset) else {
            continue;
        };
        beams += 1;
        for (name, accel) in accels
            .iter()
            .chain([("list".to_string(), Accel::List)].iter())
        {
            assert!(accel.beam_candidates(&prims, &beam, usize::MAX, &mut candidates));
            kept += candidates.len();
            let all = Reachable::all(&prims, &candidates);
            blocked += assert_shadow_rays_answered(
                &mut rng,
                &prims,
                &all,
                (apex, offset),
                &light,
                40,
                name,
            );
            rays += 40;
        }
    }
    assert!(beams > 50, "{beams}");
    assert!(blocked > rays / 20 && blocked < rays, "{blocked} of {rays}");
    // On average far fewer candidates than primitives.
    let per_beam = kept as f64 / (beams * (accels.len() + 1)) as f64;
    assert!(per_beam < prims.len() as f64 / 4.0, "{per_beam}");
    // Past the limit, the caller is told to query the whole accelerator.
    let whole = Aabb::new(Vec3::splat(-4.0), Vec3::splat(4.0));
    let beam = Beam::new(Vec3::new(0.0, -6.0, 0.0), &whole, 0.0).unwrap();
    for (name, accel) in &accels {
        assert!(
            !accel.beam_candidates(&prims, &beam, 3, &mut candidates),
            "{name}"
        );
    }
    assert!(!Accel::List.beam_candidates(&prims, &beam, 3, &mut candidates));
}

/// Shadow rays that leave from one origin, tested against only the candidates left once those
/// the origin leaves behind are set aside (`Reachable::fill`), give the answer of testing every
/// primitive: from points exactly on axis-aligned floors, walls and tiles (whose triangles
/// are set aside though the origin lies in their plane), from just above them, and from
/// anywhere; and primitives are set aside. The floor is a mesh stored as a run, whose
/// triangles the list makes from the mesh.
#[test]
fn reachable_candidates_answer_every_shadow_ray_from_their_origin() {
    use raytracer::accel::Beam;
    let mut prims = Primitives::from(mixed_scene(200, 5));
    // A floor of 8 × 8 cells at y = −4, a wall at x = 4.5, and tiles at other heights.
    let cell = 1.0;
    let mut floor = Vec::new();
    for i in 0..8 {
        for j in 0..8 {
            let (x, z) = (-4.0 + i as f32 * cell, -4.0 + j as f32 * cell);
            let p = |dx: f32, dz: f32| Vec3::new(x + dx, -4.0, z + dz);
            floor.extend([p(0.0, 0.0), p(cell, 0.0), p(cell, cell)]);
            floor.extend([p(0.0, 0.0), p(cell, cell), p(0.0, cell)]);
        }
    }
    prims.push_faces(soup(floor), 0);
    let w = |y: f32, z: f32| Vec3::new(4.5, y, z);
    prims.push(tri(w(-4.0, -4.0), w(6.0, -4.0), w(6.0, 4.0)));
    prims.push(tri(w(-4.0, -4.0), w(6.0, 4.0), w(-4.0, 4.0)));
    let mut rng = Rng(0x51de);
    let tiles: Vec<(Vec3, f32)> = (0..12)
        .map(|_| {
            (
                rng.vec(Vec3::splat(-3.0), Vec3::splat(2.0)),
                rng.range(0.3, 1.5),
            )
        })
        .collect();
    for &(c, s) in &tiles {
        prims.push(tri(
            c,
            c + Vec3::new(s, 0.0, 0.0),
            c + Vec3::new(0.0, 0.0, s),
        ));
    }
    let list = Accel::List;
    let (mut rays, mut blocked, mut floor_beams, mut set_aside) = (0, 0, 0, 0);
    let (mut candidates, mut reachable) = (Vec::new(), Reachable::default());
    for k in 0..600 {
        let light = light_box(&mut rng);
        let origin = match k % 4 {
            // On the floor's plane, exactly, and just above it.
            0 => Vec3::new(rng.range(-4.0, 4.0), -4.0, rng.range(-4.0, 4.0)),
            1 => Vec3::new(rng.range(-4.0, 4.0), -3.999_999_5, rng.range(-4.0, 4.0)),
            // On a tile's plane (inside the tile or beside it).
            2 => {
                let (t, s) = tiles[k / 4 % tiles.len()];
                t + Vec3::new(rng.range(-0.5, 1.0) * s, 0.0, rng.range(-0.5, 1.0) * s)
            }
            _ => rng.vec(Vec3::splat(-4.0), Vec3::new(4.0, 2.0, 4.0)),
        };
        let Some(beam) = Beam::new(origin, &light, 1e-4) else {
            continue;
        };
        assert!(list.beam_candidates(&prims, &beam, usize::MAX, &mut candidates));
        reachable.fill(&prims, &beam, &candidates, origin);
        let kept = reachable.numbers();
        assert!(kept.iter().all(|p| candidates.contains(p)));
        assert!(reachable.iter().all(|(p, shape)| *shape == *prims.shape(p)));
        if k % 4 == 0 {
            floor_beams += 1;
            set_aside += candidates.len() - kept.len();
        }
        for _ in 0..30 {
            let (ray, t_max) = shadow_ray(origin, rng.vec(light.min, light.max));
            let want = list.any(&prims, &ray, t_max, |_| true);
            let got = reachable.any(&ray, t_max, |_| true);
            assert_eq!(got, want, "{ray:?} to {t_max}");
            rays += 1;
            blocked += want as usize;
        }
    }
    assert!(blocked > rays / 20 && blocked < rays, "{blocked} of {rays}");
    // The floor's triangles around an origin on the floor are among its beam's candidates
    // (their bounding balls hold it), and are set aside: at least the two of its own cell.
    assert!(
        set_aside >= 2 * floor_beams,
        "{set_aside} for {floor_beams} beams"
    );
}

/// A light buffer's candidates for a shading point's beam answer every shadow ray of the beam
/// as testing every primitive does, in every accelerator the buffer is gathered through; most
/// points are served from the buffer, with lists about as short as the tree's walk gives.
#[test]
fn light_buffer_candidates_answer_every_shadow_ray_of_the_beam() {
    use raytracer::accel::{Beam, LightBuffer};
    let mut prims = Primitives::from(mixed_scene(80, 17));
    prims.push(plane(Vec3::new(0.0, 1.0, 0.0), -4.5));
    let bounds = prims.bounds();
    let mut rng = Rng(0x11b);
    let (mut rays, mut blocked, mut points, mut served) = (0usize, 0usize, 0usize, 0usize);
    let (mut from_buffer, mut from_tree) = (Vec::new(), Vec::new());
    let (mut buffer_len, mut tree_len) = (0usize, 0usize);
    for (name, accel) in accelerators(&prims) {
        for _ in 0..6 {
            let light = light_box(&mut rng);
            let (centre, radius) = light.ball();
            let buffer = LightBuffer::new(centre, radius, &prims, &accel, &bounds);
            for k in 0..150 {
                let point = rng.vec(Vec3::splat(-4.0), Vec3::new(4.0, 2.0, 4.0));
                // Origins offset as spawned ones are, and (every tenth point) farther than the
                // buffer serves.
                let offset = if k % 10 == 0 {
                    2.0 * buffer.max_offset()
                } else {
                    buffer.max_offset() * rng.next()
                };
                let Some(beam) = Beam::new(point, &light, offset) else {
                    continue;
                };
                points += 1;
                let limit = usize::MAX;
                let got = buffer.beam_candidates(&beam, point, offset, limit, &mut from_buffer);
                if k % 10 == 0 {
                    assert_eq!(got, None, "{name}: an offset past the buffer's");
                    continue;
                }
                let Some(complete) = got else { continue };
                assert!(complete);
                served += 1;
                assert!(accel.beam_candidates(&prims, &beam, limit, &mut from_tree));
                buffer_len += from_buffer.len();
                tree_len += from_tree.len();
                let candidates = Reachable::all(&prims, &from_buffer);
                blocked += assert_shadow_rays_answered(
                    &mut rng,
                    &prims,
                    &candidates,
                    (point, offset),
                    &light,
                    20,
                    &name,
                );
                rays += 20;
            }
        }
    }
    assert!(blocked > rays / 20 && blocked < rays, "{blocked} of {rays}");
    assert!(served > points / 2, "{served} of {points} points served");
    assert!(
        buffer_len <= tree_len + tree_len / 4,
        "{buffer_len} against {tree_len}"
    );
}

/// Rays that start inside a sphere (spawned below its surface, as refracted and internally
/// reflected rays are) get from `Interiors` exactly the list's answer: spheres resting on a floor
/// of triangles, touching each other, cut by a triangle, holding a smaller sphere, and alone,
/// with an infinite plane and clutter about.
#[test]
fn rays_from_inside_spheres_get_the_answers_of_the_whole_tree() {
    use raytracer::accel::Interiors;
    use raytracer::ray::Side;
    let mut prims = Primitives::from(mixed_scene(60, 11));
    let floor = [
        Vec3::new(-6.0, -5.0, -6.0),
        Vec3::new(6.0, -5.0, -6.0),
        Vec3::new(6.0, -5.0, 6.0),
        Vec3::new(-6.0, -5.0, 6.0),
    ];
    prims.push(tri(floor[0], floor[1], floor[2]));
    prims.push(tri(floor[0], floor[2], floor[3]));
    prims.push(plane(Vec3::new(0.0, 0.0, 1.0), -7.0));
    let first_sphere = prims.len();
    // Resting on the floor, two touching each other; one cut by a triangle; one holding a small
    // one; one alone above everything.
    prims.push(sphere(Vec3::new(-2.0, -4.2, 5.0), 0.8));
    prims.push(sphere(Vec3::new(-0.4, -4.2, 5.0), 0.8));
    prims.push(sphere(Vec3::new(2.0, -4.0, 5.0), 1.0));
    prims.push(tri(
        Vec3::new(1.0, -4.5, 4.0),
        Vec3::new(3.5, -3.5, 5.0),
        Vec3::new(1.5, -3.0, 6.5),
    ));
    prims.push(sphere(Vec3::new(0.0, 6.0, 0.0), 1.5));
    prims.push(sphere(Vec3::new(0.3, 6.2, 0.1), 0.4));
    prims.push(sphere(Vec3::new(0.0, 12.0, 3.0), 1.2));
    let spheres: Vec<u32> = (first_sphere..prims.len())
        .filter(|&p| matches!(prims.get(p as u32).shape, Shape::Sphere(_)))
        .map(|p| p as u32)
        .collect();
    let list = Accel::List;
    let mut rng = Rng(0x1a5e);
    let mut checked = 0;
    for (name, accel) in accelerators(&prims) {
        let interiors = Interiors::new(&prims, &accel, |_| true);
        for &s in &spheres {
            let Some(inside) = interiors.of(s) else {
                continue;
            };
            let Shape::Sphere(ball) = prims.get(s).shape else {
                unreachable!()
            };
            for k in 0..200 {
                // A point on the sphere, hit from outside, and a ray from below it inwards.
                let target = ball.center + ball.radius * rng.dir();
                let from = target + (target - ball.center).normalize() * 3.0 + rng.dir();
                let outer = Ray::new(from, (target - from).normalize());
                let Some((p, c)) = list.closest(&prims, &outer, f32::INFINITY) else {
                    continue;
                };
                if p != s {
                    continue;
                }
                let hit = prims.get(p).hit(&outer, c, p, &[]);
                let spawn = hit.spawn_points();
                let dir = match k % 4 {
                    // Towards the lowest point (a floor's contact), grazing, at random.
                    0 => (ball.center - Vec3::Y * ball.radius) - hit.point,
                    1 => {
                        let d = rng.dir();
                        (d - d.dot(hit.normal) * hit.normal) - 1e-3 * hit.normal
                    }
                    _ => rng.dir() - 1.01 * hit.normal,
                }
                .normalize_or_zero();
                if spawn.side(dir) != Side::Below {
                    continue;
                }
                let ray = spawn.ray(dir);
                for t_max in [f32::INFINITY, rng.range(0.0, 2.0 * ball.radius)] {
                    let want = key(list.closest(&prims, &ray, t_max));
                    let got = key(interiors.closest(&accel, &prims, inside, &ray, t_max));
                    assert_eq!(got, want, "{name}: sphere {s}, ray {ray:?}, t_max {t_max}");
                    checked += 1;
                }
            }
        }
        // The lone sphere and the ones on the floor have entries; the held sphere has the one it
        // holds as a neighbour, so its rays are answered too. The plain list has none.
        for &s in &spheres {
            assert!(interiors.of(s).is_some(), "{name}: sphere {s} has no entry");
        }
    }
    assert!(Interiors::new(&prims, &list, |_| true).is_empty());
    assert!(checked > 10_000, "{checked} rays checked");
}
