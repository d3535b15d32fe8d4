//! Rendering an image: tiles spread over threads with rayon, one [`Tracer`] per tile, optional
//! progress bar, and ray statistics.
//!
//! Output is independent of the thread count and tile order: each pixel's samples depend only on
//! `(pixel, sample, dimension, seed)` and pixels are written to fixed places.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::accel::{Accel, AccelKind};
use crate::film::Film;
use crate::integrator::{RayCounts, TraceOptions, Tracer};
use crate::math::{Vec2, Vec3};
use crate::sampling::{Method, SampleKey};
use crate::scene::Scene;

/// Side of the square tiles handed to threads.
const TILE: u32 = 16;

#[derive(Debug, Clone)]
pub struct RenderOptions {
    /// Samples per pixel. 1 = one ray through each pixel centre.
    pub spp: u32,
    /// Placement of pixel and lens samples.
    pub pixel_method: Method,
    pub seed: u64,
    pub accel: AccelKind,
    /// Most primitives in a BVH leaf.
    pub leaf_size: usize,
    /// Cap on recursion depth on top of the scene's `nbounces`.
    pub max_depth: u32,
    /// Light-sampling overrides and work-skipping switches (the default changes nothing).
    pub trace: TraceOptions,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Set from outside (e.g. on Ctrl-C) to stop the render early; the output is then marked
    /// cancelled and must not be written.
    pub cancel: Option<Arc<AtomicBool>>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            spp: 1,
            pixel_method: Method::Jittered,
            seed: 0,
            accel: AccelKind::Auto,
            leaf_size: 4,
            max_depth: u32::MAX,
            trace: TraceOptions::default(),
            progress: false,
            cancel: None,
        }
    }
}

/// What a render produced and how long it took.
#[derive(Debug, Clone)]
pub struct RenderOutput {
    pub film: Film,
    pub counts: RayCounts,
    pub build_time: Duration,
    pub render_time: Duration,
    /// The render was stopped through [`RenderOptions::cancel`]; the film is incomplete.
    pub cancelled: bool,
}

/// Renders `scene` with `options`.
pub fn render(scene: &Scene, options: &RenderOptions) -> RenderOutput {
    let start = Instant::now();
    let accel = Accel::build(&scene.primitives, options.accel, options.leaf_size);
    let build_time = start.elapsed();
    RenderOutput {
        build_time,
        ..render_with_accel(scene, &accel, options)
    }
}

/// Renders `scene` with an accelerator already built over its primitives (`options.accel` and
/// `options.leaf_size` are not used; `build_time` is zero).
pub fn render_with_accel(scene: &Scene, accel: &Accel, options: &RenderOptions) -> RenderOutput {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let tiles: Vec<(u32, u32)> = (0..tiles_y)
        .flat_map(|ty| (0..tiles_x).map(move |tx| (tx, ty)))
        .collect();
    let bar = if options.progress {
        let bar = indicatif::ProgressBar::new(tiles.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {wide_bar} {percent}% (eta {eta})",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };

    let start = Instant::now();
    let results: Vec<(Vec<Vec3>, RayCounts)> = tiles
        .par_iter()
        .map(|&(tx, ty)| {
            if cancelled(options) {
                return (Vec::new(), RayCounts::default());
            }
            let out = render_tile(scene, accel, options, tx * TILE, ty * TILE);
            bar.inc(1);
            out
        })
        .collect();
    bar.finish_and_clear();

    let cancelled = cancelled(options);
    let mut film = Film::new(w, h);
    let mut counts = RayCounts::default();
    for (&(tx, ty), (pixels, c)) in tiles.iter().zip(&results) {
        counts.add(c);
        let (x0, y0) = (tx * TILE, ty * TILE);
        let tw = TILE.min(w - x0);
        for (i, p) in pixels.iter().enumerate() {
            let (x, y) = (x0 + i as u32 % tw, y0 + i as u32 / tw);
            film.set(x, y, *p);
        }
    }
    RenderOutput {
        film,
        counts,
        build_time: Duration::ZERO,
        render_time: start.elapsed(),
        cancelled,
    }
}

fn cancelled(options: &RenderOptions) -> bool {
    options
        .cancel
        .as_ref()
        .is_some_and(|c| c.load(Ordering::Relaxed))
}

fn render_tile(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
    x0: u32,
    y0: u32,
) -> (Vec<Vec3>, RayCounts) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let (x1, y1) = ((x0 + TILE).min(w), (y0 + TILE).min(h));
    let mut tracer = Tracer::new(scene, accel, options.max_depth);
    tracer.options = options.trace;
    let spp = options.spp.max(1);
    let mut pixels = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
    for y in y0..y1 {
        for x in x0..x1 {
            let mut sum = Vec3::ZERO;
            for s in 0..spp {
                let key = SampleKey::new(x, y, s, spp, options.seed);
                let film = if spp == 1 {
                    Vec2::splat(0.5)
                } else {
                    key.pixel_pattern(options.pixel_method, 0)
                };
                let lens = key.pixel_pattern(options.pixel_method, 1);
                let ray = scene.camera.generate_ray(x, y, film, lens);
                sum += tracer.trace_camera(&ray, &key);
            }
            pixels.push(sum / spp as f32);
        }
    }
    (pixels, tracer.counts)
}
