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

use std::sync::atomic::{AtomicBool, Ordering};

use crate::accel::aabb::Aabb;
use crate::accel::{Accel, Inside, Interiors, LightBuffer, Reachable};
use crate::light::Light;
use crate::material::Reflection;
use crate::material::{Material, Shares};
use crate::math::{fresnel_dielectric, local_to_world, reflect, refract, Vec3};
use crate::ray::{Ray, Side, SpawnPoints};
use crate::sampling::{blinn_phong_half_vector, CameraSamples, Method, SampleKey};
use crate::scene::{RenderMode, Scene};

use super::{finite_radiance, RayCounts, TraceOptions, LIGHT_CLEARANCE};

mod direct;
mod quad_lanes;
mod shadow;
#[cfg(test)]
mod tests;

use direct::*;
use quad_lanes::Shading;
use shadow::*;

/// Shadow rays towards one area light between two looks at [`Whitted::cancel`]: one look is one
/// relaxed load, small beside this many rays, and the longest stretch without one (an area light
/// of the largest allowed sample count) stays a small fraction of the ray count.
const SHADOW_RAYS_PER_CANCEL_CHECK: u32 = 256;

/// The padded sample dimension a rough mirror's reflected direction is drawn from (each shading
/// point has its own key, so one dimension serves every depth).
const ROUGH_MIRROR_DIMENSION: u64 = 0x6d69_7272;

/// Colour of a hit in `rendermode: binary` (misses are black), as in the CGR specification.
pub const BINARY_HIT: Vec3 = Vec3::new(1.0, 0.0, 0.0);

/// Most reflection and refraction rays one camera sample may spawn. Every glass hit splits into
/// two rays, so a tree of `nbounces` levels can hold 2^nbounces rays (facing glass panes at
/// `nbounces: 50` would never finish); past this budget a branch returns only its direct light.
/// A tree of 12 full levels fits, and no test or bundled scene reaches it.
pub const MAX_SECONDARY_RAYS_PER_SAMPLE: u32 = 4096;

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
struct BranchSource<'s> {
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

impl BranchSource<'_> {
    /// The ray in direction `dir`, scaled by `factor` in the point's radiance. Its sample key is
    /// stream `0x1000 + id` of the point's; where nothing draws a sample the keys are never read,
    /// and the point's stands in.
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

/// What a shading point's surface does with the light that reaches it: its material, the shares
/// of mirror, glass and own shading, and whether the ray hit its front.
struct Surface<'m> {
    material: &'m Material,
    shares: Shares,
    front: bool,
}

/// A shading point whose reflection and refraction rays are not all traced yet. Its untraced
/// rays wait on [`Whitted::pending`], the next one on top.
#[derive(Debug, Clone, Copy)]
struct PendingPoint {
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
    open: Vec<PendingPoint>,
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
        open.push(PendingPoint {
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
                open.push(PendingPoint {
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
        let spawn = hit.spawn_points();
        let shading = Shading {
            point: hit.point,
            spawn: &spawn,
            n,
            ns,
            v: -ray.dir,
            kd_base: own.diffuse,
            ks_specular: material.ks * material.specular,
            has_highlight: material.ks > 0.0,
            exponent: material.exponent,
        };
        let (mut color, finished) = self.direct_light(&shading, own.ambient, own_scale, key);
        if !finished {
            return color; // cancelled
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
        let source = BranchSource {
            spawn: &spawn,
            sphere,
            depth: depth + 1,
            key,
            draws: self.draws,
            weight,
        };
        let surface = Surface {
            material,
            shares,
            front,
        };
        self.push_branches(&source, ray, &shading, &surface, pending);
        color
    }

    /// The ambient and direct light at a shading point (`ambient` the surface's ambient
    /// reflectance), with no shadow rays where its own terms count for nothing (`own_scale` 0).
    /// `false` beside the colour when the render was cancelled on the way.
    #[inline(always)]
    fn direct_light(
        &mut self,
        shading: &Shading,
        ambient: Vec3,
        own_scale: f32,
        key: &SampleKey,
    ) -> (Vec3, bool) {
        let scene = self.scene;
        let mut color = if scene.ambient == Vec3::ZERO {
            Vec3::ZERO
        } else {
            ambient * scene.ambient
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
                    return (color, false);
                }
                let sample = light.sample_one(shading.point);
                let surface = light.surface();
                let weighting = SampleWeighting::single(self.light_cut);
                self.add_sample(&mut color, shading, light, &surface, &sample, &weighting);
            } else if !self.area_light(&mut color, shading, li, light, count, method, key) {
                return (color, false);
            }
        }
        (color, true)
    }

    /// Pushes onto `pending` the reflected ray and then the refracted ray of the shading point
    /// `ray` hits on `surface`, each where its weight passes the cut-off.
    #[inline(always)]
    fn push_branches(
        &self,
        source: &BranchSource,
        ray: &Ray,
        shading: &Shading,
        surface: &Surface,
        pending: &mut Vec<Branch>,
    ) {
        let (material, shares, n) = (surface.material, surface.shares, shading.n);
        let weight = source.weight;
        let mut reflect_weight = shares.mirror;
        let mut refracted = None;
        if shares.glass > 0.0 {
            let eta = if surface.front {
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
                    let mut b = source.branch(t, 2, transmit);
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
                let u = source
                    .key
                    .padded(Method::Sobol, ROUGH_MIRROR_DIMENSION, 0, 1);
                let h = local_to_world(
                    shading.ns,
                    blinn_phong_half_vector(material.mirror_exponent, u),
                );
                let blurred = reflect(ray.dir, h).normalize();
                if blurred.dot(n) > 0.0 {
                    r = blurred; // else the mirror direction, rather than into the surface
                }
            }
            pending.push(source.branch(r, 1, reflect_weight));
        }
        if let Some(b) = refracted {
            pending.push(b);
        }
    }

    /// Whether a secondary ray of accumulated `weight` passes the cut-off (always, without one).
    #[inline]
    fn worth_tracing(&self, weight: f32) -> bool {
        self.options.cutoff.is_none_or(|c| weight >= c)
    }
}
