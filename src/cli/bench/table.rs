//! Table 1: every bundled and grid scene rendered with every accelerator, point and area lights.

use super::scenes::{primitive_bytes, sphere_grid, with_lights, LightVariant};
use super::timing::{ms, timed};
use std::path::PathBuf;
use std::time::{Duration, Instant};

use raytracer::accel::{Accel, AccelKind};
use raytracer::files::shown;
use raytracer::integrator::{Integrator, IntegratorKind};
use raytracer::math::Vec2;
use raytracer::render::{render_with_accel, RenderOptions};
use raytracer::sampling::SampleKey;
use raytracer::scene::{load, LoadOptions, Scene};

/// A Table 1 scene: a bundled scene file or a sphere grid.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TableScene {
    File(&'static str),
    Grid { g: u32, s: u32 },
}

impl TableScene {
    /// The scene's name in the table: the file's stem, or `grid-GxS`.
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

/// How Table 1 is run.
#[derive(Debug, Clone)]
pub struct TableOptions {
    /// Small scenes and images, one run: a smoke test.
    pub quick: bool,
    /// Renders per row (the median is reported).
    pub runs: usize,
    /// Folder of the bundled scenes.
    pub scenes_dir: PathBuf,
    /// Most primitives per BVH leaf.
    pub leaf_size: usize,
    /// Rows with `none` or `flat` whose renders are estimated to take longer than this are
    /// skipped.
    pub none_limit: Duration,
    /// How long to trace sample pixels for that estimate.
    pub estimate_budget: Duration,
}

/// One row of Table 1.
#[derive(Debug, Clone)]
pub struct TableRow {
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

impl TableRow {
    /// Million rays a second of the render; `None` when skipped.
    pub fn mrays(&self) -> Option<f64> {
        self.render
            .map(|r| self.rays as f64 / r.as_secs_f64().max(1e-9) / 1e6)
    }

    /// Memory per triangle; `None` for a scene without triangles.
    pub fn bytes_per_triangle(&self) -> Option<f64> {
        (self.triangles > 0).then(|| self.memory as f64 / self.triangles as f64)
    }
}

/// The name of the accelerator `accel` is.
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
pub fn table1(
    options: &TableOptions,
    mut report: impl FnMut(&TableRow),
) -> Result<Vec<TableRow>, String> {
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

/// One row: `scene` with accelerator `kind`, its build and render timed (a render estimated to
/// take too long without a tree is skipped).
fn table_row(
    name: &str,
    scene: &Scene,
    light: LightVariant,
    kind: AccelKind,
    options: &TableOptions,
) -> TableRow {
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
    let mut row = TableRow {
        scene: name.to_string(),
        primitives: scene.primitives.len(),
        triangles: scene.primitives.triangle_count(),
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
    let integrator = Integrator::new(
        scene,
        accel,
        IntegratorKind::chosen(options.integrator, scene),
    );
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

/// The greatest common divisor of `a` and `b` (Euclid).
fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// The columns of Table 1.
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
pub fn row_fields(r: &TableRow) -> [String; 14] {
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
