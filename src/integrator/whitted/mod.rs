//! Whitted-style recursive ray tracing: Blinn-Phong direct lighting with shadow rays, mirror
//! reflection, and refraction with Fresnel weighting and total internal reflection, bounded by
//! the scene's `nbounces`.
//!
//! For a hit with material `m`, base colour `c` (texture or `diffusecolor`), view direction `v`
//! and shading normal `n` turned towards the viewer (surfaces are two-sided):
//!
//! ```text
//! L = Le + ka·A·c + Σ_lights Σ_samples w·V·E(d)·( kd·c·id·max(0, n·l) + ks·specularcolor·is·max(0, n·h)^p )
//!   + (kr + kt·F)·L(reflected)  +  kt·(1 − F)·L(refracted)
//! ```
//! A rough mirror (a material `roughness`) reflects about a half vector drawn from its
//! Blinn-Phong lobe, one direction per camera sample, so the pixel's samples blur the
//! reflection; the weight stays `kr + kt·F`.
//! where `Le` is the material's emitted radiance (an `emissive` material; 0 otherwise), `A` the
//! scene's ambient light (0 unless the file gives one, or the file is CGR). In
//! CGR files an opaque mirror blends instead ([`Reflection::Blended`]): its own terms are scaled by
//! `1 − kr`, so that a `reflectivity` 1 mirror shows only what it reflects.
//! Above, `E(d)` is the light's fall-off, `w` the sample's share of the light (`1/n` of
//! [`crate::light::LightSample::weight`]), `V` the shadow ray's transmittance (opaque blockers
//! give 0, a transmissive one multiplies by its `kt`; a light's own shape passes),
//! `h = normalize(l + v)`, and `F` the dielectric Fresnel reflectance (1 under total
//! internal reflection). Reflection and refraction are traced only while the depth is below
//! `nbounces`.
//!
//! The ray tree is walked with an explicit stack of open shading points rather than by recursion,
//! so `nbounces` is not limited by the thread's stack: the walk is the recursion's, depth first
//! with the refracted ray's subtree before the reflected ray, every shading point's radiance
//! complete before it is scaled into its parent's, so the sums are the same to the bit. The
//! stack never holds more than [`MAX_SECONDARY_RAYS_PER_SAMPLE`] + 1 shading points, as each one
//! past the camera ray's costs a secondary ray of the sample's budget.
//!
//! Work a shading point does not need:
//! - a shadow ray towards a light sample behind the side of the surface we see (`l · n ≤ 0`) is
//!   never traced: that sample contributes nothing, whatever the visibility. A quad light wholly
//!   behind (by a margin far above rounding) is not even sampled: no beam, no probes. Always on;
//!   it changes no pixel.
//! - a shadow ray towards a point light (any light of one shadow ray) whose terms at the point
//!   are zeros, whatever the visibility, is not traced either: a mirror or glass of `kd = 0`
//!   away from its highlight, where the power underflows to zero. Likewise a quad light none
//!   of whose samples lights such a point gets no beam and no shadow ray
//!   (`Quad::highlight_may_show`). Always on; it changes no pixel. Under the cut-off below,
//!   point lights' terms too faint to matter go too (`negligible`: less than `cutoff / 64`
//!   of radiance per level of the ray tree, all lights together).
//! - [`TraceOptions::adaptive_lights`] (opt-in): before an area light's `n > 9` shadow rays, nine
//!   probes towards a 3×3 grid over it (corners, edge midpoints, centre); if they all see the same
//!   transmittance the light is taken to be uniformly visible (all `n` samples are shaded with
//!   that transmittance, or skipped when it is 0) and only the probes are traced. Penumbrae, where
//!   the probes disagree, get all `n` rays. This is POV-Ray's `adaptive` area-light idea (test a
//!   coarse set first, refine where it disagrees) cut to one level; it misses occluders that fit
//!   between the probes' rays.
//! - [`TraceOptions::cutoff`]: a reflection or refraction ray whose accumulated weight (the
//!   product of the `kr + kt·F` and `kt·(1 − F)` factors down the tree) is below the cut-off is not
//!   traced, as POV-Ray's `adc_bailout` does; at 1/255 a branch then cannot change an 8-bit pixel
//!   unless its radiance is above 1. The command line sets it to
//!   [`DEFAULT_CUTOFF`](super::DEFAULT_CUTOFF) unless `--no-skip` (the library's default traces
//!   every ray).

use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::accel::aabb::Aabb;
use crate::accel::{Accel, Beam, Inside, Interiors, LightBuffer, Reachable};
use crate::light::{Light, LightSample};
use crate::material::{highlight, Reflection};
use crate::math::{fresnel_dielectric, local_to_world, reflect, refract, Vec2, Vec3};
use crate::ray::{Ray, Side, SpawnPoints};
use crate::sampling::{blinn_phong_half_vector, CameraSamples, Method, SampleKey};
use crate::scene::{RenderMode, Scene};

use super::{finite_radiance, RayCounts, TraceOptions, LIGHT_CLEARANCE};

mod quad_lanes;

use quad_lanes::{Quad, Shading};

/// Shadow rays towards one area light between two looks at [`Whitted::cancel`]: one look is one
/// relaxed load, small beside this many rays, and the longest stretch without one (an area light
/// of the largest allowed sample count) stays a small fraction of the ray count.
const SHADOW_RAYS_PER_CANCEL_CHECK: u32 = 256;

/// The padded sample dimension a rough mirror's reflected direction is drawn from (each shading
/// point has its own key, so one dimension serves every depth).
const ROUGH_MIRROR_DIMENSION: u64 = 0x6d69_7272;

/// Colour of a hit in `rendermode: binary` (misses are black), as in the CGR specification.
pub const BINARY_HIT: Vec3 = Vec3::new(1.0, 0.0, 0.0);

/// Most primitives an area light's shadow rays from one point test one by one (see [`Beam`]);
/// past this many the whole accelerator is queried instead, which for a tree of that size costs
/// about as much.
const BEAM_CANDIDATE_LIMIT: usize = 16;

/// Most transmissive surfaces a shadow ray passes through before it counts as blocked.
const MAX_SHADOW_CROSSINGS: u32 = 32;

/// Most reflection and refraction rays one camera sample may spawn. Every glass hit splits into
/// two rays, so a tree of `nbounces` levels can hold 2^nbounces rays (facing glass panes at
/// `nbounces: 50` would never finish); past this budget a branch returns only its direct light.
/// A tree of 12 full levels fits, and no test or bundled scene reaches it.
pub const MAX_SECONDARY_RAYS_PER_SAMPLE: u32 = 4096;

/// Probe points of [`TraceOptions::adaptive_lights`]: a 3×3 grid over the light (corners, edge
/// midpoints, centre), the outer ones inset slightly so that a light whose edge touches a wall is
/// not probed through the wall. Corners alone (POV-Ray's first level) miss an occluder smaller
/// than the light that hides its middle: the umbra under it vanishes.
const ADAPTIVE_PROBES: [Vec2; 9] = {
    const E: f32 = 1e-3;
    [
        Vec2::new(E, E),
        Vec2::new(0.5, E),
        Vec2::new(1.0 - E, E),
        Vec2::new(E, 0.5),
        Vec2::new(0.5, 0.5),
        Vec2::new(1.0 - E, 0.5),
        Vec2::new(E, 1.0 - E),
        Vec2::new(0.5, 1.0 - E),
        Vec2::new(1.0 - E, 1.0 - E),
    ]
};

/// The spheres a Whitted ray can start inside of, for [`Whitted::interiors`]: the transmissive
/// ones, which refracted rays enter and then reflect inside.
pub fn interiors(scene: &Scene, accel: &Accel) -> Interiors {
    Interiors::new(&scene.primitives, accel, |p| {
        scene.materials[p.material as usize].is_transmissive()
    })
}

/// Per light, the [`LightBuffer`] that stands in for the tree's walk when gathering a shading
/// point's beam candidates: for every light with a box of samples (the area lights); `None` for
/// point lights, and empty for a scene without area lights.
pub fn light_buffers(scene: &Scene, accel: &Accel) -> Vec<Option<LightBuffer>> {
    if scene.lights.iter().all(|l| l.bounds().is_none()) {
        return Vec::new();
    }
    let bounds = scene.primitives.bounds();
    let buffer = |b: Aabb| {
        let (centre, radius) = b.ball();
        LightBuffer::new(centre, radius, &scene.primitives, accel, &bounds)
    };
    scene
        .lights
        .iter()
        .map(|l| l.bounds().map(buffer))
        .collect()
}

/// The light terms a shading point leaves untraced under the cut-off are below
/// `cutoff / LIGHT_CUT_FRACTION` of radiance, shared among the scene's lights (see
/// [`negligible`]).
const LIGHT_CUT_FRACTION: f32 = 64.0;

/// Whether a light sample's terms, `diffuse · (n·l · e)` and `specular · (spec · e)` with
/// `e = unblocked · visibility` (the visibility in `[0, 1]`), can be left out without tracing
/// the shadow ray that finds the visibility:
///
/// - **exactly**, whatever `least`, where both terms are zeros for every visibility: the
///   diffuse colour is zero and so is the highlight (or its colour). Adding them would leave the
///   colour as it is. The common case is a mirror or glass (`kd = 0`) away from its highlight,
///   where `spec` underflows to zero (`0.597^200` does). With `unblocked` finite, `e` is finite,
///   and a product of zero with a finite number is a zero; a visibility below one only shrinks
///   a product that already rounds to zero. An infinite or NaN `unblocked` always goes to the
///   full computation.
/// - **below the cut-off**, where the unblocked terms are below `least` (the light's
///   [`Whitted::light_cut`]) in every channel. A pixel's sum then loses less than
///   `cutoff / LIGHT_CUT_FRACTION` of radiance per level of its ray tree, all lights together
///   (the weights of a level's shading points sum to at most one where `kr + kt ≤ 1`): with the
///   default cut-off of 1/255 and `nbounces` up to 14, under a quarter of an 8-bit step.
///   `least` is 0 without a cut-off (`--no-skip`), and only the exact case remains.
#[inline(always)]
fn negligible(
    unblocked: f32,
    n_dot_l: f32,
    diffuse: Vec3,
    spec: f32,
    specular: Vec3,
    least: f32,
) -> bool {
    let zero =
        unblocked.is_finite() && diffuse == Vec3::ZERO && (spec == 0.0 || specular == Vec3::ZERO);
    // NaN compares false: a NaN term is never cut.
    zero || (least > 0.0
        && ((diffuse * n_dot_l + specular * spec) * unblocked)
            .abs()
            .max_element()
            < least)
}

/// A test that [`negligible`] may hold, from the diffuse term alone, before the highlight's
/// half vector and power are worked out: where it fails, so does [`negligible`] (for
/// non-negative colours, `n·l` and highlight, the diffuse term is a lower bound of the sum it
/// compares), and the shadow ray is traced as it always was.
#[inline(always)]
fn may_be_negligible(unblocked: f32, n_dot_l: f32, diffuse: Vec3, least: f32) -> bool {
    unblocked.is_finite()
        && (diffuse == Vec3::ZERO
            || (least > 0.0 && (diffuse.abs().max_element() * n_dot_l * unblocked).abs() < least))
}

/// A reflection or refraction ray not yet traced, and the factor its radiance is scaled by in
/// its parent's.
#[derive(Debug, Clone, Copy)]
struct Branch {
    ray: Ray,
    /// Depth of the shading point it leads to.
    depth: u32,
    key: SampleKey,
    /// Accumulated weight of the ray, for the cut-off.
    weight: f32,
    /// What its radiance is multiplied by at the point it leaves.
    factor: Vec3,
    /// The sphere the ray starts inside of, where [`Interiors`] answers its query.
    inside: Option<Inside>,
}

/// What the reflection and refraction rays of one shading point share.
struct Leaving<'s> {
    spawn: &'s SpawnPoints,
    /// The sphere of the hit, where [`Interiors`] knows it.
    sphere: Option<Inside>,
    /// Depth of the shading points the rays lead to.
    depth: u32,
    key: &'s SampleKey,
    /// Whether some shading point draws samples ([`Whitted::draws`]).
    draws: bool,
    /// The weight of the ray that reached the point.
    weight: f32,
}

impl Leaving<'_> {
    /// The ray in direction `dir`, scaled by `factor` in the point's radiance. Its sample key is
    /// stream `0x1000 + id` of the point's; where nothing draws a sample the keys are never read,
    /// and the point's stands in. (A method rather than a closure: called from two places, a
    /// closure was left out of line, a call per ray.)
    #[inline(always)]
    fn branch(&self, dir: Vec3, id: u64, factor: f32) -> Branch {
        Branch {
            ray: self.spawn.ray(dir),
            inside: self.sphere.filter(|_| self.spawn.side(dir) == Side::Below),
            depth: self.depth,
            key: if self.draws {
                self.key.stream(0x1000 + id)
            } else {
                *self.key
            },
            weight: self.weight * factor,
            factor: Vec3::splat(factor),
        }
    }
}

/// What a shadow ray's any-hit query notes of the surfaces it hits, in a scene with transmissive
/// ones: how many it passes (its own light's and transmissive ones), whether any is
/// transmissive, and whether every one of those lets everything through (`kt = 1`).
#[derive(Debug, Clone, Copy)]
struct Passage {
    passed: u32,
    crosses: bool,
    clear: bool,
}

impl Default for Passage {
    fn default() -> Passage {
        Passage {
            passed: 0,
            crosses: false,
            clear: true,
        }
    }
}

impl Passage {
    /// Notes a hit on primitive `p`: whether it stops the ray, as an opaque surface that is not
    /// part of the light (`surface`) does.
    #[inline]
    fn blocked_by(&mut self, scene: &Scene, surface: &Range<u32>, p: u32) -> bool {
        self.passed += 1;
        if surface.contains(&p) {
            return false;
        }
        let material = &scene.materials[scene.primitives.material(p) as usize];
        let transmissive = material.is_transmissive();
        self.crosses |= transmissive;
        self.clear &= material.kt == 1.0;
        !transmissive
    }

    /// Whether a ray that nothing blocked sees all of the light without walking its crossings:
    /// with no transmissive surface on the way, or only ones of kt = 1 that the walk could not
    /// cross more than its limit of times (a primitive is crossed at most twice by a line), the
    /// product is 1.
    #[inline]
    fn settled(&self) -> bool {
        !self.crosses || (self.clear && 2 * self.passed <= MAX_SHADOW_CROSSINGS)
    }
}

/// A shading point whose reflection and refraction rays are not all traced yet. Its untraced
/// rays wait on [`Whitted::pending`], the next one on top.
#[derive(Debug, Clone, Copy)]
struct Open {
    /// Direct light plus the scaled radiance of the branches finished so far.
    color: Vec3,
    /// Factor of this point's radiance in its parent's.
    factor: Vec3,
    /// Its rays still on [`Whitted::pending`].
    pending: u32,
}

/// Traces Whitted ray trees through one scene. Cheap to create; one per worker.
pub struct Whitted<'a> {
    pub scene: &'a Scene,
    pub accel: &'a Accel,
    /// Quick closest hits for rays that start inside glass spheres: the table [`interiors`]
    /// builds, which holds the transmissive spheres and no other primitive.
    pub interiors: &'a Interiors,
    /// Cap on recursion on top of the scene's `nbounces`.
    pub max_depth: u32,
    options: TraceOptions,
    /// How the pixel's camera samples are placed: an area light's jittered cells spread their
    /// points over the camera samples in the same way ([`SampleKey::light_set`]); remade when a
    /// camera sample's count of samples per pixel differs.
    camera: CameraSamples,
    pub counts: RayCounts,
    /// When set (from any thread), tracing stops at the next shading point or batch of shadow
    /// rays and the radiance returned is meaningless; the caller must throw the sample away.
    pub cancel: Option<&'a AtomicBool>,
    /// Secondary rays left for the current camera sample.
    budget: u32,
    /// The open shading points of the current camera sample, kept to reuse its memory.
    open: Vec<Open>,
    /// Their untraced rays: the top point's next ray on top (a refracted ray above the reflected
    /// ray of the same point), kept to reuse its memory.
    pending: Vec<Branch>,
    /// Per light, the box its samples lie in (for [`Beam`]s); `None` for point lights.
    light_bounds: Vec<Option<Aabb>>,
    /// Per light, the light buffer its beams' candidates come from, where it has one
    /// ([`light_buffers`]; none unless given, [`Whitted::with_light_buffers`]).
    light_buffers: &'a [Option<LightBuffer>],
    /// The candidates of the current light's beam, kept to reuse their memory.
    candidates: Vec<u32>,
    /// Of those, the ones a ray from either spawn origin may reach ([`Side`] as index).
    reachable: [Reachable; 2],
    /// Whether quad lights take their samples four at a time ([`quad_lanes`]); only the
    /// tests that hold the lanes to the one-sample loop turn it off.
    lanes: bool,
    /// Whether some shading point may draw a sample (an area light of more than one shadow ray,
    /// a rough mirror). Where none can, the branches' sample keys are never read and not
    /// derived.
    draws: bool,
    /// What a light's unblocked terms at a shading point must reach to be traced and added
    /// (see [`negligible`]): `cutoff / (LIGHT_CUT_FRACTION · lights)`, 0 without a cut-off.
    light_cut: f32,
}

impl<'a> Whitted<'a> {
    pub fn new(
        scene: &'a Scene,
        accel: &'a Accel,
        interiors: &'a Interiors,
        max_depth: u32,
        options: TraceOptions,
        pixel_method: Method,
    ) -> Whitted<'a> {
        let draws = scene.materials.iter().any(|m| m.has_rough_mirror())
            || scene.lights.iter().any(|l| options.light_plan(l).0 > 1);
        let light_cut = options.cutoff.map_or(0.0, |c| {
            c / (LIGHT_CUT_FRACTION * scene.lights.len().max(1) as f32)
        });
        Whitted {
            scene,
            accel,
            interiors,
            max_depth,
            options,
            camera: CameraSamples::new(pixel_method, 1),
            counts: RayCounts::default(),
            cancel: None,
            budget: MAX_SECONDARY_RAYS_PER_SAMPLE,
            open: Vec::new(),
            pending: Vec::new(),
            light_bounds: scene.lights.iter().map(Light::bounds).collect(),
            light_buffers: &[],
            candidates: Vec::new(),
            reachable: Default::default(),
            lanes: true,
            draws,
            light_cut,
        }
    }

    /// The tracer gathering its beams' candidates from `buffers` ([`light_buffers`] of the same
    /// scene and accelerator) where they have a list: the same candidates' answers, without a
    /// walk of the tree at every shading point.
    pub fn with_light_buffers(mut self, buffers: &'a [Option<LightBuffer>]) -> Whitted<'a> {
        self.light_buffers = buffers;
        self
    }

    /// Whether some shading point may draw a sample: an area light of more than one shadow ray,
    /// or a rough mirror. Where none can, no sample key is read.
    #[inline]
    pub fn draws(&self) -> bool {
        self.draws
    }

    /// Whether [`Whitted::cancel`] is set.
    #[inline]
    pub fn cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
    }

    /// Radiance along a camera ray.
    pub fn trace_camera(&mut self, ray: &Ray, key: &SampleKey) -> Vec3 {
        self.counts.camera += 1;
        self.budget = MAX_SECONDARY_RAYS_PER_SAMPLE;
        let c = self.radiance(ray, key);
        finite_radiance(c)
    }

    /// Radiance along a camera ray: the ray tree walked depth first, each shading point's
    /// radiance added, scaled, to its parent's once all its branches are done.
    fn radiance(&mut self, ray: &Ray, key: &SampleKey) -> Vec3 {
        let mut pending = std::mem::take(&mut self.pending);
        pending.clear();
        let color = self.shade(ray, 0, key, 1.0, None, &mut pending);
        if pending.is_empty() {
            self.pending = pending;
            return color;
        }
        let mut open = std::mem::take(&mut self.open);
        open.clear();
        open.push(Open {
            color,
            factor: Vec3::ONE,
            pending: pending.len() as u32,
        });
        let result = loop {
            let Some(top) = open.last_mut() else {
                break Vec3::ZERO; // not reached: the camera ray's point is popped last
            };
            if top.pending == 0 {
                let (color, factor) = (top.color, top.factor);
                open.pop();
                match open.last_mut() {
                    Some(parent) => parent.color += factor * color,
                    None => break color,
                }
                continue;
            }
            top.pending -= 1;
            let Some(branch) = pending.pop() else {
                break Vec3::ZERO; // not reached: every open point's rays are on the stack
            };
            if self.budget == 0 {
                top.color += branch.factor * Vec3::ZERO;
                continue;
            }
            if self.cancelled() {
                break Vec3::ZERO;
            }
            self.budget -= 1;
            self.counts.secondary += 1;
            let before = pending.len();
            let color = self.shade(
                &branch.ray,
                branch.depth,
                &branch.key,
                branch.weight,
                branch.inside,
                &mut pending,
            );
            let rays = (pending.len() - before) as u32;
            if rays == 0 {
                top.color += branch.factor * color;
            } else {
                open.push(Open {
                    color,
                    factor: branch.factor,
                    pending: rays,
                });
            }
        };
        self.open = open;
        self.pending = pending;
        result
    }

    /// The direct light at the point `ray` hits at `depth` and the reflection and refraction rays
    /// it spawns; `weight` is the share of the camera sample's value the ray carries (for the
    /// cut-off), and `inside` the sphere it starts inside of, if [`Interiors`] knows it.
    /// The rays are pushed onto `pending`, the reflected one and then the refracted one, so that
    /// the refracted one is taken first; the point is finished when it pushes none.
    fn shade(
        &mut self,
        ray: &Ray,
        depth: u32,
        key: &SampleKey,
        weight: f32,
        inside: Option<Inside>,
        pending: &mut Vec<Branch>,
    ) -> Vec3 {
        let scene = self.scene;
        let prims = &scene.primitives;
        let found = match inside {
            Some(i) => self
                .interiors
                .closest(self.accel, prims, i, ray, f32::INFINITY),
            None => self.accel.closest(prims, ray, f32::INFINITY),
        };
        let Some((prim, cand)) = found else {
            return match scene.mode {
                RenderMode::Binary => Vec3::ZERO,
                RenderMode::Phong | RenderMode::Path => scene.background,
            };
        };
        if scene.mode == RenderMode::Binary {
            return BINARY_HIT;
        }
        let primitive = prims.get(prim);
        let material = &scene.materials[primitive.material as usize];
        let hit = primitive.hit_with(ray, cand, prim, prims.meshes(), material.texture.is_some());
        let front = hit.normal.dot(ray.dir) < 0.0;
        let (n, ns) = if front {
            (hit.normal, hit.shading_normal)
        } else {
            (-hit.normal, -hit.shading_normal)
        };
        let v = -ray.dir;
        let base = match material.texture {
            Some(t) => scene.textures[t as usize].sample_at(hit.uv, hit.point),
            None => material.diffuse,
        };

        // What the surface's own terms may reflect: blended (CGR) files scale them by the share
        // the mirror and glass leave; the others add the mirror and glass to them, so each term
        // is capped at that share instead (`docs/scene-format.md`, "Energy").
        let shares = material.shares();
        let (own_scale, budget) = match scene.reflection {
            Reflection::Blended => (shares.own, 1.0),
            Reflection::Added => (1.0, shares.own),
        };
        let own = material.own_terms(base, budget);
        let mut color = if scene.ambient == Vec3::ZERO {
            Vec3::ZERO
        } else {
            own.ambient * scene.ambient
        };
        let spawn = hit.spawn_points();
        let shading = Shading {
            point: hit.point,
            spawn: &spawn,
            n,
            ns,
            v,
            kd_base: own.diffuse,
            ks_specular: material.ks * material.specular,
            has_highlight: material.ks > 0.0,
            exponent: material.exponent,
        };
        // A surface that shows only what it reflects and transmits needs no shadow rays.
        let lights = if own_scale > 0.0 {
            &scene.lights[..]
        } else {
            &[]
        };
        for (li, light) in lights.iter().enumerate() {
            let (count, method) = self.options.light_plan(light);
            if count == 1 {
                // One shadow ray, towards the light's centre (`sample_one`): no point is drawn.
                if self.cancelled() {
                    return color;
                }
                let sample = light.sample_one(hit.point);
                let surface = light.surface();
                let cut = Some(self.light_cut);
                self.add_sample(
                    &mut color, &shading, light, &surface, &sample, 1.0, None, None, cut,
                );
            } else if !self.area_light(&mut color, &shading, li, light, count, method, key) {
                return color; // cancelled
            }
        }

        if own_scale < 1.0 {
            color *= own_scale;
        }
        if material.emission != Vec3::ZERO {
            color += material.emission;
        }
        if depth >= scene.nbounces.min(self.max_depth) {
            return color;
        }
        // A ray leaving below a sphere's surface starts inside it. Only transmissive spheres are
        // in the table ([`interiors`]): for any other material no search is needed.
        let sphere = if material.is_transmissive() {
            self.interiors.of(prim)
        } else {
            None
        };
        let leaving = Leaving {
            spawn: &spawn,
            sphere,
            depth: depth + 1,
            key,
            draws: self.draws,
            weight,
        };
        let mut reflect_weight = shares.mirror;
        let mut refracted = None;
        if shares.glass > 0.0 {
            let eta = if front {
                1.0 / material.eta
            } else {
                material.eta
            };
            let cos_i = -ray.dir.dot(n);
            let f = fresnel_dielectric(cos_i, eta);
            reflect_weight += shares.glass * f;
            let transmit = shares.glass * (1.0 - f);
            if transmit > 0.0 && self.worth_tracing(weight * transmit) {
                if let Some(t) = refract(ray.dir, n, eta) {
                    let mut b = leaving.branch(t, 2, transmit);
                    b.factor *= material.transmit; // a coloured glass's tint
                    refracted = Some(b);
                }
            }
        }
        if reflect_weight > 0.0 && self.worth_tracing(weight * reflect_weight) {
            let mut r = reflect(ray.dir, n).normalize();
            if material.has_rough_mirror() {
                // Distribution ray tracing (Cook, Porter and Carpenter, "Distributed Ray
                // Tracing", SIGGRAPH 1984): one reflected ray per camera sample, about a half
                // vector drawn from the mirror's lobe, stratified over the pixel's samples.
                let u = key.padded(Method::Sobol, ROUGH_MIRROR_DIMENSION, 0, 1);
                let h = local_to_world(ns, blinn_phong_half_vector(material.mirror_exponent, u));
                let blurred = reflect(ray.dir, h).normalize();
                if blurred.dot(n) > 0.0 {
                    r = blurred; // else the mirror direction, rather than into the surface
                }
            }
            pending.push(leaving.branch(r, 1, reflect_weight));
        }
        if let Some(b) = refracted {
            pending.push(b);
        }
        color
    }

    /// Adds to `color` the terms of the `count > 1` samples of `light` (light `li`) at the shading
    /// point, each carrying `1/count` of what one sample alone would. `false` if the render was
    /// cancelled on the way (then `color` holds the samples before).
    ///
    /// Kept out of line, so that [`Whitted::shade`] stays small for point lights.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn area_light(
        &mut self,
        color: &mut Vec3,
        shading: &Shading,
        li: usize,
        light: &Light,
        count: u32,
        method: Method,
        key: &SampleKey,
    ) -> bool {
        let scene = self.scene;
        let spawn = shading.spawn;
        let share = 1.0 / count as f32;
        if self.camera.spp() != key.spp {
            self.camera = CameraSamples::new(self.camera.method, key.spp);
        }
        let points = key
            .stream(li as u64)
            .light_set(method, &self.camera, 0, count);
        let quad = Quad::of(light);
        if let Some(quad) = &quad {
            if quad.wholly_behind(shading.point, shading.n) {
                return true; // every sample is behind the side we see
            }
            // A mirror or glass away from the light's highlight: every sample's terms are zeros.
            let no_diffuse = shading.kd_base * light.intensity().diffuse == Vec3::ZERO;
            if no_diffuse && !quad.highlight_may_show(shading, &points, count, share) {
                return true;
            }
        }
        let surface = light.surface();
        let known = if self.options.adaptive_lights && count > ADAPTIVE_PROBES.len() as u32 {
            self.uniform_visibility(shading, light, &surface)
        } else {
            None
        };
        if known == Some(0.0) {
            return true; // every probe is blocked: the light is taken as fully hidden
        }
        // The primitives this light's shadow rays may meet, once for all of them, and of
        // those the ones the rays from each spawn origin may meet.
        let mut candidates = std::mem::take(&mut self.candidates);
        let mut reachable = std::mem::take(&mut self.reachable);
        let only = known
            .is_none()
            .then(|| self.light_bounds[li])
            .flatten()
            .and_then(|b| Beam::new(shading.point, &b, spawn.offset()))
            .filter(|beam| {
                let prims = &scene.primitives;
                let limit = BEAM_CANDIDATE_LIMIT;
                let buffer = self.light_buffers.get(li).and_then(Option::as_ref);
                buffer
                    .and_then(|b| {
                        let (point, offset) = (shading.point, spawn.offset());
                        b.beam_candidates(beam, point, offset, limit, &mut candidates)
                    })
                    .unwrap_or_else(|| {
                        self.accel
                            .beam_candidates(prims, beam, limit, &mut candidates)
                    })
            })
            .map(|beam| {
                let origins = [Side::Above, Side::Below].map(|side| spawn.origin_on(side));
                Reachable::fill_each(
                    &mut reachable,
                    &scene.primitives,
                    &beam,
                    &candidates,
                    &origins,
                );
                [&reachable[0], &reachable[1]]
            });
        let done = match (quad, known, self.lanes) {
            (Some(quad), None, true) => {
                self.quad_light_lanes(color, shading, &quad, &points, count, share, &surface, only)
            }
            _ => (0..count).all(|s| {
                if s % SHADOW_RAYS_PER_CANCEL_CHECK == 0 && self.cancelled() {
                    return false;
                }
                let sample = light.sample(shading.point, points.point(s));
                self.add_sample(
                    color, shading, light, &surface, &sample, share, known, only, None,
                );
                true
            }),
        };
        self.candidates = candidates;
        self.reachable = reachable;
        done
    }

    /// Adds to `color` the diffuse and highlight terms of one light sample, of `share` of the
    /// light (whose own primitives are `surface`), seen through the transmittance towards it
    /// (or `known`, where adaptive sampling found it; `only` as for
    /// [`Whitted::transmittance`]). Nothing for a sample behind the side of the surface we see:
    /// no shadow ray is traced for it. With `cut` (the least terms worth tracing, see
    /// [`negligible`]), nothing either for a sample whose terms are negligible.
    ///
    /// Only single-sample lights are cut: an area light's samples are traced as before, since
    /// testing them one by one (or four lanes at a time) cost `benches/peers/scenes` more
    /// instructions than the shadow rays it saved there.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn add_sample(
        &mut self,
        color: &mut Vec3,
        shading: &Shading,
        light: &Light,
        surface: &Range<u32>,
        sample: &LightSample,
        share: f32,
        known: Option<f32>,
        only: Option<[&Reachable; 2]>,
        cut: Option<f32>,
    ) {
        let to_light = sample.position - shading.point;
        if to_light.dot(shading.n) <= 0.0 {
            return; // the light is behind the side we see: no shadow ray needed
        }
        let d2 = to_light.length_squared();
        let intensity = light.intensity();
        let l = to_light / d2.sqrt();
        // The sample's terms as if nothing were in the way; the transmittance only scales them.
        let unblocked = share * sample.weight * intensity.falloff(sample.falloff_d2);
        let n_dot_l = shading.ns.dot(l).max(0.0);
        let diffuse = shading.kd_base * intensity.diffuse;
        let highlight_terms = || {
            let h = (l + shading.v).normalize_or_zero();
            let spec = highlight(shading.ns.dot(h).max(0.0), shading.exponent);
            (shading.ks_specular * intensity.specular, spec)
        };
        let mut terms = None;
        if let Some(least) = cut {
            if may_be_negligible(unblocked, n_dot_l, diffuse, least) {
                let (specular, spec) = if shading.has_highlight {
                    *terms.insert(highlight_terms())
                } else {
                    (Vec3::ZERO, 0.0)
                };
                if negligible(unblocked, n_dot_l, diffuse, spec, specular, least) {
                    return; // e.g. a mirror or glass away from its highlight: no shadow ray
                }
            }
        }
        let visibility = match known {
            Some(v) => v,
            None => self.transmittance(shading.spawn, sample.position, surface, only),
        };
        if visibility == 0.0 {
            return;
        }
        let e = unblocked * visibility;
        *color += diffuse * (n_dot_l * e);
        if shading.has_highlight {
            let (specular, spec) = terms.unwrap_or_else(highlight_terms);
            *color += specular * (spec * e);
        }
    }

    /// Whether a secondary ray of accumulated `weight` passes the cut-off (always, without one).
    #[inline]
    fn worth_tracing(&self, weight: f32) -> bool {
        self.options.cutoff.is_none_or(|c| weight >= c)
    }

    /// Adaptive area-light sampling: the transmittance the light's probe points all see from
    /// the shading point, or `None` when they disagree or a probe point is behind the surface.
    fn uniform_visibility(
        &mut self,
        shading: &Shading,
        light: &Light,
        surface: &Range<u32>,
    ) -> Option<f32> {
        let mut seen = None;
        for u in ADAPTIVE_PROBES {
            let p = light.sample(shading.point, u).position;
            if (p - shading.point).dot(shading.n) <= 0.0 {
                return None;
            }
            let v = self.transmittance(shading.spawn, p, surface, None);
            match seen {
                None => seen = Some(v),
                Some(s) if s != v => return None,
                Some(_) => {}
            }
        }
        seen
    }

    /// Fraction of light reaching the shading point of `from` from `target`: 0 behind an opaque
    /// surface, multiplied by `kt` for every transmissive surface crossed. The primitives in
    /// `surface` (the light's own, for a shape that emits) are passed through: a light is never
    /// its own shadow.
    ///
    /// One any-hit query answers most rays: it stops at the first opaque blocker (the answer is
    /// 0, whatever else lies on the way) and notes the transmissive surfaces the ray crosses; when
    /// it crosses none, or only surfaces of `kt = 1` (a product of ones, whatever their order
    /// and number within the crossing limit), the answer is 1. Only rays through glass of
    /// `kt < 1` and nothing opaque walk their crossings one closest hit at a time, as the
    /// product of `kt` needs.
    ///
    /// `only`, where given, lists every primitive the ray can meet when it leaves from either
    /// spawn origin (see [`Beam`]; [`Side`] as index); the any-hit query tests just those, and a
    /// ray that can meet none is not traced: its answer is 1.
    fn transmittance(
        &mut self,
        from: &SpawnPoints,
        target: Vec3,
        surface: &Range<u32>,
        only: Option<[&Reachable; 2]>,
    ) -> f32 {
        self.counts.shadow += 1;
        let side = from.side_to(target);
        let only = only.map(|lists| lists[side as usize]);
        if only.is_some_and(|c| c.is_empty()) {
            return 1.0; // what the query below answers when it has nothing to test
        }
        let (ray, dist) = from.ray_from(side, target);
        self.transmittance_along(&ray, dist, only, from, target, surface)
    }

    /// [`Whitted::transmittance`] for the ray `from` builds towards `target` (its
    /// [`SpawnPoints::ray_to`], `dist` long), already found (and counted), where `only` is the
    /// list of its side.
    #[inline(always)]
    fn transmittance_along(
        &mut self,
        ray: &Ray,
        dist: f32,
        only: Option<&Reachable>,
        from: &SpawnPoints,
        target: Vec3,
        surface: &Range<u32>,
    ) -> f32 {
        let scene = self.scene;
        let t_max = dist * (1.0 - LIGHT_CLEARANCE);
        if !scene.has_transmissive {
            let blocked = self.any_hit(only, ray, t_max, |p| !surface.contains(&p));
            return if blocked { 0.0 } else { 1.0 };
        }
        let mut passage = Passage::default();
        if self.any_hit(only, ray, t_max, |p| passage.blocked_by(scene, surface, p)) {
            return 0.0;
        }
        if passage.settled() {
            return 1.0;
        }
        self.walk_crossings(from, target, surface)
    }

    /// Whether `ray` hits a primitive for which `blocks` holds before `t_max`: among `only`
    /// where given (see [`Whitted::transmittance`]), else through the accelerator. Generic over
    /// `blocks`, so that each caller's test is inlined into the query, not called through a
    /// pointer at every primitive hit.
    #[inline(always)]
    fn any_hit(
        &self,
        only: Option<&Reachable>,
        ray: &Ray,
        t_max: f32,
        blocks: impl FnMut(u32) -> bool,
    ) -> bool {
        match only {
            Some(candidates) => candidates.any(ray, t_max, blocks),
            None => self.accel.any(&self.scene.primitives, ray, t_max, blocks),
        }
    }

    /// The transmittance towards `target` one closest hit at a time: the product of the `kt`
    /// of every surface crossed (the light's own passed through), 0 at an opaque one or past
    /// [`MAX_SHADOW_CROSSINGS`] crossings. What [`Whitted::transmittance`] falls back to for rays
    /// through glass of `kt < 1`.
    fn walk_crossings(&mut self, from: &SpawnPoints, target: Vec3, surface: &Range<u32>) -> f32 {
        let scene = self.scene;
        let prims = &scene.primitives;
        let (mut ray, dist) = from.ray_to(target);
        let mut t_max = dist * (1.0 - LIGHT_CLEARANCE);
        let mut through = 1.0;
        let mut inside = None;
        for _ in 0..MAX_SHADOW_CROSSINGS {
            let found = match inside {
                Some(i) => self.interiors.closest(self.accel, prims, i, &ray, t_max),
                None => self.accel.closest(prims, &ray, t_max),
            };
            let Some((p, c)) = found else {
                return through;
            };
            let prim = &prims.get(p);
            let material = &scene.materials[prim.material as usize];
            if !surface.contains(&p) {
                if !material.is_transmissive() {
                    return 0.0;
                }
                through *= material.kt;
            }
            let h = prim.hit_with(&ray, c, p, prims.meshes(), false);
            let spawn = h.spawn_points();
            let side = spawn.side_to(target);
            let (next, d) = spawn.ray_from(side, target);
            inside = self.interiors.of(p).filter(|_| side == Side::Below);
            ray = next;
            t_max = d * (1.0 - LIGHT_CLEARANCE);
        }
        0.0
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::accel::kernels::twin::Rng;
    use crate::accel::AccelKind;
    use crate::integrator::DEFAULT_CUTOFF;
    use crate::scene::{load_str, LoadOptions};

    /// Zero a quarter of the time, else in `[0, 1)`.
    fn often_zero(d: &mut Rng) -> f32 {
        if d.next() < 0.25 {
            0.0
        } else {
            d.next()
        }
    }

    /// Black half of the time, else a colour whose first channel is often zero.
    fn colour(d: &mut Rng) -> Vec3 {
        if d.next() < 0.5 {
            Vec3::ZERO
        } else {
            Vec3::new(often_zero(d), d.next(), d.next())
        }
    }

    /// Where [`negligible`] says so without a cut-off, both terms are zeros for every visibility,
    /// computed as [`Whitted::add_sample`] computes them, so leaving them out keeps every bit of
    /// the colour they would have been added to.
    #[test]
    fn negligible_terms_without_a_cutoff_are_exact_zeros() {
        let mut d = Rng(0x9e37_79b9_7f4a_7c15);
        let mut exact = 0;
        for _ in 0..200_000 {
            // Light strengths from far below one to far above, and the odd infinite one.
            let unblocked = match (d.next() * 8.0) as u32 {
                0 => f32::INFINITY,
                1 => 1e-30 * d.next(),
                2 => 1e30 * d.next(),
                _ => d.next() * 100.0,
            };
            let n_dot_l = often_zero(&mut d);
            let spec = highlight(
                often_zero(&mut d),
                [1.0, 30.0, 200.0, 1000.0][(d.next() * 4.0) as usize],
            );
            let (diffuse, specular) = (colour(&mut d), colour(&mut d));
            for least in [0.0, 1e-4] {
                if negligible(unblocked, n_dot_l, diffuse, spec, specular, least) {
                    assert!(may_be_negligible(unblocked, n_dot_l, diffuse, least));
                }
            }
            if !negligible(unblocked, n_dot_l, diffuse, spec, specular, 0.0) {
                continue;
            }
            exact += 1;
            let colour = Vec3::new(d.next(), 0.0, d.next() * 1e-3);
            for visibility in [1.0, d.next(), 1e-3 * d.next(), 0.0] {
                let e = unblocked * visibility;
                let mut c = colour;
                c += diffuse * (n_dot_l * e);
                c += specular * (spec * e);
                assert_eq!(
                    c.to_array().map(f32::to_bits),
                    colour.to_array().map(f32::to_bits),
                    "unblocked {unblocked}, n·l {n_dot_l}, diffuse {diffuse}, spec {spec}, \
                     specular {specular}, visibility {visibility}"
                );
            }
        }
        assert!(exact > 10_000, "{exact} negligible cases");
        // Not negligible: infinite or NaN strengths, and any term above zero.
        assert!(!negligible(
            f32::INFINITY,
            0.0,
            Vec3::ZERO,
            0.0,
            Vec3::ZERO,
            1.0
        ));
        assert!(!negligible(f32::NAN, 0.0, Vec3::ZERO, 0.0, Vec3::ZERO, 1.0));
        assert!(!negligible(1.0, 1e-20, Vec3::ONE, 0.0, Vec3::ZERO, 0.0));
        assert!(!negligible(1.0, 0.0, Vec3::ZERO, 1e-40, Vec3::ONE, 0.0));
        // With a cut-off: below it in every channel, not in one.
        assert!(negligible(
            1.0,
            0.5,
            Vec3::splat(1e-3),
            0.0,
            Vec3::ONE,
            1e-3
        ));
        assert!(!negligible(
            1.0,
            0.5,
            Vec3::new(1e-3, 1e-2, 0.0),
            0.0,
            Vec3::ONE,
            1e-3
        ));
    }

    /// Mirror and glass spheres of `kd = 0` with sharp highlights, a diffuse one and a floor,
    /// under a point light and a quad light.
    const SCENE: &str = r#"{
      "nbounces": 6,
      "rendermode": "phong",
      "camera": {"type": "pinhole", "width": 48, "height": 36, "fov": 50,
                 "position": [0, 2.5, 6], "lookat": [0, -0.3, -1], "up": [0, 1, 0]},
      "scene": {
        "backgroundcolor": [0.3, 0.35, 0.45],
        "lightsources": [
          {"type": "pointlight", "position": [-3, 6, 5], "intensity": [0.9, 0.9, 0.9]},
          {"type": "arealight", "v0": [1, 4, -1], "v1": [2, 4, -1], "v2": [2, 4, 0],
           "v3": [1, 4, 0], "samples": 3, "method": "jittered",
           "is": [0.4, 0.4, 0.4], "id": [0.4, 0.4, 0.4]}
        ],
        "shapes": [
          {"type": "plane", "v0": [-6, 0, 6], "v1": [6, 0, 6], "v2": [6, 0, -6], "v3": [-6, 0, -6],
           "material": {"kd": 0.8, "ks": 0.1, "specularexponent": 10,
                        "diffusecolor": [0.9, 0.9, 0.9], "specularcolor": [1, 1, 1]}},
          {"type": "sphere", "center": [-1.2, 0.8, 0], "radius": 0.8,
           "material": {"kd": 0, "ks": 0.6, "specularexponent": 200,
                        "diffusecolor": [1, 1, 1], "specularcolor": [1, 1, 1],
                        "isrefractive": true, "refractiveindex": 1.5}},
          {"type": "sphere", "center": [0.6, 0.8, -0.6], "radius": 0.8,
           "material": {"kd": 0, "ks": 0.2, "specularexponent": 200,
                        "diffusecolor": [1, 1, 1], "specularcolor": [1, 1, 1],
                        "isreflective": true, "reflectivity": 0.9}},
          {"type": "sphere", "center": [1.4, 0.4, 1.2], "radius": 0.4,
           "material": {"kd": 0.7, "ks": 0.3, "specularexponent": 40,
                        "diffusecolor": [0.8, 0.3, 0.2], "specularcolor": [1, 1, 1]}}
        ]
      }
    }"#;

    /// Every pixel's radiance (one sample at its centre) and the shadow rays traced, with the
    /// cut-off `cutoff`, the lanes on or off, and the light cut as [`Whitted::new`] sets it or
    /// (`light_cut: false`) at zero, where only exact zeros are left out.
    fn render(cutoff: Option<f32>, lanes: bool, light_cut: bool) -> (Vec<Vec3>, u64) {
        let scene = load_str(SCENE, Path::new("cut.json"), &LoadOptions::default()).unwrap();
        let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
        let interiors = interiors(&scene, &accel);
        let options = TraceOptions {
            cutoff,
            ..Default::default()
        };
        let mut w = Whitted::new(&scene, &accel, &interiors, 8, options, Method::Jittered);
        w.lanes = lanes;
        if !light_cut {
            w.light_cut = 0.0;
        }
        let mut pixels = Vec::new();
        for_each_pixel_centre(&scene, |_, _, key, ray| {
            pixels.push(w.trace_camera(ray, key))
        });
        (pixels, w.counts.shadow)
    }

    /// The radiance along `ray` by plain recursion over [`Whitted::shade`]: each point's
    /// refracted ray's subtree, then its reflected ray's, each scaled into the point's colour as
    /// it finishes, with the sample's budget of secondary rays spent in that order.
    fn recursive(
        w: &mut Whitted,
        ray: &Ray,
        depth: u32,
        key: &SampleKey,
        weight: f32,
        inside: Option<Inside>,
    ) -> Vec3 {
        let mut pending = Vec::new();
        let mut color = w.shade(ray, depth, key, weight, inside, &mut pending);
        // The refracted ray's subtree first: the one pushed last.
        for b in pending.into_iter().rev() {
            if w.budget == 0 {
                color += b.factor * Vec3::ZERO;
                continue;
            }
            w.budget -= 1;
            color += b.factor * recursive(w, &b.ray, b.depth, &b.key, b.weight, b.inside);
        }
        color
    }

    /// The explicit stack walks the ray tree as the recursion does: every pixel of a scene of
    /// glass and mirror spheres, eight bounces deep, the same bits, with and without the cut-off.
    #[test]
    fn the_walk_sums_as_the_recursion_does() {
        let scene = load_str(SCENE, Path::new("walk.json"), &LoadOptions::default()).unwrap();
        let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
        let interiors = interiors(&scene, &accel);
        for cutoff in [None, Some(DEFAULT_CUTOFF)] {
            let options = TraceOptions {
                cutoff,
                ..Default::default()
            };
            let mut w = Whitted::new(&scene, &accel, &interiors, 8, options, Method::Jittered);
            let mut deepest = 0;
            for_each_pixel_centre(&scene, |x, y, key, ray| {
                let walked = w.trace_camera(ray, key);
                w.budget = MAX_SECONDARY_RAYS_PER_SAMPLE;
                let reference =
                    crate::integrator::finite_radiance(recursive(&mut w, ray, 0, key, 1.0, None));
                deepest = deepest.max(MAX_SECONDARY_RAYS_PER_SAMPLE - w.budget);
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(
                    bits(walked),
                    bits(reference),
                    "pixel ({x}, {y}), {cutoff:?}"
                );
            });
            // Trees of several levels, so that the order of the sums is tested.
            assert!(deepest >= 4, "at most {deepest} secondary rays a pixel");
        }
    }

    /// Where no shading point draws a sample (point lights, smooth mirrors and glass: the glass
    /// peer scene), no sample key is read: every pixel is the same with a key that holds no hash
    /// ([`SampleKey::unread`], what a render passes such a tracer). Where one does (the area light
    /// of [`SCENE`]), the tracer says so.
    #[test]
    fn a_tracer_that_draws_no_sample_reads_no_key() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers/scenes/glass.json");
        let options = LoadOptions {
            width: Some(64),
            ..LoadOptions::default()
        };
        let scene = crate::scene::load(&path, &options).unwrap();
        let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
        let table = interiors(&scene, &accel);
        let options = TraceOptions::default();
        let mut w = Whitted::new(&scene, &accel, &table, 8, options, Method::Jittered);
        assert!(!w.draws());
        let mut lit = 0;
        for_each_pixel_centre(&scene, |x, y, key, ray| {
            let keyed = w.trace_camera(ray, key);
            let unread = w.trace_camera(ray, &SampleKey::unread(0, 1));
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            assert_eq!(bits(keyed), bits(unread), "pixel ({x}, {y})");
            lit += usize::from(keyed != scene.background);
        });
        assert!(lit > 1000, "{lit} pixels see the scene");
        let scene = load_str(SCENE, Path::new("draws.json"), &LoadOptions::default()).unwrap();
        let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
        let table = interiors(&scene, &accel);
        let w = Whitted::new(&scene, &accel, &table, 8, options, Method::Jittered);
        assert!(w.draws());
    }

    /// A point on glass pushes its reflected ray, then its refracted one, which is taken first:
    /// the order the walk and its sums follow. Checked on every camera ray that enters a glass
    /// sphere of [`SCENE`] (the refracted ray starts inside it, the reflected one outside).
    #[test]
    fn the_refracted_ray_is_pushed_last() {
        let scene = load_str(SCENE, Path::new("order.json"), &LoadOptions::default()).unwrap();
        let accel = Accel::build(&scene.primitives, AccelKind::Sah4, 4);
        let table = interiors(&scene, &accel);
        let options = TraceOptions::default();
        let mut w = Whitted::new(&scene, &accel, &table, 8, options, Method::Jittered);
        let mut entering = 0;
        for_each_pixel_centre(&scene, |x, y, key, ray| {
            let mut pending = Vec::new();
            w.shade(ray, 0, key, 1.0, None, &mut pending);
            if let [reflected, refracted] = pending.as_slice() {
                assert!(reflected.inside.is_none(), "pixel ({x}, {y})");
                entering += usize::from(refracted.inside.is_some());
            }
        });
        assert!(entering > 20, "{entering} camera rays enter glass");
    }

    /// Calls `f` with each pixel `(x, y)` of `scene`, row by row, its sample key (seed 7) and
    /// the camera ray through its centre.
    pub(super) fn for_each_pixel_centre(
        scene: &Scene,
        mut f: impl FnMut(u32, u32, &SampleKey, &Ray),
    ) {
        for y in 0..scene.camera.height {
            for x in 0..scene.camera.width {
                let key = SampleKey::new(x, y, 0, 1, 7);
                let ray = scene
                    .camera
                    .generate_ray(x, y, Vec2::splat(0.5), Vec2::splat(0.5));
                f(x, y, &key, &ray);
            }
        }
    }

    /// With the cut-off, light terms below it are left out: fewer shadow rays, and no pixel
    /// further from the render that traces them than `(nbounces + 1) · cutoff / 64`, the bound
    /// [`negligible`] states.
    #[test]
    fn the_light_cut_saves_shadow_rays_within_its_bound() {
        let bound = 7.0 * DEFAULT_CUTOFF / LIGHT_CUT_FRACTION;
        for lanes in [true, false] {
            let (cut, cut_rays) = render(Some(DEFAULT_CUTOFF), lanes, true);
            let (all, all_rays) = render(Some(DEFAULT_CUTOFF), lanes, false);
            assert!(cut_rays < all_rays, "{cut_rays} of {all_rays} shadow rays");
            let worst = cut
                .iter()
                .zip(&all)
                .map(|(a, b)| (*a - *b).abs().max_element())
                .fold(0.0f32, f32::max);
            assert!(worst <= bound, "lanes {lanes}: {worst} > {bound}");
        }
        // Without a cut-off only exact zeros go, and the mirror and glass spheres away from
        // their highlights still save shadow rays: fewer than with the cut, more than none.
        let (_, exact_rays) = render(None, true, true);
        let (_, cut_rays) = render(Some(DEFAULT_CUTOFF), true, true);
        assert!(exact_rays > cut_rays);
    }
}
