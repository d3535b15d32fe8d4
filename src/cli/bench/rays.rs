//! Ray throughput: camera, shadow and incoherent ray sets of a sphere grid traced by each tree,
//! and their export for other tracers. The rays are pure functions of the scene and a seed.

use super::scenes::{grid_light, primitive_bytes, sphere_grid, with_lights, LightVariant};
use super::timing::timed;
use std::path::Path;
use std::time::Duration;

use rayon::prelude::*;

use raytracer::accel::{Accel, AccelKind, Isa};
use raytracer::files::shown;
use raytracer::geometry::Shape;
use raytracer::math::{Vec2, Vec3};
use raytracer::ray::Ray;
use raytracer::render::{render_with_accel, RenderOptions};
use raytracer::sampling::{uniform_sphere, SampleKey};
use raytracer::scene::Scene;

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
/// from each primary hit's robustly offset origin ([`raytracer::ray::Hit::spawn`]); the random
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
    /// Every set, in the order they are measured.
    pub const ALL: [RayKind; 3] = [RayKind::Primary, RayKind::Shadow, RayKind::Incoherent];

    /// The set's name in the output and on the `ray_set` example's command line.
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
    /// The number of rays of one set.
    pub fn len(&self, kind: RayKind) -> usize {
        match kind {
            RayKind::Primary => self.primary.len(),
            RayKind::Shadow => self.shadow.len(),
            RayKind::Incoherent => self.incoherent.len(),
        }
    }
}

/// Throughput of one ray set.
#[derive(Debug, Clone)]
pub struct SetResult {
    pub kind: RayKind,
    pub rays: usize,
    /// Rays that hit (shadow rays: that are blocked).
    pub hits: u64,
    /// Median time on one thread.
    pub single: Duration,
    /// Median time on the current pool.
    pub parallel: Duration,
}

impl SetResult {
    /// Million rays a second in time `d`.
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
        triangles: scene.primitives.triangle_count(),
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

#[cfg(test)]
mod tests {
    use super::*;

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
