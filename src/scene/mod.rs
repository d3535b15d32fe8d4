//! The scene: everything the renderer needs, converted from the JSON file and checked.
//!
//! [`load()`] reads a scene file in any of the coursework variants (see `docs/scene-format.md`);
//! the result is immutable and shared by all render threads.

pub mod error;
pub mod json;
pub mod keys;
mod lights;
pub mod load;
pub mod mesh_file;
pub mod poly_sphere;
pub mod rectangle;
pub mod schema;
pub mod transform;

pub use error::{SceneError, Warning};
pub use load::{load, load_str, LoadOptions};

use crate::camera::Camera;
use crate::film::ToneMap;
use crate::geometry::Primitives;
use crate::light::Light;
use crate::material::{Material, Reflection};
use crate::math::Vec3;
use crate::texture::Texture;

/// `rendermode`: shaded by Whitted ray tracing, hit/miss only, or path traced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RenderMode {
    #[default]
    Phong,
    /// Hits red, misses black.
    Binary,
    /// `pathtrace` and its spellings: the path tracer (`integrator::path`).
    Path,
}

/// Which of the coursework's three scene-format variants a file follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// 2019: no camera pose, point lights with `intensity`.
    V2019,
    /// 2021–23: camera `position`/`lookat`(direction)/`up`, point lights with `is`/`id`.
    V2021,
    /// CGR 2024+: `rendermode`, camera `lookAt`(target)/`upVector`/`exposure`.
    Cgr,
}

/// A loaded scene: what the renderer needs, and what the loader warned about.
#[derive(Debug, Clone)]
pub struct Scene {
    pub variant: Variant,
    pub camera: Camera,
    /// Most reflection/refraction bounces after the camera ray.
    pub nbounces: u32,
    pub background: Vec3,
    pub mode: RenderMode,
    /// The camera's `exposure` (1 when the file gives none). In the 2019 and 2021–23 variants
    /// it scales radiance before any tone map; in CGR files it only feeds the `exposure` tone
    /// map (see [`Scene::display_exposure`]).
    pub exposure: f32,
    /// Ambient light: every surface adds `ka · ambient · base colour`.
    pub ambient: Vec3,
    /// How mirrors combine reflection with their own shading.
    pub reflection: Reflection,
    /// Samples per pixel the file asks for (`pixelsample` and other spellings); the render takes
    /// them unless told otherwise (`--spp`).
    pub pixel_samples: Option<u32>,
    /// How the file's camera places its pixel and lens samples (`sampler`), if it says; the
    /// render takes it unless told otherwise (`--pixel-sampler`, `--sampler`).
    pub pixel_method: Option<crate::sampling::Method>,
    /// Shadow rays per shading point for every area light, if the file sets them for all at once
    /// (`lightsample` and other spellings).
    pub light_samples: Option<u32>,
    /// The tone map the file asks for (`"use_tone_mapping": true`: [`ToneMap::Reinhard`]; a CGR
    /// file otherwise [`ToneMap::Cgr`]), which 8-bit output takes unless told otherwise
    /// (`--tonemap`).
    pub tone_map: Option<ToneMap>,
    pub lights: Vec<Light>,
    /// Every shape's primitives, with the meshes their triangles belong to.
    pub primitives: Primitives,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    /// Whether any material transmits light (shadow rays must then look through it).
    pub has_transmissive: bool,
    /// What the loader skipped or guessed.
    pub warnings: Vec<Warning>,
    /// The files it was read from: the scene file, then each texture and mesh file (outputs
    /// must never be one of them).
    pub inputs: Vec<std::path::PathBuf>,
}

impl Scene {
    /// The scale applied to radiance before the tone map `map`: the file's exposure, except in
    /// CGR files, whose `exposure` is not a radiance scale (the course's renders of its test
    /// scenes show none) and feeds only [`ToneMap::Exposure`].
    pub fn display_exposure(&self, map: ToneMap) -> f32 {
        match (self.variant, map) {
            (Variant::Cgr, m) if m != ToneMap::Exposure => 1.0,
            _ => self.exposure,
        }
    }
}
