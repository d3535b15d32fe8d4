//! Numerical stability under adversarial inputs: rays spawned from hits never re-hit the surface
//! they leave, closed meshes are watertight near and far from the origin, rays with NaN or
//! infinite components are harmless, and images do not change with scale and position.
//!
//! CI runs the default counts (≥ 10^5 rays per check); `RAYTRACER_STRESS=1` multiplies them by
//! ten. Each test prints what it ran. `docs/robustness.md` lists the checks and their counts.

mod common;

use common::*;
use raytracer::accel::{Accel, AccelKind};
use raytracer::geometry::{Cylinder, Mesh, MeshUv, Primitive, Primitives, Shape, Sphere};
use raytracer::math::{orthonormal_basis, Vec2, Vec3};
use raytracer::ray::{Hit, Ray};
use raytracer::render::{render, RenderOptions};
use raytracer::sampling::{hash, to_unit, uniform_sphere};

/// Multiplier on every count: 1 in CI, 10 with `RAYTRACER_STRESS=1`.
fn stress() -> usize {
    match std::env::var("RAYTRACER_STRESS") {
        Ok(v) if v == "1" => 10,
        _ => 1,
    }
}

/// A deterministic stream of uniform numbers (the renderer's own hash).
struct Rng {
    seed: u64,
    n: u64,
}

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng { seed, n: 0 }
    }
    fn next(&mut self) -> f32 {
        self.n += 1;
        to_unit(hash(&[self.seed, self.n]))
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
    /// Log-uniform in [lo, hi].
    fn log(&mut self, lo: f32, hi: f32) -> f32 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.next()).exp()
    }
    fn dir(&mut self) -> Vec3 {
        let u = Vec2::new(self.next(), self.next());
        uniform_sphere(u)
    }
    /// A direction in the hemisphere around `n` with cosine at least `min_cos`.
    fn hemisphere(&mut self, n: Vec3, min_cos: f32) -> Vec3 {
        assert!(n.is_finite() && n != Vec3::ZERO && min_cos < 0.9);
        loop {
            let d = self.dir();
            let c = d.dot(n);
            if c.abs() >= min_cos {
                return if c > 0.0 { d } else { -d };
            }
        }
    }
}

fn single_mesh(p: Vec<Vec3>, faces: Vec<[u32; 3]>) -> Primitives {
    let mesh = Mesh {
        positions: p,
        normals: None,
        uv: MeshUv::Strip,
        faces,
    };
    let mut prims = Primitives::default();
    prims.push_mesh(mesh, 0);
    prims
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum IntegratorKind {
    Sphere,
    Triangle,
    Quad,
    Cylinder,
}

/// A random shape of size `scale` at `pos`, a point on its surface to aim at, and the outward
/// normal there (for planar shapes, either side).
fn random_shape(
    rng: &mut Rng,
    kind: IntegratorKind,
    pos: Vec3,
    scale: f32,
) -> (Primitives, Vec3, Vec3) {
    let one = |shape: Shape| Primitives::from(vec![Primitive { shape, material: 0 }]);
    match kind {
        IntegratorKind::Sphere => {
            let n = rng.dir();
            let s = Sphere::new(pos, scale, Vec3::Y, Vec3::NEG_X);
            (one(Shape::Sphere(s)), pos + n * scale, n)
        }
        IntegratorKind::Triangle => {
            let p: Vec<Vec3> = (0..3).map(|_| pos + rng.dir() * scale).collect();
            let (a, b) = (rng.range(0.05, 0.9), rng.next());
            let target = p[0] + a * ((p[1] - p[0]) + b * (p[2] - p[1]));
            let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or(Vec3::Z);
            (single_mesh(p, vec![[0, 1, 2]]), target, n)
        }
        IntegratorKind::Quad => {
            let (e1, e2) = (rng.dir() * scale, rng.dir() * scale);
            let p = vec![pos, pos + e1, pos + e1 + e2, pos + e2];
            let target = pos + rng.range(0.02, 0.98) * e1 + rng.range(0.02, 0.98) * e2;
            let n = e1.cross(e2).normalize_or(Vec3::Z);
            (single_mesh(p, vec![[0, 1, 2], [0, 2, 3]]), target, n)
        }
        IntegratorKind::Cylinder => {
            let axis = rng.dir();
            let half = scale * rng.range(0.2, 5.0);
            let c = Cylinder::new(pos, axis, scale, half);
            let (t, b) = orthonormal_basis(axis);
            let phi = rng.range(0.0, std::f32::consts::TAU);
            let radial = phi.cos() * t + phi.sin() * b;
            let (target, n) = if rng.next() < 0.7 {
                let along = axis * half * rng.range(-0.95, 0.95);
                (pos + scale * radial + along, radial)
            } else {
                (pos + axis * half + 0.9 * scale * rng.next() * radial, axis)
            };
            (one(Shape::Cylinder(c)), target, n)
        }
    }
}

fn hit_any(prims: &Primitives, ray: &Ray, t_max: f32) -> Option<f32> {
    prims
        .iter()
        .filter_map(|p| p.shape.intersect(ray, t_max))
        .map(|c| c.t)
        .reduce(f32::min)
}

/// Smallest shape, in float spacings at its position, that the re-intersection check takes on.
const MIN_SIZE_IN_SPACINGS: f32 = 1.0;

/// From hits on random shapes of sizes 10^-6..10^6 up to 10^6 from the origin, rays spawned into
/// the outer hemisphere (reflection-like), towards random points on the outer side (shadow-like),
/// and into the inner hemisphere (transmission-like) never hit the surface they left. Planar
/// shapes must not be hit again at all; a sphere entered must be hit at its far side, never near
/// the spawn point (checked where the chord is long enough to be told from the error bound).
#[test]
fn spawned_rays_never_hit_the_surface_they_leave() {
    let shapes = 2500 * stress();
    let per_hit = 16;
    let mut rng = Rng::new(0x5eed);
    let (mut shadow_checked, mut unrepresentable) = (0, 0);
    let (mut rays, mut failures, mut missed_aim, mut transmission_checked) =
        (0usize, Vec::new(), 0, 0);
    for i in 0..shapes {
        let kind = [
            IntegratorKind::Sphere,
            IntegratorKind::Triangle,
            IntegratorKind::Quad,
            IntegratorKind::Cylinder,
        ][i % 4];
        let scale = rng.log(1e-6, 1e6);
        let pos = if rng.next() < 0.2 {
            Vec3::ZERO
        } else {
            rng.dir() * rng.log(1e-3, 1e6)
        };
        // A shape a few float spacings across at its position cannot be told from its rounding
        // error (a 1 mm sphere 10^5 away spans a tenth of an f32 step); those are counted, not
        // checked.
        let spacing = pos.abs().max_element() * f32::EPSILON;
        if scale < MIN_SIZE_IN_SPACINGS * spacing {
            unrepresentable += 1;
            continue;
        }
        let (prims, target, normal) = random_shape(&mut rng, kind, pos, scale);
        // From outside: across the tangent plane, on the outer side of a convex shape (either side
        // of a planar one).
        let planar = matches!(kind, IntegratorKind::Triangle | IntegratorKind::Quad);
        let side = if planar && rng.next() < 0.5 {
            -normal
        } else {
            normal
        };
        let from = target + rng.hemisphere(side, 0.1) * scale * rng.log(1.5, 100.0);
        let aim = Ray::new(from, (target - from).normalize());
        let best = prims
            .iter()
            .enumerate()
            .filter_map(|(k, p)| p.shape.intersect(&aim, f32::INFINITY).map(|c| (k, c)))
            .min_by(|a, b| a.1.t.total_cmp(&b.1.t));
        let Some((k, c)) = best else {
            missed_aim += 1;
            continue;
        };
        let hit: Hit = prims.get(k as u32).hit(&aim, c, k as u32, prims.meshes());
        let outward = if hit.normal.dot(aim.dir) < 0.0 {
            hit.normal
        } else {
            -hit.normal
        };
        let planar = matches!(kind, IntegratorKind::Triangle | IntegratorKind::Quad);
        for _ in 0..per_hit {
            // Reflection-like.
            let w = rng.hemisphere(outward, 0.0);
            let r = hit.spawn(w);
            rays += 1;
            if let Some(t) = hit_any(&prims, &r, f32::INFINITY) {
                failures.push(format!(
                    "{kind:?} s={scale:e} |p|={:e}: reflected ray hit at t={t:e}",
                    pos.length()
                ));
            }
            // Shadow-like, towards a point on the outer side.
            let q = hit.point + rng.hemisphere(outward, 0.01) * scale * rng.log(1e-2, 1e3);
            let (r, d) = hit.spawn_to(q);
            rays += 1;
            // Only targets provably above the tangent plane count: the height of the rounded q,
            // in f64, must exceed the hit point's error bound plus the rounding of q itself.
            let height = (q.as_dvec3() - hit.point.as_dvec3()).dot(outward.as_dvec3());
            let margin = hit.error.length() as f64 + 4.0 * f32::EPSILON as f64 * q.length() as f64;
            if height > margin {
                shadow_checked += 1;
                if let Some(t) = hit_any(&prims, &r, d) {
                    failures.push(format!(
                        "{kind:?} s={scale:e} |p|={:e}: shadow ray hit at t={t:e} of {d:e}",
                        pos.length()
                    ));
                }
            }
            // Transmission-like.
            let min_cos = if planar { 0.0 } else { 0.05 };
            let w = -rng.hemisphere(outward, min_cos);
            let r = hit.spawn(w);
            rays += 1;
            let t = hit_any(&prims, &r, f32::INFINITY);
            if planar {
                if let Some(t) = t {
                    failures.push(format!(
                        "{kind:?} s={scale:e} |p|={:e}: transmitted ray hit at t={t:e}",
                        pos.length()
                    ));
                }
            } else if kind == IntegratorKind::Sphere {
                let chord = 2.0 * scale as f64 * (w.dot(-outward) as f64);
                if chord > 1e3 * hit.error.length() as f64 {
                    transmission_checked += 1;
                    match t {
                        Some(t) if (t as f64) > 0.5 * chord => {}
                        other => failures.push(format!(
                            "sphere s={scale:e} |p|={:e}: entering ray found {other:?}, chord {chord:e}",
                            pos.length()
                        )),
                    }
                }
            }
        }
    }
    println!(
        "re-intersection: {shapes} shapes, {rays} spawned rays ({shadow_checked} shadow rays with targets \
         provably outside), {transmission_checked} sphere entries checked, \
         {unrepresentable} shapes too small for f32 at their position, \
         {missed_aim} aiming rays missed, {} failures",
        failures.len()
    );
    assert!(rays >= 100_000);
    assert!(
        failures.is_empty(),
        "{} failures, e.g. {:?}",
        failures.len(),
        &failures[..failures.len().min(5)]
    );
}

/// An icosphere subdivided `levels` times: a closed mesh with shared vertices.
fn icosphere(levels: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut p: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::with_capacity(f.len() * 4);
        let mut midpoint = |a: u32, b: u32, p: &mut Vec<Vec3>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                p.push(((p[a as usize] + p[b as usize]) * 0.5).normalize());
                p.len() as u32 - 1
            })
        };
        for [a, b, c] in f {
            let (ab, bc, ca) = (
                midpoint(a, b, &mut p),
                midpoint(b, c, &mut p),
                midpoint(c, a, &mut p),
            );
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    (p, f)
}

/// A latitude/longitude sphere with shared vertices (poles included), each vertex jittered.
fn jittered_uv_sphere(n: u32, rng: &mut Rng) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut p = vec![Vec3::Y];
    for i in 1..n {
        let theta = std::f32::consts::PI * i as f32 / n as f32;
        for j in 0..2 * n {
            let phi = std::f32::consts::PI * j as f32 / n as f32;
            let v = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            p.push(v * rng.range(0.9, 1.1));
        }
    }
    p.push(-Vec3::Y);
    let ring = |i: u32, j: u32| 1 + (i - 1) * 2 * n + (j % (2 * n));
    let south = p.len() as u32 - 1;
    let mut f = Vec::new();
    for j in 0..2 * n {
        f.push([0, ring(1, j + 1), ring(1, j)]);
        f.push([south, ring(n - 1, j), ring(n - 1, j + 1)]);
    }
    for i in 1..n - 1 {
        for j in 0..2 * n {
            f.push([ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)]);
            f.push([ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)]);
        }
    }
    (p, f)
}

fn cube() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let p: Vec<Vec3> = (0..8)
        .map(|i| {
            Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32) * 2.0
                - Vec3::ONE
        })
        .collect();
    let q = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    (
        p,
        q.iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect(),
    )
}

/// Closed meshes leak no ray: rays from inside in random directions, and rays from inside and
/// outside aimed exactly at vertices and edge midpoints, all hit the mesh — at the origin and
/// with the mesh moved to (148376, 1234, −223423), through every accelerator.
#[test]
fn closed_meshes_are_watertight_near_and_far() {
    let mut rng = Rng::new(77);
    let meshes = [
        ("icosphere", icosphere(3)),
        ("cube", cube()),
        ("jittered uv sphere", jittered_uv_sphere(24, &mut rng)),
    ];
    let far = Vec3::new(148376.0, 1234.0, -223423.0);
    let (mut rays, mut misses) = (0usize, Vec::new());
    for (name, (p, f)) in &meshes {
        for offset in [Vec3::ZERO, far] {
            // At the far offset f32 spacing is 1.6 cm, so a 2 cm mesh would collapse.
            let scales: &[f32] = if offset == far {
                &[1.0, 50.0]
            } else {
                &[1.0, 1e-2, 50.0]
            };
            for &scale in scales {
                let pts: Vec<Vec3> = p.iter().map(|v| *v * scale + offset).collect();
                let prims = single_mesh(pts.clone(), f.clone());
                for kind in [AccelKind::None, AccelKind::Median] {
                    let accel = Accel::build(&prims, kind, 4);
                    let mut targets: Vec<Vec3> = pts.clone();
                    targets.extend(f.iter().flat_map(|t| {
                        [
                            (pts[t[0] as usize] + pts[t[1] as usize]) * 0.5,
                            (pts[t[1] as usize] + pts[t[2] as usize]) * 0.5,
                        ]
                    }));
                    let n_random = 2000 * stress();
                    for k in 0..targets.len() + n_random {
                        // Inside points: the centre, or a random point well inside.
                        let inside = offset + rng.dir() * scale * rng.range(0.0, 0.4);
                        let ray = if k < targets.len() {
                            Ray::new(inside, targets[k] - inside)
                        } else {
                            Ray::new(inside, rng.dir())
                        };
                        rays += 1;
                        if accel.closest(&prims, &ray, f32::INFINITY).is_none() {
                            misses
                                .push(format!("{name} x{scale} at {offset}: ray {ray:?} escaped"));
                        }
                        // From outside, through a vertex or an edge midpoint towards the inside
                        // point, so the ray enters the (convex) mesh exactly there.
                        if k < targets.len() {
                            let outside =
                                targets[k] + (targets[k] - inside).normalize() * scale * 3.0;
                            let ray = Ray::new(outside, targets[k] - outside);
                            rays += 1;
                            if accel.closest(&prims, &ray, f32::INFINITY).is_none() {
                                misses.push(format!(
                                    "{name} x{scale} at {offset}: ray {ray:?} slipped through"
                                ));
                            }
                        }
                    }
                }
            }
        }
    }
    println!("watertight: {rays} rays, {} misses", misses.len());
    assert!(rays >= 100_000);
    assert!(
        misses.is_empty(),
        "{} misses, e.g. {:?}",
        misses.len(),
        &misses[..misses.len().min(5)]
    );
}

/// Rays with NaN or infinite components neither panic nor hang; they report no hit. Zero
/// directions are handled the same way.
#[test]
fn nan_and_infinite_rays_report_no_hit() {
    let (p, f) = icosphere(2);
    let mut prims = single_mesh(p, f);
    prims.push(Primitive {
        shape: Shape::Sphere(Sphere::new(
            Vec3::new(3.0, 0.0, 0.0),
            1.0,
            Vec3::Y,
            Vec3::NEG_X,
        )),
        material: 0,
    });
    prims.push(Primitive {
        shape: Shape::Cylinder(Cylinder::new(Vec3::new(-3.0, 0.0, 0.0), Vec3::Y, 1.0, 1.0)),
        material: 0,
    });
    let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY];
    let mut rays = 0;
    for kind in [AccelKind::None, AccelKind::Median] {
        let accel = Accel::build(&prims, kind, 2);
        for &b in &bad {
            for axis in 0..3 {
                let mut o = Vec3::new(0.0, 0.0, -10.0);
                o[axis] = b;
                let mut d = Vec3::new(0.01, 0.02, 1.0);
                for (origin, dir) in [
                    (o, d),
                    (Vec3::new(0.0, 0.0, -10.0), {
                        d[axis] = b;
                        d
                    }),
                    (o, Vec3::ZERO),
                ] {
                    let ray = Ray::new(origin, dir);
                    rays += 1;
                    assert!(
                        accel.closest(&prims, &ray, f32::INFINITY).is_none(),
                        "{ray:?}"
                    );
                    assert!(!accel.any(&prims, &ray, f32::INFINITY, |_| true), "{ray:?}");
                }
            }
        }
        // A good ray with a NaN or negative-infinite t_max hits nothing either.
        let good = Ray::new(Vec3::new(0.0, 0.0, -10.0), Vec3::Z);
        assert!(accel.closest(&prims, &good, f32::INFINITY).is_some());
        for t_max in [f32::NAN, f32::NEG_INFINITY, -1.0] {
            rays += 1;
            assert!(
                accel.closest(&prims, &good, t_max).is_none(),
                "t_max {t_max}"
            );
            assert!(!accel.any(&prims, &good, t_max, |_| true), "t_max {t_max}");
        }
    }
    println!("non-finite rays: {rays}, none hit");
}

const GRAZING: &str = r#"{ "nbounces": 0,
  "camera": { "type": "pinhole", "width": 96, "height": 64, "fov": 40,
              "position": [0, -10, 3], "lookat": [0, 1, -0.25], "up": [0, 0, 1] },
  "scene": { "backgroundcolor": [0, 0, 0],
    "lightsources": [ { "type": "pointlight", "position": [-40, 30, 0.8], "is": [0, 0, 0], "id": [400000, 400000, 400000] } ],
    "shapes": [ { "type": "plane", "v0": [-50, -50, 0], "v1": [50, -50, 0], "v2": [50, 50, 0], "v3": [-50, 50, 0],
                  "material": { "kd": 1, "ks": 0, "specularexponent": 1, "diffusecolor": [1, 1, 1] } } ] } }"#;

/// A large plane lit at a grazing angle (the light 0.8 units above it, up to 90 units away, so
/// light arrives at down to half a degree) shows no shadow acne: every pixel that sees the plane
/// has the analytic irradiance `I·cosθ/(4πd²)` to within 0.1%; a self-shadowed pixel would be 0.
#[test]
fn grazing_light_shows_no_acne() {
    let scene = load_json(GRAZING);
    let film = render(&scene, &RenderOptions::default()).unwrap().film;
    let light = glam::DVec3::new(-40.0, 30.0, 0.8);
    let (mut checked, mut worst, mut min_cos) = (0, 0.0f64, 1.0f64);
    for y in 0..film.height {
        for x in 0..film.width {
            let ray = scene
                .camera
                .generate_ray(x, y, Vec2::splat(0.5), Vec2::ZERO);
            let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
            if d.z >= 0.0 {
                continue;
            }
            let p = o + d * (-o.z / d.z);
            if p.x.abs() > 50.0 || p.y.abs() > 50.0 {
                continue;
            }
            let to = light - p;
            let cos = to.z / to.length();
            let expected = 400000.0 * cos / (4.0 * std::f64::consts::PI * to.length_squared());
            let got = film.get(x, y).x as f64;
            worst = worst.max((got - expected).abs() / expected);
            min_cos = min_cos.min(cos);
            checked += 1;
        }
    }
    println!(
        "grazing plane: {checked} pixels, light down to {:.2}° above the surface, largest relative error {worst:.2e}",
        min_cos.asin().to_degrees()
    );
    assert!(checked > 4000);
    assert!(worst < 1e-3, "relative error {worst}");
}

/// The same scene scaled by 10^4 and moved 10^6 away (light power scaled by 10^8 to keep the
/// irradiance) gives the same image: mean absolute difference below 0.5% and no pixel off by more
/// than 0.05 away from silhouettes.
#[test]
fn scenes_render_the_same_at_any_scale_and_place() {
    let scene = |s: f32, o: Vec3| {
        let p = |v: [f32; 3]| {
            let q = Vec3::from(v) * s + o;
            format!("[{}, {}, {}]", q.x, q.y, q.z)
        };
        format!(
            r#"{{ "nbounces": 2,
              "camera": {{ "type": "pinhole", "width": 64, "height": 48, "fov": 45,
                          "position": {cam}, "lookat": [0, 1, -0.3], "up": [0, 0, 1] }},
              "scene": {{ "backgroundcolor": [0.1, 0.1, 0.1],
                "lightsources": [ {{ "type": "pointlight", "position": {light}, "is": [{i}, {i}, {i}], "id": [{i}, {i}, {i}] }} ],
                "shapes": [
                  {{ "type": "sphere", "center": {c}, "radius": {r}, "material": {{ "kd": 0.8, "ks": 0.3, "specularexponent": 20, "diffusecolor": [0.9, 0.3, 0.2], "kr": 0.2 }} }},
                  {{ "type": "cylinder", "center": {cy}, "axis": [0, 0, 1], "radius": {cr}, "height": {ch}, "material": {{ "kd": 0.8, "diffusecolor": [0.2, 0.4, 0.9] }} }},
                  {{ "type": "plane", "v0": {a}, "v1": {b}, "v2": {cc}, "v3": {d}, "material": {{ "kd": 0.8, "ks": 0.1, "specularexponent": 5, "diffusecolor": [0.9, 0.9, 0.9], "kr": 0.2 }} }} ] }} }}"#,
            cam = p([0.0, -6.0, 3.0]),
            light = p([2.0, -2.0, 4.0]),
            i = 400.0 * s * s,
            c = p([-0.8, 1.0, 0.8]),
            r = 0.8 * s,
            cy = p([1.2, 1.5, 0.6]),
            cr = 0.5 * s,
            ch = 0.6 * s,
            a = p([-4.0, -4.0, 0.0]),
            b = p([4.0, -4.0, 0.0]),
            cc = p([4.0, 4.0, 0.0]),
            d = p([-4.0, 4.0, 0.0]),
        )
    };
    let base = render_default(&scene(1.0, Vec3::ZERO));
    let moved = render_default(&scene(1e4, Vec3::new(1e6, -1e6, 1e6)));
    let mut sum = 0.0f64;
    let mut outliers = 0;
    for (a, b) in base.pixels.iter().zip(&moved.pixels) {
        let d = (*a - *b).abs().max_element();
        sum += d as f64;
        if d > 0.05 {
            outliers += 1;
        }
    }
    let mean = sum / base.pixels.len() as f64;
    println!("scale 10^4 at 10^6: mean abs difference {mean:.2e}, {outliers} pixels over 0.05");
    assert!(base.pixels.iter().any(|p| p.x > 0.3), "the scene is lit");
    assert!(mean < 0.005, "mean difference {mean}");
    assert!(outliers <= (base.pixels.len() / 100), "{outliers} outliers");
}

/// A closed mesh in front of a bright background lets none of it through: every pixel whose ray
/// passes through the mesh's inscribed sphere is a hit, near the origin and far from it.
#[test]
fn closed_mesh_lets_no_background_through() {
    let (p, f) = icosphere(3);
    for offset in [Vec3::ZERO, Vec3::new(148376.0, 1234.0, -223423.0)] {
        let verts: Vec<String> = p
            .iter()
            .map(|v| {
                let q = *v + offset;
                format!("[{}, {}, {}]", q.x, q.y, q.z)
            })
            .collect();
        let faces: Vec<String> = f
            .iter()
            .map(|t| format!("[{}, {}, {}]", t[0], t[1], t[2]))
            .collect();
        let cam = offset + Vec3::new(0.0, 0.0, 4.0);
        let json = format!(
            r#"{{ "nbounces": 0, "rendermode": "binary",
               "camera": {{ "type": "pinhole", "width": 96, "height": 96, "fov": 40,
                           "position": [{}, {}, {}], "lookAt": [{}, {}, {}], "upVector": [0, 1, 0] }},
               "scene": {{ "backgroundcolor": [1, 1, 1], "shapes": [ {{ "type": "trimesh", "vertices": [{}], "faces": [{}] }} ] }} }}"#,
            cam.x,
            cam.y,
            cam.z,
            offset.x,
            offset.y,
            offset.z,
            verts.join(","),
            faces.join(",")
        );
        let scene = load_json(&json);
        let film = render(&scene, &RenderOptions::default()).unwrap().film;
        // Inscribed radius of a level-3 icosphere: above 0.99 of the circumradius.
        let mut inside = 0;
        for y in 0..96 {
            for x in 0..96 {
                let ray = scene
                    .camera
                    .generate_ray(x, y, Vec2::splat(0.5), Vec2::ZERO);
                let to_c = offset - ray.origin;
                let miss_distance = (to_c - to_c.dot(ray.dir) * ray.dir).length();
                if miss_distance < 0.98 {
                    inside += 1;
                    assert_eq!(
                        film.get(x, y),
                        Vec3::X,
                        "background through pixel ({x},{y}) at {offset}"
                    );
                }
            }
        }
        assert!(inside > 1000);
    }
}

/// Rays that start inside glass: from the centre of a glass sphere every camera ray leaves at
/// normal incidence, so the wall behind shows through, dimmed by the Fresnel reflectance
/// ((η−1)/(η+1))² = 4%; from near the surface, looking along a chord where the incidence is 64°
/// (past the 41.8° critical angle of η = 1.5), light is totally reflected and the bright
/// background does not show.
#[test]
fn rays_from_inside_glass_refract_or_reflect_totally() {
    let scene = |camera: &str, eta: f32, nbounces: u32| {
        format!(
            r#"{{ "nbounces": {nbounces},
              "camera": {{ "type": "pinhole", "width": 9, "height": 9, "fov": 2, {camera} }},
              "scene": {{ "backgroundcolor": [1, 1, 1],
                "lightsources": [],
                "shapes": [ {{ "type": "sphere", "center": [0, 0.9, 0], "radius": 1,
                    "material": {{ "kd": 0, "ks": 0, "specularexponent": 1, "diffusecolor": [0, 0, 0], "kt": 1, "eta": {eta} }} }} ] }} }}"#
        )
    };
    let centre = r#""position": [0, 0.9, 0], "lookat": [1, 0, 0], "up": [0, 0, 1]"#;
    let chord = r#""position": [0, 0, 0], "lookat": [1, 0, 0], "up": [0, 0, 1]"#;
    // One bounce: the refracted ray reaches the background, the reflected one stops inside.
    let through = render_default(&scene(centre, 1.5, 1)).get(4, 4);
    let r0 = (0.5f32 / 2.5).powi(2);
    assert!(
        (through.x - (1.0 - r0)).abs() < 0.02,
        "seen through glass from inside: {through}"
    );
    let trapped = render_default(&scene(chord, 1.5, 6)).get(4, 4);
    assert!(
        trapped.max_element() < 0.05,
        "total internal reflection let {trapped} through"
    );
    let open = render_default(&scene(chord, 1.0, 6)).get(4, 4);
    assert!(
        open.min_element() > 0.99,
        "η = 1 must let the background through: {open}"
    );
}

/// Absurd but finite inputs never put NaN or infinity on the film: a light of 3·10^38 saturates
/// the pixels it lights.
#[test]
fn extreme_values_never_reach_the_film_as_nan_or_infinity() {
    let film = render_default(
        r#"{ "nbounces": 3,
          "camera": { "type": "pinhole", "width": 16, "height": 12, "fov": 40,
                      "position": [0, -4, 1], "lookat": [0, 1, -0.2], "up": [0, 0, 1] },
          "scene": { "backgroundcolor": [0, 0, 0],
            "lightsources": [ { "type": "pointlight", "position": [0, 0, 3], "is": [3e38, 3e38, 3e38], "id": [3e38, 3e38, 3e38] } ],
            "shapes": [ { "type": "sphere", "center": [0, 0, 0.5], "radius": 0.5,
                          "material": { "kd": 1, "ks": 1, "specularexponent": 1e30, "diffusecolor": [1, 1, 1], "kr": 1, "kt": 1, "eta": 1.5 } },
                        { "type": "plane", "v0": [-3, -3, 0], "v1": [3, -3, 0], "v2": [3, 3, 0], "v3": [-3, 3, 0],
                          "material": { "kd": 1, "diffusecolor": [1, 1, 1] } } ] } }"#,
    );
    assert!(film
        .pixels
        .iter()
        .all(|p| p.is_finite() && p.min_element() >= 0.0));
    let bytes = raytracer::film::to_rgb8(&film, raytracer::film::ToneMap::Linear, 1.0);
    assert!(bytes.iter().filter(|&&b| b == 255).count() > 100);
}
