//! Lights: points, ambient terms, and area lights of every shape.

use super::shape::{quad_edges, right_angle_corner};
use super::spellings::{light, type_names, type_of, LIGHT_TYPES, SHAPE_TYPES};
use super::{nearest, non_negative_color, opt_f32, required, required_positive, Loader};
use crate::light::{Falloff, Intensity, Light};
use crate::math::Vec3;
use crate::sampling::Method;
use crate::scene::json::Node;
use crate::scene::lights;
use crate::scene::{RenderMode, SceneError, Variant};

/// Sides of the polygon a disc light is sampled as: its area is the disc's, and its outline
/// strays from the circle by under 0.2% of the radius.
const DISC_SIDES: usize = 64;

impl Loader<'_> {
    /// Reads the light `l` into the scene's lights (an ambient one into the ambient term); a
    /// light of unknown `type` is skipped with a warning.
    pub(super) fn light(&mut self, l: &Node) -> Result<(), SceneError> {
        if !l.is_object() {
            return Err(l.error(format!("a light is an object, found {}", l.kind())));
        }
        let type_node = required(l, light::TYPE)?;
        let name = type_node.str()?;
        let Some(kind) = type_of(LIGHT_TYPES, name) else {
            let near = nearest(name, &type_names(LIGHT_TYPES));
            l.mark_all_read(); // skipped whole, with this warning
            self.warn(
                &type_node,
                format!("unknown light type '{name}' (nearest known: '{near}'); skipped"),
            );
            return Ok(());
        };
        if kind == "ambient" {
            let n = required(l, light::AMBIENT_LEVEL)?;
            let a = non_negative_color(&n)?;
            self.ambient = Some(self.ambient.unwrap_or(Vec3::ZERO) + a);
            return Ok(());
        }
        let intensity = self.intensity(l)?;
        match kind {
            "point" if l.contains_any(light::AXIS_U) && l.contains_any(light::AXIS_V) => {
                self.warn(
                    &type_node,
                    "a point light with edges 'u' and 'v' is read as an area light centred on \
                     its position",
                );
                self.area_light(l, intensity)
            }
            "point" => {
                let position = required(l, light::POSITION)?.vec3()?;
                self.lights.push(Light::Point {
                    position,
                    intensity,
                });
                Ok(())
            }
            "sphere" => self.sphere_light(l, intensity),
            "disc" => self.disc_light(l, intensity),
            _ => self.area_light(l, intensity),
        }
    }

    /// A ball of light: a centre and a radius.
    fn sphere_light(&mut self, l: &Node, intensity: Intensity) -> Result<(), SceneError> {
        let center = required(l, light::POSITION)?.vec3()?;
        let radius = required_positive(l, light::RADIUS)?;
        self.push_sphere_light(l, center, radius, intensity)
    }

    /// The ball of light `center`, `radius`, sampled as light `l` says.
    fn push_sphere_light(
        &mut self,
        l: &Node,
        center: Vec3,
        radius: f32,
        intensity: Intensity,
    ) -> Result<(), SceneError> {
        let (samples, method) = self.area_sampling(l)?;
        self.lights.push(Light::Sphere {
            center,
            radius,
            intensity,
            samples,
            method,
            surface: 0..0,
        });
        Ok(())
    }

    /// A flat disc of light: a centre, a radius and the normal it faces (default −y, a ceiling
    /// light), sampled as a fan of [`DISC_SIDES`] triangles of the disc's own area.
    fn disc_light(&mut self, l: &Node, intensity: Intensity) -> Result<(), SceneError> {
        let center = required(l, light::POSITION)?.vec3()?;
        let radius = required_positive(l, light::RADIUS)?;
        let normal = match l.get_any(light::NORMAL) {
            Some(n) => {
                let v = n.vec3()?;
                if v.length_squared() == 0.0 || !v.is_finite() {
                    return Err(n.error("a disc light's normal must be a finite non-zero vector"));
                }
                v.normalize()
            }
            None => Vec3::NEG_Y,
        };
        let (a, b) = crate::math::orthonormal_basis(normal);
        // The polygon's corners lie farther out than the circle by the factor that gives it
        // the circle's area: n/2 · R² · sin(2π/n) = π r².
        let n = DISC_SIDES as f32;
        let step = std::f32::consts::TAU / n;
        let r = radius * (std::f32::consts::TAU / (n * step.sin())).sqrt();
        let corner = |k: usize| {
            let t = step * k as f32;
            center + r * (t.cos() * a + t.sin() * b)
        };
        let triangles: Vec<[Vec3; 3]> = (0..DISC_SIDES)
            .map(|k| [center, corner(k), corner(k + 1)])
            .collect();
        let (samples, method) = self.area_sampling(l)?;
        self.lights
            .push(Light::triangles(triangles, intensity, samples, method));
        Ok(())
    }

    /// `is`/`id` (power, 1/(4πd²)) or `intensity` (1/d² in 2019 files, no fall-off in CGR
    /// files), possibly tinted by `color` or split into `diffuse`/`specular`; attenuation
    /// coefficients `kc`/`kl`/`kq` replace the fall-off in any variant.
    pub(super) fn intensity(&mut self, l: &Node) -> Result<Intensity, SceneError> {
        let attenuation = self.attenuation(l)?;
        let is = l
            .get_any(light::SPECULAR_INTENSITY)
            .map(|n| n.color())
            .transpose()?;
        let id = l
            .get_any(light::DIFFUSE_INTENSITY)
            .map(|n| n.color())
            .transpose()?;
        if is.is_some() || id.is_some() {
            let mut s = is.or(id).unwrap_or(Vec3::ONE);
            let mut d = id.or(is).unwrap_or(Vec3::ONE);
            // With an `intensity` beside them, `is` and `id` give the colours (on any scale:
            // the brightest channel counts as 1) and `intensity` the strength.
            if let Some(n) = l.get_any(light::INTENSITY) {
                let strength = n.f32()?;
                if !(strength >= 0.0 && strength.is_finite()) {
                    return Err(n.error(format!(
                        "a light's intensity must be a finite number ≥ 0, found {strength}"
                    )));
                }
                let unit = |c: Vec3| {
                    let m = c.max_element();
                    if m > 0.0 {
                        c / m
                    } else {
                        c
                    }
                };
                s = unit(s) * strength;
                d = unit(d) * strength;
            }
            return Ok(Intensity {
                diffuse: d,
                specular: s,
                falloff: attenuation.unwrap_or(Falloff::InverseSquare {
                    scale: 1.0 / (4.0 * std::f32::consts::PI),
                }),
            });
        }
        let base = match l.get_any(light::INTENSITY) {
            Some(n) => n.color()?,
            None => Vec3::ONE,
        };
        let tint = l
            .get_any(light::COLOUR)
            .map(|n| n.color())
            .transpose()?
            .unwrap_or(Vec3::ONE);
        let diffuse = l
            .get_any(light::DIFFUSE)
            .map(|n| n.color())
            .transpose()?
            .unwrap_or(Vec3::ONE);
        let specular = l
            .get_any(light::SPECULAR)
            .map(|n| n.color())
            .transpose()?
            .unwrap_or(diffuse);
        if !l.has_any(light::INTENSITY) && !l.has_any(light::COLOUR) && !l.has_any(light::DIFFUSE) {
            self.warn(
                l,
                "the light gives no intensity ('is'/'id' or 'intensity'); using 1",
            );
        }
        let falloff = match (attenuation, self.variant) {
            (Some(a), _) => a,
            (None, Variant::Cgr) => Falloff::NONE,
            (None, Variant::V2019 | Variant::V2021) => Falloff::InverseSquare { scale: 1.0 },
        };
        Ok(Intensity {
            diffuse: base * tint * diffuse,
            specular: base * tint * specular,
            falloff,
        })
    }

    /// A light's attenuation coefficients `kc`, `kl`, `kq` (`1/(kc + kl·d + kq·d²)`), if it gives
    /// any; those it leaves out are 1, 0 and 0 (no fall-off).
    pub(super) fn attenuation(&self, l: &Node) -> Result<Option<Falloff>, SceneError> {
        if !light::ATTENUATION.iter().any(|keys| l.contains_any(keys)) {
            return Ok(None);
        }
        let mut k = [1.0, 0.0, 0.0];
        for (slot, keys) in k.iter_mut().zip(light::ATTENUATION) {
            if let Some(n) = l.get_any(keys) {
                let v = n.f32()?;
                if v < 0.0 {
                    return Err(n.error(format!("{} must be ≥ 0, found {v}", keys[0])));
                }
                *slot = v;
            }
        }
        if k == [0.0; 3] {
            return Err(l.error("the attenuation kc + kl·d + kq·d² is zero at every distance"));
        }
        Ok(Some(Falloff::Polynomial {
            kc: k[0],
            kl: k[1],
            kq: k[2],
        }))
    }

    /// An area light: a quad from its corners or edges, or the sphere, quad or triangle of its
    /// `shape`, or the scene shape its `shapeid` names (resolved after the shapes are read).
    pub(super) fn area_light(&mut self, l: &Node, intensity: Intensity) -> Result<(), SceneError> {
        let any = |k: &[&str]| l.get_any(k).map(|n| n.vec3()).transpose();
        let (origin, edge_u, edge_v) = if let Some(quad) = light_quad(l)? {
            quad
        } else if l.contains_any(light::POSITION) && l.contains_any(light::RADIUS) {
            // A centre and a radius: a ball of light.
            return self.sphere_light(l, intensity);
        } else if let Some(shape) = l.get_any(light::SHAPE) {
            return self.shaped_area_light(l, &shape, intensity);
        } else if let Some(id) = l.get_any(light::SHAPE_ID) {
            let (samples, method) = self.area_sampling(l)?;
            self.shape_lights
                .want(self.lights.len(), &id, intensity, samples, method)?;
            // A placeholder, replaced once the shapes are read.
            self.lights.push(Light::Point {
                position: Vec3::ZERO,
                intensity,
            });
            return Ok(());
        } else if let (Some(p), RenderMode::Path) = (any(light::POSITION)?, self.mode) {
            // The one renderer whose path-tracing files give area lights only a position makes
            // them 1 × 1 squares spanning x and y, centred there (docs/scene-format.md).
            (p - 0.5 * (Vec3::X + Vec3::Y), Vec3::X, Vec3::Y)
        } else if let Some(p) = any(light::POSITION)? {
            self.warn(
                l,
                format!(
                    "an area light given only by a position (no corners, edges, 'shape' or \
                     'shapeid'); treated as a point light at [{}, {}, {}]",
                    p.x, p.y, p.z
                ),
            );
            self.lights.push(Light::Point {
                position: p,
                intensity,
            });
            return Ok(());
        } else {
            return Err(l.error(
                "an area light needs corners 'v0'..'v3' (or 'p'+'e0'+'e1', 'position'+'u'+'v', \
                 'position'+'radius', a 'shape' or a 'shapeid')",
            ));
        };
        let (samples, method) = self.area_sampling(l)?;
        let mut light = Light::quad(origin, edge_u, edge_v, intensity, samples, method);
        if let Some(n) = l.get_any(light::NORMAL) {
            let v = n.vec3()?;
            if v == Vec3::ZERO {
                return Err(n.error("an area light's normal must not be zero"));
            }
            if let Light::Quad { facing, .. } = &mut light {
                *facing = Some(v.normalize());
            }
        }
        self.lights.push(light);
        Ok(())
    }

    /// An area light given by its own `shape`: a sphere, or a quad or triangle under the corner
    /// spellings of shapes.
    pub(super) fn shaped_area_light(
        &mut self,
        l: &Node,
        shape: &Node,
        intensity: Intensity,
    ) -> Result<(), SceneError> {
        if !shape.is_object() {
            return Err(shape.error(format!(
                "a light's shape is an object, found {}",
                shape.kind()
            )));
        }
        let type_node = required(shape, super::spellings::shape::TYPE)?;
        let kind = type_node.str()?.to_ascii_lowercase();
        if type_of(SHAPE_TYPES, &kind) == Some("sphere") {
            let (center, radius) = lights::sphere(shape)?;
            return self.push_sphere_light(l, center, radius, intensity);
        }
        let light = if let Some(n) = lights::flat_corners(&kind) {
            let p = self.corners(shape, n)?;
            let (samples, method) = self.area_sampling(l)?;
            if n == 4 {
                let (origin, edge_u, edge_v) = quad_edges([p[0], p[1], p[2], p[3]]);
                if edge_u.cross(edge_v) == Vec3::ZERO {
                    return Err(shape.error("the quad has zero area (its corners are collinear)"));
                }
                Light::quad(origin, edge_u, edge_v, intensity, samples, method)
            } else {
                let triangles = vec![[p[0], p[1], p[2]]];
                if (p[1] - p[0]).cross(p[2] - p[0]) == Vec3::ZERO {
                    return Err(
                        shape.error("the triangle has zero area (its corners are collinear)")
                    );
                }
                Light::triangles(triangles, intensity, samples, method)
            }
        } else {
            return Err(type_node.error(format!(
                "an area light's shape must be a sphere, a triangle or a quad ('plane'), found '{kind}'"
            )));
        };
        self.lights.push(light);
        Ok(())
    }

    /// An area light's shadow rays per shading point and their placement: `method` (default
    /// jittered) and `samples` (default 4; the grid's side for jittered, the total otherwise).
    pub(super) fn area_sampling(&mut self, l: &Node) -> Result<(u32, Method), SceneError> {
        let method = self
            .sampling_method(l)?
            .or(self.method)
            .unwrap_or(Method::Jittered);
        let samples_node = l.get_any(light::SAMPLES);
        let samples = match &samples_node {
            Some(n) => n.u32()?.max(1),
            None => 4,
        };
        // `jittered`: `samples` is the side of the grid; `random` and `sobol`: the total.
        let total = match method {
            Method::Jittered => samples as u64 * samples as u64,
            Method::Random | Method::Sobol => samples as u64,
        };
        if total > self.options.max_light_samples as u64 {
            let n = samples_node.unwrap_or_else(|| l.clone());
            return Err(n.error(format!(
                "{total} shadow rays per point is over the limit of {} (raise it with --max-light-samples)",
                self.options.max_light_samples
            )));
        }
        Ok((total as u32, method))
    }
}

/// The parallelogram (origin and two edges) of an area light given by its corners (`v0`..`v3`
/// or `c1`..`c3`), a corner and two edges, two edges about its centre, or a centre and a `size`;
/// `None` if it is given in none of these forms.
fn light_quad(l: &Node) -> Result<Option<(Vec3, Vec3, Vec3)>, SceneError> {
    let any = |k: &[&str]| l.get_any(k).map(|n| n.vec3()).transpose();
    let [v0, v1, v2, v3] = light::CORNERS;
    let [c1, c2, c3] = light::RIGHT_ANGLE_CORNERS;
    let quad = if let (Some(a), Some(b), Some(c)) = (any(v0)?, any(v1)?, any(v2)?) {
        match any(v3)? {
            Some(d) => quad_edges([a, b, c, d]),
            None => right_angle_corner(a, b, c),
        }
    } else if let (Some(a), Some(b), Some(c)) = (any(c1)?, any(c2)?, any(c3)?) {
        right_angle_corner(a, b, c)
    } else if let (Some(p), Some(e0), Some(e1)) = (
        any(light::CORNER)?,
        any(light::EDGE_1)?,
        any(light::EDGE_2)?,
    ) {
        (p, e0, e1)
    } else if let (Some(p), Some(u), Some(v)) = (
        any(light::POSITION)?,
        any(light::AXIS_U)?,
        any(light::AXIS_V)?,
    ) {
        centred_quad(l, p, u, v)?
    } else if let (Some(p), Some(size)) = (any(light::POSITION)?, l.get_any(light::SIZE)) {
        let (sw, sh) = match size.numbers() {
            Ok(v) if v.len() == 2 => (v[0] as f32, v[1] as f32),
            _ => {
                let s = size.f32()?;
                (s, s)
            }
        };
        // A horizontal rectangle (in the x–z plane).
        let eu = Vec3::X * sw;
        let ev = Vec3::Z * sh;
        (p - 0.5 * eu - 0.5 * ev, eu, ev)
    } else {
        return Ok(None);
    };
    Ok(Some(quad))
}

/// The parallelogram centred on `p` with edges `u`, `v`, or with `width`/`height` given, edges
/// along `u`, `v` of those lengths.
fn centred_quad(l: &Node, p: Vec3, u: Vec3, v: Vec3) -> Result<(Vec3, Vec3, Vec3), SceneError> {
    let w = opt_f32(l, light::WIDTH)?;
    let h = opt_f32(l, light::HEIGHT)?;
    let eu = match w {
        Some(w) => u.normalize_or_zero() * w,
        None => u,
    };
    let ev = match h {
        Some(h) => v.normalize_or_zero() * h,
        None => v,
    };
    Ok((p - 0.5 * eu - 0.5 * ev, eu, ev))
}
