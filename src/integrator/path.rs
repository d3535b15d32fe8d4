//! Unidirectional path tracing (`"rendermode": "pathtrace"`, or `--integrator path`).
//!
//! From each camera ray the path scatters off surfaces by their [`Bsdf`]: at every vertex up to
//! `nbounces` it takes next-event estimates towards every light (one sample per light and vertex,
//! or the file's `lightsample`, placed as `Light::sample` places them), then continues in one
//! BSDF-sampled direction. Light is therefore found two ways, by a light sample and by a scattered
//! ray that hits an emitter, and both are weighted by the power heuristic ([`mis`](super::mis));
//! directions only one way can find (point lights; mirror and glass bounces; the background) take
//! all the weight. A ray that leaves the scene returns `backgroundcolor` as radiance.
//!
//! ```text
//! vertex 0 (first hit) … vertex N (N = nbounces): light samples + one BSDF sample each;
//! the ray scattered from vertex N only collects the light it hits (N = 0: direct light only).
//! ```
//! Past [`ROULETTE_START`] vertices a path continues with probability `q` = its largest
//! throughput channel (at most [`ROULETTE_MAX`]) and is divided by `q` when it does: Russian
//! roulette, unbiased. Shadow rays are blocked by every scene shape (glass included: caustics come
//! only from scattered rays) and by the lights' own surfaces other than the target light's.
//!
//! Every random number comes from a [`PathSampler`], placed with the render's pixel sampler
//! (Owen-scrambled Sobol by default). Each vertex takes the same dimensions in the same order: a
//! 4D point (BSDF direction, lobe choice, roulette), then one dimension per light for its samples,
//! taken even where no light is sampled, so that vertex `d` of every camera sample of a pixel
//! reads the same padded sets. So a pixel's value depends only on (pixel, sample, dimension,
//! seed).

use std::sync::atomic::{AtomicBool, Ordering};

use crate::accel::Accel;
use crate::light::Light;
use crate::math::{next_float_up, Vec2, Vec3};
use crate::ray::{Hit, Ray, SpawnPoints};
use crate::sampling::{Method, PathSampler, SampleKey};
use crate::scene::Scene;

use super::bsdf::Bsdf;
use super::emitters::Emitters;
use super::mis::power_heuristic;
use super::{finite_radiance, RayCounts, TraceOptions, LIGHT_CLEARANCE};

/// The vertex from which Russian roulette may end a path (the first hit is vertex 0): the first
/// bounces of indirect light carry most of it and are always traced. An earlier start saves less
/// time than it adds noise (`docs/path-tracing.md`), so the roulette waits for paths longer than
/// most scenes' `nbounces`.
pub const ROULETTE_START: u32 = 8;

/// Highest survival probability: even a white path ends at some point.
pub const ROULETTE_MAX: f32 = 0.95;

/// Traces paths through one scene. One per worker.
pub struct PathTracer<'a> {
    scene: &'a Scene,
    accel: &'a Accel,
    emitters: &'a Emitters,
    /// Cap on the path's vertices on top of the scene's `nbounces`.
    max_depth: u32,
    options: TraceOptions,
    /// How the path's samples are placed (the render's pixel sampler).
    method: Method,
    pub counts: RayCounts,
    cancel: Option<&'a AtomicBool>,
}

/// Where the last scattering happened, for weighing what the scattered ray finds.
#[derive(Debug, Clone, Copy)]
enum Scattered {
    /// From the camera, a mirror or a dielectric: no light sample could have found the
    /// direction, so what it hits counts in full.
    Delta,
    /// From `point` by a smooth lobe of solid-angle density `pdf`.
    Smooth { point: Vec3, pdf: f32 },
}

impl<'a> PathTracer<'a> {
    pub fn new(
        scene: &'a Scene,
        accel: &'a Accel,
        emitters: &'a Emitters,
        max_depth: u32,
        options: TraceOptions,
        method: Method,
        cancel: Option<&'a AtomicBool>,
    ) -> PathTracer<'a> {
        PathTracer {
            scene,
            accel,
            emitters,
            max_depth,
            options,
            method,
            counts: RayCounts::default(),
            cancel,
        }
    }

    #[inline]
    pub fn cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
    }

    /// Radiance along a camera ray: one path.
    pub fn trace_camera(&mut self, camera_ray: &Ray, key: &SampleKey) -> Vec3 {
        self.counts.camera += 1;
        let scene = self.scene;
        let lights = &scene.lights;
        let last_vertex = scene.nbounces.min(self.max_depth);
        let mut sampler = PathSampler::new(key, self.method);
        let mut radiance = Vec3::ZERO;
        let mut beta = Vec3::ONE;
        let mut ray = *camera_ray;
        let mut from = Scattered::Delta;
        let mut depth = 0u32;
        loop {
            if self.cancelled() {
                return Vec3::ZERO;
            }
            if depth > last_vertex && self.emitters.lights_are_own_surfaces() {
                radiance += beta * self.last_ray(&ray, from);
                break;
            }
            let closest = self.accel.closest(&scene.primitives, &ray, f32::INFINITY);
            let t_shape = closest.map_or(f32::INFINITY, |(_, c)| c.t);
            if let Some(h) = self.emitters.intersect(&ray, t_shape, None) {
                radiance += beta * self.emitted(h.light, h.point, h.normal, -ray.dir, from);
                break; // a light's own surface absorbs what it does not emit
            }
            let Some((prim, candidate)) = closest else {
                radiance += beta * scene.background;
                break;
            };
            let primitive = scene.primitives.get(prim);
            let material = &scene.materials[primitive.material as usize];
            let hit = primitive.hit_with(
                &ray,
                candidate,
                prim,
                scene.primitives.meshes(),
                material.texture.is_some(),
            );
            if let Some(light) = self.emitters.light_of(prim) {
                radiance += beta * self.emitted(light, hit.point, hit.normal, -ray.dir, from);
            }
            if depth > last_vertex {
                break; // the ray from the last vertex only collects light
            }
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
            let bsdf = Bsdf::new(material, base, ns, n, front);
            let wo = -ray.dir;
            // One 4D point: the direction in its first two (best stratified) dimensions, the lobe
            // and the roulette in the other two.
            let [u0, u1, u_lobe, u_roulette] = sampler.get4();
            let spawn = hit.spawn_points();
            if bsdf.has_non_delta() {
                radiance += beta * self.direct(&bsdf, &hit, &spawn, wo, &mut sampler);
            } else {
                sampler.skip(lights.len() as u64);
            }
            let Some(s) = bsdf.sample(wo, u_lobe, Vec2::new(u0, u1)) else {
                break;
            };
            beta *= s.weight;
            if beta.max_element() <= 0.0 || !beta.is_finite() {
                break;
            }
            if depth >= ROULETTE_START {
                let q = beta.max_element().min(ROULETTE_MAX);
                if u_roulette >= q {
                    break;
                }
                beta /= q;
            }
            from = if s.delta {
                Scattered::Delta
            } else {
                Scattered::Smooth {
                    point: hit.point,
                    pdf: s.pdf,
                }
            };
            ray = spawn.ray(s.dir);
            self.counts.secondary += 1;
            depth += 1;
        }
        finite_radiance(radiance)
    }

    /// What the ray scattered from the last vertex brings back, when every emitter is a light's
    /// own surface (no scene shape emits): the light it reaches, or the background if it leaves
    /// the scene. Equal to what the loop of [`PathTracer::trace_camera`] finds, but asked as
    /// occlusion queries, which need no closest hit, and none at all for a ray that misses every
    /// light under a black background.
    fn last_ray(&mut self, ray: &Ray, from: Scattered) -> Vec3 {
        let scene = self.scene;
        let prims = &scene.primitives;
        match self.emitters.intersect(ray, f32::INFINITY, None) {
            // The loop counts the light when it is nearer than every shape: no shape at `t ≤ h.t`.
            Some(h) => {
                let limit = next_float_up(h.t);
                if self.accel.any(prims, ray, limit, |_| true) {
                    Vec3::ZERO
                } else {
                    self.emitted(h.light, h.point, h.normal, -ray.dir, from)
                }
            }
            None if scene.background == Vec3::ZERO => Vec3::ZERO,
            None if self.accel.any(prims, ray, f32::INFINITY, |_| true) => Vec3::ZERO,
            None => scene.background,
        }
    }

    /// What light `light` sends back along a ray that hit it at `point` (surface normal `normal`),
    /// towards `out`, weighed against the light samples that could have found it.
    fn emitted(&self, light: u32, point: Vec3, normal: Vec3, out: Vec3, from: Scattered) -> Vec3 {
        let lights = &self.scene.lights;
        let le = self
            .emitters
            .radiance(lights, light as usize, point, normal, out);
        match from {
            Scattered::Delta => le,
            Scattered::Smooth { point: p, pdf } => {
                let l = &lights[light as usize];
                let count = self.light_samples(l);
                let pl = l.pdf(p, point, normal);
                le * power_heuristic(1.0, pdf, count as f32, pl)
            }
        }
    }

    /// Light samples per vertex for `light`: the scene-wide count (`lightsample`), else one.
    /// A light's own `samples` is Whitted's shadow-ray count per shading point; a path already
    /// averages over many vertices, and one sample each is what other path tracers take.
    #[inline]
    fn light_samples(&self, light: &Light) -> u32 {
        if light.is_point() {
            1
        } else {
            self.options.light_samples.unwrap_or(1).max(1)
        }
    }

    /// Next-event estimation at `hit`: every light's samples, each weighed against the BSDF
    /// sample that could have found it.
    fn direct(
        &mut self,
        bsdf: &Bsdf,
        hit: &Hit,
        spawn: &SpawnPoints,
        wo: Vec3,
        sampler: &mut PathSampler,
    ) -> Vec3 {
        let lights = &self.scene.lights;
        let mut sum = Vec3::ZERO;
        for (li, light) in lights.iter().enumerate() {
            let count = self.light_samples(light);
            let share = 1.0 / count as f32;
            let dimension = sampler.get_set();
            for j in 0..count {
                let u = dimension.point(j, count);
                let s = light.sample(hit.point, u);
                let to = s.position - hit.point;
                let d2 = to.length_squared();
                let wi = to / d2.sqrt();
                let (f, bsdf_pdf) = bsdf.eval_pdf(wo, wi);
                if f == Vec3::ZERO {
                    continue;
                }
                let arriving = match light.is_point() {
                    true => self.emitters.intensity(li) / d2,
                    false => {
                        if !(s.pdf > 0.0 && s.pdf.is_finite()) {
                            continue;
                        }
                        let le = self
                            .emitters
                            .radiance(lights, li, s.position, s.normal, -wi);
                        let w = power_heuristic(count as f32, s.pdf, 1.0, bsdf_pdf);
                        le * (w / s.pdf)
                    }
                };
                let c = f * arriving * (bsdf.cos(wi) * share);
                if c.max_element() <= 0.0 || !self.unblocked(spawn, s.position, light, li as u32) {
                    continue;
                }
                sum += c;
            }
        }
        sum
    }

    /// Whether nothing lies between the shading point of `from` and `target` on light `li`: no
    /// scene shape (bar the light's own), and no other light's own surface.
    fn unblocked(&mut self, from: &SpawnPoints, target: Vec3, light: &Light, li: u32) -> bool {
        self.counts.shadow += 1;
        let (ray, dist) = from.ray_to(target);
        let t_max = dist * (1.0 - LIGHT_CLEARANCE);
        let surface = light.surface();
        let scene = self.scene;
        if self.emitters.intersect(&ray, t_max, Some(li)).is_some() {
            return false;
        }
        !self
            .accel
            .any(&scene.primitives, &ray, t_max, |p| !surface.contains(&p))
    }
}
