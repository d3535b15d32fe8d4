//! Materials: Blinn-Phong surfaces that may also reflect like a mirror and transmit like glass.
//!
//! ```json
//! "material": { "ks": 0.6, "kd": 0.7, "specularexponent": 10, "diffusecolor": [1, 1, 1],
//!               "specularcolor": [1, 1, 1], "kr": 0.3, "kt": 0.0, "eta": 1.5,
//!               "tPath": "../textures/sicily.jpg", "tWidth": 600, "tHeight": 490 }
//! ```
//! The CGR spellings `isreflective`/`reflectivity` and `isrefractive`/`refractiveindex` map onto
//! `kr`, `kt` and `eta` (see `docs/scene-format.md`). A texture replaces the diffuse colour.

use crate::math::Vec3;

#[derive(Debug, Clone, PartialEq)]
pub struct Material {
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
