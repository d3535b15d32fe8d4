//! `raytracer bench --kinds SCENE…`: a scene's ray queries by kind (camera, reflection,
//! refraction, shadow), each kind's rays traced on one thread with the accelerator a render builds.

use std::time::{Duration, Instant};

use super::timing::median;
use raytracer::accel::Accel;
use raytracer::integrator::LIGHT_CLEARANCE;
use raytracer::math::{reflect, refract, Vec2};
use raytracer::ray::Ray;
use raytracer::scene::Scene;

/// Most shadow rays per light and camera hit: an area light's samples, stratified.
pub const SHADOW_SAMPLES_PER_LIGHT: u32 = 16;

/// The kinds of ray, in the order the table lists them.
pub const KINDS: [&str; 4] = ["camera", "reflection", "refraction", "shadow"];

/// A scene's rays of each kind: from the centre of every pixel, the camera ray; at its hit, the
/// reflection ray (materials with `kr > 0` or glass) and the refraction ray (glass, unless
/// totally reflected) the Whitted integrator would spawn there, and the shadow rays towards every
/// light (one for a point light, up to [`SHADOW_SAMPLES_PER_LIGHT`] stratified samples of an area
/// light).
#[derive(Debug, Default)]
pub struct KindRays {
    /// Camera, reflection and refraction rays (closest-hit queries).
    pub closest: [Vec<Ray>; 3],
    /// Shadow rays with their bounds (any-hit queries).
    pub shadow: Vec<(Ray, f32)>,
}

/// The rays of every kind for `scene` with its accelerator `accel`.
pub fn kind_rays(scene: &Scene, accel: &Accel) -> KindRays {
    let prims = &scene.primitives;
    let mut rays = KindRays::default();
    for y in 0..scene.camera.height {
        for x in 0..scene.camera.width {
            let ray = scene
                .camera
                .generate_ray(x, y, Vec2::splat(0.5), Vec2::splat(0.5));
            rays.closest[0].push(ray);
            let Some((p, c)) = accel.closest(prims, &ray, f32::INFINITY) else {
                continue;
            };
            let primitive = prims.get(p);
            let material = &scene.materials[primitive.material as usize];
            let hit = primitive.hit_with(&ray, c, p, prims.meshes(), false);
            let front = hit.normal.dot(ray.dir) < 0.0;
            let n = if front { hit.normal } else { -hit.normal };
            if material.kr > 0.0 || material.kt > 0.0 {
                rays.closest[1].push(hit.spawn(reflect(ray.dir, n).normalize()));
            }
            if material.kt > 0.0 {
                let eta = if front {
                    1.0 / material.eta
                } else {
                    material.eta
                };
                if let Some(t) = refract(ray.dir, n, eta) {
                    rays.closest[2].push(hit.spawn(t));
                }
            }
            let spawn = hit.spawn_points();
            for light in &scene.lights {
                let count = light.sample_count().min(SHADOW_SAMPLES_PER_LIGHT);
                let side = (count as f32).sqrt().ceil() as u32;
                for i in 0..count {
                    let sample = if count == 1 {
                        light.sample_one(hit.point)
                    } else {
                        let u = Vec2::new((i % side) as f32 + 0.5, (i / side) as f32 + 0.5);
                        light.sample(hit.point, u / side as f32)
                    };
                    if (sample.position - hit.point).dot(n) <= 0.0 {
                        continue;
                    }
                    let (ray, dist) = spawn.ray_to(sample.position);
                    rays.shadow.push((ray, dist * (1.0 - LIGHT_CLEARANCE)));
                }
            }
        }
    }
    rays
}

/// The timing of one kind's rays.
#[derive(Debug, Clone)]
pub struct KindTime {
    /// One of [`KINDS`].
    pub kind: &'static str,
    pub rays: usize,
    /// Rays that hit something (shadow rays: that are blocked).
    pub hits: usize,
    /// Median time to trace them all.
    pub time: Duration,
}

impl KindTime {
    /// Million rays a second; `None` for no rays.
    pub fn mrays(&self) -> Option<f64> {
        (self.rays > 0).then(|| self.rays as f64 / self.time.as_secs_f64().max(1e-9) / 1e6)
    }

    /// Nanoseconds a ray; `None` for no rays.
    pub fn ns_per_ray(&self) -> Option<f64> {
        (self.rays > 0).then(|| self.time.as_secs_f64() * 1e9 / self.rays as f64)
    }
}

/// Traces each kind of `rays` `runs` times (at least once) on the calling thread: the median
/// time and the number of hits per kind, in the order of [`KINDS`]. Camera, reflection and
/// refraction rays are closest-hit queries, shadow rays any-hit queries: the accelerator's cost
/// per ray of each kind, without the shading a render adds or the beams through which it traces
/// an area light's shadow rays (`docs/performance.md`).
pub fn time_kinds(scene: &Scene, accel: &Accel, rays: &KindRays, runs: usize) -> Vec<KindTime> {
    let prims = &scene.primitives;
    let timed = |f: &dyn Fn() -> usize| {
        let mut times = Vec::new();
        let mut hits = 0;
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            hits = std::hint::black_box(f());
            times.push(start.elapsed());
        }
        (median(times), hits)
    };
    let mut out = Vec::new();
    for (kind, set) in KINDS.iter().zip(&rays.closest) {
        let (time, hits) = timed(&|| {
            set.iter()
                .filter(|r| accel.closest(prims, r, f32::INFINITY).is_some())
                .count()
        });
        out.push(KindTime {
            kind,
            rays: set.len(),
            hits,
            time,
        });
    }
    let (time, hits) = timed(&|| {
        rays.shadow
            .iter()
            .filter(|(r, t)| accel.any(prims, r, *t, |_| true))
            .count()
    });
    out.push(KindTime {
        kind: KINDS[3],
        rays: rays.shadow.len(),
        hits,
        time,
    });
    out
}
