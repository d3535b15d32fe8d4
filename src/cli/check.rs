//! `raytracer check SCENE...`: what a render would say before it starts, without rendering: the
//! variant and integrator, the image and its samples, what the scene holds, every warning with
//! its location, and an estimate of the rays and the time the render would take here.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::Parser;

use raytracer::accel::Accel;
use raytracer::files::shown;
use raytracer::film::{Film, ToneMap};
use raytracer::image_io::encode_image;
use raytracer::integrator::IntegratorKind;
use raytracer::render::{render_with_accel, RenderOptions};
use raytracer::scene::{load, RenderMode, Scene, Variant};

use crate::batch::summary::json_string;
use crate::exit_code::{self, Failure};
use crate::image_flags::ImageFlags;
use crate::load_flags::LoadFlags;
use crate::values;

#[derive(Parser, Debug)]
#[command(
    name = "raytracer check",
    about = "Says what rendering each scene would do, without rendering it: its variant, integrator, image, contents, warnings and an estimate of its rays and time on this machine.",
    after_help = "Exit codes: 0 every scene loads; 1 a scene or an asset is bad; 2 usage error.\n\
                  The estimate times the render of a few thousand pixel samples of the scene at a lower resolution and scales it to the whole image; docs/check.md gives its accuracy."
)]
struct CheckCli {
    /// Scene files (JSON).
    #[arg(required = true)]
    scenes: Vec<PathBuf>,
    /// The render's flags: the estimate is for the render they ask for.
    #[command(flatten)]
    image: ImageFlags,
    #[command(flatten)]
    load: LoadFlags,
    /// The render's worker threads (default: all cores).
    #[arg(long, value_parser = values::thread_count())]
    threads: Option<u64>,
    /// No estimate: load and report only.
    #[arg(long)]
    no_estimate: bool,
    /// One JSON object per scene, in an array, on standard output.
    #[arg(long)]
    json: bool,
}

/// The estimate's stated range, as factors of the estimate (`docs/check.md` compares it with
/// real renders).
const RANGE: (f64, f64) = (0.5, 2.0);

/// The timed sample renders grow until one takes at least this long.
const SAMPLE_TIME: Duration = Duration::from_millis(150);

/// Pixel samples of the first timed render.
const FIRST_SAMPLES: u64 = 4096;

/// What a check found about one scene.
struct Report {
    scene: PathBuf,
    loaded: Result<Summary, String>,
}

/// A scene that loads: what its render would be.
struct Summary {
    variant: &'static str,
    integrator: &'static str,
    width: u32,
    height: u32,
    spp: u32,
    adaptive: bool,
    bounces: u32,
    primitives: usize,
    triangles: usize,
    lights: usize,
    textures: Vec<String>,
    warnings: Vec<String>,
    estimate: Option<Estimate>,
}

/// The render's estimated cost on this machine.
struct Estimate {
    seconds: f64,
    rays: f64,
}

/// Runs `raytracer check` (`args` start with `check`) and returns its exit status.
pub fn main(args: &[OsString]) -> ExitCode {
    let cli = match exit_code::parse::<CheckCli>(args) {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    let pool = match values::thread_pool(cli.threads) {
        Ok(pool) => pool,
        Err(e) => return Failure::Input(e).report(),
    };
    let reports: Vec<Report> = cli
        .scenes
        .iter()
        .map(|scene| pool.install(|| check(&cli, scene)))
        .collect();
    if cli.json {
        outln!("{}", json(&reports));
    } else {
        for r in &reports {
            out!("{}", text(r, pool.current_num_threads()));
        }
    }
    if reports.iter().all(|r| r.loaded.is_ok()) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(exit_code::BAD_INPUT)
    }
}

/// Parses `args` as [`main`] would, without running anything.
pub(super) fn try_parse(args: &[OsString]) -> Result<(), clap::Error> {
    CheckCli::try_parse_from(args).map(|_| ())
}

/// Loads `path` and, unless told not to, estimates its render.
fn check(cli: &CheckCli, path: &Path) -> Report {
    let options = cli.load.options();
    let start = Instant::now();
    let loaded = load(path, &options).map(|mut scene| {
        let load_time = start.elapsed();
        let render = cli.image.render_options(&scene);
        let tone_map = (
            cli.image.tone_map(&scene),
            cli.image.display_exposure(&scene),
        );
        let estimate =
            (!cli.no_estimate).then(|| estimate(&mut scene, &render, tone_map, load_time));
        summary(&scene, &render, estimate)
    });
    Report {
        scene: path.to_path_buf(),
        loaded: loaded.map_err(|e| e.to_string()),
    }
}

/// What `scene` holds and how `render` would render it.
fn summary(scene: &Scene, render: &RenderOptions, estimate: Option<Estimate>) -> Summary {
    let textures = scene
        .textures
        .iter()
        .map(|t| match t.checker {
            Some(_) => "checkerboard".to_string(),
            None => format!("{}×{}", t.width, t.height),
        })
        .collect();
    Summary {
        variant: match scene.variant {
            Variant::V2019 => "2019",
            Variant::V2021 => "2021–23",
            Variant::Cgr => "CGR",
        },
        integrator: match (scene.mode, render.integrator) {
            (RenderMode::Binary, _) => "binary (hit or miss)",
            (_, Some(IntegratorKind::Path)) => "path tracing",
            _ => "Whitted",
        },
        width: scene.camera.width,
        height: scene.camera.height,
        spp: render.spp,
        adaptive: render.adaptive.is_some(),
        bounces: scene.nbounces,
        primitives: scene.primitives.len(),
        triangles: scene.primitives.triangle_count(),
        lights: scene.lights.len(),
        textures,
        warnings: scene.warnings.iter().map(ToString::to_string).collect(),
        estimate,
    }
}

/// The time and rays of rendering `scene` with `render` to a PNG through `tone_map` (and its
/// exposure), from renders of growing numbers of pixel samples at a lower resolution: the last
/// two give the cost of one pixel sample and of what a render does once, scaled to the whole
/// image, and encoding the last one gives the cost of a pixel of the PNG. Adaptive sampling is
/// timed as uniform sampling at its cap, so its estimate is an upper bound.
fn estimate(
    scene: &mut Scene,
    render: &RenderOptions,
    tone_map: (ToneMap, f32),
    load_time: Duration,
) -> Estimate {
    let start = Instant::now();
    let accel = Accel::build(&scene.primitives, render.accel, render.leaf_size);
    let fixed = load_time + start.elapsed();
    let (width, height) = (scene.camera.width, scene.camera.height);
    let total = width as u64 * height as u64 * render.spp as u64;
    let mut points: Vec<(f64, f64, f64)> = Vec::new(); // (pixel samples, seconds, rays)
    let mut n = FIRST_SAMPLES.min(total);
    let film = loop {
        let (seconds, rays, done, film) = timed_render(scene, &accel, render, n, (width, height));
        points.push((done as f64, seconds, rays));
        if seconds >= SAMPLE_TIME.as_secs_f64() || done >= total {
            break film;
        }
        n = (n * 4).min(total);
    };
    (scene.camera.width, scene.camera.height) = (width, height);
    let &(n2, t2, r2) = points.last().expect("one render at least");
    let (per_sample, once) = match points.len() {
        1 => (t2 / n2, 0.0),
        k => {
            let (n1, t1, _) = points[k - 2];
            let per = ((t2 - t1) / (n2 - n1)).max(0.0);
            (per, (t1 - per * n1).max(0.0))
        }
    };
    let start = Instant::now();
    let _ = encode_image(Path::new("estimate.png"), &film, tone_map.0, tone_map.1);
    let per_pixel = start.elapsed().as_secs_f64() / (film.width as f64 * film.height as f64);
    let encode = per_pixel * width as f64 * height as f64;
    Estimate {
        seconds: fixed.as_secs_f64() + once + per_sample * total as f64 + encode,
        rays: r2 / n2 * total as f64,
    }
}

/// Renders about `n` pixel samples of `scene` (`full` its image size): the image scaled down to
/// that many pixels at one sample each, or the whole image with the samples that fit. The
/// seconds, the rays, the pixel samples rendered and the image.
fn timed_render(
    scene: &mut Scene,
    accel: &Accel,
    render: &RenderOptions,
    n: u64,
    full: (u32, u32),
) -> (f64, f64, u64, Film) {
    let pixels = full.0 as u64 * full.1 as u64;
    let (w, h, samples) = if n < pixels {
        let scale = (n as f64 / pixels as f64).sqrt();
        let w = ((full.0 as f64 * scale).round() as u32).max(1);
        let h = ((full.1 as f64 * scale).round() as u32).max(1);
        (w, h, 1)
    } else {
        (
            full.0,
            full.1,
            (n / pixels).clamp(1, render.spp as u64) as u32,
        )
    };
    (scene.camera.width, scene.camera.height) = (w, h);
    let options = RenderOptions {
        samples: Some(0..samples),
        adaptive: None,
        ..render.clone()
    };
    let start = Instant::now();
    let out = render_with_accel(scene, accel, &options);
    let seconds = start.elapsed().as_secs_f64();
    let (rays, film) = match out {
        Ok(o) => (o.counts.total() as f64, o.film),
        Err(_) => (0.0, Film::new(w, h)),
    };
    (seconds, rays, w as u64 * h as u64 * samples as u64, film)
}

/// `seconds` as a person reads a duration.
fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 1.0 => format!("{:.0} ms", s * 1e3),
        s if s < 120.0 => format!("{s:.1} s"),
        s if s < 7200.0 => format!("{:.1} min", s / 60.0),
        s => format!("{:.1} h", s / 3600.0),
    }
}

/// The report of one scene as lines of text.
fn text(r: &Report, threads: usize) -> String {
    let name = shown(&r.scene);
    let s = match &r.loaded {
        Err(e) => return format!("error: {e}\n"),
        Ok(s) => s,
    };
    let samples = match (s.spp, s.adaptive) {
        (1, false) => "1 sample a pixel".to_string(),
        (n, false) => format!("{n} samples a pixel"),
        (n, true) => format!("adaptive, at most {n} samples a pixel"),
    };
    let mut out = format!(
        "{name}: {} file, {}; {}×{}, {samples}, {} bounces\n  {} primitives ({} triangles), {} lights, {} textures{}\n",
        s.variant,
        s.integrator,
        s.width,
        s.height,
        s.bounces,
        s.primitives,
        s.triangles,
        s.lights,
        s.textures.len(),
        if s.textures.is_empty() {
            String::new()
        } else {
            format!(" ({})", s.textures.join(", "))
        },
    );
    for w in &s.warnings {
        out.push_str(&format!("  warning: {w}\n"));
    }
    if let Some(e) = &s.estimate {
        out.push_str(&format!(
            "  estimate: {} ({} to {}) on {threads} thread{}, about {:.3} M rays\n",
            duration(e.seconds),
            duration(e.seconds * RANGE.0),
            duration(e.seconds * RANGE.1),
            if threads == 1 { "" } else { "s" },
            e.rays / 1e6,
        ));
    }
    out
}

/// The reports as a JSON array, one object per scene.
fn json(reports: &[Report]) -> String {
    let objects: Vec<String> = reports
        .iter()
        .map(|r| {
            let scene = json_string(&r.scene.to_string_lossy());
            match &r.loaded {
                Err(e) => format!("{{\"scene\":{scene},\"error\":{}}}", json_string(e)),
                Ok(s) => format!("{{\"scene\":{scene},{}}}", summary_json(s)),
            }
        })
        .collect();
    format!("[{}]", objects.join(","))
}

/// The members of a loaded scene's JSON object.
fn summary_json(s: &Summary) -> String {
    let list = |items: &[String]| {
        let quoted: Vec<String> = items.iter().map(|i| json_string(i)).collect();
        format!("[{}]", quoted.join(","))
    };
    let estimate = match &s.estimate {
        None => "null".to_string(),
        Some(e) => format!(
            "{{\"seconds\":{:.6},\"low\":{:.6},\"high\":{:.6},\"rays\":{:.0}}}",
            e.seconds,
            e.seconds * RANGE.0,
            e.seconds * RANGE.1,
            e.rays
        ),
    };
    format!(
        "\"variant\":{},\"integrator\":{},\"width\":{},\"height\":{},\"spp\":{},\"adaptive\":{},\"bounces\":{},\"primitives\":{},\"triangles\":{},\"lights\":{},\"textures\":{},\"warnings\":{},\"estimate\":{estimate}",
        json_string(s.variant),
        json_string(s.integrator),
        s.width,
        s.height,
        s.spp,
        s.adaptive,
        s.bounces,
        s.primitives,
        s.triangles,
        s.lights,
        list(&s.textures),
        list(&s.warnings),
    )
}
