//! Rendering an image: tiles spread over threads with rayon, one [`Tracer`] per tile, optional
//! progress bar, and ray statistics. All pixel memory is allocated before anything is traced, so
//! an image too large for the machine is an error ([`RenderError`]) rather than an abort.
//!
//! Output is independent of the thread count and tile order: each pixel's samples depend only on
//! `(pixel, sample, dimension, seed)` and pixels are written to fixed places.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
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
    /// cancelled and must not be written. Looked at before every camera sample, shading point
    /// and batch of shadow rays, so a render stops within a few hundred rays per thread.
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

/// Why a render could not start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The film and the buffer the tiles are traced into cannot be allocated.
    #[error(
        "an image of {width}×{height} needs {} GiB of memory for its pixels, more than can be allocated",
        gib(*width, *height)
    )]
    TooLarge { width: u32, height: u32 },
}

/// Memory of a render's two pixel buffers (the film and the tiles), in GiB.
fn gib(width: u32, height: u32) -> String {
    let bytes = 2.0 * width as f64 * height as f64 * std::mem::size_of::<Vec3>() as f64;
    format!("{:.1}", bytes / (1u64 << 30) as f64)
}

/// Renders `scene` with `options`.
pub fn render(scene: &Scene, options: &RenderOptions) -> Result<RenderOutput, RenderError> {
    let buffers = Buffers::new(scene)?;
    let start = Instant::now();
    let accel = Accel::build(&scene.primitives, options.accel, options.leaf_size);
    let build_time = start.elapsed();
    Ok(RenderOutput {
        build_time,
        ..render_into(scene, &accel, options, buffers, None)
    })
}

/// Renders `scene` with an accelerator already built over its primitives (`options.accel` and
/// `options.leaf_size` are not used; `build_time` is zero).
pub fn render_with_accel(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
) -> Result<RenderOutput, RenderError> {
    Ok(render_into(
        scene,
        accel,
        options,
        Buffers::new(scene)?,
        None,
    ))
}

/// [`render_with_accel`], adding one to `pixels_done` as each pixel is finished (from the worker
/// threads, so another thread can follow the render or stop it after so many pixels).
pub fn render_with_accel_counting(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
    pixels_done: &AtomicU64,
) -> Result<RenderOutput, RenderError> {
    let buffers = Buffers::new(scene)?;
    Ok(render_into(
        scene,
        accel,
        options,
        buffers,
        Some(pixels_done),
    ))
}

/// The memory a render writes pixels to, allocated before anything is traced.
struct Buffers {
    film: Film,
    /// The image in bands of `TILE` rows, each band its tiles one after the other, each tile its
    /// rows: every tile is one contiguous slice a thread can own.
    tiles: Vec<Vec3>,
}

impl Buffers {
    fn new(scene: &Scene) -> Result<Buffers, RenderError> {
        let (width, height) = (scene.camera.width, scene.camera.height);
        let too_large = || RenderError::TooLarge { width, height };
        let film = Film::try_new(width, height).ok_or_else(too_large)?;
        let tiles = Film::try_new(width, height).ok_or_else(too_large)?.pixels;
        Ok(Buffers { film, tiles })
    }
}

fn render_into(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
    buffers: Buffers,
    pixels_done: Option<&AtomicU64>,
) -> RenderOutput {
    let Buffers {
        mut film,
        mut tiles,
    } = buffers;
    let (w, h) = (scene.camera.width as usize, scene.camera.height as usize);
    let tile = TILE as usize;
    let bar = if options.progress {
        let bar = indicatif::ProgressBar::new((w.div_ceil(tile) * h.div_ceil(tile)) as u64);
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
    let band = w * tile;
    let counts = if band == 0 || h == 0 {
        RayCounts::default()
    } else {
        tiles
            .par_chunks_mut(band)
            .enumerate()
            .flat_map(|(ty, rows)| {
                let th = rows.len() / w;
                rows.par_chunks_mut(tile * th)
                    .enumerate()
                    .map(move |(tx, pixels)| ((tx * tile) as u32, (ty * tile) as u32, pixels))
            })
            .map(|(x0, y0, pixels)| {
                if cancelled(options) {
                    return RayCounts::default();
                }
                let counts = render_tile(scene, accel, options, x0, y0, pixels, pixels_done);
                bar.inc(1);
                counts
            })
            .reduce(RayCounts::default, |mut a, b| {
                a.add(&b);
                a
            })
    };
    bar.finish_and_clear();

    let cancelled = cancelled(options);
    if !cancelled && band > 0 {
        film.pixels
            .par_chunks_mut(band)
            .zip(tiles.par_chunks(band))
            .for_each(|(rows, by_tile)| {
                let th = rows.len() / w;
                let mut at = 0;
                for x0 in (0..w).step_by(tile) {
                    let tw = tile.min(w - x0);
                    for y in 0..th {
                        rows[y * w + x0..][..tw].copy_from_slice(&by_tile[at..at + tw]);
                        at += tw;
                    }
                }
            });
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

/// Traces the tile whose top left pixel is `(x0, y0)` into `pixels` (its rows, top first) and
/// returns the rays it took. Stops early, leaving pixels unset, when the render is cancelled.
fn render_tile(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
    x0: u32,
    y0: u32,
    pixels: &mut [Vec3],
    pixels_done: Option<&AtomicU64>,
) -> RayCounts {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let (x1, y1) = ((x0 + TILE).min(w), (y0 + TILE).min(h));
    let mut tracer = Tracer::new(scene, accel, options.max_depth);
    tracer.options = options.trace;
    tracer.cancel = options.cancel.as_deref();
    let spp = options.spp.max(1);
    let coords = (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y)));
    for ((x, y), pixel) in coords.zip(pixels.iter_mut()) {
        let mut sum = Vec3::ZERO;
        for s in 0..spp {
            if tracer.cancelled() {
                return tracer.counts;
            }
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
        *pixel = sum / spp as f32;
        if let Some(done) = pixels_done {
            done.fetch_add(1, Ordering::Relaxed);
        }
    }
    tracer.counts
}
