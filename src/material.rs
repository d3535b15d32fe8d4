//! Materials: Blinn-Phong surfaces that may also reflect like a mirror and transmit like glass.
//!
//! ```json
//! "material": { "ks": 0.6, "kd": 0.7, "specularexponent": 10, "diffusecolor": [1, 1, 1],
//!               "specularcolor": [1, 1, 1], "kr": 0.3, "kt": 0.0, "eta": 1.5,
//!               "tPath": "../textures/sicily.jpg", "tWidth": 600, "tHeight": 490 }
//! ```
//! The CGR spellings `isreflective`/`reflectivity` and `isrefractive`/`refractiveindex` map onto
//! `kr`, `kt` and `eta` (see `docs/scene-format.md`). A texture replaces the diffuse colour.
//! `ka` scales the scene's ambient light (CGR files have one; see [`Reflection`] for the other
//! way CGR files differ).

use crate::math::Vec3;

#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Ambient weight: the surface adds `ka · ambient · base colour`.
    pub ka: f32,
    /// Diffuse weight.
    pub kd: f32,
    /// Specular weight.
    pub ks: f32,
    /// Blinn-Phong exponent.
    pub exponent: f32,
    pub diffuse: Vec3,
    pub specular: Vec3,
    /// Mirror reflectivity.
    pub kr: f32,
    /// Transmission: a fraction `kt` of the light goes through a dielectric interface, split
    /// between reflection and refraction by the Fresnel equations.
    pub kt: f32,
    /// Index of refraction of the inside.
    pub eta: f32,
    /// Index into the scene's textures.
    pub texture: Option<u32>,
}

impl Default for Material {
    fn default() -> Material {
        Material {
            ka: 1.0,
            kd: 0.8,
            ks: 0.0,
            exponent: 1.0,
            diffuse: Vec3::splat(0.8),
            specular: Vec3::ONE,
            kr: 0.0,
            kt: 0.0,
            eta: 1.0,
            texture: None,
        }
    }
}

impl Material {
    /// Whether shadow rays pass (attenuated) through this material.
    pub fn is_transmissive(&self) -> bool {
        self.kt > 0.0
    }
}

/// How a mirror's reflection combines with the light its surface shades itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reflection {
    /// `local + kr · reflected`: what the official 2021–23 reference render shows (its mirror
    /// sphere keeps its highlight and diffuse colour).
    #[default]
    Added,
    /// `(1 − kr) · local + kr · reflected`: a `reflectivity` 1 mirror shows only what it
    /// reflects, as every available CGR student render of the course's test scenes does.
    Blended,
}
