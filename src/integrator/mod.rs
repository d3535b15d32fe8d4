//! Integrators: what a camera ray's radiance is. Two side by side, chosen once per render:
//! - [`whitted`]: Whitted ray trees: Blinn-Phong direct light with shadow rays, mirrors and glass
//!   by recursion (the `phong` and `binary` render modes);
//! - [`path`]: unidirectional path tracing with next-event estimation and multiple importance
//!   sampling (`"rendermode": "pathtrace"`), over the BSDFs of [`bsdf`] and the emitters of
//!   [`emitters`], weighted by [`mis`].
//!
//! [`Integrator`] is the choice for one render (the file's `rendermode`, or `--integrator`) and
//! what it needs built once; each worker takes a [`Tracer`] from it. The tracer's one `match` per
//! camera sample is the only place the two meet: neither integrator's loops look at the mode.

pub mod bsdf;
pub mod emitters;
pub mod mis;
pub mod path;
pub mod whitted;

use std::sync::atomic::AtomicBool;

use crate::accel::{Accel, Interiors, LightBuffer};
use crate::light::Light;
use crate::math::Vec3;
use crate::ray::Ray;
use crate::sampling::{Method, SampleKey};
use crate::scene::{RenderMode, Scene};

pub use whitted::{Whitted, BINARY_HIT, MAX_SECONDARY_RAYS_PER_SAMPLE};

/// Which integrator renders a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Whitted ray tracing (the `phong` and `binary` render modes).
    Whitted,
    /// Path tracing.
    Path,
}

impl IntegratorKind {
    /// The integrator a scene asks for: the path tracer for `"rendermode": "pathtrace"` (and its
    /// spellings), Whitted ray tracing otherwise.
    pub fn of_scene(scene: &Scene) -> IntegratorKind {
        match scene.mode {
            RenderMode::Path => IntegratorKind::Path,
            RenderMode::Phong | RenderMode::Binary => IntegratorKind::Whitted,
        }
    }

    /// `choice` (a command line's or options' `--integrator`), else what `scene` asks for.
    pub fn chosen(choice: Option<IntegratorKind>, scene: &Scene) -> IntegratorKind {
        choice.unwrap_or_else(|| IntegratorKind::of_scene(scene))
    }

    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Whitted => "whitted",
            IntegratorKind::Path => "path",
        }
    }
}

impl std::str::FromStr for IntegratorKind {
    type Err = String;

    fn from_str(s: &str) -> Result<IntegratorKind, String> {
        match s.to_ascii_lowercase().as_str() {
            "whitted" | "phong" => Ok(IntegratorKind::Whitted),
            "path" | "pathtrace" | "pathtracer" | "pathtracing" => Ok(IntegratorKind::Path),
            other => Err(format!(
                "unknown integrator '{other}' (expected whitted or path)"
            )),
        }
    }
}

impl std::fmt::Display for IntegratorKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// One render's integrator: its kind, and what it builds once for the whole image (the path
/// tracer's emitters).
pub struct Integrator<'a> {
    scene: &'a Scene,
    accel: &'a Accel,
    emitters: Option<emitters::Emitters>,
    /// The Whitted tracer's quick answers for rays inside glass spheres.
    interiors: Interiors,
    /// The Whitted tracer's light buffers, per light (see [`whitted::light_buffers`]).
    light_buffers: Vec<Option<LightBuffer>>,
}

impl<'a> Integrator<'a> {
    pub fn new(scene: &'a Scene, accel: &'a Accel, kind: IntegratorKind) -> Integrator<'a> {
        Integrator {
            scene,
            accel,
            emitters: (kind == IntegratorKind::Path).then(|| emitters::Emitters::new(scene)),
            interiors: match kind {
                IntegratorKind::Whitted => whitted::interiors(scene, accel),
                IntegratorKind::Path => Interiors::default(),
            },
            light_buffers: match kind {
                IntegratorKind::Whitted => whitted::light_buffers(scene, accel),
                IntegratorKind::Path => Vec::new(),
            },
        }
    }

    /// A tracer for one worker: `max_depth` caps the scene's `nbounces`, `method` places the path
    /// tracer's samples (the render's pixel sampler), `cancel` (when set from any thread) stops it
    /// within a sample.
    pub fn tracer(
        &'a self,
        max_depth: u32,
        options: TraceOptions,
        method: Method,
        cancel: Option<&'a AtomicBool>,
    ) -> Tracer<'a> {
        match &self.emitters {
            None => {
                let mut w = Whitted::new(
                    self.scene,
                    self.accel,
                    &self.interiors,
                    max_depth,
                    options,
                    method,
                )
                .with_light_buffers(&self.light_buffers);
                w.cancel = cancel;
                Tracer::Whitted(w)
            }
            Some(e) => Tracer::Path(path::PathTracer::new(
                self.scene, self.accel, e, max_depth, options, method, cancel,
            )),
        }
    }
}

/// Traces camera rays for one worker, with the render's integrator. One is made per worker and
/// tile, so the variants' difference in size costs nothing, where boxing the larger one would
/// add a pointer to follow at every camera sample.
#[allow(clippy::large_enum_variant)]
pub enum Tracer<'a> {
    Whitted(Whitted<'a>),
    Path(path::PathTracer<'a>),
}

impl Tracer<'_> {
    /// Radiance along a camera ray, finite and ≥ 0 in every channel.
    #[inline]
    pub fn trace_camera(&mut self, ray: &Ray, key: &SampleKey) -> Vec3 {
        match self {
            Tracer::Whitted(t) => t.trace_camera(ray, key),
            Tracer::Path(t) => t.trace_camera(ray, key),
        }
    }

    /// Whether its camera samples' keys are read: always by the path tracer; by the Whitted
    /// tracer only where a shading point may draw a sample ([`whitted::Whitted::draws`]).
    #[inline]
    pub fn reads_keys(&self) -> bool {
        match self {
            Tracer::Whitted(t) => t.draws(),
            Tracer::Path(_) => true,
        }
    }

    /// The rays traced so far.
    pub fn counts(&self) -> RayCounts {
        match self {
            Tracer::Whitted(t) => t.counts,
            Tracer::Path(t) => t.counts,
        }
    }

    /// Whether the render was cancelled: the radiance of the sample in progress is then
    /// meaningless and must be thrown away.
    #[inline]
    pub fn cancelled(&self) -> bool {
        match self {
            Tracer::Whitted(t) => t.cancelled(),
            Tracer::Path(t) => t.cancelled(),
        }
    }
}

/// A light exactly on a surface (an area light drawn onto a ceiling) must not be shadowed by that
/// surface: shadow rays stop this fraction of their length short of the light.
pub const LIGHT_CLEARANCE: f32 = 1e-4;

/// What reaches the film: NaN channels (0·∞ in extreme scenes) become 0, infinite or negative
/// ones are clamped to [0, f32::MAX], so a blown-out pixel stays white rather than turning black.
#[inline]
pub fn finite_radiance(c: Vec3) -> Vec3 {
    let fix = |x: f32| {
        if x.is_nan() {
            0.0
        } else {
            x.clamp(0.0, f32::MAX)
        }
    };
    Vec3::new(fix(c.x), fix(c.y), fix(c.z))
}

/// The POV-Ray default `adc_bailout`: one 8-bit step.
pub const DEFAULT_CUTOFF: f32 = 1.0 / 255.0;

/// Changes to how a [`Tracer`] samples lights and prunes the ray tree. The default changes
/// nothing: every light is sampled as its scene says and every ray is traced.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TraceOptions {
    /// Sample every area light with this method instead of its own.
    pub light_method: Option<Method>,
    /// Take this many shadow rays per shading point towards every area light instead of its own
    /// count (the total, whatever the method).
    pub light_samples: Option<u32>,
    /// Probe a 3×3 grid on each area light first and skip its other shadow rays where the probes
    /// agree (see [`whitted`]).
    pub adaptive_lights: bool,
    /// Do not trace reflection or refraction rays whose accumulated weight is below this.
    pub cutoff: Option<f32>,
}

impl TraceOptions {
    /// Shadow rays per shading point and their placement for `light`.
    pub fn light_plan(&self, light: &Light) -> (u32, Method) {
        if light.is_point() {
            (1, light.method())
        } else {
            (
                self.light_samples.unwrap_or(light.sample_count()).max(1),
                self.light_method.unwrap_or(light.method()),
            )
        }
    }
}

/// Counts of the rays traced, by kind.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayCounts {
    pub camera: u64,
    pub secondary: u64,
    pub shadow: u64,
}

impl RayCounts {
    pub fn total(&self) -> u64 {
        self.camera + self.secondary + self.shadow
    }

    pub fn add(&mut self, o: &RayCounts) {
        self.camera += o.camera;
        self.secondary += o.secondary;
        self.shadow += o.shadow;
    }
}
