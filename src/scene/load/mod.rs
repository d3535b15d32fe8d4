//! From a scene file to a [`Scene`]: every variant of the coursework format and the key spellings
//! real files use (the full list is in `docs/scene-format.md`).
//!
//! Rules:
//! - Objects whose `type` is unknown are skipped with a warning naming the nearest known type
//!   (people switch objects off by misspelling them).
//! - A missing or ill-typed required value is an error with `file:line:column` and the JSON path.
//! - Asset paths (textures, meshes) resolve against the scene file's folder, then each
//!   [`LoadOptions::asset_dirs`] entry, then the working directory; a missing asset is an error
//!   that names every path tried.
//! - Limits on image size, recursion depth, light samples and triangle count are checked before
//!   the render allocates anything for them (mesh files are read first; their readers refuse
//!   counts the file cannot hold).

mod assets;
mod camera;
mod light;
mod material;
mod mesh;
mod shape;
pub mod spellings;
mod texture;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use super::error::{SceneError, Warning};
use super::json::{Node, Source};
use super::keys;
use super::lights::ShapeLights;
use super::{RenderMode, Scene, Variant};
use crate::files::input::{self, SizeLimit};
use crate::files::raise_hint;
use crate::film::ToneMap;
use crate::geometry::Primitives;
use crate::light::Light;
use crate::material::{Material, Reflection};
use crate::math::Vec3;
use crate::sampling::Method;
use crate::texture::Texture;
use texture::Libraries;

/// Default cap on `width × height`: about 134 megapixels (e.g. 11585²).
pub const DEFAULT_MAX_PIXELS: u64 = 1 << 27;
/// Default cap on `nbounces`.
pub const DEFAULT_MAX_BOUNCES: u32 = 64;
/// Default cap on the total number of triangles.
pub const DEFAULT_MAX_TRIANGLES: usize = 50_000_000;
/// Default cap on shadow rays per shading point for one area light.
pub const DEFAULT_MAX_LIGHT_SAMPLES: u32 = 65_536;
/// Default cap on the samples per pixel that a scene file asks for (`--spp` is not capped by it).
/// The most in the coursework corpus is 1000.
pub const DEFAULT_MAX_PIXEL_SAMPLES: u32 = 65_536;
/// Default cap on the scene file's size: 64 MiB. The parsed document takes about ten times the
/// file's size in memory, and the largest real scene files (inline meshes) are under 2 MiB.
pub const DEFAULT_MAX_SCENE_BYTES: u64 = 64 << 20;
/// Default cap on one texture's `width × height`: 2^26 texels (e.g. 8192²; 192 MiB of 8-bit or
/// 768 MiB of float texels). Checked from the image's header before decoding, so a small file
/// claiming a huge image fails at once.
pub const DEFAULT_MAX_TEXTURE_PIXELS: u64 = 1 << 26;
/// Default cap on a mesh file's size: 2 GiB. Mesh files are read whole into memory; the largest
/// in the coursework corpus are about 1 MB.
pub const DEFAULT_MAX_MESH_BYTES: u64 = 2 << 30;
/// Index of refraction of a transmissive material that gives none (crown glass).
pub const DEFAULT_ETA: f32 = 1.5;
/// `nbounces` when a file has none.
pub const DEFAULT_NBOUNCES: u32 = 3;

/// How to load a scene.
#[derive(Debug, Clone)]
pub struct LoadOptions {
    /// Override the image width (the height follows the scene's aspect ratio unless also given).
    pub width: Option<u32>,
    /// Override the image height.
    pub height: Option<u32>,
    /// Extra folders to resolve asset paths against, after the scene's own folder.
    pub asset_dirs: Vec<PathBuf>,
    pub max_pixels: u64,
    pub max_bounces: u32,
    pub max_triangles: usize,
    pub max_light_samples: u32,
    /// Most samples per pixel a scene file may ask for.
    pub max_pixel_samples: u32,
    /// Largest scene file accepted, in bytes.
    pub max_scene_bytes: u64,
    /// Most texels (`width × height`) one texture may have, checked from the image's header.
    pub max_texture_pixels: u64,
    /// Largest mesh file accepted, in bytes.
    pub max_mesh_bytes: u64,
    /// Memory the mesh files may take, all together, in bytes ([`MeshLimits::max_memory`](crate::scene::mesh_file::MeshLimits::max_memory)):
    /// the command line gives what the process can have ([`crate::memory::available`]) unless
    /// `--max-memory` says otherwise. `None` (the default): not checked.
    pub max_memory: Option<u64>,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            width: None,
            height: None,
            asset_dirs: Vec::new(),
            max_pixels: DEFAULT_MAX_PIXELS,
            max_bounces: DEFAULT_MAX_BOUNCES,
            max_triangles: DEFAULT_MAX_TRIANGLES,
            max_light_samples: DEFAULT_MAX_LIGHT_SAMPLES,
            max_pixel_samples: DEFAULT_MAX_PIXEL_SAMPLES,
            max_scene_bytes: DEFAULT_MAX_SCENE_BYTES,
            max_texture_pixels: DEFAULT_MAX_TEXTURE_PIXELS,
            max_mesh_bytes: DEFAULT_MAX_MESH_BYTES,
            max_memory: None,
        }
    }
}

/// Reads and converts the scene file at `path`: a regular file of at most
/// [`LoadOptions::max_scene_bytes`] (a FIFO or a device is refused without blocking).
pub fn load(path: &Path, options: &LoadOptions) -> Result<Scene, SceneError> {
    let limit = SizeLimit {
        bytes: options.max_scene_bytes,
        flag: Some("--max-scene-bytes"),
    };
    let bytes = input::read(path, limit).map_err(|source| SceneError::Read {
        file: path.to_path_buf(),
        source,
    })?;
    let text = match String::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let offset = e.utf8_error().valid_up_to();
            let valid = String::from_utf8_lossy(&e.as_bytes()[..offset]).into_owned();
            let (line, column) = Source::new(path, &valid).line_column(offset);
            return Err(SceneError::Syntax {
                file: path.to_path_buf(),
                line,
                column,
                message: "the file is not UTF-8 text".into(),
            });
        }
    };
    let mut scene = load_str(&text, path, options)?;
    scene.inputs.insert(0, path.to_path_buf());
    Ok(scene)
}

/// Converts scene text; `path` names the file in messages and anchors relative asset paths.
pub fn load_str(text: &str, path: &Path, options: &LoadOptions) -> Result<Scene, SceneError> {
    let src = Source::new(path, text);
    let value = src.parse()?;
    let root = Node::root(&value, &src);
    if !root.is_object() {
        return Err(root.error(format!("a scene is a JSON object, found {}", root.kind())));
    }
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let loader = Loader {
        options,
        base,
        warnings: Vec::new(),
        textures: Vec::new(),
        texture_index: HashMap::new(),
        materials: Vec::new(),
        primitives: Primitives::default(),
        lights: Vec::new(),
        ambient: None,
        variant: Variant::V2021,
        mode: RenderMode::Phong,
        shape_lights: ShapeLights::default(),
        method: None,
        triangles: 0,
        inputs: Vec::new(),
    };
    loader.scene(&root)
}

/// The scene read so far, and what reading it needs.
struct Loader<'o> {
    options: &'o LoadOptions,
    base: PathBuf,
    warnings: Vec<Warning>,
    textures: Vec<Texture>,
    /// Textures loaded so far, by file and uv offset (the offset's bits): each pair is stored once.
    texture_index: HashMap<(PathBuf, [u32; 2]), u32>,
    materials: Vec<Material>,
    primitives: Primitives,
    lights: Vec<Light>,
    /// Ambient light given by the file (a scene key or a light of type `ambient`).
    ambient: Option<Vec3>,
    variant: Variant,
    /// The file's `rendermode` (read first).
    mode: RenderMode,
    /// How samples are placed where the file says so for all at once (`use_jitter_sample`, a
    /// top-level `sampling`).
    method: Option<Method>,
    /// Area lights whose surface is a shape of the scene, resolved after the shapes are read.
    shape_lights: ShapeLights,
    triangles: usize,
    inputs: Vec<PathBuf>,
}

/// Sphere texture frame: the top pole (`v = 0`) is world +y and the seam (`u = 0`) faces −x, with
/// `u` growing towards +z. This is the frame in which the official reference render of the
/// example scene shows its sky map (the black corners of the map at the lower left of the sphere).
pub const SPHERE_POLE: Vec3 = Vec3::Y;
/// See [`SPHERE_POLE`].
pub const SPHERE_SEAM: Vec3 = Vec3::NEG_X;

/// The first present member among `keys` (spellings of one key); its absence is an error.
pub(super) fn required<'a, 't>(
    node: &Node<'a, 't>,
    keys: &[&str],
) -> Result<Node<'a, 't>, SceneError> {
    node.get_any(keys).ok_or_else(|| {
        let spelled = if keys.len() == 1 {
            format!("'{}'", keys[0])
        } else {
            format!("'{}' (or {})", keys[0], keys[1..].join(", "))
        };
        node.error(format!("missing required key {spelled}"))
    })
}

/// The required number under `keys` (spellings of one key), which must be > 0.
pub(super) fn required_positive(node: &Node, keys: &[&str]) -> Result<f32, SceneError> {
    let n = required(node, keys)?;
    let v = n.f32()?;
    if v <= 0.0 {
        return Err(n.error(format!("the {} must be > 0, found {v}", keys[0])));
    }
    Ok(v)
}

/// The number under the first present member among `keys`, if any.
fn opt_f32(node: &Node, keys: &[&str]) -> Result<Option<f32>, SceneError> {
    node.get_any(keys).map(|n| n.f32()).transpose()
}

/// The 3-vector under the first present member among `keys`, if any.
fn opt_vec3(node: &Node, keys: &[&str]) -> Result<Option<Vec3>, SceneError> {
    node.get_any(keys).map(|n| n.vec3()).transpose()
}

/// A colour (or one number for grey) with no negative or non-finite channel.
fn non_negative_color(n: &Node) -> Result<Vec3, SceneError> {
    let c = n.color()?;
    if !(c.min_element() >= 0.0 && c.is_finite()) {
        return Err(n.error(format!(
            "a light colour must be finite and ≥ 0, found [{}, {}, {}]",
            c.x, c.y, c.z
        )));
    }
    Ok(c)
}

/// The nearest of `known` to `name` by edit distance.
fn nearest<'k>(name: &str, known: &[&'k str]) -> &'k str {
    let lower = name.to_ascii_lowercase();
    known
        .iter()
        .min_by_key(|k| strsim::levenshtein(&lower, k))
        .copied()
        .unwrap_or("")
}

impl Loader<'_> {
    /// Records a warning at `node`.
    fn warn(&mut self, node: &Node, message: impl Into<String>) {
        self.warnings.push(Warning {
            location: node.location(),
            message: message.into(),
        });
    }

    /// The whole scene from the document's `root`: the camera and the file-wide settings, then
    /// the lights and shapes, then the warnings for keys nothing read.
    fn scene(mut self, root: &Node) -> Result<Scene, SceneError> {
        let mode = self.render_mode(root)?;
        let camera_node = required(root, spellings::scene::CAMERA)?;
        let variant = variant(root, &camera_node);
        self.variant = variant;
        self.mode = mode;
        let (camera, exposure, lens_samples) = self.camera(root, &camera_node)?;
        // How the whole file's samples are placed, unless a camera or a light says otherwise.
        self.method = match root.get_any(spellings::scene::JITTER) {
            Some(n) if n.bool()? => Some(Method::Jittered),
            Some(_) => Some(Method::Random),
            None => self.sampling_method(root)?,
        };
        let pixel_method = self.sampling_method(&camera_node)?.or(self.method);
        // Hit/miss images are not exposed: a hit is full red whatever the camera says.
        let exposure = if mode == RenderMode::Binary {
            1.0
        } else {
            exposure
        };
        let nbounces = self.nbounces(root)?;
        let scene_node = scene_object(root)?;
        let background = match scene_node.get_any(spellings::scene::BACKGROUND) {
            Some(n) => n.color()?,
            None => Vec3::ZERO,
        };
        if let Some(n) = scene_node.get_any(spellings::scene::AMBIENT) {
            self.ambient = Some(non_negative_color(&n)?);
        }
        self.lights_and_shapes(root, &scene_node)?;
        let (pixel_samples, light_samples) = self.sample_counts(root, lens_samples)?;
        let tone_map = self.renderer_switches(root)?;
        // Last, when every lookup is done: the keys none of them read.
        for (node, message) in keys::unknown_keys(root) {
            self.warn(&node, message);
        }
        let has_transmissive = self.materials.iter().any(Material::is_transmissive);
        let (ambient, reflection, tone_map) =
            conventions(variant, self.ambient, background, tone_map);
        Ok(Scene {
            variant,
            camera,
            nbounces,
            background,
            mode,
            exposure,
            ambient,
            reflection,
            pixel_samples,
            pixel_method,
            light_samples,
            tone_map,
            lights: self.lights,
            primitives: self.primitives,
            materials: self.materials,
            textures: self.textures,
            has_transmissive,
            warnings: self.warnings,
            inputs: self.inputs,
        })
    }

    /// The file's `rendermode` (Phong when it gives none, or one not supported, with a warning).
    fn render_mode(&mut self, root: &Node) -> Result<RenderMode, SceneError> {
        let Some(n) = root.get_any(spellings::scene::RENDER_MODE) else {
            return Ok(RenderMode::Phong);
        };
        let name = n.str()?;
        Ok(match spellings::type_of(spellings::RENDER_MODES, name) {
            Some("binary") => RenderMode::Binary,
            Some("path") => RenderMode::Path,
            Some(_) => RenderMode::Phong,
            None => {
                self.warn(
                    &n,
                    format!("rendermode '{name}' is not supported; rendering with phong"),
                );
                RenderMode::Phong
            }
        })
    }

    /// `nbounces`: a whole number within [`LoadOptions::max_bounces`].
    fn nbounces(&self, root: &Node) -> Result<u32, SceneError> {
        let Some(n) = root.get_any(spellings::scene::BOUNCES) else {
            return Ok(DEFAULT_NBOUNCES);
        };
        let v = n.f64()?;
        if v < 0.0 || v.fract() != 0.0 {
            return Err(n.error(format!("nbounces must be a whole number ≥ 0, found {v}")));
        }
        if v > self.options.max_bounces as f64 {
            return Err(n.error(format!(
                "nbounces {v} is over the limit of {} (raise it with --max-bounces)",
                self.options.max_bounces
            )));
        }
        Ok(v as u32)
    }

    /// Reads the lights, the material and texture libraries and the shapes of `scene_node`, then
    /// ties area lights to their shapes; a scene with neither lights nor shapes is warned about.
    fn lights_and_shapes(&mut self, root: &Node, scene_node: &Node) -> Result<(), SceneError> {
        let mut listed = 0;
        if let Some(lights) = scene_node.get_any(spellings::scene::LIGHT_LISTS) {
            for l in lights.elements()? {
                listed += 1;
                self.light(&l)?;
            }
        }
        let mut libraries = Libraries::read(&[root, scene_node])?;
        if let Some(shapes) = scene_node.get_any(spellings::scene::SHAPE_LISTS) {
            for s in shapes.elements()? {
                listed += 1;
                self.listed_shape(&s, &mut libraries)?;
            }
        }
        std::mem::take(&mut self.shape_lights).resolve(
            &mut self.lights,
            &self.primitives,
            &mut self.warnings,
        )?;
        if listed == 0 {
            self.warn(
                scene_node,
                "the scene has no shapes and no lights; the image is the background",
            );
        }
        Ok(())
    }

    /// Reads one shape of the scene's list, noting its `id` and whether its material emits.
    fn listed_shape(&mut self, s: &Node, libraries: &mut Libraries) -> Result<(), SceneError> {
        let first = self.primitives.len();
        self.shape(s, self.mode, libraries)?;
        self.shape_lights
            .note_shape(s, first..self.primitives.len());
        if first < self.primitives.len() {
            let material = self.primitives.material(first as u32);
            let emission = self.materials[material as usize].emission;
            if emission.max_element() > 0.0 {
                self.shape_lights
                    .note_glowing(s, first..self.primitives.len(), emission);
            }
        }
        Ok(())
    }

    /// The scene's samples per pixel and shadow rays per area light, from the top-level keys or
    /// the thin-lens camera's sample count `lens_samples` (docs/scene-format.md, "Samples").
    fn sample_counts(
        &mut self,
        root: &Node,
        lens_samples: Option<Node>,
    ) -> Result<(Option<u32>, Option<u32>), SceneError> {
        let count = |n: &Node, what: &str, limit: u32, flag: &str| -> Result<u32, SceneError> {
            // 0 means one sample, as in the files' own renderers.
            let v = n.u32()?.max(1);
            if v > limit {
                return Err(n.error(format!(
                    "{v} {what} is over the limit of {limit}{}",
                    raise_hint(Some(flag))
                )));
            }
            Ok(v)
        };
        let settings = root
            .get_any(spellings::scene::SETTINGS)
            .filter(|n| n.is_object());
        let pixel = match root
            .get_any(spellings::scene::PIXEL_SAMPLES)
            .or(lens_samples)
            .or_else(|| settings.and_then(|st| st.get_any(spellings::scene::SETTINGS_SAMPLES)))
            .or_else(|| {
                root.get_any(spellings::scene::SAMPLER)
                    .filter(|n| n.f64().is_ok())
            }) {
            Some(n) => Some(count(
                &n,
                "samples per pixel",
                self.options.max_pixel_samples,
                "--max-pixel-samples",
            )?),
            None => None,
        };
        let light = match root.get_any(spellings::scene::LIGHT_SAMPLES) {
            Some(n) => Some(count(
                &n,
                "shadow rays per area light",
                self.options.max_light_samples,
                "--max-light-samples",
            )?),
            None => None,
        };
        if let Some(n) = root.get_any(spellings::scene::PATH_SAMPLES) {
            n.u32()?;
            self.warn(
                &n,
                "'path_sample_num' (rays per bounce of a branching path tracer) is ignored: paths \
                 here take one scattered ray per bounce, and their number per pixel is the pixel \
                 samples (--spp)",
            );
        }
        Ok((pixel, light))
    }

    /// Top-level switches of the renderers path-tracing files were written for: sampling and
    /// global illumination switches are read quietly (they change how fast the image converges,
    /// not what to), post-processes not done here (a denoiser, a blur) are warned about, and the
    /// tone map the file names or turns on is returned.
    fn renderer_switches(&mut self, root: &Node) -> Result<Option<ToneMap>, SceneError> {
        for &key in spellings::scene::CONVERGENCE_SWITCHES {
            if let Some(n) = root.get(key) {
                n.bool()?;
            }
        }
        for &key in spellings::scene::CONVERGENCE_COUNTS {
            if let Some(n) = root.get(key) {
                n.f64()?;
            }
        }
        for (keys, what) in [
            (spellings::scene::DENOISER, "a denoiser"),
            (spellings::scene::BLUR, "a Gaussian blur"),
        ] {
            if let Some(n) = root.get_any(keys) {
                if n.bool()? {
                    self.warn(
                        &n,
                        format!("{what} is not applied: the image is the renderer's radiance"),
                    );
                }
            }
        }
        // A tone map named in the camera or at the top level (`"tone_mapping": "aces"`).
        let named = root
            .get_any(spellings::scene::CAMERA)
            .and_then(|c| c.get_any(spellings::scene::TONE_MAP))
            .or_else(|| root.get_any(spellings::scene::TONE_MAP));
        if let Some(n) = named {
            match n.str()?.parse::<ToneMap>() {
                Ok(map) => return Ok(Some(map)),
                Err(e) => self.warn(&n, format!("{e}; the default tone map is used")),
            }
        }
        // Kierandon's renderer applies Reinhard's `x/(1+x)` per channel.
        match root.get_any(spellings::scene::REINHARD) {
            Some(n) if n.bool()? => Ok(Some(ToneMap::Reinhard)),
            _ => Ok(None),
        }
    }

    /// A sampling method named by `method`, `sampler` or `sampling` in `node`, if any.
    fn sampling_method(&mut self, node: &Node) -> Result<Option<Method>, SceneError> {
        let Some(n) = node.get_any(spellings::scene::SAMPLER) else {
            return Ok(None);
        };
        if n.f64().is_ok() {
            return Ok(None); // a count (a top-level `sampling`: samples per pixel)
        }
        let name = n.str()?;
        Ok(Some(
            match spellings::type_of(spellings::SAMPLING_METHODS, name) {
                Some("random") => Method::Random,
                Some("sobol") => Method::Sobol,
                Some(_) => Method::Jittered,
                None => {
                    self.warn(
                        &n,
                        format!("unknown sampling method '{name}'; using jittered"),
                    );
                    Method::Jittered
                }
            },
        ))
    }
}

/// The object that holds the scene's lists: `scene`, or the top level when the lists are there.
fn scene_object<'a, 't>(root: &Node<'a, 't>) -> Result<Node<'a, 't>, SceneError> {
    let scene_node =
        match root.get_any(spellings::scene::SCENE) {
            Some(n) => n,
            // Some files put the scene's lists at the top level.
            None if root.has_any(spellings::scene::SHAPE_LISTS)
                || root.has_any(spellings::scene::LIGHT_LISTS) =>
            {
                root.clone()
            }
            None => return Err(root.error(
                "nothing to render: no 'scene' object (nor top-level 'shapes' or 'lightsources')",
            )),
        };
    if !scene_node.is_object() {
        return Err(scene_node.error(format!("expected an object, found {}", scene_node.kind())));
    }
    // One renderer's count of rays per rough reflection: here each camera sample traces one.
    if !std::ptr::eq(scene_node.value, root.value) {
        if let Some(n) = scene_node.get_any(spellings::scene::ROUGH_SAMPLES) {
            n.u32()?;
        }
    }
    Ok(scene_node)
}

/// The ambient light, the way mirrors combine with their shading, and the tone map of a file of
/// `variant`, from what the file gives. The CGR conventions (`docs/scene-format.md`, "CGR
/// conventions"): the background is the ambient light, mirrors blend, and the course's display
/// transform.
fn conventions(
    variant: Variant,
    ambient: Option<Vec3>,
    background: Vec3,
    tone_map: Option<ToneMap>,
) -> (Vec3, Reflection, Option<ToneMap>) {
    match variant {
        Variant::Cgr => (
            ambient.unwrap_or(background.max(Vec3::ZERO)),
            Reflection::Blended,
            tone_map.or(Some(ToneMap::Cgr)),
        ),
        Variant::V2019 | Variant::V2021 => {
            (ambient.unwrap_or(Vec3::ZERO), Reflection::Added, tone_map)
        }
    }
}

/// Which variant of the format a file follows, from its top level and its camera.
fn variant(root: &Node, camera: &Node) -> Variant {
    if is_cgr(root, camera) {
        Variant::Cgr
    } else if camera.has_any(spellings::camera::V2021_KEYS) {
        Variant::V2021
    } else {
        Variant::V2019
    }
}

/// Whether a file follows the CGR 2024+ variant: a top-level `rendermode`, or the CGR camera keys
/// `upVector`/`exposure` (some CGR files omit `rendermode`).
pub(super) fn is_cgr(root: &Node, camera: &Node) -> bool {
    root.get_any(spellings::scene::RENDER_MODE).is_some()
        || camera.has_any(spellings::camera::CGR_KEYS)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load_text(text: &str) -> Result<Scene, SceneError> {
        load_str(text, Path::new("t.json"), &LoadOptions::default())
    }

    #[test]
    fn a_huge_face_size_is_an_error_not_an_overflow() {
        let text = r#"{"camera": {"width": 4, "height": 4, "fov": 45},
            "shapes": [{"type": "trimesh", "vertices": [[0,0,0], [1,0,0], [0,1,0]],
                        "vertexindex": [0, 1, 2], "faceindex": [3, 1e30]}]}"#;
        let e = load_text(text)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            e.starts_with("t.json:")
                && e.contains("face 1 needs 1000000000000000000000000000000 indices")
                && e.contains("0 left"),
            "{e}"
        );
    }
}
