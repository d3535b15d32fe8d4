//! Helpers shared by the fuzz targets.
//!
//! Scratch space: one folder per fuzzing process under the system temporary directory. Only the
//! harness writes there (the input under test and copies of the bundled assets); the library code
//! under test only reads.
//!
//! Every target includes this file with `mod common;` and uses only part of it, hence the
//! `dead_code` allowances.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use raytracer::accel::AccelKind;
use raytracer::film::{to_rgb8, Film, ToneMap};
use raytracer::image_io::ImageError;
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{LoadOptions, Scene, SceneError};

/// This process's scratch folder, created on first use.
pub fn scratch() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("raytracer-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the fuzz scratch folder");
        dir
    })
}

/// Writes `data` to `name` in the scratch folder and returns its path.
pub fn write_input(name: &str, data: &[u8]) -> PathBuf {
    let path = scratch().join(name);
    std::fs::write(&path, data).expect("write the fuzz input");
    path
}

/// Most pixels an image read under fuzzing may have: 2^20 (12 MiB as float RGB), so that an
/// image the limits allow never trips the 2 GB memory limit, while one that claims more must be
/// refused by the limit check, before anything is allocated.
pub const FUZZ_MAX_IMAGE_PIXELS: u64 = 1 << 20;

/// The one place the fuzz targets call the image reader, with the fuzzing limits.
pub fn read_image(path: &Path) -> Result<Film, ImageError> {
    let limits = raytracer::image_io::ReadLimits {
        max_pixels: FUZZ_MAX_IMAGE_PIXELS,
        flag: None,
    };
    raytracer::image_io::read_image_with(path, &limits)
}

/// Small limits, so that one input renders in milliseconds; every bundled scene fits them.
/// Fields not named here keep their defaults.
pub fn load_options() -> LoadOptions {
    LoadOptions {
        width: Some(4),
        height: Some(4),
        asset_dirs: Vec::new(),
        max_pixels: 16,
        max_bounces: 8,
        max_triangles: 20_000,
        max_light_samples: 16,
        max_pixel_samples: 16,
        max_texture_pixels: FUZZ_MAX_IMAGE_PIXELS,
        ..LoadOptions::default()
    }
}

/// Recursion depth of the render, below the loader's bounce limit: a glass tree of depth 4 is at
/// most 31 rays per sample.
pub const RENDER_DEPTH: u32 = 4;

/// `<scratch>/scenes/fuzz.json`, with `<scratch>/scenes/meshes` and `<scratch>/textures` filled
/// with copies of the bundled meshes and textures, so that the relative asset paths the bundled
/// scenes use (`meshes/blob.ply`, `../textures/checker.png`) resolve.
pub fn scene_path() -> &'static Path {
    static PATH: OnceLock<PathBuf> = OnceLock::new();
    PATH.get_or_init(|| {
        let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let root = scratch();
        copy_dir(&repo.join("scenes/meshes"), &root.join("scenes/meshes"));
        copy_dir(&repo.join("textures"), &root.join("textures"));
        // One render thread: fuzzing processes run side by side.
        std::env::set_var("RAYON_NUM_THREADS", "1");
        root.join("scenes/fuzz.json")
    })
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("create an asset folder");
    for entry in std::fs::read_dir(from)
        .expect("list an asset folder")
        .flatten()
    {
        let p = entry.path();
        if p.is_file() {
            if let Some(name) = p.file_name() {
                std::fs::copy(&p, to.join(name)).expect("copy an asset");
            }
        }
    }
}

/// An error from loading the scene at `file` must start with that path (asset errors name the
/// asset after it).
pub fn check_scene_error(file: &Path, e: &SceneError) {
    let text = e.to_string();
    let name = file.display().to_string();
    assert!(text.starts_with(&name), "error without the file: {text}");
}

/// How a loaded scene is rendered.
#[derive(Debug, Clone, Copy)]
pub struct RenderChoice {
    /// Samples per pixel, 1 or 2.
    pub spp: u32,
    /// The BVH (false) or the plain list of primitives (true).
    pub plain_list: bool,
}

/// Renders a loaded scene at the harness's 4×4 size and tone-maps it with all three tone maps;
/// returns the film.
pub fn render_scene(scene: &Scene, choice: RenderChoice) -> Film {
    let pixels = scene.camera.width as usize * scene.camera.height as usize;
    assert_eq!(pixels, 16);
    let render_options = RenderOptions {
        spp: choice.spp,
        accel: if choice.plain_list {
            AccelKind::None
        } else {
            AccelKind::Auto
        },
        max_depth: RENDER_DEPTH,
        ..RenderOptions::default()
    };
    let out = render(scene, &render_options).expect("a 4×4 film always fits in memory");
    assert_eq!(out.film.pixels.len(), pixels);
    for map in [ToneMap::Linear, ToneMap::Srgb, ToneMap::Reinhard] {
        let bytes = to_rgb8(&out.film, map, scene.exposure);
        assert_eq!(bytes.len(), 3 * pixels);
    }
    out.film
}
