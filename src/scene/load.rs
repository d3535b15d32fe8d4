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

use std::collections::{HashMap, HashSet};
use std::path::{Component, Path, PathBuf};

use super::error::{SceneError, Warning};
use super::json::{NameIndex, Node, Source};
use super::keys;
use super::lights::{self, Emitters};
use super::mesh_file::{read_mesh_with, MeshData, MeshLimits};
use super::transform::{self, Affine};
use super::{poly_sphere, rectangle};
use super::{RenderMode, Scene, Variant};
use crate::accel::aabb::Aabb;
use crate::camera::{Camera, Handedness, Lens};
use crate::files::input::{self, SizeLimit};
use crate::files::{raise_hint, shown};
use crate::film::ToneMap;
use crate::geometry::{Cylinder, Mesh, MeshUv, Plane, Primitive, Primitives, Shape, Sphere};
use crate::image_io::ReadLimits;
use crate::light::{Falloff, Intensity, Light};
use crate::material::{roughness_exponent, Material, Reflection};
use crate::math::{Vec2, Vec3};
use crate::sampling::Method;
use crate::texture::Texture;

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
/// Default cap on one texture's `width × height`: 2^26 texels (67 megapixels, e.g. 8192²). A
/// texture from an 8-bit image keeps 3 bytes a texel (192 MiB at this cap), other images 12-byte
/// float texels (768 MiB); the check uses the image's
/// header, before anything is decoded, so a small file claiming a huge image fails at once.
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
    /// Memory the mesh files may take, all together, in bytes ([`MeshLimits::max_memory`]):
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
        emitters: Emitters::default(),
        triangles: 0,
        inputs: Vec::new(),
    };
    loader.scene(&root)
}

const SHAPE_TYPES: &[&str] = &[
    "sphere",
    "plane",
    "planarquad",
    "quad",
    "rectangle",
    "triangle",
    "trimesh",
    "mesh",
    "ply",
    "trianglemesh",
    "cylinder",
    "box",
    "rectanglexy",
    "rectanglexz",
    "rectangleyz",
];
const LIGHT_TYPES: &[&str] = &["pointlight", "arealight"];
const SHAPE_LIST_KEYS: &[&str] = &["shapes", "objects", "geometry"];
const LIGHT_LIST_KEYS: &[&str] = &["lightsources", "lights", "lightSources"];
/// Top-level samples per pixel (each the total per pixel; `sample_number` also sets the light
/// samples). The evidence for each is in docs/scene-format.md.
const PIXEL_SAMPLE_KEYS: &[&str] = &[
    "pixelsample",
    "pixel_sample_num",
    "nspp",
    "camera samples",
    "nsamples",
    "sample_number",
];
/// Top-level shadow rays per area light and shading point (the total).
const LIGHT_SAMPLE_KEYS: &[&str] = &["lightsample", "shadow samples", "spp", "sample_number"];
/// Material `type`s the loader knows: the Blinn-Phong model the other keys describe, and the
/// physically based forms of path-tracing files (see `Loader::material_kind`).
const MATERIAL_TYPES: &[&str] = &[
    "phong",
    "blinnphong",
    "blinn-phong",
    "blinn_phong",
    "diffuse",
    "lambertian",
    "matte",
    "metal",
    "conductor",
    "mirror",
    "dielectric",
    "glass",
    "emissive",
    "emitter",
    "light",
    "emission",
];
/// A thin-lens camera's lens radius.
const LENS_RADIUS_KEYS: &[&str] = &["lensRadius", "lensradius", "lens_radius", "radius"];
/// A thin-lens camera's lens diameter.
/// `size` is the side of the square aperture of one renderer (TsFreddie's jittered lens sampler
/// spreads samples over `[−size/2, size/2]²`), read as the diameter of our round one.
const LENS_DIAMETER_KEYS: &[&str] = &["aperture", "aperture_size", "diameter", "ap", "d", "size"];
/// The lens diameter at the top level.
const ROOT_DIAMETER_KEYS: &[&str] = &["aperture"];
/// A thin-lens camera's focus distance.
const FOCUS_KEYS: &[&str] = &[
    "focusdistance",
    "focus_distance",
    "focalDistance",
    "focusDistance",
    "focus_dist",
    "focalLength",
    "focal_length",
    "focal",
    "focus",
    "f",
];
/// The focus distance at the top level.
const ROOT_FOCUS_KEYS: &[&str] = &["focus_distance", "focusdistance"];
/// A thin-lens camera's rays per pixel (the total).
const LENS_SAMPLE_KEYS: &[&str] = &["samplesize", "nsamples"];

/// Materials defined once by name (`"materials": [{"name": "red", …}]`) and referred to by it,
/// in file order; a name defined twice means its first definition. Found through an index, as a
/// scene can define and use tens of thousands.
#[derive(Default)]
struct Library<'a, 't> {
    defs: Vec<(String, Node<'a, 't>)>,
    index: NameIndex,
}

impl<'a, 't> Library<'a, 't> {
    fn push(&mut self, def: (String, Node<'a, 't>)) {
        self.index.push(&def.0);
        self.defs.push(def);
    }

    fn find(&self, name: &str) -> Option<&(String, Node<'a, 't>)> {
        let i = self.index.find(name, |i| self.defs[i].0.as_str())?;
        Some(&self.defs[i])
    }

    fn names(&self) -> Vec<&str> {
        self.defs.iter().map(|(n, _)| n.as_str()).collect()
    }
}

/// The named definitions shapes refer to: materials and textures (top-level or `scene`-level
/// `materials` and `textures` arrays), with what has been made of the textures so far.
#[derive(Default)]
struct Libraries<'a, 't> {
    materials: Library<'a, 't>,
    textures: Library<'a, 't>,
    /// Library textures already loaded: name → index into the scene's textures.
    loaded: HashMap<String, u32>,
    /// Texture names already warned about (a name that is neither defined nor a file).
    warned: HashSet<String>,
}

impl<'a, 't> Libraries<'a, 't> {
    /// Reads the `materials` and `textures` arrays of `holders`, in order. Entries without a
    /// `name` cannot be referred to and are passed over.
    fn read(holders: &[&Node<'a, 't>]) -> Result<Self, SceneError> {
        let mut libs = Libraries::default();
        for holder in holders {
            for (key, lib) in [
                ("materials", &mut libs.materials),
                ("textures", &mut libs.textures),
            ] {
                if let Some(list) = holder.get(key) {
                    for m in list.elements()? {
                        // Not a read of the entry: one that nothing uses stays unread.
                        if let Some(name) = m.peek("name") {
                            lib.push((name.str()?.to_string(), m.clone()));
                        }
                    }
                }
            }
        }
        Ok(libs)
    }
}

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
    /// Area lights whose surface is a shape of the scene, resolved after the shapes are read.
    emitters: Emitters,
    triangles: usize,
    inputs: Vec<PathBuf>,
}

/// Sphere texture frame: the top pole (`v = 0`) is world +y and the seam (`u = 0`) faces −x, with
/// `u` growing towards +z. This is the frame in which the official reference render of the
/// example scene shows its sky map (the black corners of the map at the lower left of the sphere).
pub const SPHERE_POLE: Vec3 = Vec3::Y;
/// See [`SPHERE_POLE`].
pub const SPHERE_SEAM: Vec3 = Vec3::NEG_X;

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

/// The required number `key`, which must be > 0.
pub(super) fn positive(node: &Node, key: &str) -> Result<f32, SceneError> {
    let n = required(node, &[key])?;
    let v = n.f32()?;
    if v <= 0.0 {
        return Err(n.error(format!("the {key} must be > 0, found {v}")));
    }
    Ok(v)
}

fn opt_f32(node: &Node, keys: &[&str]) -> Result<Option<f32>, SceneError> {
    node.get_any(keys).map(|n| n.f32()).transpose()
}

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

/// `a` joined with `b`, with `.` and `..` removed lexically (so a folder named in the path need
/// not exist, as with paths written relative to a build folder).
fn join_lexically(a: &Path, b: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in a.join(b).components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

impl<'o> Loader<'o> {
    fn warn(&mut self, node: &Node, message: impl Into<String>) {
        self.warnings.push(Warning {
            location: node.location(),
            message: message.into(),
        });
    }

    fn scene(mut self, root: &Node) -> Result<Scene, SceneError> {
        let mode = match root.get("rendermode") {
            None => RenderMode::Phong,
            Some(n) => match n.str()?.to_ascii_lowercase().as_str() {
                "binary" => RenderMode::Binary,
                "phong" => RenderMode::Phong,
                "pathtrace" | "pathtracer" | "pathtracing" | "path" | "pt" => RenderMode::Path,
                other => {
                    self.warn(
                        &n,
                        format!("rendermode '{other}' is not supported; rendering with phong"),
                    );
                    RenderMode::Phong
                }
            },
        };
        let camera_node = required(root, &["camera"])?;
        let variant = if is_cgr(root, &camera_node) {
            Variant::Cgr
        } else if camera_node.has_any(&["position", "lookat", "up"]) {
            Variant::V2021
        } else {
            Variant::V2019
        };
        self.variant = variant;
        self.mode = mode;
        let (camera, exposure, lens_samples) = self.camera(root, &camera_node)?;
        let pixel_method = self.sampling_method(&camera_node)?;
        // Hit/miss images are not exposed: a hit is full red whatever the camera says.
        let exposure = if mode == RenderMode::Binary {
            1.0
        } else {
            exposure
        };

        let nbounces = match root.get_any(&["nbounces", "maxdepth", "max_depth"]) {
            None => DEFAULT_NBOUNCES,
            Some(n) => {
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
                v as u32
            }
        };

        let scene_node = match root.get("scene") {
            Some(n) => n,
            // Some files put the scene's lists at the top level.
            None if root.has_any(SHAPE_LIST_KEYS) || root.has_any(LIGHT_LIST_KEYS) => root.clone(),
            None => return Err(root.error(
                "nothing to render: no 'scene' object (nor top-level 'shapes' or 'lightsources')",
            )),
        };
        if !scene_node.is_object() {
            return Err(
                scene_node.error(format!("expected an object, found {}", scene_node.kind()))
            );
        }
        let background =
            match scene_node.get_any(&["backgroundcolor", "backgroundcolour", "background"]) {
                Some(n) => n.color()?,
                None => Vec3::ZERO,
            };
        if let Some(n) = scene_node.get_any(&["ambientlight", "ambientintensity", "ambient"]) {
            self.ambient = Some(non_negative_color(&n)?);
        }
        let mut listed = 0;
        if let Some(lights) = scene_node.get_any(LIGHT_LIST_KEYS) {
            for l in lights.elements()? {
                listed += 1;
                self.light(&l)?;
            }
        }
        let mut libraries = Libraries::read(&[root, &scene_node])?;
        if let Some(shapes) = scene_node.get_any(SHAPE_LIST_KEYS) {
            for s in shapes.elements()? {
                listed += 1;
                let first = self.primitives.len();
                self.shape(&s, mode, &mut libraries)?;
                self.emitters.shape(&s, first..self.primitives.len());
                if first < self.primitives.len() {
                    let material = self.primitives.material(first as u32);
                    let emission = self.materials[material as usize].emission;
                    if emission.max_element() > 0.0 {
                        self.emitters
                            .glowing(&s, first..self.primitives.len(), emission);
                    }
                }
            }
        }
        std::mem::take(&mut self.emitters).resolve(
            &mut self.lights,
            &self.primitives,
            &mut self.warnings,
        )?;
        if listed == 0 {
            self.warn(
                &scene_node,
                "the scene has no shapes and no lights; the image is the background",
            );
        }
        let (pixel_samples, light_samples) = self.sample_counts(root, lens_samples)?;
        let tone_map = self.renderer_switches(root)?;
        // Last, when every lookup is done: the keys none of them read.
        for (node, message) in keys::unknown_keys(root) {
            self.warn(&node, message);
        }
        let has_transmissive = self.materials.iter().any(Material::is_transmissive);
        // The CGR conventions (`docs/scene-format.md`, "CGR conventions"): the background is
        // the ambient light, mirrors blend, and the course's display transform.
        let (ambient, reflection, tone_map) = match variant {
            Variant::Cgr => (
                self.ambient.unwrap_or(background.max(Vec3::ZERO)),
                Reflection::Blended,
                tone_map.or(Some(ToneMap::Cgr)),
            ),
            Variant::V2019 | Variant::V2021 => (
                self.ambient.unwrap_or(Vec3::ZERO),
                Reflection::Added,
                tone_map,
            ),
        };
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
        let pixel = match root.get_any(PIXEL_SAMPLE_KEYS).or(lens_samples) {
            Some(n) => Some(count(
                &n,
                "samples per pixel",
                self.options.max_pixel_samples,
                "--max-pixel-samples",
            )?),
            None => None,
        };
        let light = match root.get_any(LIGHT_SAMPLE_KEYS) {
            Some(n) => Some(count(
                &n,
                "shadow rays per area light",
                self.options.max_light_samples,
                "--max-light-samples",
            )?),
            None => None,
        };
        if let Some(n) = root.get("path_sample_num") {
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

    /// The camera, its exposure, and (for a thin-lens camera) its count of lens samples per pixel.
    fn camera<'a, 't>(
        &mut self,
        root: &Node<'a, 't>,
        cam: &Node<'a, 't>,
    ) -> Result<(Camera, f32, Option<Node<'a, 't>>), SceneError> {
        if !cam.is_object() {
            return Err(cam.error(format!("expected an object, found {}", cam.kind())));
        }
        let kind = match cam.get("type") {
            Some(t) => t.str()?.to_ascii_lowercase(),
            None => "pinhole".into(),
        };
        // A top-level `use_dof` (with `aperture` and `focus_distance` beside it) turns the
        // camera into a thin lens, as the files of one CGR renderer write it.
        let use_dof = match root.get("use_dof") {
            Some(n) => n.bool()?,
            None => false,
        };
        let thin_lens = match kind.as_str() {
            _ if use_dof => true,
            "pinhole" | "perspective" => false,
            "thinlens" | "thinlen" | "thin_lens" | "lens" | "aperture" | "dof" => true,
            other => {
                let t = cam.get("type").unwrap_or_else(|| cam.clone());
                self.warn(
                    &t,
                    format!("unknown camera type '{other}'; using a pinhole camera"),
                );
                false
            }
        };
        let settings = root.get("settings").filter(|n| n.is_object());
        let size_holder = match &settings {
            Some(st) if !cam.has_any(&["width"]) && st.has_any(&["width"]) => st.clone(),
            _ => cam.clone(),
        };
        let width_node = required(&size_holder, &["width"])?;
        let height_node = required(&size_holder, &["height"])?;
        let (w0, h0) = (width_node.u32()?, height_node.u32()?);
        if w0 == 0 || h0 == 0 {
            let n = if w0 == 0 { &width_node } else { &height_node };
            return Err(n.error("the image size must be at least 1×1"));
        }
        let (width, height) = match (self.options.width, self.options.height) {
            (Some(w), Some(h)) => (w, h),
            (Some(w), None) => (
                w,
                ((w as f64 * h0 as f64 / w0 as f64).round() as u32).max(1),
            ),
            (None, Some(h)) => (
                ((h as f64 * w0 as f64 / h0 as f64).round() as u32).max(1),
                h,
            ),
            (None, None) => (w0, h0),
        };
        if width == 0 || height == 0 {
            return Err(width_node.error("the image size must be at least 1×1"));
        }
        if width as u64 * height as u64 > self.options.max_pixels {
            return Err(width_node.error(format!(
                "an image of {width}×{height} is over the limit of {} pixels (raise it with --max-pixels)",
                self.options.max_pixels
            )));
        }
        let aspect = width as f32 / height as f32;
        let fov_y = if let Some(n) = cam.get("fov") {
            let f = n.f32()?;
            if !(f > 0.0 && f < 180.0) {
                return Err(n.error(format!("fov must be between 0 and 180 degrees, found {f}")));
            }
            f
        } else if let Some(n) = cam.get("hfov") {
            let f = n.f32()?;
            if !(f > 0.0 && f < 180.0) {
                return Err(n.error(format!("hfov must be between 0 and 180 degrees, found {f}")));
            }
            2.0 * ((0.5 * f.to_radians()).tan() / aspect).atan().to_degrees()
        } else {
            return Err(required(cam, &["fov", "hfov"])
                .err()
                .unwrap_or_else(|| cam.error("missing fov")));
        };

        let position_keys = [
            "position", "location", "origin", "lookfrom", "camPos", "eye",
        ];
        let target_keys = ["lookAt", "look_at", "look", "camView", "target"];
        let position = opt_vec3(cam, &position_keys)?;
        let direction = if let Some(n) = cam.get("lookat") {
            // The 2021–23 skeleton's `lookat` is a direction, not a point. Some files write a
            // target point there; a zero direction can only mean that.
            let d = n.vec3()?;
            if d == Vec3::ZERO && position.is_some_and(|p| p != Vec3::ZERO) {
                self.warn(
                    &n,
                    "'lookat' is a direction, and [0,0,0] is none; read as the point to look at",
                );
                Some((-position.unwrap_or(Vec3::ZERO), n))
            } else {
                Some((d, n))
            }
        } else if let Some(n) = cam.get_any(&target_keys) {
            Some((n.vec3()? - position.unwrap_or(Vec3::ZERO), n))
        } else {
            None
        };
        let up = opt_vec3(cam, &["up", "upVector", "vup", "camAxis"])?;
        let (position, dir, up, dir_node) = match (position, direction) {
            (None, None) => (Vec3::ZERO, -Vec3::Z, up.unwrap_or(Vec3::Y), cam.clone()),
            (p, Some((d, n))) => (p.unwrap_or(Vec3::ZERO), d, up.unwrap_or(Vec3::Y), n),
            (Some(p), None) => {
                self.warn(
                    cam,
                    "the camera has a position but no viewing direction; looking along −z",
                );
                (p, -Vec3::Z, up.unwrap_or(Vec3::Y), cam.clone())
            }
        };
        // An up hint parallel to the view needs a stand-in.
        let up = if dir.cross(up).length_squared() > 0.0 {
            up
        } else if dir.cross(Vec3::Y).length_squared() > 0.0 {
            self.warn(
                &dir_node,
                "the up vector is parallel to the viewing direction; using +y",
            );
            Vec3::Y
        } else {
            self.warn(
                &dir_node,
                "the up vector is parallel to the viewing direction; using +z",
            );
            Vec3::Z
        };

        let exposure = match cam.get("exposure").or_else(|| root.get("exposure")) {
            Some(n) => {
                let e = n.f32()?;
                if e < 0.0 {
                    return Err(n.error(format!("exposure must be ≥ 0, found {e}")));
                }
                e
            }
            None => 1.0,
        };

        let lens = if thin_lens {
            let radius = if let Some(r) = opt_f32(cam, LENS_RADIUS_KEYS)? {
                Some(r)
            } else if let Some(d) = opt_f32(cam, LENS_DIAMETER_KEYS)? {
                Some(0.5 * d)
            } else {
                opt_f32(root, ROOT_DIAMETER_KEYS)?.map(|d| 0.5 * d)
            };
            let focus = match opt_f32(cam, FOCUS_KEYS)? {
                Some(f) => Some(f),
                None => opt_f32(root, ROOT_FOCUS_KEYS)?,
            };
            match radius {
                Some(r) if r < 0.0 => {
                    return Err(cam.error(format!("the aperture must be ≥ 0, found {r}")))
                }
                Some(r) if r > 0.0 => {
                    let focus = match (focus, cam.get_any(&target_keys)) {
                        (Some(f), _) => f,
                        // Without a focus distance, focus on the point looked at.
                        (None, Some(_)) => dir.length(),
                        (None, None) => {
                            return Err(cam.error(
                                "a thin-lens camera needs a focus distance ('focusdistance' or a spelling listed in docs/scene-format.md)",
                            ))
                        }
                    };
                    if focus <= 0.0 {
                        return Err(
                            cam.error(format!("the focus distance must be > 0, found {focus}"))
                        );
                    }
                    Some(Lens {
                        radius: r,
                        focus_distance: focus,
                    })
                }
                Some(_) => None,
                None => {
                    self.warn(
                        cam,
                        "a thin-lens camera without an aperture; rendering as a pinhole",
                    );
                    None
                }
            }
        } else {
            // A pinhole camera has no lens: its lens keys are known but have nothing to set.
            for keys in [LENS_RADIUS_KEYS, LENS_DIAMETER_KEYS, FOCUS_KEYS] {
                cam.mark_read(keys);
            }
            root.mark_read(ROOT_DIAMETER_KEYS);
            root.mark_read(ROOT_FOCUS_KEYS);
            None
        };

        let handedness = if is_cgr(root, cam) {
            Handedness::UpCrossForward
        } else {
            Handedness::ForwardCrossUp
        };
        let camera = Camera::new(position, dir, up, handedness, width, height, fov_y, lens)
            .ok_or_else(|| dir_node.error("the viewing direction is zero"))?;

        // A thin-lens camera's rays per pixel; a pinhole camera's count is ignored, as the files'
        // renderers do (one ray through each pixel).
        let lens_samples = if thin_lens {
            cam.get_any(LENS_SAMPLE_KEYS)
        } else {
            cam.mark_read(LENS_SAMPLE_KEYS);
            None
        };
        Ok((camera, exposure, lens_samples))
    }

    fn light(&mut self, l: &Node) -> Result<(), SceneError> {
        if !l.is_object() {
            return Err(l.error(format!("a light is an object, found {}", l.kind())));
        }
        let type_node = required(l, &["type"])?;
        let kind = type_node.str()?.to_ascii_lowercase();
        match kind.as_str() {
            "pointlight" | "point" | "point_light" => {
                let intensity = self.intensity(l)?;
                let position = required(l, &["position", "pos"])?.vec3()?;
                self.lights.push(Light::Point {
                    position,
                    intensity,
                });
            }
            "ambient" | "ambientlight" => {
                let n = required(l, &["intensity", "color", "colour"])?;
                let a = non_negative_color(&n)?;
                self.ambient = Some(self.ambient.unwrap_or(Vec3::ZERO) + a);
            }
            "arealight" | "area" | "area_light" | "quadlight" => {
                let intensity = self.intensity(l)?;
                self.area_light(l, intensity)?
            }
            other => {
                let near = nearest(other, LIGHT_TYPES);
                l.mark_all_read(); // skipped whole, with this warning
                self.warn(
                    &type_node,
                    format!("unknown light type '{other}' (nearest known: '{near}'); skipped"),
                );
            }
        }
        Ok(())
    }

    /// `is`/`id` (power, 1/(4πd²)) or `intensity` (1/d² in 2019 files, no fall-off in CGR
    /// files), possibly tinted by `color` or split into `diffuse`/`specular`; attenuation
    /// coefficients `kc`/`kl`/`kq` replace the fall-off in any variant.
    fn intensity(&mut self, l: &Node) -> Result<Intensity, SceneError> {
        let attenuation = self.attenuation(l)?;
        let is = l.get("is").map(|n| n.color()).transpose()?;
        let id = l.get("id").map(|n| n.color()).transpose()?;
        if is.is_some() || id.is_some() {
            let s = is.or(id).unwrap_or(Vec3::ONE);
            let d = id.or(is).unwrap_or(Vec3::ONE);
            return Ok(Intensity {
                diffuse: d,
                specular: s,
                falloff: attenuation.unwrap_or(Falloff::InverseSquare {
                    scale: 1.0 / (4.0 * std::f32::consts::PI),
                }),
            });
        }
        let base = match l.get_any(&["intensity", "power"]) {
            Some(n) => n.color()?,
            None => Vec3::ONE,
        };
        let tint = l
            .get_any(&["color", "colour"])
            .map(|n| n.color())
            .transpose()?
            .unwrap_or(Vec3::ONE);
        let diffuse = l
            .get("diffuse")
            .map(|n| n.color())
            .transpose()?
            .unwrap_or(Vec3::ONE);
        let specular = l
            .get("specular")
            .map(|n| n.color())
            .transpose()?
            .unwrap_or(diffuse);
        if l.get_any(&["intensity", "power", "color", "colour", "diffuse"])
            .is_none()
        {
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
    fn attenuation(&self, l: &Node) -> Result<Option<Falloff>, SceneError> {
        if !l.has_any(&["kc", "kl", "kq"]) {
            return Ok(None);
        }
        let mut k = [1.0, 0.0, 0.0];
        for (slot, key) in k.iter_mut().zip(["kc", "kl", "kq"]) {
            if let Some(n) = l.get(key) {
                let v = n.f32()?;
                if v < 0.0 {
                    return Err(n.error(format!("{key} must be ≥ 0, found {v}")));
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
    fn area_light(&mut self, l: &Node, intensity: Intensity) -> Result<(), SceneError> {
        let corner = |k: &str| l.get(k).map(|n| n.vec3()).transpose();
        let (origin, edge_u, edge_v) = if let (Some(a), Some(b), Some(c)) =
            (corner("v0")?, corner("v1")?, corner("v2")?)
        {
            match corner("v3")? {
                Some(d) => quad_edges([a, b, c, d]),
                None => right_angle_corner(a, b, c),
            }
        } else if let (Some(a), Some(b), Some(c)) = (corner("c1")?, corner("c2")?, corner("c3")?) {
            right_angle_corner(a, b, c)
        } else if let (Some(p), Some(e0), Some(e1)) = (corner("p")?, corner("e0")?, corner("e1")?) {
            (p, e0, e1)
        } else if let (Some(p), Some(u), Some(v)) =
            (corner("position")?, corner("u")?, corner("v")?)
        {
            // Centred on `position`; with `width`/`height` the edges are `u`, `v` scaled to those
            // lengths, otherwise `u` and `v` are the edges.
            let w = opt_f32(l, &["width"])?;
            let h = opt_f32(l, &["height"])?;
            let eu = match w {
                Some(w) => u.normalize_or_zero() * w,
                None => u,
            };
            let ev = match h {
                Some(h) => v.normalize_or_zero() * h,
                None => v,
            };
            (p - 0.5 * eu - 0.5 * ev, eu, ev)
        } else if let (Some(p), Some(size)) = (corner("position")?, l.get("size")) {
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
        } else if let Some(shape) = l.get("shape") {
            return self.shaped_area_light(l, &shape, intensity);
        } else if let Some(id) = l.get("shapeid") {
            let (samples, method) = self.area_sampling(l)?;
            self.emitters
                .want(self.lights.len(), &id, intensity, samples, method)?;
            // A placeholder, replaced once the shapes are read.
            self.lights.push(Light::Point {
                position: Vec3::ZERO,
                intensity,
            });
            return Ok(());
        } else if let (Some(p), RenderMode::Path) = (corner("position")?, self.mode) {
            // The one renderer whose path-tracing files give area lights only a position makes
            // them 1 × 1 squares spanning x and y, centred there (docs/scene-format.md).
            (p - 0.5 * (Vec3::X + Vec3::Y), Vec3::X, Vec3::Y)
        } else if let Some(p) = corner("position")? {
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
                 a 'shape' or a 'shapeid')",
            ));
        };
        let (samples, method) = self.area_sampling(l)?;
        let mut light = Light::quad(origin, edge_u, edge_v, intensity, samples, method);
        if let Some(n) = l.get("normal") {
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
    fn shaped_area_light(
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
        let type_node = required(shape, &["type"])?;
        let kind = type_node.str()?.to_ascii_lowercase();
        let light = if kind == "sphere" || kind == "uvsphere" {
            let (center, radius) = lights::sphere(shape)?;
            let (samples, method) = self.area_sampling(l)?;
            Light::Sphere {
                center,
                radius,
                intensity,
                samples,
                method,
                surface: 0..0,
            }
        } else if let Some(n) = lights::flat_corners(&kind) {
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
                Light::Triangles {
                    cumulative_area: crate::light::cumulative_areas(&triangles),
                    triangles,
                    intensity,
                    samples,
                    method,
                    surface: 0..0,
                }
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
    /// A sampling method named by `method`, `sampler` or `sampling` in `node`, if any.
    fn sampling_method(&mut self, node: &Node) -> Result<Option<Method>, SceneError> {
        let Some(n) = node.get_any(&["method", "sampler", "sampling"]) else {
            return Ok(None);
        };
        Ok(Some(match n.str()?.to_ascii_lowercase().as_str() {
            "random" | "uniform" => Method::Random,
            "jittered" | "stratified" | "jitter" => Method::Jittered,
            "sobol" => Method::Sobol,
            other => {
                self.warn(
                    &n,
                    format!("unknown sampling method '{other}'; using jittered"),
                );
                Method::Jittered
            }
        }))
    }

    fn area_sampling(&mut self, l: &Node) -> Result<(u32, Method), SceneError> {
        let method = self.sampling_method(l)?.unwrap_or(Method::Jittered);
        let samples_node = l.get_any(&["samples", "nsamples", "samplesize", "cell"]);
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

    fn shape(
        &mut self,
        s: &Node,
        mode: RenderMode,
        libraries: &mut Libraries,
    ) -> Result<(), SceneError> {
        if !s.is_object() {
            return Err(s.error(format!("a shape is an object, found {}", s.kind())));
        }
        let type_node = required(s, &["type"])?;
        let kind = type_node.str()?.to_ascii_lowercase();
        let known = matches!(
            kind.as_str(),
            "sphere"
                | "uvsphere"
                | "plane"
                | "planarquad"
                | "planerquad"
                | "quad"
                | "rectangle"
                | "triangle"
                | "trimesh"
                | "mesh"
                | "ply"
                | "trianglemesh"
                | "tris"
                | "cylinder"
                | "uvcylinder"
                | "box"
                | "rectanglexy"
                | "rectanglexz"
                | "rectangleyz"
        );
        if !known {
            let near = nearest(&kind, SHAPE_TYPES);
            s.mark_all_read(); // skipped whole, with this warning
            self.warn(
                &type_node,
                format!("unknown shape type '{kind}' (nearest known: '{near}'); skipped"),
            );
            return Ok(());
        }
        let material = self.material(s, mode, libraries)?;
        match kind.as_str() {
            "sphere" | "uvsphere" => {
                let center = required(s, &["center", "centre", "position"])?.vec3()?;
                let radius = positive(s, "radius")?;
                self.primitives.push(Primitive {
                    shape: Shape::Sphere(Sphere::new(center, radius, SPHERE_POLE, SPHERE_SEAM)),
                    material,
                });
            }
            "cylinder" | "uvcylinder" => {
                let center = required(s, &["center", "centre", "position"])?.vec3()?;
                let an = required(s, &["axis"])?;
                let axis = an.vec3()?;
                if axis.length_squared() == 0.0 {
                    return Err(an.error("the axis must not be zero"));
                }
                let radius = positive(s, "radius")?;
                let half = positive(s, "height")?;
                self.primitives.push(Primitive {
                    shape: Shape::Cylinder(Cylinder::new(center, axis, radius, half)),
                    material,
                });
            }
            "triangle" => {
                let p = self.corners(s, 3)?;
                if (p[1] - p[0]).cross(p[2] - p[0]) == Vec3::ZERO {
                    return Err(s.error("the triangle has zero area (its corners are collinear)"));
                }
                let uv = self.corner_uvs(s, 3)?.unwrap_or_else(|| {
                    vec![
                        Vec2::new(0.0, 0.0),
                        Vec2::new(1.0, 0.0),
                        Vec2::new(1.0, 1.0),
                    ]
                });
                self.add_mesh(s, p, None, MeshUv::PerVertex(uv), vec![[0, 1, 2]], material)?;
            }
            "plane" | "planarquad" | "planerquad" | "quad" | "rectangle" => {
                let has_corners =
                    s.contains_any(&["v0", "v1", "point1", "p0", "points", "vertices", "corner1"]);
                if s.contains_any(&["normal", "distance"]) && !has_corners {
                    let plane = infinite_plane(s)?;
                    self.primitives.push(Primitive {
                        shape: Shape::Plane(plane),
                        material,
                    });
                    return Ok(());
                }
                let p = if let (Some(a), Some(b)) = (s.get("corner1"), s.get("corner2")) {
                    axis_rectangle(s, a.vec3()?, b.vec3()?)?
                } else if !has_corners && s.contains_any(&["center", "centre"]) {
                    centred_rectangle(s)?
                } else {
                    self.corners(s, 4)?
                };
                // Corners in "Z order" are put in cycle order; explicit uvs follow their corners,
                // the default ones put image pixel (0,0) at v0 and the first row along v0→v1.
                let order = cycle_order([p[0], p[1], p[2], p[3]]);
                let p: Vec<Vec3> = order.iter().map(|&i| p[i]).collect();
                let area2 = (p[1] - p[0]).cross(p[2] - p[0]) + (p[2] - p[0]).cross(p[3] - p[0]);
                if area2 == Vec3::ZERO {
                    return Err(s.error("the quad has zero area (its corners are collinear)"));
                }
                let uv = match self.corner_uvs(s, 4)? {
                    Some(uv) => order.iter().map(|&i| uv[i]).collect(),
                    None => vec![
                        Vec2::new(0.0, 0.0),
                        Vec2::new(1.0, 0.0),
                        Vec2::new(1.0, 1.0),
                        Vec2::new(0.0, 1.0),
                    ],
                };
                self.add_mesh(
                    s,
                    p,
                    None,
                    MeshUv::PerVertex(uv),
                    vec![[0, 1, 2], [0, 2, 3]],
                    material,
                )?;
            }
            "box" => {
                let (min, max) = if let Some(c) = s.get_any(&["center", "centre"]) {
                    // Centre and edge lengths along x (`width`), y (`height`), z (`depth`).
                    let c = c.vec3()?;
                    let size = Vec3::new(
                        required(s, &["width"])?.f32()?,
                        required(s, &["height"])?.f32()?,
                        required(s, &["depth"])?.f32()?,
                    );
                    (c - 0.5 * size, c + 0.5 * size)
                } else {
                    (
                        required(s, &["min"])?.vec3()?,
                        required(s, &["max"])?.vec3()?,
                    )
                };
                let (mut p, faces) = box_mesh(min.min(max), min.max(max));
                // A box given by its centre turns about its centre; one given by its corners
                // turns about the world origin (docs/scene-format.md gives the evidence).
                if let Some(r) = transform::rotation(s)? {
                    let pivot = if s.has_any(&["center", "centre"]) {
                        0.5 * (min + max)
                    } else {
                        Vec3::ZERO
                    };
                    let a = Affine {
                        linear: r,
                        translation: pivot - r * pivot,
                    };
                    p.iter_mut().for_each(|q| *q = a.point(*q));
                }
                self.add_mesh(s, p, None, MeshUv::Strip, faces, material)?;
            }
            "rectanglexy" | "rectanglexz" | "rectangleyz" => {
                let r = rectangle::read(s, &kind)?;
                self.add_mesh(
                    s,
                    r.corners.to_vec(),
                    None,
                    MeshUv::PerVertex(r.uvs.to_vec()),
                    vec![[0, 1, 2], [0, 2, 3]],
                    material,
                )?;
            }
            _ => self.mesh(s, material)?,
        }
        Ok(())
    }

    /// The corner points of a triangle (`n = 3`) or quad (`n = 4`), under any of the spellings.
    fn corners(&self, s: &Node, n: usize) -> Result<Vec<Vec3>, SceneError> {
        for keys in [
            ["v0", "v1", "v2", "v3"],
            ["v1", "v2", "v3", "v4"],
            ["point1", "point2", "point3", "point4"],
            ["p0", "p1", "p2", "p3"],
        ] {
            if s.get(keys[0]).is_some() {
                return keys[..n]
                    .iter()
                    .map(|k| required(s, &[k])?.vec3())
                    .collect();
            }
        }
        if let Some(list) = s.get_any(&["points", "vertices"]) {
            let e = list.elements()?;
            if n == 4 && e.len() == 3 {
                // Three corners of a parallelogram: complete it at the corner opposite the one
                // where the edges meet squarely.
                let (o, a, b) = right_angle_corner(e[0].vec3()?, e[1].vec3()?, e[2].vec3()?);
                return Ok(vec![o, o + a, o + a + b, o + b]);
            }
            if e.len() != n {
                return Err(list.error(format!("expected {n} points, found {}", e.len())));
            }
            return e.iter().map(|p| p.vec3()).collect();
        }
        Err(s.error(format!(
            "missing the corners 'v0'..'v{}' (or 'point1'..'point{n}', or 'points')",
            n - 1
        )))
    }

    fn corner_uvs(&self, s: &Node, n: usize) -> Result<Option<Vec<Vec2>>, SceneError> {
        for keys in [["uv0", "uv1", "uv2", "uv3"], ["uv1", "uv2", "uv3", "uv4"]] {
            if s.get(keys[0]).is_some() && s.get(keys[n - 1]).is_some() {
                let mut out = Vec::with_capacity(n);
                for k in &keys[..n] {
                    let node = required(s, &[k])?;
                    let v = node.numbers()?;
                    if v.len() != 2 {
                        return Err(node.error(format!("expected 2 numbers, found {}", v.len())));
                    }
                    out.push(Vec2::new(v[0] as f32, v[1] as f32));
                }
                return Ok(Some(out));
            }
        }
        Ok(None)
    }

    fn mesh(&mut self, s: &Node, material: u32) -> Result<(), SceneError> {
        if !s.contains_any(MESH_FILE_KEYS) && poly_sphere::applies(s) {
            let budget = self.options.max_triangles.saturating_sub(self.triangles);
            for m in poly_sphere::read(s, budget)? {
                let uv = m.uvs.map_or(MeshUv::Strip, MeshUv::PerVertex);
                self.add_mesh(s, m.positions, m.normals, uv, m.faces, material)?;
            }
            return Ok(());
        }
        let mut data = if let Some(fnode) = s.get_any(MESH_FILE_KEYS) {
            let rel = fnode.str()?;
            let path = self.resolve(&fnode, rel)?;
            let limits = MeshLimits {
                max_bytes: self.options.max_mesh_bytes,
                max_triangles: self.options.max_triangles,
                triangles_before: self.triangles,
                max_memory: self.options.max_memory,
            };
            let mut data =
                read_mesh_with(&path, &limits).map_err(|e| fnode.error(e.to_string()))?;
            // PLY and OBJ files put v = 0 at the bottom of the image (the OpenGL convention of
            // the tools that write them); textures here have v = 0 at the top row.
            if let Some(uvs) = data.uvs.as_mut() {
                uvs.iter_mut().for_each(|uv| uv.y = 1.0 - uv.y);
            }
            data
        } else {
            self.inline_mesh(s)?
        };
        // Scale, then rotate, then translate.
        let placement = transform::mesh_placement(s)?;
        transform::place_mesh(&placement, &mut data.positions, &mut data.normals);
        let uv = match data.uvs {
            Some(uv) => MeshUv::PerVertex(uv),
            None => MeshUv::Strip,
        };
        self.add_mesh(s, data.positions, data.normals, uv, data.faces, material)
    }

    /// A mesh written in the scene file. Spellings: `vertices`/`vs` with `faces`/`fs`/`tris`/
    /// `triangles` (lists of index lists, polygons are fanned); `vertex`/`face` counts with
    /// `v0…`/`f0…` keys; `vertexindex` (flat) with `faceindex` (polygon sizes) and `texturemap`
    /// (per-vertex uv); `points` alone (consecutive triples when the count is a multiple of 3,
    /// otherwise one convex polygon).
    fn inline_mesh(&self, s: &Node) -> Result<MeshData, SceneError> {
        let mut positions = Vec::new();
        let counted = s
            .get("vertex")
            .filter(|n| n.numbers().is_err() && n.u32().is_ok());
        let vn = if let Some(count) = counted {
            for i in 0..count.u32()? {
                positions.push(required(s, &[&format!("v{i}")])?.vec3()?);
            }
            count
        } else if let Some(list) = s
            .get("triangles")
            .filter(|t| t.elements().is_ok_and(|e| e.iter().all(|x| x.is_object())))
        {
            // A list of triangle objects, each with its corners.
            let mut faces = Vec::new();
            for t in list.elements()? {
                let n = positions.len() as u32;
                for k in ["v0", "v1", "v2"] {
                    positions.push(required(&t, &[k])?.vec3()?);
                }
                faces.push([n, n + 1, n + 2]);
            }
            if faces.is_empty() {
                return Err(list.error("the mesh has no triangles"));
            }
            return Ok(MeshData {
                positions,
                normals: None,
                uvs: None,
                faces,
            });
        } else {
            let vn = required(s, &["vertices", "vs", "vertex", "points"])?;
            for v in vn.elements()? {
                positions.push(v.vec3()?);
            }
            vn
        };
        let check = |node: &Node, i: f64| -> Result<u32, SceneError> {
            if i < 0.0 || i.fract() != 0.0 || i >= positions.len() as f64 {
                return Err(node.error(format!(
                    "vertex index {i} is out of range (the mesh has {} vertices)",
                    positions.len()
                )));
            }
            Ok(i as u32)
        };
        // One face written as a list of vertex indices.
        let indices = |f: &Node| -> Result<Vec<u32>, SceneError> {
            f.numbers()?.into_iter().map(|i| check(f, i)).collect()
        };
        let mut polygons: Vec<(Node, Vec<u32>)> = Vec::new();
        if let (Some(sizes), Some(flat)) = (s.get("faceindex"), s.get("vertexindex")) {
            let idx = flat.numbers()?;
            let mut at = 0usize;
            for (k, size) in sizes.numbers()?.into_iter().enumerate() {
                // `at + n` could overflow for a huge size (1e30 saturates to usize::MAX), so the
                // size is compared with what is left; `at <= idx.len()` holds on every pass.
                let n = size.max(0.0) as usize;
                let left = idx.len() - at;
                if n > left {
                    return Err(sizes.error(format!(
                        "face {k} needs {size} indices but 'vertexindex' has only {left} left"
                    )));
                }
                let ids = idx[at..at + n]
                    .iter()
                    .map(|&i| check(&flat, i))
                    .collect::<Result<Vec<_>, _>>()?;
                polygons.push((sizes.clone(), ids));
                at += n;
            }
        } else if let Some(count) = s.get("face").filter(|n| n.u32().is_ok()) {
            for i in 0..count.u32()? {
                let f = required(s, &[&format!("f{i}")])?;
                let ids = indices(&f)?;
                polygons.push((f, ids));
            }
        } else if let Some(fnode) = s.get_any(&["faces", "fs", "tris", "triangles", "face"]) {
            for f in fnode.elements()? {
                let ids = indices(&f)?;
                polygons.push((f, ids));
            }
        } else if vn.path.ends_with("points") && !positions.is_empty() {
            let n = positions.len() as u32;
            if n.is_multiple_of(3) {
                for t in 0..n / 3 {
                    polygons.push((vn.clone(), vec![3 * t, 3 * t + 1, 3 * t + 2]));
                }
            } else {
                polygons.push((vn.clone(), (0..n).collect()));
            }
        } else {
            return Err(required(s, &["faces", "fs", "tris", "triangles"])
                .err()
                .unwrap_or_else(|| s.error("missing faces")));
        }
        if polygons.is_empty() {
            return Err(s.error("the mesh has no faces"));
        }
        let mut faces = Vec::new();
        for (node, ids) in polygons {
            if ids.len() < 3 {
                return Err(node.error(format!(
                    "a face needs at least 3 vertex indices, found {}",
                    ids.len()
                )));
            }
            for k in 1..ids.len() - 1 {
                faces.push([ids[0], ids[k], ids[k + 1]]);
            }
        }
        let uvs = match s.get("texturemap") {
            Some(t) => {
                let mut uv = Vec::new();
                for e in t.elements()? {
                    let v = e.numbers()?;
                    if v.len() != 2 {
                        return Err(e.error(format!("expected 2 numbers, found {}", v.len())));
                    }
                    uv.push(Vec2::new(v[0] as f32, v[1] as f32));
                }
                if uv.len() != positions.len() {
                    return Err(t.error(format!(
                        "{} texture coordinates for {} vertices",
                        uv.len(),
                        positions.len()
                    )));
                }
                Some(uv)
            }
            None => None,
        };
        Ok(MeshData {
            positions,
            normals: None,
            uvs,
            faces,
        })
    }

    fn add_mesh(
        &mut self,
        node: &Node,
        positions: Vec<Vec3>,
        normals: Option<Vec<Vec3>>,
        uv: MeshUv,
        faces: Vec<[u32; 3]>,
        material: u32,
    ) -> Result<(), SceneError> {
        self.triangles += faces.len();
        if self.triangles > self.options.max_triangles {
            return Err(node.error(format!(
                "the scene has over {} triangles (raise the limit with --max-triangles)",
                self.options.max_triangles
            )));
        }
        let mesh = Mesh {
            positions,
            normals,
            uv,
            faces,
        };
        self.primitives.push_mesh(mesh, material);
        Ok(())
    }

    fn material(
        &mut self,
        s: &Node,
        mode: RenderMode,
        libraries: &mut Libraries,
    ) -> Result<u32, SceneError> {
        let mut m = Material::default();
        // A shape without a `material` may carry the material's keys itself (as some files do).
        let mut node = s.get("material").or_else(|| Some(s.clone()));
        // Whether `node` is a material object rather than the shape standing in for one (whose
        // `type` is the shape's).
        let own_material = s.peek("material").is_some();
        if let Some(named) = node.as_ref().and_then(|n| n.str().ok()) {
            match libraries.materials.find(named) {
                Some((_, def)) => node = Some(def.clone()),
                None => {
                    let names = libraries.materials.names();
                    let at = node.unwrap_or_else(|| s.clone());
                    return Err(at.error(format!(
                        "no material named '{named}' (the scene defines: {})",
                        if names.is_empty() {
                            "none".to_string()
                        } else {
                            names.join(", ")
                        }
                    )));
                }
            }
        }
        if let Some(n) = &node {
            if !n.is_object() {
                return Err(n.error(format!("a material is an object, found {}", n.kind())));
            }
            if let Some(v) = opt_f32(n, &["ka"])? {
                m.ka = v;
            }
            if let Some(v) = opt_f32(n, &["kd"])? {
                m.kd = v;
            }
            if let Some(v) = opt_f32(n, &["ks"])? {
                m.ks = v;
            }
            if let Some(v) = opt_f32(
                n,
                &[
                    "specularexponent",
                    "specular_exponent",
                    "shininess",
                    "exponent",
                    "alpha",
                ],
            )? {
                if v < 0.0 {
                    return Err(n.error(format!("the specular exponent must be ≥ 0, found {v}")));
                }
                m.exponent = v;
            }
            if let Some(c) = n.get_any(&[
                "diffusecolor",
                "diffusecolour",
                "diffuse_color",
                "color",
                "colour",
            ]) {
                m.diffuse = c.color()?;
            } else if let Some(c) = n.get("diffuse").filter(|c| c.str().is_err()) {
                m.diffuse = c.color()?; // `diffuse` as a string is a texture (below)
            }
            if let Some(c) = n.get_any(&["specularcolor", "specularcolour", "specular_color"]) {
                m.specular = c.color()?;
            }
            let reflective = n
                .get_any(&["isreflective", "isReflective"])
                .map(|b| b.bool())
                .transpose()?;
            if let Some(v) = opt_f32(n, &["kr", "reflectivity", "reflection", "reflectance"])? {
                m.kr = if reflective == Some(false) { 0.0 } else { v };
            } else if reflective == Some(true) {
                m.kr = 1.0;
            }
            let refractive = n
                .get_any(&["isrefractive", "isRefractive", "isGlass"])
                .map(|b| b.bool())
                .transpose()?;
            if let Some(v) = opt_f32(n, &["kt", "transparency", "transmit", "transmittance"])? {
                m.kt = if refractive == Some(false) { 0.0 } else { v };
            } else if refractive == Some(true) {
                m.kt = 1.0;
            }
            let eta_node = n.get_any(&[
                "eta",
                "refractiveindex",
                "refractiveIndex",
                "refractive_index",
                "ior",
            ]);
            m.eta = match &eta_node {
                Some(e) => e.f32()?,
                None => DEFAULT_ETA,
            };
            for (name, v) in [
                ("ka", m.ka),
                ("kd", m.kd),
                ("ks", m.ks),
                ("kr", m.kr),
                ("kt", m.kt),
            ] {
                if v < 0.0 {
                    let at = n.get(name).unwrap_or_else(|| n.clone());
                    return Err(at.error(format!("{name} must be ≥ 0, found {v}")));
                }
            }
            // A metal's roughness is its own (see `material_kind`); any other material's blurs
            // its mirror part.
            let roughness_read = own_material && self.material_kind(n, &mut m)?;
            if let Some(r) = n.get("roughness").filter(|_| !roughness_read) {
                m.mirror_exponent = self.mirror_roughness(&r, m.kr)?;
            }
            // Checked once the material's `type` has said whether it transmits.
            if let Some(e) = eta_node.filter(|_| m.eta <= 0.0 && m.kt > 0.0) {
                return Err(e.error(format!(
                    "the index of refraction must be > 0, found {}",
                    m.eta
                )));
            }
        }
        node.iter()
            .chain([s])
            .for_each(|n| n.mark_read(&TEXTURE_KEYS)); // known in every mode
        if let Some(n) = &node {
            n.mark_read(&["diffuse"]);
        }
        if mode != RenderMode::Binary {
            let tex_node = node
                .as_ref()
                .and_then(|n| {
                    n.get_any(&TEXTURE_KEYS)
                        .or_else(|| n.get("diffuse").filter(|d| d.str().is_ok()))
                })
                .or_else(|| s.get_any(&TEXTURE_KEYS));
            if let Some(t) = tex_node {
                m.texture = self.texture(&t, libraries)?;
            }
        }
        self.materials.push(m);
        Ok(self.materials.len() as u32 - 1)
    }

    /// Top-level switches of the renderers path-tracing files were written for. Sampling
    /// strategies change how fast an image converges, not what it converges to, and global
    /// illumination and caustics are what the path tracer does: those are read quietly.
    /// Post-processes this renderer does not do (a denoiser, a blur) are warned about when a file
    /// turns them on; the tone map a file turns on (`use_tone_mapping`: Kierandon's renderer
    /// applies Reinhard's `x/(1+x)` per channel) is returned.
    fn renderer_switches(&mut self, root: &Node) -> Result<Option<ToneMap>, SceneError> {
        for key in [
            "use_stratified_sampling",
            "use_importance_sampling",
            "usegi",
            "useGI",
            "usecaustics",
        ] {
            if let Some(n) = root.get(key) {
                n.bool()?;
            }
        }
        for key in [
            "importance_sampling_min_samples",
            "importance_sampling_max_samples",
        ] {
            if let Some(n) = root.get(key) {
                n.f64()?;
            }
        }
        for (key, what) in [
            ("use_denoiser", "a denoiser"),
            ("use_gaussian_blur", "a Gaussian blur"),
        ] {
            if let Some(n) = root.get(key) {
                if n.bool()? {
                    self.warn(
                        &n,
                        format!("{what} is not applied: the image is the renderer's radiance"),
                    );
                }
            }
        }
        match root.get("use_tone_mapping") {
            Some(n) if n.bool()? => Ok(Some(ToneMap::Reinhard)),
            _ => Ok(None),
        }
    }

    /// The mirror lobe's exponent for a Blinn-Phong material's `roughness` r ≥ 0 (some CGR files
    /// give one; their renderers blur the mirror part with a GGX lobe of α = r², the convention
    /// of Burley's "Physically Based Shading at Disney", SIGGRAPH 2012 course notes): a
    /// microfacet roughness α = r², so 0 keeps a perfect mirror. Past 1 it is taken as 1 (the
    /// roughest lobe) with a warning where there is a mirror to blur; a material without a
    /// mirror part has nothing it applies to.
    fn mirror_roughness(&mut self, r: &Node, kr: f32) -> Result<f32, SceneError> {
        let v = r.f32()?;
        if !(v >= 0.0 && v.is_finite()) {
            return Err(r.error(format!("roughness must be a finite number ≥ 0, found {v}")));
        }
        if v > 1.0 && kr > 0.0 {
            self.warn(r, format!("roughness is at most 1, found {v}; taken as 1"));
        }
        let alpha = v.min(1.0);
        Ok(roughness_exponent(alpha * alpha))
    }

    /// The physically based material forms path-tracing files use (`"type"` with `albedo`,
    /// `roughness`, `ior`, an emitted `colour` × `intensity`), and `emittance` on any material:
    /// see `docs/scene-format.md`, "Material types". Returns whether the type read `roughness`
    /// as its own (a metal's).
    fn material_kind(&mut self, n: &Node, m: &mut Material) -> Result<bool, SceneError> {
        if let Some(e) = n.get("emittance") {
            m.emission = e.color()?;
        }
        let Some(t) = n.peek("type") else {
            return Ok(false);
        };
        let Ok(kind) = t.str().map(str::to_ascii_lowercase) else {
            return Ok(false); // not a type name: left for the unknown-key warning
        };
        if !MATERIAL_TYPES.contains(&kind.as_str()) {
            return Ok(false); // a model of another renderer: left for the unknown-key warning
        }
        n.mark_read(&["type"]);
        let albedo = match n.get("albedo") {
            Some(a) => Some(a.color()?),
            None => None,
        };
        match kind.as_str() {
            "diffuse" | "lambertian" | "matte" => {
                m.kd = 1.0;
                m.ks = 0.0;
                m.diffuse = albedo.unwrap_or(m.diffuse);
            }
            "metal" | "conductor" | "mirror" => {
                let tint = albedo.unwrap_or(m.specular);
                let roughness = match n.get_any(&["roughness", "fuzz"]) {
                    Some(r) => {
                        let v = r.f32()?;
                        if !(0.0..=1.0).contains(&v) {
                            return Err(
                                r.error(format!("a metal's roughness is in [0, 1], found {v}"))
                            );
                        }
                        v
                    }
                    None => 0.0,
                };
                m.kd = 0.0;
                if roughness == 0.0 {
                    m.ks = 0.0;
                    m.kr = 1.0;
                    m.mirror = tint;
                } else {
                    m.ks = 1.0;
                    m.specular = tint;
                    m.exponent = roughness_exponent(roughness);
                }
                return Ok(true);
            }
            "dielectric" | "glass" => {
                m.kd = 0.0;
                m.ks = 0.0;
                m.kt = 1.0;
            }
            "emissive" | "emitter" | "light" | "emission" => {
                let colour = match n.get_any(&["colour", "color", "emission", "emittance"]) {
                    Some(c) => c.color()?,
                    None => Vec3::ONE,
                };
                let strength = opt_f32(n, &["intensity", "strength"])?.unwrap_or(1.0);
                if !(strength >= 0.0 && strength.is_finite()) {
                    let at = n.get_any(&["intensity", "strength"]).unwrap_or(t);
                    return Err(at.error(format!(
                        "an emitter's intensity must be a finite number ≥ 0, found {strength}"
                    )));
                }
                m.emission = colour * strength;
                m.kd = 0.0;
                m.ks = 0.0;
                m.diffuse = Vec3::ZERO;
            }
            _ => {} // Blinn-Phong: the keys already say it all
        }
        Ok(false)
    }

    /// A texture reference: the name of a texture library entry, a path string, or an object
    /// with a path.
    fn texture(&mut self, t: &Node, libraries: &mut Libraries) -> Result<Option<u32>, SceneError> {
        if matches!(t.value, jsonc_parser::ast::Value::Array(_)) {
            return Ok(None); // texture coordinates (`texturemap` on meshes), read with the mesh
        }
        let (node, rel) = if t.is_object() {
            match t.get_any(&["path", "file", "filename", "tPath"]) {
                Some(p) => {
                    let s = p.str()?;
                    (p, s)
                }
                None => {
                    self.warn(t, "a texture object without a 'path'; ignored");
                    return Ok(None);
                }
            }
        } else {
            let s = t.str()?;
            (t.clone(), s)
        };
        if !t.is_object() {
            if let Some(&done) = libraries.loaded.get(rel) {
                return Ok(Some(done));
            }
            if let Some((name, def)) = libraries.textures.find(rel) {
                let (name, def) = (name.clone(), def.clone());
                let done = self.library_texture(&def)?;
                libraries.loaded.insert(name, done);
                return Ok(Some(done));
            }
        }
        if rel.is_empty() {
            self.warn(&node, "an empty texture file name; texture ignored");
            return Ok(None);
        }
        if Path::new(rel).extension().is_none() {
            // A procedural texture of the file's own program (`wood`, `rainbow`), or a typo.
            if libraries.warned.insert(rel.to_string()) {
                self.warn(
                    &node,
                    format!(
                        "no texture named '{rel}' is defined and it is not an image file; the \
                         material's diffuse colour is used (warned once per name)"
                    ),
                );
            }
            return Ok(None);
        }
        self.image_texture(&node, rel, Vec2::ZERO).map(Some)
    }

    /// An entry of the texture library (see [`crate::texture`] for the forms).
    fn library_texture(&mut self, def: &Node) -> Result<u32, SceneError> {
        let type_node = required(def, &["type"])?;
        match type_node.str()?.to_ascii_lowercase().as_str() {
            "constant" => {
                let c = required(def, &["colour", "color"])?.color()?;
                self.textures.push(Texture::constant(c));
                Ok(self.textures.len() as u32 - 1)
            }
            "image" => {
                let img = required(def, &["image", "path", "file", "filename"])?;
                let rel = img.str()?;
                // The file's own program reads image row (1 − v − offset_v)·height: its v grows
                // up the image, so its offset moves the lookup up (−v here).
                let offset = Vec2::new(
                    opt_f32(def, &["offset_u"])?.unwrap_or(0.0),
                    -opt_f32(def, &["offset_v"])?.unwrap_or(0.0),
                );
                self.image_texture(&img, rel, offset)
            }
            other => Err(type_node.error(format!(
                "unknown texture type '{other}' (known: constant, image)"
            ))),
        }
    }

    /// The image file `rel` (resolved as assets are) as a texture with uv offset `offset`, loaded
    /// once per file and offset.
    fn image_texture(&mut self, node: &Node, rel: &str, offset: Vec2) -> Result<u32, SceneError> {
        let path = self.resolve(node, rel)?;
        let key = (path.clone(), [offset.x.to_bits(), offset.y.to_bits()]);
        if let Some(&i) = self.texture_index.get(&key) {
            return Ok(i);
        }
        // The same file under another offset: a copy of its texels, not a second read.
        if let Some((_, &i)) = self.texture_index.iter().find(|((p, _), _)| *p == path) {
            let moved = self.textures[i as usize].clone().with_offset(offset);
            self.textures.push(moved);
            let i = self.textures.len() as u32 - 1;
            self.texture_index.insert(key, i);
            return Ok(i);
        }
        let limits = ReadLimits {
            max_pixels: self.options.max_texture_pixels,
            flag: Some("--max-texture-pixels"),
        };
        let tex = Texture::load_with(&path, &limits)
            .map_err(|e| node.error(format!("cannot load the texture: {e}")))?;
        if tex.width == 0 || tex.height == 0 {
            return Err(node.error(format!("the texture {} is empty", shown(&path))));
        }
        self.textures.push(tex.with_offset(offset));
        let i = self.textures.len() as u32 - 1;
        self.texture_index.insert(key, i);
        Ok(i)
    }

    /// The first existing file among the scene's folder, the asset folders and the working
    /// directory joined with `rel`, recorded as one of the scene's inputs. A path that exists but
    /// is not a regular file (a folder, a FIFO, a device) is an error, never opened.
    fn resolve(&mut self, node: &Node, rel: &str) -> Result<PathBuf, SceneError> {
        let rel_path = PathBuf::from(rel.replace('\\', "/"));
        let mut tried = Vec::new();
        let mut bases = vec![self.base.clone()];
        bases.extend(self.options.asset_dirs.iter().cloned());
        if let Ok(cwd) = std::env::current_dir() {
            bases.push(cwd);
        }
        if rel_path.is_absolute() {
            bases = vec![PathBuf::new()];
        }
        let mut candidates: Vec<PathBuf> =
            bases.iter().map(|b| join_lexically(b, &rel_path)).collect();
        // Last, the bare file name beside the scene (assets copied next to it).
        if let Some(name) = rel_path.file_name() {
            candidates.push(self.base.join(name));
        }
        for candidate in candidates {
            if let Ok(meta) = std::fs::metadata(&candidate) {
                if let Err(e) = input::check_regular(&meta) {
                    return Err(node.error(format!("cannot read '{}': {e}", shown(&candidate))));
                }
                if !self.inputs.contains(&candidate) {
                    self.inputs.push(candidate.clone());
                }
                return Ok(candidate);
            }
            if !tried.contains(&candidate) {
                tried.push(candidate);
            }
        }
        let list: Vec<String> = tried.iter().map(|p| shown(p).to_string()).collect();
        Err(node.error(format!(
            "file '{rel}' not found (tried {})",
            list.join(", ")
        )))
    }
}

/// The keys that name a mesh file.
const MESH_FILE_KEYS: &[&str] = &[
    "mPath",
    "plyPath",
    "modelpath",
    "model",
    "path",
    "file",
    "filename",
];

const TEXTURE_KEYS: [&str; 7] = [
    "tPath",
    "texture",
    "texturepath",
    "texture_file",
    "texturemap",
    "texture_path",
    "tpath",
];

/// Whether a file follows the CGR 2024+ variant: a top-level `rendermode`, or the CGR camera keys
/// `upVector`/`exposure` (some CGR files omit `rendermode`).
fn is_cgr(root: &Node, camera: &Node) -> bool {
    root.get("rendermode").is_some() || camera.has_any(&["upVector", "exposure"])
}

/// The order that lists four corners as a cycle. They already are when the diagonals `p0p2` and
/// `p1p3` share a midpoint; corners written in "Z order" (`p3` opposite `p0`, as some files do)
/// are reordered to `p0, p1, p3, p2`.
/// An area light's parallelogram from four corners: the corners in cycle order c0..c3, then the
/// origin c0 and the edges c1 − c0 and c3 − c0 (the corner opposite c0 is not used).
fn quad_edges(p: [Vec3; 4]) -> (Vec3, Vec3, Vec3) {
    let [i0, i1, _, i3] = cycle_order(p);
    (p[i0], p[i1] - p[i0], p[i3] - p[i0])
}

fn cycle_order(p: [Vec3; 4]) -> [usize; 4] {
    let cycle = (p[0] + p[2] - p[1] - p[3]).length_squared();
    let z_order = (p[0] + p[3] - p[1] - p[2]).length_squared();
    if z_order < cycle {
        [0, 1, 3, 2]
    } else {
        [0, 1, 2, 3]
    }
}

/// Three corners of a rectangle: the one where the edges meet most squarely is the origin.
fn right_angle_corner(a: Vec3, b: Vec3, c: Vec3) -> (Vec3, Vec3, Vec3) {
    let score = |o: Vec3, x: Vec3, y: Vec3| {
        let (u, v) = ((x - o).normalize_or_zero(), (y - o).normalize_or_zero());
        u.dot(v).abs()
    };
    let options = [(a, b, c), (b, a, c), (c, a, b)];
    let (o, x, y) = options
        .into_iter()
        .min_by(|p, q| score(p.0, p.1, p.2).total_cmp(&score(q.0, q.1, q.2)))
        .unwrap_or((a, b, c));
    (o, x - o, y - o)
}

/// An axis-aligned rectangle from two opposite corners that share one coordinate.
fn axis_rectangle(s: &Node, a: Vec3, b: Vec3) -> Result<Vec<Vec3>, SceneError> {
    let d = (b - a).abs();
    let flat = if d.x <= d.y && d.x <= d.z {
        0
    } else if d.y <= d.z {
        1
    } else {
        2
    };
    let (i, j) = ((flat + 1) % 3, (flat + 2) % 3);
    let mut c1 = a;
    c1[i] = b[i];
    let mut c3 = a;
    c3[j] = b[j];
    if d[flat] != 0.0 {
        return Err(s.error("the corners of an axis-aligned rectangle must share one coordinate"));
    }
    if d[i] == 0.0 || d[j] == 0.0 {
        return Err(s.error("the rectangle's corners span no area"));
    }
    Ok(vec![a, c1, b, c3])
}

/// The infinite plane `normal · x = distance` (unit normal): `{"normal": [0, 1, 0], "distance":
/// -1}` is the floor `y = −1`. The corpus files put the plane where the rest of the scene rests
/// only under this sign (docs/scene-format.md).
fn infinite_plane(s: &Node) -> Result<Plane, SceneError> {
    let nn = required(s, &["normal"])?;
    let normal = nn.vec3()?;
    if normal == Vec3::ZERO {
        return Err(nn.error("the plane's normal must not be zero"));
    }
    let len = normal.length();
    if !(len.is_finite() && len > 0.0 && (normal / len).is_finite()) {
        return Err(nn.error(format!(
            "the plane's normal [{}, {}, {}] is too long or too short to normalise",
            normal.x, normal.y, normal.z
        )));
    }
    let distance = required(s, &["distance"])?.f32()?;
    Ok(Plane::new(normal, distance))
}

/// A rectangle given by its centre, `width` (along x) and `height` (along z), lying in the
/// plane y = centre.y with normal +y before the optional rotation (`rot`, `rotation`, `euler`:
/// Euler degrees, see [`transform`]) about its centre. Corners in cycle order, starting at
/// (−width/2, −height/2).
fn centred_rectangle(s: &Node) -> Result<Vec<Vec3>, SceneError> {
    let c = required(s, &["center", "centre"])?.vec3()?;
    let w = positive(s, "width")?;
    let h = positive(s, "height")?;
    let r = transform::rotation(s)?.unwrap_or(glam::Mat3::IDENTITY);
    let local = [
        Vec3::new(-0.5 * w, 0.0, -0.5 * h),
        Vec3::new(0.5 * w, 0.0, -0.5 * h),
        Vec3::new(0.5 * w, 0.0, 0.5 * h),
        Vec3::new(-0.5 * w, 0.0, 0.5 * h),
    ];
    Ok(local.iter().map(|&p| c + r * p).collect())
}

/// The 12 triangles of an axis-aligned box.
fn box_mesh(lo: Vec3, hi: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let corners = Aabb::new(lo, hi);
    let p: Vec<Vec3> = (0..8).map(|i| corners.corner(i)).collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let faces = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (p, faces)
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
