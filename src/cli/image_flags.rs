//! The flags that decide an image's bytes, shared by `raytracer SCENE OUT` and `raytracer batch`
//! (flattened into both with clap), and how they combine with a scene's own settings: both
//! subcommands write the same image for the same flags.

use raytracer::accel::AccelKind;
use raytracer::film::ToneMap;
use raytracer::render::adaptive::{Adaptive, DEFAULT_THRESHOLD};
use raytracer::render::RenderOptions;
use raytracer::sampling::Method;
use raytracer::scene::Scene;

use super::values;

/// The samples a pixel may take under `--time-limit` without `--spp`.
const TIME_LIMIT_SPP: u32 = 65_536;

#[derive(clap::Args, Debug, Clone)]
pub(crate) struct ImageFlags {
    /// Samples per pixel (stratified); 1 traces one ray through each pixel centre. Default: the
    /// scene's own count (`pixelsample` and its spellings), else 1.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    pub spp: Option<u32>,
    /// Placement of pixel and lens samples: random, jittered or sobol. Default: the scene
    /// camera's `sampler`, else jittered (sobol with --adaptive).
    #[arg(long)]
    pub pixel_sampler: Option<Method>,
    /// Sampler for pixel, lens and every area light (overrides --pixel-sampler and each light's
    /// method): random, jittered or sobol.
    #[arg(long)]
    pub sampler: Option<Method>,
    /// Adaptive sampling: each pixel takes samples in rounds (4, 8, 16, …) until the error
    /// estimate around it is at most --noise-threshold (from 16 samples on; after 8, at most half
    /// of it), --spp at most (pixel samples then default to sobol, whose prefixes are stratified).
    #[arg(long)]
    pub adaptive: bool,
    /// The error at which an adaptive pixel stops: the standard error of its mean, estimated from
    /// the spread of the means of four consecutive quarters of its samples, summed over RGB, over
    /// 10⁻⁴ + √(RGB sum of the mean), as Cycles scales it. Default 0.01.
    #[arg(long, value_name = "T", requires = "adaptive", value_parser = values::positive_f32)]
    pub noise_threshold: Option<f32>,
    /// Render progressively for this many seconds, then write what is there: rounds of samples
    /// (as --adaptive, which may also be given) up to --spp, or 65,536 samples a pixel without
    /// it. The one mode whose image depends on the machine and its load, not only on the flags.
    #[arg(long, value_name = "SECONDS", value_parser = values::positive_f64)]
    pub time_limit: Option<f64>,
    /// Adaptive area lights: probe a 3×3 grid on each light first and trace all its shadow rays
    /// only where the probes disagree (faster; can miss occluders between the probes' rays).
    #[arg(long)]
    pub adaptive_lights: bool,
    /// Skip reflection/refraction rays whose accumulated weight is below X (POV-Ray's
    /// adc_bailout), and point-light terms below X/64 of radiance. Default: 1/255 = 0.0039, one
    /// 8-bit step (0 traces every ray).
    #[arg(long, value_name = "X", value_parser = values::unit_interval_f32)]
    pub adc_bailout: Option<f32>,
    /// Trace every ray the scene asks for: no --adc-bailout cut-off (the full-work render the
    /// default is measured against; see docs/adaptive.md).
    #[arg(long, conflicts_with_all = ["adc_bailout", "adaptive_lights"])]
    pub no_skip: bool,
    /// Seed for every random number (the image is a pure function of the scene, options and seed).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Tone map for 8-bit output: linear (the coursework's: ×255, clamp), srgb, reinhard,
    /// exposure (1 − exp(−x·exposure); the only one a CGR file's camera exposure feeds), cgr
    /// (the CGR course's display transform), or aces (Narkowicz's ACES filmic fit, no gamma).
    /// Default: the file's "tone_mapping" if it names one, else cgr for CGR files, else linear;
    /// reinhard for a file that sets "use_tone_mapping": true.
    #[arg(long)]
    pub tonemap: Option<ToneMap>,
    /// Multiplies the scene's exposure (a finite number ≥ 0, as in the scene file); for CGR files,
    /// a radiance scale of its own.
    #[arg(long, default_value_t = 1.0, value_parser = values::non_negative_f32)]
    pub exposure: f32,
    /// Accelerator: auto (the four-wide SAH BVH), none (every primitive, one by one), flat (every primitive in one SIMD-tested leaf), median, sah (binary), sah4 (four-wide), sah8 (eight-wide).
    #[arg(long, default_value = "auto")]
    pub accel: AccelKind,
    /// Most primitives per BVH leaf.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u64).range(1..=255))]
    pub leaf_size: u64,
    /// Cap on reflection/refraction depth (path tracing: on the path's bounces), on top of the
    /// scene's nbounces.
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// Integrator: whitted (ray trees with Blinn-Phong direct light) or path (path tracing with
    /// next-event estimation and MIS). Default: the scene's rendermode (pathtrace → path).
    #[arg(long)]
    pub integrator: Option<raytracer::integrator::IntegratorKind>,
}

impl ImageFlags {
    /// The render options for `scene`: each flag given, else the scene's own setting, else the
    /// default. The rest (no progress bar, no cancel flag) are the defaults; callers set them.
    /// Adaptive sampling places pixel samples with Sobol unless told otherwise: the first 2^k
    /// points of a Sobol sequence are stratified, where a prefix of a jittered pattern of all
    /// `spp` strata is a random subset of them.
    pub(crate) fn render_options(&self, scene: &Scene) -> RenderOptions {
        let time_limit = self.time_limit.map(std::time::Duration::from_secs_f64);
        let adaptive = match (self.adaptive, time_limit) {
            (false, None) => None,
            // Without --adaptive a time limit samples every pixel alike: only one whose samples
            // are all equal (an error of exactly 0) stops before the time is up.
            (adaptive, _) => Some(Adaptive {
                threshold: if adaptive {
                    self.noise_threshold.unwrap_or(DEFAULT_THRESHOLD)
                } else {
                    0.0
                },
                time_limit,
            }),
        };
        let spp_cap = match (self.spp, time_limit) {
            (None, Some(_)) => Some(TIME_LIMIT_SPP),
            (spp, _) => spp,
        };
        let integrator = raytracer::integrator::IntegratorKind::chosen(self.integrator, scene);
        // The path tracer's own dimensions are Sobol; its pixel and lens samples follow.
        let default_method = match (adaptive, integrator) {
            (Some(_), _) | (None, raytracer::integrator::IntegratorKind::Path) => Method::Sobol,
            (None, raytracer::integrator::IntegratorKind::Whitted) => Method::Jittered,
        };
        RenderOptions {
            spp: spp_cap.or(scene.pixel_samples).unwrap_or(1),
            pixel_method: self
                .sampler
                .or(self.pixel_sampler)
                .or(scene.pixel_method)
                .unwrap_or(default_method),
            adaptive,
            seed: self.seed,
            accel: self.accel,
            leaf_size: self.leaf_size as usize,
            max_depth: self.max_depth.unwrap_or(u32::MAX),
            trace: raytracer::integrator::TraceOptions {
                light_method: self.sampler,
                light_samples: scene.light_samples,
                adaptive_lights: self.adaptive_lights,
                cutoff: if self.no_skip {
                    None
                } else {
                    Some(
                        self.adc_bailout
                            .unwrap_or(raytracer::integrator::DEFAULT_CUTOFF),
                    )
                },
            },
            integrator: Some(integrator),
            ..RenderOptions::default()
        }
    }

    /// The tone map of `scene`'s 8-bit output: `--tonemap`, else the one the file asks for, else
    /// linear.
    pub(crate) fn tone_map(&self, scene: &Scene) -> ToneMap {
        ToneMap::chosen(self.tonemap, scene.tone_map)
    }

    /// The exposure the tone map applies to `scene`'s film (see [`Scene::display_exposure`]).
    pub(crate) fn display_exposure(&self, scene: &Scene) -> f32 {
        scene.display_exposure(self.tone_map(scene)) * self.exposure
    }
}
