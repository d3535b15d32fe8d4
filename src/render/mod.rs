//! Rendering an image: tiles spread over threads with rayon, one [`Tracer`] per tile, optional
//! progress bar, and ray statistics. All pixel memory is allocated before anything is traced, so
//! an image too large for the machine is an error ([`RenderError`]) rather than an abort.
//!
//! Output is independent of the thread count and tile order: each pixel's samples depend only on
//! `(pixel, sample, dimension, seed)`, they are summed exactly ([`PixelSum`]), and pixels are
//! written to fixed places. A render can be cut into parts, a rectangle of pixels
//! ([`RenderOptions::crop`]) and a range of each pixel's samples ([`RenderOptions::samples`]),
//! whose exact sums ([`RenderOptions::keep_sums`]) add up to the whole render bit for bit.

pub mod adaptive;

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::accel::{Accel, AccelKind};
use crate::film::sum::MAX_SAMPLES;
use crate::film::{Film, PixelRect, PixelSum};
use crate::integrator::{Integrator, IntegratorKind, RayCounts, TraceOptions, Tracer};
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
    /// The integrator, in place of the one the scene's `rendermode` asks for.
    pub integrator: Option<IntegratorKind>,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Set from outside (e.g. on Ctrl-C) to stop the render early; the output is then marked
    /// cancelled and must not be written. Looked at before every camera sample, shading point
    /// and batch of shadow rays, so a render stops within a few hundred rays per thread.
    pub cancel: Option<Arc<AtomicBool>>,
    /// Trace only these pixels of the image (default: all). The film then holds just them.
    pub crop: Option<PixelRect>,
    /// Trace only these of each pixel's `spp` samples (default: all). `spp` stays the total, so
    /// the samples traced are the very ones of the whole render.
    pub samples: Option<Range<u32>>,
    /// Keep each pixel's exact sample sums ([`RenderOutput::sums`]), for parts to be merged.
    pub keep_sums: bool,
    /// Sample each pixel until its error estimate is below a threshold, `spp` at most
    /// ([`adaptive`]); `None` takes `spp` samples everywhere.
    pub adaptive: Option<adaptive::Adaptive>,
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
            integrator: None,
            progress: false,
            cancel: None,
            crop: None,
            samples: None,
            keep_sums: false,
            adaptive: None,
        }
    }
}

impl RenderOptions {
    /// The samples of each pixel a render with these options traces.
    pub fn sample_range(&self) -> Range<u32> {
        self.samples.clone().unwrap_or(0..self.spp.max(1))
    }
}

/// What a render produced and how long it took.
#[derive(Debug, Clone)]
pub struct RenderOutput {
    /// The mean of the samples traced, for the pixels traced (the crop, else the whole image).
    pub film: Film,
    /// Where the film lies in the whole image.
    pub window: PixelRect,
    /// The exact sums behind `film`, row-major like it, when [`RenderOptions::keep_sums`].
    pub sums: Option<Vec<PixelSum>>,
    /// The samples each pixel took, row-major like `film`, for adaptive renders.
    pub sample_counts: Option<Vec<u32>>,
    pub counts: RayCounts,
    pub build_time: Duration,
    pub render_time: Duration,
    /// The render was stopped through [`RenderOptions::cancel`]; the film is incomplete.
    pub cancelled: bool,
}

/// Why a render could not start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The film (and, for a part, its sums) cannot be allocated.
    #[error(
        "an image of {width}×{height} needs {gib:.1} GiB of memory for its pixels, more than can be allocated"
    )]
    TooLarge { width: u32, height: u32, gib: f64 },
    /// The crop does not lie inside the image.
    #[error("the crop {crop} is not inside the {width}×{height} image")]
    CropOutside {
        crop: PixelRect,
        width: u32,
        height: u32,
    },
    /// The sample range is empty or reaches past the samples per pixel.
    #[error("the sample range {}..{} is not a non-empty part of the {spp} samples per pixel, 0..{spp}", .range.start, .range.end)]
    SampleRange { range: Range<u32>, spp: u32 },
    /// Adaptive sampling decides from all of a pixel's samples so far; it cannot take a range.
    #[error("adaptive sampling takes all of a pixel's samples from the first: it cannot trace a sample range")]
    AdaptiveRange,
    /// More samples per pixel than an exact sum holds.
    #[error("{spp} samples per pixel is more than the {MAX_SAMPLES} a render can sum")]
    TooManySamples { spp: u32 },
}

/// Renders `scene` with `options`.
pub fn render(scene: &Scene, options: &RenderOptions) -> Result<RenderOutput, RenderError> {
    let plan = Plan::new(scene, options)?;
    let start = Instant::now();
    let accel = Accel::build(&scene.primitives, options.accel, options.leaf_size);
    let build_time = start.elapsed();
    Ok(RenderOutput {
        build_time,
        ..plan.run(scene, &accel, options, None)
    })
}

/// Renders `scene` with an accelerator already built over its primitives (`options.accel` and
/// `options.leaf_size` are not used; `build_time` is zero).
pub fn render_with_accel(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
) -> Result<RenderOutput, RenderError> {
    Ok(Plan::new(scene, options)?.run(scene, accel, options, None))
}

/// [`render_with_accel`], adding one to `pixels_done` as each pixel is finished (from the worker
/// threads, so another thread can follow the render or stop it after so many pixels).
pub fn render_with_accel_counting(
    scene: &Scene,
    accel: &Accel,
    options: &RenderOptions,
    pixels_done: &AtomicU64,
) -> Result<RenderOutput, RenderError> {
    Ok(Plan::new(scene, options)?.run(scene, accel, options, Some(pixels_done)))
}

/// What a pixel of the tile buffers holds: the mean of its samples, or their exact sums.
trait TracedPixel: Copy + Default + Send + Sync {
    fn from_sum(sum: &PixelSum, count: u32) -> Self;

    /// The pixel of the one sample `c`: what [`TracedPixel::from_sum`] gives for its sum.
    #[inline]
    fn from_one(c: Vec3) -> Self {
        let mut sum = PixelSum::default();
        sum.add(c);
        Self::from_sum(&sum, 1)
    }
}

impl TracedPixel for Vec3 {
    fn from_sum(sum: &PixelSum, count: u32) -> Vec3 {
        sum.mean(count)
    }

    /// The sample itself wherever the exact sum would give it back (most values: see
    /// [`PixelSum::mean_of_one`]), which spares one-sample renders the sum.
    #[inline]
    fn from_one(c: Vec3) -> Vec3 {
        PixelSum::mean_of_one(c)
    }
}

impl TracedPixel for PixelSum {
    fn from_sum(sum: &PixelSum, _count: u32) -> PixelSum {
        *sum
    }
}

/// `len` default values, or `None` when they cannot be allocated.
fn try_buffer<T: Clone + Default>(len: u64) -> Option<Vec<T>> {
    let len = usize::try_from(len).ok()?;
    let mut v = Vec::new();
    v.try_reserve_exact(len).ok()?;
    v.resize(len, T::default());
    Some(v)
}

/// A checked render: its window and samples, and the memory it writes pixels to, allocated
/// before anything is traced.
struct Plan {
    window: PixelRect,
    samples: Range<u32>,
    spp: u32,
    buffers: Buffers,
}

enum Buffers {
    Means {
        film: Vec<Vec3>,
    },
    Sums {
        sums: Vec<PixelSum>,
        film: Vec<Vec3>,
    },
    /// Adaptive sampling: the state of every pixel of `region`, the window with its apron.
    Adaptive {
        states: Vec<adaptive::PixelState>,
        region: PixelRect,
        settings: adaptive::Adaptive,
    },
}

impl Plan {
    fn new(scene: &Scene, options: &RenderOptions) -> Result<Plan, RenderError> {
        let (width, height) = (scene.camera.width, scene.camera.height);
        let full = PixelRect::full(width, height);
        let window = options.crop.unwrap_or(full);
        if window.is_empty() || !window.within(&full) {
            return Err(RenderError::CropOutside {
                crop: window,
                width,
                height,
            });
        }
        let spp = options.spp.max(1);
        if spp > MAX_SAMPLES {
            return Err(RenderError::TooManySamples { spp });
        }
        let samples = options.sample_range();
        if options.adaptive.is_some() && samples != (0..spp) {
            return Err(RenderError::AdaptiveRange);
        }
        if samples.start >= samples.end || samples.end > spp {
            return Err(RenderError::SampleRange {
                range: samples,
                spp,
            });
        }
        let n = window.area();
        let too_large = |pixels: u64, per_pixel: usize| RenderError::TooLarge {
            width: window.width(),
            height: window.height(),
            gib: pixels as f64 * per_pixel as f64 / (1u64 << 30) as f64,
        };
        let buffers = if let Some(settings) = options.adaptive {
            let region = adaptive::traced_region(window, full, spp);
            let per_pixel = std::mem::size_of::<adaptive::PixelState>();
            Buffers::Adaptive {
                states: try_buffer(region.area())
                    .ok_or_else(|| too_large(region.area(), per_pixel))?,
                region,
                settings,
            }
        } else if options.keep_sums {
            let per_pixel = std::mem::size_of::<PixelSum>() + std::mem::size_of::<Vec3>();
            let too_large = || too_large(n, per_pixel);
            Buffers::Sums {
                sums: try_buffer(n).ok_or_else(too_large)?,
                film: try_buffer(n).ok_or_else(too_large)?,
            }
        } else {
            let too_large = || too_large(n, std::mem::size_of::<Vec3>());
            Buffers::Means {
                film: try_buffer(n).ok_or_else(too_large)?,
            }
        };
        Ok(Plan {
            window,
            samples,
            spp,
            buffers,
        })
    }

    fn run(
        self,
        scene: &Scene,
        accel: &Accel,
        options: &RenderOptions,
        pixels_done: Option<&AtomicU64>,
    ) -> RenderOutput {
        let start = Instant::now();
        let Plan {
            window,
            samples,
            spp,
            buffers,
        } = self;
        let integrator = Integrator::new(
            scene,
            accel,
            IntegratorKind::chosen(options.integrator, scene),
        );
        let work = Work {
            scene,
            integrator: &integrator,
            options,
            window,
            samples: samples.clone(),
            spp,
            pixels_done,
        };
        let count = samples.end - samples.start;
        let (pixels, sums, counts, cancelled) = match buffers {
            Buffers::Adaptive {
                states,
                region,
                settings,
            } => {
                let traced = adaptive::trace(&work, settings, states, region);
                let pixels = traced
                    .sums
                    .par_iter()
                    .zip(traced.counts.par_iter())
                    .map(|(s, &k)| s.mean(k))
                    .collect();
                return RenderOutput {
                    film: Film::from_pixels(window.width(), window.height(), pixels),
                    window,
                    sums: options.keep_sums.then_some(traced.sums),
                    sample_counts: Some(traced.counts),
                    counts: traced.rays,
                    build_time: Duration::ZERO,
                    render_time: start.elapsed(),
                    cancelled: traced.cancelled,
                };
            }
            Buffers::Means { mut film } => {
                let (counts, cancelled) = work.trace(&mut film);
                (film, None, counts, cancelled)
            }
            Buffers::Sums { mut sums, mut film } => {
                let (counts, cancelled) = work.trace(&mut sums);
                film.par_iter_mut()
                    .zip(sums.par_iter())
                    .for_each(|(m, s)| *m = s.mean(count));
                (film, Some(sums), counts, cancelled)
            }
        };
        RenderOutput {
            film: Film::from_pixels(window.width(), window.height(), pixels),
            window,
            sums,
            sample_counts: None,
            counts,
            build_time: Duration::ZERO,
            render_time: start.elapsed(),
            cancelled,
        }
    }
}

/// One render's inputs, shared by its tiles.
pub(crate) struct Work<'a> {
    scene: &'a Scene,
    integrator: &'a Integrator<'a>,
    options: &'a RenderOptions,
    window: PixelRect,
    samples: Range<u32>,
    spp: u32,
    pixels_done: Option<&'a AtomicU64>,
}

impl Work<'_> {
    /// Traces every tile of the window into `out`, row-major over the window: the window is cut
    /// into bands of `TILE` rows and each band's rows into `TILE`-wide pieces, so a tile is the
    /// pieces of one column of a band, which its thread owns. Returns the rays traced and whether
    /// the render was cancelled (`out` is then incomplete).
    fn trace<T: TracedPixel>(&self, out: &mut [T]) -> (RayCounts, bool) {
        let (w, h) = (self.window.width() as usize, self.window.height() as usize);
        let tile = TILE as usize;
        let bar = if self.options.progress {
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

        let band = w * tile;
        let (x_origin, y_origin) = (self.window.x0, self.window.y0);
        let counts = out
            .par_chunks_mut(band)
            .enumerate()
            .flat_map(|(ty, rows)| {
                let mut tiles: Vec<Vec<&mut [T]>> = (0..w.div_ceil(tile))
                    .map(|_| Vec::with_capacity(tile))
                    .collect();
                for row in rows.chunks_mut(w) {
                    for (column, piece) in tiles.iter_mut().zip(row.chunks_mut(tile)) {
                        column.push(piece);
                    }
                }
                tiles.into_par_iter().enumerate().map(move |(tx, rows)| {
                    let x0 = x_origin + (tx * tile) as u32;
                    let y0 = y_origin + (ty * tile) as u32;
                    (x0, y0, rows)
                })
            })
            .map(|(x0, y0, mut rows)| {
                if cancelled(self.options) {
                    return RayCounts::default();
                }
                let counts = self.tile(x0, y0, &mut rows);
                bar.inc(1);
                counts
            })
            .reduce(RayCounts::default, |mut a, b| {
                a.add(&b);
                a
            });
        bar.finish_and_clear();
        (counts, cancelled(self.options))
    }

    /// A tracer for one tile's or row's pixels.
    fn tracer(&self) -> Tracer<'_> {
        self.integrator.tracer(
            self.options.max_depth,
            self.options.trace,
            self.options.pixel_method,
            self.options.cancel.as_deref(),
        )
    }

    /// The radiance of camera sample `s` (of `spp`) of pixel `(x, y)`.
    #[inline]
    fn sample(&self, tracer: &mut Tracer, x: u32, y: u32, s: u32) -> Vec3 {
        let options = self.options;
        let thin_lens = self.scene.camera.lens.is_some();
        // One sample a pixel goes through its centre; a pinhole camera has no lens to sample.
        // Then a tracer that reads no key needs none.
        let mut key = if self.spp == 1 && !thin_lens && !tracer.reads_keys() {
            SampleKey::unread(s, self.spp)
        } else {
            SampleKey::new(x, y, s, self.spp, options.seed)
        };
        let method = options.pixel_method;
        let centre = Vec2::splat(0.5);
        let (film, lens) = match (thin_lens, self.spp == 1) {
            (false, true) => (centre, centre),
            (false, false) => (key.pinhole_pattern(method), centre),
            (true, true) => (centre, key.camera_pattern(method).1),
            (true, false) => key.camera_pattern(method),
        };
        let ray = self.scene.camera.generate_ray(x, y, film, lens);
        tracer.trace_camera(&ray, &key)
    }

    /// Traces the tile whose top left pixel is `(x0, y0)` (in the whole image) into `rows` (its
    /// rows, top first) and returns the rays it took. Stops early, leaving pixels unset, when
    /// the render is cancelled.
    fn tile<T: TracedPixel>(&self, x0: u32, y0: u32, rows: &mut [&mut [T]]) -> RayCounts {
        let mut tracer = self.tracer();
        let count = self.samples.end - self.samples.start;
        let pixels = (y0..).zip(rows.iter_mut()).flat_map(|(y, row)| {
            (x0..)
                .zip(row.iter_mut())
                .map(move |(x, pixel)| (x, y, pixel))
        });
        for (x, y, pixel) in pixels {
            if count == 1 {
                if tracer.cancelled() {
                    return tracer.counts();
                }
                *pixel = T::from_one(self.sample(&mut tracer, x, y, self.samples.start));
            } else {
                let mut sum = PixelSum::default();
                for s in self.samples.clone() {
                    if tracer.cancelled() {
                        return tracer.counts();
                    }
                    sum.add(self.sample(&mut tracer, x, y, s));
                }
                *pixel = T::from_sum(&sum, count);
            }
            if let Some(done) = self.pixels_done {
                done.fetch_add(1, Ordering::Relaxed);
            }
        }
        tracer.counts()
    }
}

fn cancelled(options: &RenderOptions) -> bool {
    options
        .cancel
        .as_ref()
        .is_some_and(|c| c.load(Ordering::Relaxed))
}
