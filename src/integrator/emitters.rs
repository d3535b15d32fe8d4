//! What the scene's lights emit, for the path tracer, and the light-only surfaces its rays can hit.
//!
//! The conventions (`docs/scene-format.md`, "Path tracing"), with `I` a light's diffuse intensity
//! (`id`, or `intensity`) times the inverse-square scale of its variant (`1/(4π)` for `is`/`id`
//! lights, 1 otherwise; attenuation coefficients are a Whitted-only convention and are ignored:
//! light falls off as `1/d²`):
//! - a **point light** has radiant intensity `π·I` in every direction, so that a diffuse surface
//!   it lights directly reflects `kd·c·I·cos θ / d²`: the Whitted diffuse term wherever Whitted
//!   shading uses inverse-square fall-off;
//! - a **quad** light of area `A` emits radiance `π·I/A` from one side: the side of its file's
//!   `normal`, or else the side facing the centre of the scene's bounds;
//! - a **sphere** light emits `π·I/A` outwards over its whole surface, `A = 4πr²`;
//! - a **shape** light (a scene triangle or quad named by `shapeid`) emits `π·I/A` over its total
//!   area `A`, from the side facing the centre of the scene's bounds.
//!
//! Quad lights and spheres given by a light's own `shape` are not scene shapes: this module
//! intersects them for camera and scattered rays (they are opaque, absorbing and emitting), and
//! for shadow rays towards other lights.

use std::f32::consts::PI;
use std::ops::Range;

use crate::accel::aabb::Aabb;
use crate::geometry::sphere::Sphere;
use crate::light::{Falloff, Light};
use crate::math::Vec3;
use crate::ray::Ray;
use crate::scene::Scene;

/// The scene's lights as emitters. Built once per render.
#[derive(Debug, Clone)]
pub struct Emitters {
    /// Per light (same indices as `Scene::lights`): its radiance (area lights) or radiant
    /// intensity (point lights).
    emission: Vec<Vec3>,
    /// Centre of the scene's bounds, which one-sided lights without a `normal` face.
    centre: Vec3,
    /// The lights that are not scene shapes but have a surface (quads, own spheres).
    own_surfaces: Vec<(u32, OwnSurface)>,
    /// Scene primitives that are lights: (primitives, light).
    shapes: Vec<(Range<u32>, u32)>,
}

/// A hit on a light's own surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightHit {
    pub light: u32,
    pub t: f32,
    pub point: Vec3,
    /// Unit normal of the surface there (either side for flat lights).
    pub normal: Vec3,
}

/// `I` of the module docs: what a light's intensity is as a point source with `1/d²` fall-off.
fn point_intensity(light: &Light) -> Vec3 {
    let i = light.intensity();
    match i.falloff {
        Falloff::InverseSquare { scale } => i.diffuse * scale,
        Falloff::Polynomial { .. } => i.diffuse,
    }
}

impl Emitters {
    pub fn new(scene: &Scene) -> Emitters {
        let bounds = scene.primitives.bounds();
        let bounds = if bounds.min.x <= bounds.max.x {
            bounds
        } else {
            scene
                .lights
                .iter()
                .fold(Aabb::EMPTY, |b, l| b.grow(l.center()))
        };
        let centre = bounds.center();
        let mut own_surfaces = Vec::new();
        let mut shapes = Vec::new();
        let emission = scene
            .lights
            .iter()
            .enumerate()
            .map(|(i, light)| {
                let power = PI * point_intensity(light);
                let surface = light.surface();
                if !surface.is_empty() {
                    shapes.push((surface, i as u32));
                }
                if let Some(own) = OwnSurface::of(light) {
                    own_surfaces.push((i as u32, own));
                }
                match light.area() {
                    None => power,
                    Some(area) => power / area,
                }
            })
            .collect();
        Emitters {
            emission,
            centre,
            own_surfaces,
            shapes,
        }
    }

    /// The radiant intensity of point light `light` (`π·I`).
    #[inline]
    pub fn intensity(&self, light: usize) -> Vec3 {
        self.emission[light]
    }

    /// The radiance area light `light` of the scene (`lights[light]`) emits from `point`, whose
    /// surface normal is `normal`, in the direction `out` (unit, away from the light).
    pub fn radiance(
        &self,
        lights: &[Light],
        light: usize,
        point: Vec3,
        normal: Vec3,
        out: Vec3,
    ) -> Vec3 {
        let Some(side) = lights[light].emitting_side(point, normal, self.centre) else {
            return Vec3::ZERO;
        };
        if side.dot(out) > 0.0 {
            self.emission[light]
        } else {
            Vec3::ZERO
        }
    }

    /// Whether every emitter is a light's own surface: no scene primitive emits.
    #[inline]
    pub fn lights_are_own_surfaces(&self) -> bool {
        self.shapes.is_empty()
    }

    /// The light that scene primitive `prim` is part of, if any.
    #[inline]
    pub fn light_of(&self, prim: u32) -> Option<u32> {
        self.shapes
            .iter()
            .find(|(r, _)| r.contains(&prim))
            .map(|&(_, l)| l)
    }

    /// The nearest hit before `t_max` on a light's own surface (a quad light, a sphere light
    /// that is not a scene shape), other than light `skip`'s.
    pub fn intersect(&self, ray: &Ray, t_max: f32, skip: Option<u32>) -> Option<LightHit> {
        let mut best: Option<LightHit> = None;
        for &(i, ref surface) in &self.own_surfaces {
            if Some(i) == skip {
                continue;
            }
            let limit = best.map_or(t_max, |b| b.t);
            let hit = match surface {
                OwnSurface::Quad(q) => q.hit(ray, limit),
                OwnSurface::Sphere(s) => s.intersect(ray, limit).map(|c| {
                    let p = ray.at(c.t);
                    (c.t, p, (p - s.center).normalize_or_zero())
                }),
            };
            if let Some((t, point, normal)) = hit {
                best = Some(LightHit {
                    light: i,
                    t,
                    point,
                    normal,
                });
            }
        }
        best
    }
}

/// A light's own surface, with what its ray test needs worked out once.
#[derive(Debug, Clone)]
enum OwnSurface {
    Quad(Parallelogram),
    Sphere(Sphere),
}

impl OwnSurface {
    /// The surface a ray can meet of a light that is not a scene shape: a quad light's
    /// parallelogram and a sphere light's ball; `None` for the others.
    fn of(light: &Light) -> Option<OwnSurface> {
        match light {
            Light::Quad {
                origin,
                edge_u,
                edge_v,
                normal,
                ..
            } => Some(OwnSurface::Quad(Parallelogram::new(
                *origin, *edge_u, *edge_v, *normal,
            ))),
            Light::Sphere {
                center,
                radius,
                surface,
                ..
            } if surface.is_empty() => Some(OwnSurface::Sphere(Sphere::new(
                *center,
                *radius,
                Vec3::Y,
                Vec3::X,
            ))),
            _ => None,
        }
    }
}

/// The parallelogram `origin + s·eu + t·ev` (`s, t ∈ [0, 1]`) with unit normal `n`.
#[derive(Debug, Clone, Copy)]
struct Parallelogram {
    origin: Vec3,
    n: Vec3,
    /// The dual basis of (eu, ev) in the plane, unnormalised: `s = d·a / (eu·a)`, `t = d·b /
    /// (ev·b)` for `d` from the origin, with `a = ev × n`, `b = n × eu`.
    a: Vec3,
    b: Vec3,
    eu_a: f32,
    ev_b: f32,
}

impl Parallelogram {
    fn new(origin: Vec3, eu: Vec3, ev: Vec3, n: Vec3) -> Parallelogram {
        let a = ev.cross(n);
        let b = n.cross(eu);
        Parallelogram {
            origin,
            n,
            a,
            b,
            eu_a: eu.dot(a),
            ev_b: ev.dot(b),
        }
    }

    /// The ray's hit before `t_max`: distance, point and normal.
    #[inline]
    fn hit(&self, ray: &Ray, t_max: f32) -> Option<(f32, Vec3, Vec3)> {
        let denom = self.n.dot(ray.dir);
        if denom == 0.0 || !denom.is_finite() {
            return None;
        }
        let t = self.n.dot(self.origin - ray.origin) / denom;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let p = ray.at(t);
        let d = p - self.origin;
        let s = d.dot(self.a) / self.eu_a;
        let u = d.dot(self.b) / self.ev_b;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&u) {
            Some((t, p, self.n))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light::Intensity;
    use crate::sampling::Method;

    #[test]
    fn parallelogram_hits_inside_and_misses_outside() {
        let (o, eu, ev) = (
            Vec3::new(-1.0, 2.0, -1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.5, 0.0, 2.0),
        );
        let n = eu.cross(ev).normalize();
        let up = |x: f32, z: f32| Ray::new(Vec3::new(x, 0.0, z), Vec3::Y);
        let q = Parallelogram::new(o, eu, ev, n);
        let (t, p, _) = q.hit(&up(0.0, 0.0), f32::INFINITY).unwrap();
        assert!((t - 2.0).abs() < 1e-6 && (p.y - 2.0).abs() < 1e-6);
        assert!(q.hit(&up(1.6, 0.1), f32::INFINITY).is_none());
        assert!(q.hit(&up(1.3, 0.9), f32::INFINITY).is_some());
        assert!(q.hit(&up(0.0, 0.0), 1.5).is_none());
    }

    #[test]
    fn a_quad_emits_pi_i_over_a_from_one_side() {
        let i = Intensity {
            diffuse: Vec3::splat(2.0),
            specular: Vec3::splat(2.0),
            falloff: Falloff::NONE,
        };
        let mut light = Light::quad(Vec3::ZERO, Vec3::X * 2.0, Vec3::Z, i, 1, Method::Random);
        let scene_centre_below = Emitters {
            emission: vec![Vec3::splat(PI * 2.0 / 2.0)],
            centre: Vec3::new(0.0, -3.0, 0.0),
            own_surfaces: vec![],
            shapes: vec![],
        };
        let lights = [light.clone()];
        let p = Vec3::new(1.0, 0.0, 0.5);
        let down = scene_centre_below.radiance(&lights, 0, p, Vec3::Y, Vec3::NEG_Y);
        assert_eq!(down, Vec3::splat(PI));
        assert_eq!(
            scene_centre_below.radiance(&lights, 0, p, Vec3::Y, Vec3::Y),
            Vec3::ZERO
        );
        if let Light::Quad { facing, .. } = &mut light {
            *facing = Some(Vec3::Y);
        }
        let lights = [light];
        assert_eq!(
            scene_centre_below.radiance(&lights, 0, p, Vec3::Y, Vec3::Y),
            Vec3::splat(PI)
        );
        assert_eq!(
            scene_centre_below.radiance(&lights, 0, p, Vec3::Y, Vec3::NEG_Y),
            Vec3::ZERO
        );
    }
}
