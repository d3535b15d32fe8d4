//! The benchmarks behind `raytracer bench`: procedural scenes, the "Table 1" renders over every
//! accelerator, the ray-throughput sets, and the measurement of the `auto` crossover.
//!
//! Everything here is deterministic except the timings: scenes and rays are pure functions of
//! their parameters (random numbers come from [`crate::sampling`]'s hashes).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rayon::prelude::*;

pub mod kinds;

use crate::accel::{Accel, AccelKind, Isa};
use crate::camera::{Camera, Handedness};
use crate::files::shown;
use crate::geometry::{Mesh, MeshUv, Primitive, Primitives, Shape, Sphere, Triangle};
use crate::integrator::{Integrator, Kind};
use crate::light::{Intensity, Light};
use crate::material::Material;
use crate::math::{orthonormal_basis, Vec2, Vec3};
use crate::ray::Ray;
use crate::render::{render_with_accel, RenderOptions};
use crate::sampling::{hash, to_unit, uniform_sphere, Method, SampleKey};
use crate::scene::{load, LoadOptions, RenderMode, Scene, Variant};

/// Number of triangles of [`sphere_grid`]: `2·S²` per sphere (pole quads give degenerate
/// triangles, still counted) plus the two of the ground quad.
pub fn sphere_grid_triangles(g: u32, s: u32) -> usize {
    (g as usize).pow(2) * 2 * (s as usize).pow(2) + 2
}

/// The ray-throughput scene, specified so that other tracers can build the same one: a `G×G` grid
/// of UV spheres, sphere `(i, j)` centred at `(i − G/2 + 0.5, 0.45, j − G/2 + 0.5)` with radius
/// 0.45, each made of `S×S` latitude/longitude quads (θ from 0 to π, φ from 0 to 2π, point
/// `c + r·(sin θ cos φ, cos θ, sin θ sin φ)`) split into two triangles, on a ground quad `y = 0`
/// spanning `x, z ∈ [−G, G]`. Camera at `(0, 0.6G, −1.1G)` looking at the origin, up `+y`, 60°
/// horizontal field of view, `width × height` pixels. A point light at `(0, 2G, 0)`.
pub fn sphere_grid(g: u32, s: u32, width: u32, height: u32) -> Scene {
    let gf = g as f32;
    let ground = Mesh {
        positions: vec![
            Vec3::new(-gf, 0.0, -gf),
            Vec3::new(gf, 0.0, -gf),
            Vec3::new(gf, 0.0, gf),
            Vec3::new(-gf, 0.0, gf),
        ],
        normals: None,
        uv: MeshUv::PerVertex(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ]),
        faces: vec![[0, 1, 2], [0, 2, 3]],
    };
    let ring = s as usize + 1;
    let per_sphere = ring * ring;
    let spheres = (g as usize).pow(2);
    let mut positions = Vec::with_capacity(spheres * per_sphere);
    let mut normals = Vec::with_capacity(spheres * per_sphere);
    let mut uvs = Vec::with_capacity(spheres * per_sphere);
    let mut faces = Vec::with_capacity(spheres * 2 * (s as usize).pow(2));
    let half = g as f64 / 2.0;
    for i in 0..g {
        for j in 0..g {
            let c = Vec3::new(
                (i as f64 - half + 0.5) as f32,
                0.45,
                (j as f64 - half + 0.5) as f32,
            );
            let base = positions.len() as u32;
            for a in 0..=s {
                let theta = std::f64::consts::PI * a as f64 / s as f64;
                for b in 0..=s {
                    let phi = std::f64::consts::TAU * b as f64 / s as f64;
                    let n = Vec3::new(
                        (theta.sin() * phi.cos()) as f32,
                        theta.cos() as f32,
                        (theta.sin() * phi.sin()) as f32,
                    );
                    positions.push(c + 0.45 * n);
                    normals.push(n);
                    uvs.push(Vec2::new(b as f32 / s as f32, a as f32 / s as f32));
                }
            }
            let r = ring as u32;
            for a in 0..s {
                for b in 0..s {
                    let v00 = base + a * r + b;
                    let (v10, v11, v01) = (v00 + r, v00 + r + 1, v00 + 1);
                    faces.push([v00, v10, v11]);
                    faces.push([v00, v11, v01]);
                }
            }
        }
    }
    let balls = Mesh {
        positions,
        normals: Some(normals),
        uv: MeshUv::PerVertex(uvs),
        faces,
    };
    let mut primitives = Primitives::default();
    primitives.push_mesh(ground, 0);
    primitives.push_mesh(balls, 0);
    let eye = Vec3::new(0.0, 0.6 * gf, -1.1 * gf);
    let fov_y = 2.0 * ((30.0f32).to_radians().tan() * height as f32 / width as f32).atan();
    let camera = Camera::new(
        eye,
        -eye,
        Vec3::Y,
        Handedness::ForwardCrossUp,
        width,
        height,
        fov_y.to_degrees(),
        None,
    )
    .expect("the grid camera's direction is not parallel to +y");
    let light = grid_light(g);
    Scene {
        variant: Variant::V2021,
        camera,
        nbounces: 1,
        background: Vec3::splat(0.05),
        mode: RenderMode::Phong,
        exposure: 1.0,
        ambient: Vec3::ZERO,
        reflection: crate::material::Reflection::Added,
        pixel_samples: None,
        pixel_method: None,
        tone_map: None,
        light_samples: None,
        lights: vec![Light::Point {
            position: light,
            intensity: Intensity {
                diffuse: Vec3::splat(light.length_squared()),
                specular: Vec3::splat(light.length_squared()),
                falloff: crate::light::Falloff::InverseSquare { scale: 1.0 },
            },
        }],
        primitives,
        materials: vec![Material::default()],
        textures: Vec::new(),
        has_transmissive: false,
        warnings: Vec::new(),
        inputs: Vec::new(),
    }
}

/// The light position of the grid scene: `(0, 2G, 0)`.
pub fn grid_light(g: u32) -> Vec3 {
    Vec3::new(0.0, 2.0 * g as f32, 0.0)
}

/// Bytes of the primitive records (and of the runs standing in for large meshes' records).
pub fn primitive_bytes(scene: &Scene) -> usize {
    scene.primitives.record_bytes()
}

/// Number of triangle primitives.
pub fn triangle_count(scene: &Scene) -> usize {
    scene
        .primitives
        .iter()
        .filter(|p| matches!(p.shape, Shape::Triangle(_)))
        .count()
}

/// Median of durations (the upper one of the middle two for an even count).
pub fn median(mut d: Vec<Duration>) -> Duration {
    d.sort();
    d.get(d.len() / 2).copied().unwrap_or_default()
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Times `f` `runs` times (at least once); the median and the last result.
fn timed<T>(runs: usize, mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        let out = f();
        times.push(start.elapsed());
        last = Some(out);
    }
    (median(times), last.expect("ran at least once"))
}

// ---------------------------------------------------------------------------------------------
// Table 1

/// Light setup of a Table 1 row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LightVariant {
    /// Every light a point light (a quad becomes a point at its centre).
    Point,
    /// Every light a 16-sample jittered quad (a point becomes a square around it).
    Area,
}

impl LightVariant {
    pub fn name(self) -> &'static str {
        match self {
            LightVariant::Point => "point",
            LightVariant::Area => "area",
        }
    }
}

/// Shadow rays per shading point of an area light in the `area` variant.
pub const AREA_SAMPLES: u32 = 16;

/// `scene` with its lights replaced according to `variant`. An area light made from a point light
/// is a square facing the scene's centre, its side 5% of the scene's diagonal.
pub fn with_lights(scene: &Scene, variant: LightVariant) -> Scene {
    let bounds = scene
        .primitives
        .iter()
        .filter(|p| p.shape.is_bounded())
        .fold(crate::accel::aabb::Aabb::EMPTY, |b, p| {
            b.union(p.shape.bounds())
        });
    let (centre, diagonal) = if bounds == crate::accel::aabb::Aabb::EMPTY {
        (Vec3::ZERO, 1.0)
    } else {
        (bounds.center(), bounds.extent().length())
    };
    let lights = scene
        .lights
        .iter()
        .map(|l| match (variant, l) {
            (LightVariant::Point, Light::Point { .. }) => l.clone(),
            (
                LightVariant::Point,
                Light::Quad {
                    origin,
                    edge_u,
                    edge_v,
                    intensity,
                    ..
                },
            ) => Light::Point {
                position: *origin + 0.5 * (*edge_u + *edge_v),
                intensity: *intensity,
            },
            (
                LightVariant::Area,
                Light::Quad {
                    origin,
                    edge_u,
                    edge_v,
                    intensity,
                    ..
                },
            ) => Light::quad(
                *origin,
                *edge_u,
                *edge_v,
                *intensity,
                AREA_SAMPLES,
                Method::Jittered,
            ),
            (
                LightVariant::Area,
                Light::Point {
                    position,
                    intensity,
                },
            ) => {
                let facing = (centre - *position).normalize_or(Vec3::Y);
                let (u, v) = orthonormal_basis(facing);
                let side = 0.05 * diagonal;
                Light::quad(
                    *position - 0.5 * side * (u + v),
                    side * u,
                    side * v,
                    *intensity,
                    AREA_SAMPLES,
                    Method::Jittered,
                )
            }
            (LightVariant::Point, Light::Sphere { .. } | Light::Triangles { .. }) => Light::Point {
                position: l.center(),
                intensity: *l.intensity(),
            },
            (LightVariant::Area, Light::Sphere { .. } | Light::Triangles { .. }) => {
                let mut l = l.clone();
                if let Light::Sphere {
                    samples, method, ..
                }
                | Light::Triangles {
                    samples, method, ..
                } = &mut l
                {
                    (*samples, *method) = (AREA_SAMPLES, Method::Jittered);
                }
                l
            }
        })
        .collect();
    Scene {
        lights,
        ..scene.clone()
    }
}

/// A Table 1 scene: a bundled scene file or a sphere grid.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TableScene {
    File(&'static str),
    Grid { g: u32, s: u32 },
}

impl TableScene {
    pub fn name(&self) -> String {
        match self {
            TableScene::File(f) => f.trim_end_matches(".json").to_string(),
            TableScene::Grid { g, s } => format!("grid-{g}x{s}"),
        }
    }
}

/// The six scenes of Table 1, from a few objects to over a million triangles (`quick`: small
/// grids, for a smoke run).
pub fn table_scenes(quick: bool) -> Vec<TableScene> {
    let grids: [(u32, u32); 4] = if quick {
        [(1, 4), (2, 4), (2, 8), (4, 8)]
    } else {
        [(4, 16), (8, 32), (16, 32), (24, 32)]
    };
    let mut v = vec![
        TableScene::File("example.json"),
        TableScene::File("demo.json"),
    ];
    v.extend(grids.iter().map(|&(g, s)| TableScene::Grid { g, s }));
    v
}

#[derive(Debug, Clone)]
pub struct TableOptions {
    /// Small scenes and images, one run: a smoke test.
    pub quick: bool,
    /// Renders per row (the median is reported).
    pub runs: usize,
    /// Folder of the bundled scenes.
    pub scenes_dir: PathBuf,
    pub leaf_size: usize,
    /// Rows with `none` or `flat` whose renders are estimated to take longer than this are
    /// skipped.
    pub none_limit: Duration,
    /// How long to trace sample pixels for that estimate.
    pub estimate_budget: Duration,
}

/// One row of Table 1.
#[derive(Debug, Clone)]
pub struct Row {
    pub scene: String,
    pub primitives: usize,
    pub triangles: usize,
    pub width: u32,
    pub height: u32,
    pub light: LightVariant,
    pub accel: AccelKind,
    /// What `accel` built: `list`, `flat`, `median` or `sah`.
    pub built: &'static str,
    pub build: Duration,
    /// `None` when skipped.
    pub render: Option<Duration>,
    /// Estimated time of the skipped renders.
    pub estimate: Option<Duration>,
    pub rays: u64,
    /// Accelerator plus primitive records.
    pub memory: usize,
}

impl Row {
    pub fn mrays(&self) -> Option<f64> {
        self.render
            .map(|r| self.rays as f64 / r.as_secs_f64().max(1e-9) / 1e6)
    }

    pub fn bytes_per_triangle(&self) -> Option<f64> {
        (self.triangles > 0).then(|| self.memory as f64 / self.triangles as f64)
    }
}

fn built_name(accel: &Accel) -> &'static str {
    match accel {
        Accel::List => "list",
        Accel::Bvh(_) => "bvh",
        Accel::Bvh4(_) => "bvh4",
        Accel::Bvh8(_) => "bvh8",
    }
}

/// Loads or generates a Table 1 scene.
pub fn table_scene(which: &TableScene, options: &TableOptions) -> Result<Scene, String> {
    let (w, h) = if options.quick { (64, 48) } else { (640, 480) };
    match which {
        TableScene::Grid { g, s } => Ok(sphere_grid(*g, *s, w, h)),
        TableScene::File(f) => {
            let path = options.scenes_dir.join(f);
            let load_options = LoadOptions {
                width: options.quick.then_some(w),
                ..LoadOptions::default()
            };
            load(&path, &load_options).map_err(|e| format!("{}: {e}", shown(&path)))
        }
    }
}

/// Runs Table 1: every scene, light variant and accelerator. `report` sees each row as it is
/// done.
pub fn table1(options: &TableOptions, mut report: impl FnMut(&Row)) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    for which in table_scenes(options.quick) {
        let base = table_scene(&which, options)?;
        for variant in [LightVariant::Point, LightVariant::Area] {
            let scene = with_lights(&base, variant);
            for kind in AccelKind::ALL {
                let row = table_row(&which.name(), &scene, variant, kind, options);
                report(&row);
                rows.push(row);
            }
        }
    }
    Ok(rows)
}

fn table_row(
    name: &str,
    scene: &Scene,
    light: LightVariant,
    kind: AccelKind,
    options: &TableOptions,
) -> Row {
    let (build, accel) = timed(options.runs, || {
        Accel::build(&scene.primitives, kind, options.leaf_size)
    });
    let built = match (&accel, kind.resolved()) {
        (Accel::Bvh(_), AccelKind::Median) => "median",
        (Accel::Bvh(_), AccelKind::Flat) => "flat",
        (Accel::Bvh(_), _) => "sah",
        (Accel::Bvh4(_), _) => "sah4",
        (Accel::Bvh8(_), _) => "sah8",
        (a, _) => built_name(a),
    };
    let render_options = RenderOptions {
        accel: kind,
        leaf_size: options.leaf_size,
        ..RenderOptions::default()
    };
    let mut row = Row {
        scene: name.to_string(),
        primitives: scene.primitives.len(),
        triangles: triangle_count(scene),
        width: scene.camera.width,
        height: scene.camera.height,
        light,
        accel: kind,
        built,
        build,
        render: None,
        estimate: None,
        rays: 0,
        memory: accel.memory_bytes() + primitive_bytes(scene),
    };
    // Without a tree, every ray tests every primitive: large scenes are estimated first.
    let treeless = matches!(accel, Accel::List) || built == "flat";
    if treeless && scene.primitives.len() > 64 {
        let estimate = estimate_render(scene, &accel, &render_options, options.estimate_budget)
            * options.runs as u32;
        if estimate > options.none_limit {
            row.estimate = Some(estimate);
            return row;
        }
    }
    let (render, out) = timed(options.runs, || {
        render_with_accel(scene, &accel, &render_options)
            .expect("the pixel buffers of a loaded scene fit in memory")
    });
    row.render = Some(render);
    row.rays = out.counts.total();
    row
}

/// Estimated time of one full render, from camera samples at pixels spread over the image, traced
/// for about `budget` on this thread and scaled to the image and the pool's threads.
pub fn estimate_render(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
    budget: Duration,
) -> Duration {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let pixels = w as u64 * h as u64;
    if pixels == 0 {
        return Duration::ZERO;
    }
    let integrator = Integrator::new(scene, accel, Kind::chosen(options.integrator, scene));
    let mut tracer =
        integrator.tracer(options.max_depth, options.trace, options.pixel_method, None);
    let start = Instant::now();
    let mut traced = 0u64;
    // A stride coprime with the pixel count visits pixels spread over the whole image.
    let stride = (0..)
        .map(|k| 7919 + 2 * k)
        .find(|s| gcd(*s, pixels) == 1)
        .unwrap_or(1);
    while traced < pixels && (traced < 4 || start.elapsed() < budget) {
        let i = (traced * stride) % pixels;
        let (x, y) = ((i % w as u64) as u32, (i / w as u64) as u32);
        let key = SampleKey::new(x, y, 0, 1, options.seed);
        let lens = key.camera_pattern(options.pixel_method).1;
        let ray = scene.camera.generate_ray(x, y, Vec2::splat(0.5), lens);
        std::hint::black_box(tracer.trace_camera(&ray, &key));
        traced += 1;
    }
    let per_pixel = start.elapsed().as_secs_f64() / traced as f64;
    let threads = rayon::current_num_threads().max(1) as f64;
    Duration::from_secs_f64(per_pixel * pixels as f64 * options.spp as f64 / threads)
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

pub const TABLE_HEADER: [&str; 14] = [
    "scene",
    "prims",
    "tris",
    "size",
    "light",
    "accel",
    "built",
    "build_ms",
    "render_ms",
    "rays",
    "mrays_s",
    "memory_bytes",
    "bytes_per_tri",
    "note",
];

/// A row's fields, in [`TABLE_HEADER`] order.
pub fn row_fields(r: &Row) -> [String; 14] {
    let opt = |v: Option<f64>, digits: usize| v.map_or(String::new(), |v| format!("{v:.digits$}"));
    [
        r.scene.clone(),
        r.primitives.to_string(),
        r.triangles.to_string(),
        format!("{}x{}", r.width, r.height),
        r.light.name().to_string(),
        r.accel.name().to_string(),
        r.built.to_string(),
        format!("{:.2}", ms(r.build)),
        opt(r.render.map(ms), 1),
        if r.render.is_some() {
            r.rays.to_string()
        } else {
            String::new()
        },
        opt(r.mrays(), 2),
        r.memory.to_string(),
        opt(r.bytes_per_triangle(), 1),
        r.estimate.map_or(String::new(), |e| {
            format!("skipped (est. {:.0} s)", e.as_secs_f64())
        }),
    ]
}

/// Fixed-width text table.
pub fn format_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in rows {
        for (w, f) in widths.iter_mut().zip(r) {
            *w = (*w).max(f.chars().count());
        }
    }
    let line = |fields: Vec<String>| {
        let cells: Vec<String> = fields
            .iter()
            .zip(&widths)
            .map(|(f, w)| format!("{f:>w$}"))
            .collect();
        cells.join("  ").trim_end().to_string() + "\n"
    };
    let mut out = line(header.iter().map(|h| h.to_string()).collect());
    for r in rows {
        out += &line(r.clone());
    }
    out
}

/// CSV with a header line (no field here contains a comma or a quote).
pub fn format_csv(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut out = header.join(",") + "\n";
    for r in rows {
        out += &(r.join(",") + "\n");
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Ray throughput

/// The three ray sets of the throughput benchmark.
#[derive(Debug, Clone, Default)]
pub struct RaySets {
    /// One ray through each pixel centre (closest hit).
    pub primary: Vec<Ray>,
    /// From each primary hit towards the light, with the distance to it (any hit).
    pub shadow: Vec<(Ray, f32)>,
    /// From each primary hit in a uniformly random direction (closest hit).
    pub incoherent: Vec<Ray>,
}

/// The ray sets for `scene` (a [`sphere_grid`]) with the light at `light`. Secondary rays start
/// from each primary hit's robustly offset origin ([`crate::ray::Hit::spawn`]); the random
/// directions hash `(pixel, seed)`.
pub fn ray_sets(scene: &Scene, accel: &Accel, light: Vec3, seed: u64) -> RaySets {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut sets = RaySets::default();
    for y in 0..h {
        for x in 0..w {
            let ray = scene
                .camera
                .generate_ray(x, y, Vec2::splat(0.5), Vec2::splat(0.5));
            sets.primary.push(ray);
            let Some((p, c)) = accel.closest(&scene.primitives, &ray, f32::INFINITY) else {
                continue;
            };
            let prims = &scene.primitives;
            let hit = prims.get(p).hit(&ray, c, p, prims.meshes());
            sets.shadow.push(hit.spawn_to(light));
            let key = SampleKey::new(x, y, 0, 1, seed);
            sets.incoherent
                .push(hit.spawn(uniform_sphere(key.uniform2(0))));
        }
    }
    sets
}

/// Writes grid `(g, s)`'s triangles (`scene`) and its three ray sets to `dir` as raw
/// little-endian `f32` files. `grid_G{g}_S{s}.tris.f32`: 9 numbers per triangle (its corners);
/// `.primary.f32` and `.incoherent.f32`: 6 per ray (origin, direction); `.shadow.f32`: 7 per ray
/// (origin, direction, and the distance to the light, which bounds the any-hit query).
fn export_grid(
    dir: &Path,
    (g, s): (u32, u32),
    scene: &Scene,
    sets: &RaySets,
) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", shown(dir)))?;
    let ray = |r: &Ray| [r.origin.to_array(), r.dir.to_array()].concat();
    let tables: [(&str, Vec<f32>); 4] = [
        (
            "tris",
            scene
                .primitives
                .iter()
                .filter_map(|p| match &p.shape {
                    Shape::Triangle(t) => Some(t.p.map(|v| v.to_array()).concat()),
                    _ => None,
                })
                .flatten()
                .collect(),
        ),
        ("primary", sets.primary.iter().flat_map(ray).collect()),
        (
            "shadow",
            sets.shadow
                .iter()
                .flat_map(|(r, t)| [ray(r), vec![*t]].concat())
                .collect(),
        ),
        ("incoherent", sets.incoherent.iter().flat_map(ray).collect()),
    ];
    for (what, numbers) in tables {
        let bytes: Vec<u8> = numbers.iter().flat_map(|x| x.to_le_bytes()).collect();
        let path = dir.join(format!("grid_G{g}_S{s}.{what}.f32"));
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", shown(&path)))?;
    }
    Ok(())
}

/// Which query a ray set uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RayKind {
    Primary,
    Shadow,
    Incoherent,
}

impl RayKind {
    pub const ALL: [RayKind; 3] = [RayKind::Primary, RayKind::Shadow, RayKind::Incoherent];

    pub fn name(self) -> &'static str {
        match self {
            RayKind::Primary => "primary",
            RayKind::Shadow => "shadow",
            RayKind::Incoherent => "incoherent",
        }
    }
}

/// Traces a ray set; the number of hits (occluded rays for shadows).
pub fn trace_set(
    scene: &Scene,
    accel: &Accel,
    sets: &RaySets,
    kind: RayKind,
    parallel: bool,
) -> u64 {
    let prims = &scene.primitives;
    let closest = |rays: &[Ray]| {
        rays.iter()
            .filter(|r| accel.closest(prims, r, f32::INFINITY).is_some())
            .count() as u64
    };
    let any = |rays: &[(Ray, f32)]| {
        rays.iter()
            .filter(|(r, t)| accel.any(prims, r, *t, |_| true))
            .count() as u64
    };
    const CHUNK: usize = 1024;
    match (kind, parallel) {
        (RayKind::Primary, false) => closest(&sets.primary),
        (RayKind::Incoherent, false) => closest(&sets.incoherent),
        (RayKind::Shadow, false) => any(&sets.shadow),
        (RayKind::Primary, true) => sets.primary.par_chunks(CHUNK).map(closest).sum(),
        (RayKind::Incoherent, true) => sets.incoherent.par_chunks(CHUNK).map(closest).sum(),
        (RayKind::Shadow, true) => sets.shadow.par_chunks(CHUNK).map(any).sum(),
    }
}

impl RaySets {
    pub fn len(&self, kind: RayKind) -> usize {
        match kind {
            RayKind::Primary => self.primary.len(),
            RayKind::Shadow => self.shadow.len(),
            RayKind::Incoherent => self.incoherent.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.primary.is_empty()
    }
}

/// Throughput of one ray set.
#[derive(Debug, Clone)]
pub struct SetResult {
    pub kind: RayKind,
    pub rays: usize,
    pub hits: u64,
    pub single: Duration,
    pub parallel: Duration,
}

impl SetResult {
    pub fn mrays(&self, d: Duration) -> f64 {
        self.rays as f64 / d.as_secs_f64().max(1e-9) / 1e6
    }
}

/// Results of the throughput benchmark on one grid with one accelerator.
#[derive(Debug, Clone)]
pub struct TreeThroughput {
    pub kind: AccelKind,
    /// What its queries ran with.
    pub isa: Isa,
    pub build: Duration,
    pub accel_bytes: usize,
    /// Of `accel_bytes`, the leaves' blocks.
    pub leaf_bytes: usize,
    pub nodes: usize,
    pub depth: usize,
    pub sets: Vec<SetResult>,
    /// Whitted render of the grid with the area light: one thread, then the pool's threads.
    pub render_single: Duration,
    pub render_parallel: Duration,
    pub render_rays: u64,
}

/// Results of the throughput benchmark on one grid.
#[derive(Debug, Clone)]
pub struct Throughput {
    pub g: u32,
    pub s: u32,
    pub triangles: usize,
    pub build_median_split: Duration,
    pub primitive_bytes: usize,
    /// Bytes of the meshes' vertex and face buffers, which every representation keeps.
    pub mesh_bytes: usize,
    /// One entry per tree of [`THROUGHPUT_TREES`].
    pub trees: Vec<TreeThroughput>,
}

/// The trees `raytracer bench --rays` measures: the binary SAH tree and its four- and eight-wide
/// collapses.
pub const THROUGHPUT_TREES: [AccelKind; 3] = [AccelKind::Sah, AccelKind::Sah4, AccelKind::Sah8];

/// Runs the throughput benchmark on the `g×g`, `s×s` grid: for each tree of
/// [`THROUGHPUT_TREES`] (and once more with the baseline's instructions, for a tree whose queries
/// use more: [`Isa`]), its build (median of `runs`, or one build if `runs` is 0), each ray set
/// on one thread and on the current pool (medians of `runs`), and a full render on one thread
/// and on the pool; and the median-split build's time. Every tree traces the same rays. With
/// `export`, the grid's triangles and ray sets are first written to that folder (see
/// `export_grid`), for other tracers to trace.
pub fn throughput(
    g: u32,
    s: u32,
    runs: usize,
    leaf_size: usize,
    export: Option<&Path>,
) -> Result<Throughput, String> {
    let scene = sphere_grid(g, s, 640, 480);
    let (build_median_split, _) = timed(runs, || {
        Accel::build(&scene.primitives, AccelKind::Median, leaf_size)
    });
    let mut sets = None;
    let mut trees = Vec::new();
    for kind in THROUGHPUT_TREES {
        let (build, accel) = timed(runs, || Accel::build(&scene.primitives, kind, leaf_size));
        let sets = sets.get_or_insert_with(|| ray_sets(&scene, &accel, grid_light(g), 0));
        if let (Some(dir), None) = (export, trees.first()) {
            export_grid(dir, (g, s), &scene, sets)?;
        }
        trees.push(tree_throughput(&scene, kind, build, &accel, sets, runs));
        if accel.isa() != Isa::BASELINE {
            // The same tree again with the baseline's instructions, for the ratio in one run.
            let baseline = accel.with_isa(Isa::BASELINE);
            trees.push(tree_throughput(&scene, kind, build, &baseline, sets, runs));
        }
    }
    Ok(Throughput {
        g,
        s,
        triangles: triangle_count(&scene),
        build_median_split,
        primitive_bytes: primitive_bytes(&scene),
        mesh_bytes: scene.primitives.mesh_bytes(),
        trees,
    })
}

/// The ray sets and renders of [`throughput`] with one built tree.
fn tree_throughput(
    scene: &Scene,
    kind: AccelKind,
    build: Duration,
    accel: &Accel,
    sets: &RaySets,
    runs: usize,
) -> TreeThroughput {
    let mut results = Vec::new();
    for ray_kind in RayKind::ALL {
        let (single, hits) = timed(runs, || trace_set(scene, accel, sets, ray_kind, false));
        let (parallel, _) = timed(runs, || trace_set(scene, accel, sets, ray_kind, true));
        results.push(SetResult {
            kind: ray_kind,
            rays: sets.len(ray_kind),
            hits,
            single,
            parallel,
        });
    }
    let area = with_lights(scene, LightVariant::Area);
    let options = RenderOptions {
        accel: kind,
        ..RenderOptions::default()
    };
    let render = || {
        render_with_accel(&area, accel, &options)
            .expect("the pixel buffers of a loaded scene fit in memory")
    };
    let (render_single, out) = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
        Ok(pool) => timed(runs, || pool.install(render)),
        Err(_) => timed(runs, render),
    };
    let (render_parallel, _) = timed(runs, render);
    let stats = accel.stats().unwrap_or_default();
    TreeThroughput {
        kind,
        isa: accel.isa(),
        build,
        accel_bytes: accel.memory_bytes(),
        leaf_bytes: accel.leaf_bytes(),
        nodes: stats.nodes,
        depth: stats.depth,
        sets: results,
        render_single,
        render_parallel,
        render_rays: out.counts.total(),
    }
}

// ---------------------------------------------------------------------------------------------
// The `auto` crossover

/// `n` primitives (alternately spheres and triangles) at hashed random places in the cube
/// `[-1, 1]³`, seen from `(0, 0, -4)`, lit by one point light. With `backdrop`, the first two
/// primitives are instead the halves of a quad behind the cube that fills the view, so that every
/// camera ray hits something.
pub fn random_scene(n: usize, width: u32, height: u32, backdrop: bool) -> Scene {
    let u = |i: usize, d: u64| to_unit(hash(&[i as u64, d, 0x5eed]));
    let v = |i: usize, d: u64| 2.0 * Vec3::new(u(i, d), u(i, d + 1), u(i, d + 2)) - Vec3::ONE;
    let mut meshes = Vec::new();
    let mut primitives = Vec::new();
    let quad = [
        Vec3::new(-4.0, -4.0, 2.0),
        Vec3::new(4.0, -4.0, 2.0),
        Vec3::new(4.0, 4.0, 2.0),
        Vec3::new(-4.0, 4.0, 2.0),
    ];
    for i in 0..n {
        let c = v(i, 0);
        let shape = if backdrop && i < 2 {
            let p = if i == 0 {
                [quad[0], quad[1], quad[2]]
            } else {
                [quad[0], quad[2], quad[3]]
            };
            meshes.push(Mesh {
                positions: p.to_vec(),
                normals: None,
                uv: MeshUv::Strip,
                faces: vec![[0, 1, 2]],
            });
            Shape::Triangle(Triangle {
                p,
                mesh: meshes.len() as u32 - 1,
                face: 0,
            })
        } else if i % 2 == 0 {
            Shape::Sphere(Sphere::new(c, 0.05 + 0.2 * u(i, 3), Vec3::Y, Vec3::X))
        } else {
            let p = [c, c + 0.4 * v(i, 4), c + 0.4 * v(i, 7)];
            meshes.push(Mesh {
                positions: p.to_vec(),
                normals: None,
                uv: MeshUv::Strip,
                faces: vec![[0, 1, 2]],
            });
            Shape::Triangle(Triangle {
                p,
                mesh: meshes.len() as u32 - 1,
                face: 0,
            })
        };
        primitives.push(Primitive { shape, material: 0 });
    }
    let eye = Vec3::new(0.0, 0.0, -4.0);
    let camera = Camera::new(
        eye,
        -eye,
        Vec3::Y,
        Handedness::ForwardCrossUp,
        width,
        height,
        35.0,
        None,
    )
    .expect("valid camera");
    Scene {
        variant: Variant::V2021,
        camera,
        nbounces: 1,
        background: Vec3::ZERO,
        mode: RenderMode::Phong,
        exposure: 1.0,
        ambient: Vec3::ZERO,
        reflection: crate::material::Reflection::Added,
        pixel_samples: None,
        pixel_method: None,
        tone_map: None,
        light_samples: None,
        lights: vec![Light::Point {
            position: Vec3::new(2.0, 3.0, -3.0),
            intensity: Intensity {
                diffuse: Vec3::splat(20.0),
                specular: Vec3::splat(20.0),
                falloff: crate::light::Falloff::InverseSquare { scale: 1.0 },
            },
        }],
        primitives: Primitives::from_records(primitives, meshes),
        materials: vec![Material::default()],
        textures: Vec::new(),
        has_transmissive: false,
        warnings: Vec::new(),
        inputs: Vec::new(),
    }
}

/// Query times of `random_scene(n, backdrop)` with `none`, `flat`, `sah` and `sah4` (the tree
/// `auto` builds), for each `n`: the
/// three ray sets of [`ray_sets`] (camera rays at 320×240, shadow rays to the light, random
/// secondary rays) traced on this thread, medians of `runs`. Timing the queries alone, not whole
/// renders, keeps shading and ray generation, which the accelerators share, out of the
/// comparison.
pub fn crossover(
    sizes: &[usize],
    backdrop: bool,
    runs: usize,
    leaf_size: usize,
) -> Vec<(usize, [Duration; 4])> {
    sizes
        .iter()
        .map(|&n| {
            let scene = random_scene(n, 320, 240, backdrop);
            let light = match scene.lights.first() {
                Some(Light::Point { position, .. }) => *position,
                _ => Vec3::Y,
            };
            let sah = Accel::build(&scene.primitives, AccelKind::Sah, leaf_size);
            let sets = ray_sets(&scene, &sah, light, 0);
            let time = |accel: &Accel| {
                timed(runs, || {
                    RayKind::ALL
                        .iter()
                        .map(|&k| trace_set(&scene, accel, &sets, k, false))
                        .sum::<u64>()
                })
                .0
            };
            let flat = Accel::build(&scene.primitives, AccelKind::Flat, leaf_size);
            let sah4 = Accel::build(&scene.primitives, AccelKind::Sah4, leaf_size);
            (
                n,
                [time(&Accel::List), time(&flat), time(&sah), time(&sah4)],
            )
        })
        .collect()
}

/// The default folder of the bundled scenes: `scenes/` in the working directory if it has the
/// Table 1 files, else the one in the source tree this binary was built from.
pub fn default_scenes_dir() -> PathBuf {
    let here = Path::new("scenes");
    if here.join("example.json").is_file() {
        here.to_path_buf()
    } else {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_triangle_counts_are_as_specified() {
        assert_eq!(sphere_grid_triangles(4, 16), 8_194);
        assert_eq!(sphere_grid_triangles(16, 32), 524_290);
        assert_eq!(sphere_grid_triangles(32, 64), 8_388_610);
        let scene = sphere_grid(4, 16, 8, 6);
        assert_eq!(scene.primitives.len(), 8_194);
        assert_eq!(triangle_count(&scene), 8_194);
    }

    #[test]
    fn grid_vertices_lie_on_their_spheres() {
        let scene = sphere_grid(2, 8, 8, 6);
        for p in scene.primitives.iter().skip(2) {
            let Shape::Triangle(t) = &p.shape else {
                panic!("only triangles");
            };
            let c = Vec3::new(
                (t.p[0].x + 1.0).floor() - 0.5,
                0.45,
                (t.p[0].z + 1.0).floor() - 0.5,
            );
            for v in t.p {
                assert!(((v - c).length() - 0.45).abs() < 1e-5, "{v} {c}");
            }
        }
    }

    #[test]
    fn most_primary_rays_hit_and_sets_match() {
        let scene = sphere_grid(4, 8, 32, 24);
        let accel = Accel::build(&scene.primitives, AccelKind::Sah, 4);
        let sets = ray_sets(&scene, &accel, grid_light(4), 0);
        assert_eq!(sets.primary.len(), 32 * 24);
        assert!(sets.shadow.len() > 32 * 24 / 2);
        assert_eq!(sets.shadow.len(), sets.incoherent.len());
        let hits = trace_set(&scene, &accel, &sets, RayKind::Primary, false);
        assert_eq!(hits as usize, sets.shadow.len());
        for kind in RayKind::ALL {
            assert_eq!(
                trace_set(&scene, &accel, &sets, kind, false),
                trace_set(&scene, &accel, &sets, kind, true)
            );
        }
    }
}
