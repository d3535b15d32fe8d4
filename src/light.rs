//! Lights: points and quads (area lights).
//!
//! ```json
//! { "type": "pointlight", "position": [0, 1, 1.5], "is": [100, 100, 100], "id": [100, 100, 100] }
//! { "type": "pointlight", "position": [0, 1, 0.5], "intensity": [0.5, 0.5, 0.5] }
//! { "type": "arealight", "v0": […], "v1": […], "v2": […], "v3": […], "samples": 4,
//!   "method": "jittered", "is": […], "id": […] }
//! ```
//! Fall-off ([`Falloff`]) is inverse-square in the 2019 and 2021–23 variants. A light with
//! `is`/`id` (2021–23) gives the irradiance `I / (4π d²)` — the point source of power `I` —
//! which is what the official reference render shows; a light with `intensity` (2019) gives
//! `I / d²`. CGR lights do not fall off, unless they give OpenGL-style attenuation
//! coefficients, `I / (kc + kl·d + kq·d²)`:
//! ```json
//! { "type": "pointlight", "position": [0, 1, 0.5], "intensity": [0.75, 0.75, 0.75],
//!   "kc": 1.0, "kl": 0.22, "kq": 0.2 }
//! ```
//! (the evidence for each reading is in `docs/scene-format.md`). An area light is the parallelogram
//! `v0 + s(v1 − v0) + t(v3 − v0)`, `s, t ∈ [0,1]`, sampled with shadow rays: each of its `n`
//! samples carries `1/n` of its power, as if it were `n` point lights spread over the quad.

use crate::math::{Vec2, Vec3};
use crate::sampling::Method;

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
    },
}

/// One sample position on a light and the weight its contribution carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightSample {
    pub position: Vec3,
    /// The fraction of the light's intensity this sample carries.
    pub weight: f32,
}

impl Light {
    /// How many shadow rays this light takes per shading point.
    pub fn sample_count(&self) -> u32 {
        match self {
            Light::Point { .. } => 1,
            Light::Quad { samples, .. } => (*samples).max(1),
        }
    }

    pub fn intensity(&self) -> &Intensity {
        match self {
            Light::Point { intensity, .. } | Light::Quad { intensity, .. } => intensity,
        }
    }

    /// The sample at `u ∈ [0,1)²`.
    pub fn sample(&self, u: Vec2) -> LightSample {
        match self {
            Light::Point { position, .. } => LightSample {
                position: *position,
                weight: 1.0,
            },
            Light::Quad {
                origin,
                edge_u,
                edge_v,
                samples,
                ..
            } => LightSample {
                position: *origin + u.x * *edge_u + u.y * *edge_v,
                weight: 1.0 / (*samples).max(1) as f32,
            },
        }
    }

    /// The sampling method of an area light (points use none).
    pub fn method(&self) -> Method {
        match self {
            Light::Point { .. } => Method::Random,
            Light::Quad { method, .. } => *method,
        }
    }
}

impl Intensity {
    /// The factor of the intensity that reaches squared distance `d2`.
    #[inline]
    pub fn falloff(&self, d2: f32) -> f32 {
        match self.falloff {
            Falloff::InverseSquare { scale } => scale / d2,
            Falloff::Polynomial { kc, kl, kq } => 1.0 / (kc + kl * d2.sqrt() + kq * d2),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_samples_cover_the_parallelogram_and_share_the_power() {
        let l = Light::Quad {
            origin: Vec3::ZERO,
            edge_u: Vec3::X * 2.0,
            edge_v: Vec3::Y,
            intensity: Intensity {
                diffuse: Vec3::ONE,
                specular: Vec3::ONE,
                falloff: Falloff::InverseSquare { scale: 1.0 },
            },
            samples: 16,
            method: Method::Jittered,
        };
        let s = l.sample(Vec2::new(1.0, 1.0));
        assert_eq!(s.position, Vec3::new(2.0, 1.0, 0.0));
        assert_eq!(s.weight, 1.0 / 16.0);
        assert_eq!(l.sample_count(), 16);
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
