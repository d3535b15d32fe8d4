//! Lights: points, quads, spheres, and shapes of the scene that emit (area lights).
//!
//! ```json
//! { "type": "pointlight", "position": [0, 1, 1.5], "is": [100, 100, 100], "id": [100, 100, 100] }
//! { "type": "pointlight", "position": [0, 1, 0.5], "intensity": [0.5, 0.5, 0.5] }
//! { "type": "arealight", "v0": […], "v1": […], "v2": […], "v3": […], "samples": 4,
//!   "method": "jittered", "is": […], "id": […] }
//! { "type": "arealight", "intensity": [20, 20, 20], "samplesize": 10,
//!   "shape": { "type": "sphere", "center": [-2, 2, 2], "radius": 1 } }
//! { "type": "arealight", "shapeid": "myarealightshape", "is": […], "id": […] }
//! ```
//! Fall-off ([`Falloff`]) is inverse-square in the 2019 and 2021–23 variants. A light with
//! `is`/`id` (2021–23) gives the irradiance `I / (4π d²)` — the point source of power `I` —
//! which is what the official reference render shows; a light with `intensity` (2019) gives
//! `I / d²`; a CGR light with `intensity` does not fall off at all. A light of any variant that
//! gives OpenGL-style attenuation coefficients falls off as `I / (kc + kl·d + kq·d²)`:
//! ```json
//! { "type": "pointlight", "position": [0, 1, 0.5], "intensity": [0.75, 0.75, 0.75],
//!   "kc": 1.0, "kl": 0.22, "kq": 0.2 }
//! ```
//! (the evidence for each reading is in `docs/scene-format.md`).
//!
//! Every light is sampled as a set of point sources: a [`LightSample`] is a point on the light and
//! a `weight`, and the shading point receives `weight · I · falloff` from it, divided by the
//! number of samples taken, the fall-off being taken at the distance
//! [`LightSample::falloff_d2`] gives. So an area light has the same power as the point light it
//! would be with the same `is`/`id`/`intensity`:
//! - a **quad** (`v0`..`v3`, `p`+`e0`+`e1`, …) is the parallelogram `origin + s·e_u + t·e_v`,
//!   `s, t ∈ [0,1]`, sampled uniformly; every sample has weight 1 and falls off from where it is,
//!   as if the light were `n` point lights spread over the quad;
//! - a **sphere** (`"shape": {"type": "sphere", …}`, or a sphere named by `shapeid`) is a ball of
//!   uniform brightness `L = I/(π r²)` (a uniformly bright ball of radius `r` has the radiant
//!   intensity `π r² L` in every direction, so it is an isotropic source of intensity `I`). From
//!   outside, its samples are taken uniformly in the cone of directions it subtends, as pbrt-v4
//!   does (Pharr, Jakob, Humphreys, *Physically Based Rendering*, 4th ed., §6.2.4, sphere sampling
//!   with a reference point): they lie on the cap seen from the shading point, and a sample's weight
//!   is `2 (1 − cos θ_max) d_c² / r²`, i.e. `L / pdf` in solid angle over the point source's
//!   `I / d_c²`, with the fall-off taken at the distance `d_c` to the centre. For a sphere wholly
//!   above the surface's horizon the expected irradiance is then exactly that of a point light at
//!   its centre, at any distance and for any fall-off. From inside (or on) the sphere, samples are
//!   uniform over its whole surface with weight `4 |cos θ_l|` (`L |cos θ_l| / (d² · pdf_area)`
//!   over `I / d²`, `pdf_area = 1/(4π r²)`), falling off from where they are;
//! - a **triangle or quad of the scene** named by `shapeid` is sampled uniformly by area over its
//!   triangles (weight 1, like a quad light). Its own primitives ([`Light::surface`]) never block
//!   its shadow rays; they are still shapes for camera rays and for other lights.

use std::ops::Range;

use crate::accel::aabb::Aabb;
use crate::math::{orthonormal_basis, Vec2, Vec3};
use crate::sampling::{uniform_sphere, Method};

/// Per-channel strength of a light's diffuse and specular contributions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Intensity {
    /// Diffuse intensity (`id`).
    pub diffuse: Vec3,
    /// Specular intensity (`is`).
    pub specular: Vec3,
    pub falloff: Falloff,
}

/// How a light's irradiance falls off with the distance `d` to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Falloff {
    /// `scale / d²`: `scale` is `1/(4π)` for power-style (`is`/`id`) lights, 1 for `intensity`
    /// lights of the 2019 variant.
    InverseSquare { scale: f32 },
    /// `1 / (kc + kl·d + kq·d²)`, the attenuation of fixed-function OpenGL lights; `kc = 1`,
    /// `kl = kq = 0` is no fall-off at all (CGR lights without coefficients).
    Polynomial { kc: f32, kl: f32, kq: f32 },
}

impl Falloff {
    /// No fall-off: the irradiance is the intensity at any distance.
    pub const NONE: Falloff = Falloff::Polynomial {
        kc: 1.0,
        kl: 0.0,
        kq: 0.0,
    };
}

#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    Point {
        position: Vec3,
        intensity: Intensity,
    },
    Quad {
        /// Corner `v0`.
        origin: Vec3,
        /// `v1 − v0`.
        edge_u: Vec3,
        /// `v3 − v0`.
        edge_v: Vec3,
        intensity: Intensity,
        /// Number of shadow rays per shading point.
        samples: u32,
        method: Method,
        /// Unit normal of the quad (`edge_u × edge_v`, normalised), kept for its samples.
        normal: Vec3,
        /// Area of the quad, kept for its samples' pdf.
        area: f32,
        /// The side the quad emits towards when it is a path tracer's emitter (the file's
        /// `normal`); without one, the side facing the centre of the scene.
        facing: Option<Vec3>,
    },
    /// A uniformly bright ball.
    Sphere {
        center: Vec3,
        /// > 0.
        radius: f32,
        intensity: Intensity,
        /// Number of shadow rays per shading point.
        samples: u32,
        method: Method,
        /// The scene primitives that are this sphere (a sphere named by `shapeid`), or none.
        surface: Range<u32>,
    },
    /// Flat triangles of the scene (a triangle or a quad named by `shapeid`), sampled uniformly
    /// by area.
    Triangles {
        /// Corner positions; at least one triangle, with a total area > 0.
        triangles: Vec<[Vec3; 3]>,
        /// `cumulative_area[i]`: the area of triangles `0..=i`.
        cumulative_area: Vec<f32>,
        intensity: Intensity,
        /// Number of shadow rays per shading point.
        samples: u32,
        method: Method,
        /// The scene primitives that are these triangles.
        surface: Range<u32>,
    },
}

/// One sample position on a light, as seen from a shading point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightSample {
    pub position: Vec3,
    /// Unit normal of the light's surface at `position` (either side for flat lights, outwards
    /// for spheres); zero for a point light.
    pub normal: Vec3,
    /// What the sample carries relative to a point source of the light's intensity at
    /// `position`, for one sample alone (the caller divides by the number of samples): 1 for
    /// points, quads and shape triangles.
    pub weight: f32,
    /// Density of the sample's direction in solid angle at the shading point (what a path
    /// tracer's light sampling needs); 0 for a point light, whose direction is certain. Infinite
    /// where a flat light is seen edge-on.
    pub pdf: f32,
    /// The squared distance at which the light's [`Falloff`] is taken for this sample: the
    /// sample's own, except for a sphere seen from outside, whose weight is relative to a point
    /// source at its centre.
    pub falloff_d2: f32,
}

impl Light {
    /// The parallelogram light `origin + s·edge_u + t·edge_v`, `s, t ∈ [0, 1]`, with its normal
    /// and area worked out once rather than for every sample.
    pub fn quad(
        origin: Vec3,
        edge_u: Vec3,
        edge_v: Vec3,
        intensity: Intensity,
        samples: u32,
        method: Method,
    ) -> Light {
        let cross = edge_u.cross(edge_v);
        Light::Quad {
            origin,
            edge_u,
            edge_v,
            intensity,
            samples,
            method,
            normal: cross.normalize_or_zero(),
            area: cross.length(),
            facing: None,
        }
    }

    /// Flat triangles of light, of their own (no scene primitive is them), sampled by area.
    pub fn triangles(
        triangles: Vec<[Vec3; 3]>,
        intensity: Intensity,
        samples: u32,
        method: Method,
    ) -> Light {
        Light::Triangles {
            cumulative_area: cumulative_areas(&triangles),
            triangles,
            intensity,
            samples,
            method,
            surface: 0..0,
        }
    }

    /// Whether the light is a point: one position, no area, seen by no ray.
    pub fn is_point(&self) -> bool {
        matches!(self, Light::Point { .. })
    }

    /// The area the light emits from; `None` for a point light.
    pub fn area(&self) -> Option<f32> {
        match self {
            Light::Point { .. } => None,
            Light::Quad { area, .. } => Some(*area),
            Light::Sphere { radius, .. } => Some(4.0 * std::f32::consts::PI * radius * radius),
            Light::Triangles {
                cumulative_area, ..
            } => Some(cumulative_area.last().copied().unwrap_or(0.0)),
        }
    }

    /// The side a path tracer sees the light's surface emit towards at `point`, whose normal is
    /// `normal`: a sphere's outside, a quad's `facing`, else the side facing `centre` (the
    /// scene's). `None` for a point light, which no ray meets.
    pub fn emitting_side(&self, point: Vec3, normal: Vec3, centre: Vec3) -> Option<Vec3> {
        Some(match self {
            Light::Point { .. } => return None,
            Light::Sphere { .. } => normal,
            Light::Quad {
                facing: Some(f), ..
            } => *f,
            Light::Quad { .. } | Light::Triangles { .. } => {
                if normal.dot(centre - point) < 0.0 {
                    -normal
                } else {
                    normal
                }
            }
        })
    }

    /// The light with `count` shadow rays per shading point placed with `method`; a point light,
    /// which takes one, as it is.
    pub fn with_samples(mut self, count: u32, placed: Method) -> Light {
        if let Light::Quad {
            samples, method, ..
        }
        | Light::Sphere {
            samples, method, ..
        }
        | Light::Triangles {
            samples, method, ..
        } = &mut self
        {
            (*samples, *method) = (count, placed);
        }
        self
    }

    /// How many shadow rays this light takes per shading point.
    pub fn sample_count(&self) -> u32 {
        match self {
            Light::Point { .. } => 1,
            Light::Quad { samples, .. }
            | Light::Sphere { samples, .. }
            | Light::Triangles { samples, .. } => (*samples).max(1),
        }
    }

    pub fn intensity(&self) -> &Intensity {
        match self {
            Light::Point { intensity, .. }
            | Light::Quad { intensity, .. }
            | Light::Sphere { intensity, .. }
            | Light::Triangles { intensity, .. } => intensity,
        }
    }

    /// The sample at `u ∈ [0,1)²` for the shading point `from`. Inlined, so that a caller
    /// that does not read the solid-angle `pdf` does not pay for its division.
    #[inline(always)]
    pub fn sample(&self, from: Vec3, u: Vec2) -> LightSample {
        match self {
            Light::Point { position, .. } => LightSample {
                position: *position,
                normal: Vec3::ZERO,
                weight: 1.0,
                pdf: 0.0,
                falloff_d2: (*position - from).length_squared(),
            },
            Light::Quad {
                origin,
                edge_u,
                edge_v,
                normal,
                area,
                ..
            } => {
                let position = *origin + u.x * *edge_u + u.y * *edge_v;
                flat_sample(from, position, *normal, *area)
            }
            Light::Sphere { center, radius, .. } => sample_sphere(*center, *radius, from, u),
            Light::Triangles {
                triangles,
                cumulative_area,
                ..
            } => sample_triangles(triangles, cumulative_area, from, u),
        }
    }

    /// The sample of a light that gets a single shadow ray: its middle. That is the sample at
    /// `(½, ½)` for every light but shape triangles, where `(½, ½)` falls on a corner of one of
    /// them; theirs is the centroid by area.
    pub fn sample_one(&self, from: Vec3) -> LightSample {
        match self {
            Light::Triangles {
                triangles,
                cumulative_area,
                ..
            } => {
                let total = cumulative_area.last().copied().unwrap_or(0.0);
                let normal = triangles
                    .first()
                    .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero())
                    .unwrap_or(Vec3::ZERO);
                flat_sample(from, self.center(), normal, total)
            }
            _ => self.sample(from, Vec2::splat(0.5)),
        }
    }

    /// The solid-angle density at `from` with which [`Light::sample`] (for uniform `u`) picks
    /// `point` of the light's surface, whose unit normal there is `normal`: what a path tracer
    /// weighs a direction against when its BSDF sample hits the light. 0 for a point light.
    pub fn pdf(&self, from: Vec3, point: Vec3, normal: Vec3) -> f32 {
        let area_pdf = |area: f32| area_to_solid_angle(point - from, normal, area);
        match self {
            Light::Point { .. } => 0.0,
            Light::Quad { area, .. } => area_pdf(*area),
            Light::Triangles {
                cumulative_area, ..
            } => area_pdf(cumulative_area.last().copied().unwrap_or(0.0)),
            Light::Sphere { center, radius, .. } => {
                let r2 = radius * radius;
                let dc2 = (from - *center).length_squared();
                if dc2 <= r2 {
                    area_pdf(4.0 * std::f32::consts::PI * r2)
                } else {
                    1.0 / (2.0 * std::f32::consts::PI * cone_one_minus_cos(r2, dc2))
                }
            }
        }
    }

    /// The sampling method of an area light (points use none).
    pub fn method(&self) -> Method {
        match self {
            Light::Point { .. } => Method::Random,
            Light::Quad { method, .. }
            | Light::Sphere { method, .. }
            | Light::Triangles { method, .. } => *method,
        }
    }

    /// The light's centre: its position, the quad's or the sphere's centre, the triangles'
    /// centroid by area.
    pub fn center(&self) -> Vec3 {
        match self {
            Light::Point { position, .. } => *position,
            Light::Quad {
                origin,
                edge_u,
                edge_v,
                ..
            } => *origin + 0.5 * (*edge_u + *edge_v),
            Light::Sphere { center, .. } => *center,
            Light::Triangles {
                triangles,
                cumulative_area,
                ..
            } => {
                let mut low = 0.0;
                let mut sum = Vec3::ZERO;
                for (t, &c) in triangles.iter().zip(cumulative_area) {
                    sum += (c - low) * (t[0] + t[1] + t[2]) / 3.0;
                    low = c;
                }
                sum / low
            }
        }
    }

    /// A box holding every sample position of the light; `None` for a point light.
    pub fn bounds(&self) -> Option<Aabb> {
        match self {
            Light::Point { .. } => None,
            Light::Quad {
                origin,
                edge_u,
                edge_v,
                ..
            } => Some(
                Aabb::EMPTY
                    .grow(*origin)
                    .grow(*origin + *edge_u)
                    .grow(*origin + *edge_v)
                    .grow(*origin + *edge_u + *edge_v),
            ),
            Light::Sphere { center, radius, .. } => Some(Aabb::new(
                *center - Vec3::splat(*radius),
                *center + Vec3::splat(*radius),
            )),
            Light::Triangles { triangles, .. } => Some(
                triangles
                    .iter()
                    .flatten()
                    .fold(Aabb::EMPTY, |b, &p| b.grow(p)),
            ),
        }
    }

    /// The scene primitives that are this light's own surface: its shadow rays pass through them
    /// (empty for lights that are not shapes of the scene).
    pub fn surface(&self) -> Range<u32> {
        match self {
            Light::Sphere { surface, .. } | Light::Triangles { surface, .. } => surface.clone(),
            Light::Point { .. } | Light::Quad { .. } => 0..0,
        }
    }
}

/// A uniform-by-area sample at `position` on a flat light of total `area` and unit `normal`:
/// weight 1, solid-angle density `d² / (area · |cos θ_l|)`.
#[inline(always)]
fn flat_sample(from: Vec3, position: Vec3, normal: Vec3, area: f32) -> LightSample {
    let d = position - from;
    LightSample {
        position,
        normal,
        weight: 1.0,
        pdf: area_to_solid_angle(d, normal, area),
        falloff_d2: d.length_squared(),
    }
}

/// The solid-angle density, seen along `d` (shading point to sample), of a point sampled
/// uniformly by area on a surface of total `area` whose unit normal there is `normal`:
/// `|d|² / (area · |cos θ_l|)`. Infinite where the surface is seen edge-on.
#[inline(always)]
fn area_to_solid_angle(d: Vec3, normal: Vec3, area: f32) -> f32 {
    let d2 = d.length_squared();
    let cos_l = normal.dot(d).abs() / d2.sqrt();
    d2 / (area * cos_l)
}

/// `1 − cos θ_max` of the cone a ball of squared radius `r2` fills seen from squared distance
/// `dc2 > r2` to its centre (sin θ_max = r / d_c), computed without cancellation so that a
/// small, distant ball (cos θ_max close to 1) keeps its precision.
#[inline(always)]
fn cone_one_minus_cos(r2: f32, dc2: f32) -> f32 {
    let sin2_max = r2 / dc2;
    sin2_max / (1.0 + (1.0 - sin2_max).max(0.0).sqrt())
}

/// A sample of the ball `(center, radius)` seen from `from` (see the module docs).
fn sample_sphere(center: Vec3, radius: f32, from: Vec3, u: Vec2) -> LightSample {
    let r2 = radius * radius;
    let axis = from - center;
    let dc2 = axis.length_squared();
    if dc2 <= r2 {
        // Inside or on the surface: uniform over the whole sphere.
        let normal = uniform_sphere(u);
        let position = center + radius * normal;
        let d = from - position;
        let d2 = d.length_squared();
        let cos_l = (normal.dot(d) / d2.sqrt()).abs();
        return LightSample {
            position,
            normal,
            weight: 4.0 * cos_l,
            pdf: d2 / (cos_l * 4.0 * std::f32::consts::PI * r2),
            falloff_d2: d2,
        };
    }
    let dc = dc2.sqrt();
    let w = axis / dc;
    // θ is the angle at `from` between a direction and the one to the centre; the sphere fills
    // θ ≤ θ_max with sin θ_max = r / d_c. `1 − cos θ` is kept as the sampled quantity itself, so
    // that a small, distant sphere (cos θ_max close to 1) loses nothing to cancellation.
    let one_minus_cos_max = cone_one_minus_cos(r2, dc2);
    let a = u.x * one_minus_cos_max; // 1 − cos θ, uniform in [0, 1 − cos θ_max]
    let cos_t = 1.0 - a;
    let sin2_t = a * (2.0 - a);
    // The ray at angle θ meets the sphere first at the point whose angle α at the centre, from
    // the axis towards `from`, has cos α = (d_c/r) sin²θ + cos θ · sqrt(1 − (d_c/r)² sin²θ).
    let ratio = dc / radius;
    let cos_a = (ratio * sin2_t + cos_t * (1.0 - ratio * ratio * sin2_t).max(0.0).sqrt()).min(1.0);
    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
    let phi = 2.0 * std::f32::consts::PI * u.y;
    let (t, b) = orthonormal_basis(w);
    let normal = cos_a * w + sin_a * (phi.cos() * t + phi.sin() * b);
    let position = center + radius * normal;
    LightSample {
        position,
        normal,
        weight: 2.0 * one_minus_cos_max * dc2 / r2,
        pdf: 1.0 / (2.0 * std::f32::consts::PI * one_minus_cos_max),
        falloff_d2: dc2,
    }
}

/// A uniform-by-area sample of `triangles`: `u.x` picks the triangle in proportion to its area
/// and is stretched back to [0, 1) within it, then the square is warped onto the triangle with
/// the square-root map of Osada et al., "Shape Distributions" (ACM TOG 21(4), 2002, §4.2).
fn sample_triangles(
    triangles: &[[Vec3; 3]],
    cumulative_area: &[f32],
    from: Vec3,
    u: Vec2,
) -> LightSample {
    let total = cumulative_area.last().copied().unwrap_or(0.0);
    let x = u.x * total;
    let i = cumulative_area
        .partition_point(|&c| c <= x)
        .min(triangles.len().saturating_sub(1));
    let low = if i == 0 { 0.0 } else { cumulative_area[i - 1] };
    let width = cumulative_area[i] - low;
    let ux = if width > 0.0 {
        ((x - low) / width).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let [p0, p1, p2] = triangles[i];
    let s = ux.sqrt();
    // From a corner along the edges, so that a point of an axis-aligned triangle keeps the
    // plane's coordinate exactly.
    let position = p0 + (s * (1.0 - u.y)) * (p1 - p0) + (s * u.y) * (p2 - p0);
    let normal = (p1 - p0).cross(p2 - p0).normalize_or_zero();
    flat_sample(from, position, normal, total)
}

/// The running sums of the triangles' areas, for [`Light::Triangles`].
pub fn cumulative_areas(triangles: &[[Vec3; 3]]) -> Vec<f32> {
    let mut sum = 0.0;
    triangles
        .iter()
        .map(|[a, b, c]| {
            sum += 0.5 * (*b - *a).cross(*c - *a).length();
            sum
        })
        .collect()
}

impl Intensity {
    /// The factor of the intensity that reaches squared distance `d2`.
    #[inline]
    pub fn falloff(&self, d2: f32) -> f32 {
        match self.falloff {
            Falloff::InverseSquare { scale } => scale / d2,
            // Without distance terms (every CGR `intensity` light) the square root is not
            // needed: for a finite `d² ≥ 0`, `kl·d` and `kq·d²` are zeros of the signs of `kl`
            // and `kq`, the very values written here.
            Falloff::Polynomial { kc, kl, kq } if kl == 0.0 && kq == 0.0 && d2.is_finite() => {
                1.0 / (kc + kl * 0.0 + kq * 0.0)
            }
            Falloff::Polynomial { kc, kl, kq } => 1.0 / (kc + kl * d2.sqrt() + kq * d2),
        }
    }

    /// [`Intensity::falloff`] of four squared distances, lane by lane the same bits.
    #[inline(always)]
    pub fn falloff4(&self, d2: glam::Vec4) -> glam::Vec4 {
        use glam::Vec4;
        match self.falloff {
            Falloff::InverseSquare { scale } => Vec4::splat(scale) / d2,
            Falloff::Polynomial { kc, kl, kq } => {
                let general = Vec4::ONE
                    / (Vec4::splat(kc) + Vec4::splat(kl) * crate::math::sqrt4(d2) + kq * d2);
                if kl == 0.0 && kq == 0.0 {
                    let constant = Vec4::splat(self.falloff(0.0));
                    Vec4::select(d2.is_finite_mask(), constant, general)
                } else {
                    general
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_samples_cover_the_parallelogram_and_share_the_power() {
        let l = Light::quad(
            Vec3::ZERO,
            Vec3::X * 2.0,
            Vec3::Y,
            Intensity {
                diffuse: Vec3::ONE,
                specular: Vec3::ONE,
                falloff: Falloff::InverseSquare { scale: 1.0 },
            },
            16,
            Method::Jittered,
        );
        let s = l.sample(Vec3::new(0.0, 0.0, 1.0), Vec2::new(1.0, 1.0));
        assert_eq!(s.position, Vec3::new(2.0, 1.0, 0.0));
        assert_eq!(s.weight, 1.0);
        assert_eq!(s.normal, Vec3::Z);
        // Seen from (0, 0, 1): d² = 6, cos θ_l = 1/√6, area 2.
        assert!((s.pdf - 6.0 / (2.0 / 6.0f32.sqrt())).abs() < 1e-4);
        assert_eq!(l.sample_count(), 16);
    }

    fn unit() -> Intensity {
        Intensity {
            diffuse: Vec3::ONE,
            specular: Vec3::ONE,
            falloff: Falloff::InverseSquare { scale: 1.0 },
        }
    }

    fn ball(center: Vec3, radius: f32) -> Light {
        Light::Sphere {
            center,
            radius,
            intensity: unit(),
            samples: 1,
            method: Method::Jittered,
            surface: 0..0,
        }
    }

    /// The midpoints of a k × k grid over the unit square.
    fn grid(k: u32) -> impl Iterator<Item = Vec2> {
        (0..k * k).map(move |i| {
            Vec2::new(
                ((i % k) as f32 + 0.5) / k as f32,
                ((i / k) as f32 + 0.5) / k as f32,
            )
        })
    }

    /// The irradiance the light's samples give at `p` (normal `n`), as the integrator sums it
    /// (weight · cos · fall-off at `falloff_d2`, averaged over the samples), for a light of
    /// intensity 1 and fall-off 1/d².
    fn irradiance(l: &Light, p: Vec3, n: Vec3, k: u32) -> f64 {
        irradiance_with(l, p, n, k, Falloff::InverseSquare { scale: 1.0 })
    }

    fn irradiance_with(l: &Light, p: Vec3, n: Vec3, k: u32, falloff: Falloff) -> f64 {
        let i = Intensity {
            diffuse: Vec3::ONE,
            specular: Vec3::ONE,
            falloff,
        };
        let mut sum = 0.0f64;
        for u in grid(k) {
            let s = l.sample(p, u);
            let d = s.position - p;
            let cos = (n.dot(d) / d.length()).max(0.0);
            sum += (s.weight * cos * i.falloff(s.falloff_d2)) as f64;
        }
        sum / (k * k) as f64
    }

    /// `Light::pdf` gives back the density `Light::sample` reports for the point it chose.
    #[test]
    fn pdf_of_a_sampled_point_is_the_samples_pdf() {
        let tri = [
            [Vec3::ZERO, Vec3::X, Vec3::Y],
            [Vec3::X, Vec3::new(1.0, 1.0, 0.5), Vec3::Y],
        ];
        let lights = [
            Light::quad(
                Vec3::ZERO,
                Vec3::X * 2.0,
                Vec3::new(0.0, 0.5, 1.0),
                unit(),
                4,
                Method::Sobol,
            ),
            ball(Vec3::new(0.0, 0.0, -1.0), 0.5),
            ball(Vec3::new(0.0, 0.0, 3.0), 4.0),
            Light::Triangles {
                cumulative_area: cumulative_areas(&tri),
                triangles: tri.to_vec(),
                intensity: unit(),
                samples: 4,
                method: Method::Sobol,
                surface: 0..0,
            },
        ];
        let from = Vec3::new(0.3, 2.0, 1.5);
        for l in &lights {
            for u in grid(8) {
                let s = l.sample(from, u);
                let p = l.pdf(from, s.position, s.normal);
                assert!((p / s.pdf - 1.0).abs() < 1e-3, "{l:?}: {p} vs {}", s.pdf);
            }
        }
    }

    /// Under any fall-off, a sphere light above the horizon lights a point as the point light at
    /// its centre with that fall-off: here none at all (a CGR light) and OpenGL attenuation.
    #[test]
    fn a_sphere_light_follows_its_lights_falloff_from_its_centre() {
        let l = ball(Vec3::ZERO, 0.5);
        let p = Vec3::new(0.0, 4.0, 0.0);
        for falloff in [
            Falloff::NONE,
            Falloff::Polynomial {
                kc: 1.0,
                kl: 0.22,
                kq: 0.2,
            },
        ] {
            let e = irradiance_with(&l, p, Vec3::NEG_Y, 64, falloff);
            let point = Intensity {
                diffuse: Vec3::ONE,
                specular: Vec3::ONE,
                falloff,
            }
            .falloff(16.0) as f64;
            assert!(
                (e / point - 1.0).abs() < 5e-3,
                "{falloff:?}: {e} vs {point}"
            );
        }
    }

    /// Far from a small sphere light, its irradiance is a point light's of the same intensity at
    /// its centre (1/d² here): within 0.1% with a 32 × 32 grid of samples.
    #[test]
    fn a_far_small_sphere_lights_like_a_point_at_its_centre() {
        let c = Vec3::new(1.0, -2.0, 0.5);
        let l = ball(c, 0.05);
        let p = c + Vec3::new(0.0, 0.0, 40.0);
        let e = irradiance(&l, p, Vec3::NEG_Z, 32);
        let point = 1.0 / 1600.0;
        assert!((e / point - 1.0).abs() < 1e-3, "{e} vs {point}");
    }

    /// A sphere wholly above a surface's horizon gives exactly a point light's irradiance at any
    /// distance (the uniform ball's classic property): here at 3 radii, tilted 40° (the sphere
    /// spans 19.5°), within 0.5%.
    #[test]
    fn a_near_sphere_above_the_horizon_still_matches_the_point_light() {
        let l = ball(Vec3::ZERO, 1.0);
        let p = Vec3::new(0.0, 3.0, 0.0);
        let tilt = 40f32.to_radians();
        let n = Vec3::new(tilt.sin(), -tilt.cos(), 0.0);
        let e = irradiance(&l, p, n, 64);
        let point = (tilt.cos() / 9.0) as f64;
        assert!((e / point - 1.0).abs() < 5e-3, "{e} vs {point}");
    }

    /// Samples lie on the sphere, on the cap seen from the shading point, and reach across it.
    #[test]
    fn sphere_samples_lie_on_the_visible_cap() {
        let (c, r) = (Vec3::new(0.2, -0.1, 0.4), 1.2f32);
        let l = ball(c, r);
        let p = c + Vec3::new(0.3, 2.5, -1.0);
        let w = (p - c).normalize();
        let cap_edge = r / (p - c).length(); // cos α at the cap's rim
        let mut lowest = 1.0f32;
        for u in grid(40) {
            let s = l.sample(p, u);
            let q = s.position - c;
            assert!((q.length() / r - 1.0).abs() < 1e-5, "off the sphere: {q}");
            assert!((s.normal - q / r).length() < 1e-5);
            let cos_a = q.dot(w) / r;
            assert!(
                cos_a >= cap_edge - 1e-5,
                "behind the rim: {cos_a} < {cap_edge}"
            );
            lowest = lowest.min(cos_a);
        }
        // Near the rim cos α moves as the square root of the distance to it (the ray grazes the
        // sphere there), so the last row of a 40-row grid is still about 0.09 inside it.
        assert!(
            lowest < cap_edge + 0.1,
            "the samples stop short of the rim: {lowest}"
        );
    }

    /// Inside the sphere the samples cover all of it, and the irradiance is π L = I/r².
    #[test]
    fn inside_a_sphere_light_samples_cover_it_all() {
        let r = 2.0f32;
        let l = ball(Vec3::ZERO, r);
        let e = irradiance(&l, Vec3::ZERO, Vec3::Z, 64);
        assert!((e * (r * r) as f64 - 1.0).abs() < 1e-2, "{e}");
        let below = grid(16)
            .filter(|&u| l.sample(Vec3::ZERO, u).position.z < 0.0)
            .count();
        assert_eq!(below, 128);
    }

    /// Shape triangles are sampled uniformly by area: each sample lies in a triangle, and a
    /// triangle three times larger gets three times the samples.
    #[test]
    fn triangle_samples_are_uniform_by_area() {
        let triangles = vec![
            [Vec3::ZERO, Vec3::X, Vec3::Y * 2.0],
            [
                Vec3::new(5.0, 0.0, 1.0),
                Vec3::new(8.0, 0.0, 1.0),
                Vec3::new(5.0, 2.0, 1.0),
            ],
        ];
        let cumulative_area = cumulative_areas(&triangles);
        assert_eq!(cumulative_area, vec![1.0, 4.0]);
        let l = Light::Triangles {
            triangles: triangles.clone(),
            cumulative_area,
            intensity: unit(),
            samples: 1,
            method: Method::Random,
            surface: 0..2,
        };
        let from = Vec3::new(3.0, 1.0, 5.0);
        let mut in_second = 0;
        for u in grid(32) {
            let s = l.sample(from, u);
            let t = if s.position.x > 4.0 { 1 } else { 0 };
            in_second += t;
            let [a, b, c] = triangles[t];
            // Barycentric coordinates of the sample in its triangle.
            let (e1, e2, q) = (b - a, c - a, s.position - a);
            let n = e1.cross(e2);
            let b1 = q.cross(e2).dot(n) / n.length_squared();
            let b2 = e1.cross(q).dot(n) / n.length_squared();
            assert!(q.dot(n).abs() < 1e-5, "off the plane");
            assert!(
                b1 >= -1e-6 && b2 >= -1e-6 && b1 + b2 <= 1.0 + 1e-6,
                "outside"
            );
            assert_eq!(s.weight, 1.0);
        }
        assert_eq!(in_second, 768);
        assert_eq!(l.surface(), 0..2);
    }

    #[test]
    fn four_falloffs_are_four_times_the_one() {
        let d2 = [
            glam::Vec4::new(0.0, 1e-30, 2.5, 1e30),
            glam::Vec4::new(f32::INFINITY, f32::NAN, 7.0, -0.0),
        ];
        for falloff in [
            Falloff::InverseSquare { scale: 0.25 },
            Falloff::NONE,
            Falloff::Polynomial {
                kc: 1.0,
                kl: 0.22,
                kq: 0.2,
            },
            Falloff::Polynomial {
                kc: 0.5,
                kl: 0.0,
                kq: 0.0,
            },
        ] {
            let i = Intensity {
                diffuse: Vec3::ONE,
                specular: Vec3::ONE,
                falloff,
            };
            for d in d2 {
                let lanes = i.falloff4(d);
                for l in 0..4 {
                    assert_eq!(
                        lanes[l].to_bits(),
                        i.falloff(d[l]).to_bits(),
                        "{falloff:?} at {}",
                        d[l]
                    );
                }
            }
        }
    }

    #[test]
    fn falloff_is_inverse_square() {
        let i = Intensity {
            diffuse: Vec3::ONE,
            specular: Vec3::ONE,
            falloff: Falloff::InverseSquare {
                scale: 0.25 / std::f32::consts::PI,
            },
        };
        assert!((i.falloff(4.0) * 4.0 - i.falloff(1.0)).abs() < 1e-7);
    }

    #[test]
    fn polynomial_falloff_is_opengl_attenuation_and_none_is_constant() {
        let at = |falloff, d: f32| {
            Intensity {
                diffuse: Vec3::ONE,
                specular: Vec3::ONE,
                falloff,
            }
            .falloff(d * d)
        };
        let f = Falloff::Polynomial {
            kc: 1.0,
            kl: 0.22,
            kq: 0.2,
        };
        assert!((at(f, 2.0) - 1.0 / (1.0 + 0.44 + 0.8)).abs() < 1e-6);
        for d in [0.01, 1.0, 100.0] {
            assert_eq!(at(Falloff::NONE, d), 1.0);
        }
    }
}
