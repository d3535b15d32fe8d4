//! Image decoders (textures and reference images): the first byte chooses the file's extension
//! (`.png`, `.jpg`, `.ppm`, `.exr`, or none), the rest is the file. It is read with
//! `image_io::read_image`, then, when it has an extension, loaded as the texture of a small
//! scene with `scene::load` and rendered at 4×4 pixels.
//!
//! The decoders pick the format from the contents, so any extension can reach any decoder; the
//! extension matters when the contents match no format (then it names the decoder) and for the
//! loader, which ignores a texture whose name has no extension.
//!
//! Checked: no panic or abort; an error names the file; an image that loads has
//! `width * height == pixels.len()` and finite, non-negative texels, in [0, 1] for the integer
//! formats (PNG, JPEG, PPM: value/255 or value/65535). EXR values are floats read as stored
//! (negative, infinite and NaN values included, as `write_image` writes them), so only their
//! count is checked. The scene loads if and only if the image did (an image with no pixels is
//! the loader's error), its error starts with the scene's path and names the image, and the
//! scene's texture is the image.
#![no_main]

mod common;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use raytracer::film::Film;
use raytracer::scene::load;

/// Extensions chosen by the first byte, and the file name each one gives.
const KINDS: &[(&str, &str)] = &[
    ("png", "img.png"),
    ("jpg", "img.jpg"),
    ("ppm", "img.ppm"),
    ("exr", "img.exr"),
    ("", "img"),
];

fuzz_target!(|data: &[u8]| {
    let Some((&first, bytes)) = data.split_first() else {
        return;
    };
    let (ext, name) = KINDS[first as usize % KINDS.len()];
    let path = common::write_input(name, bytes);
    let shown = path.display().to_string();
    let image = common::read_image(&path);
    match &image {
        Err(e) => {
            let text = e.to_string();
            assert!(text.contains(&shown), "error without the file: {text}");
        }
        Ok(film) => check_film(film, is_exr(bytes, &path)),
    }
    if ext.is_empty() {
        // The loader ignores a texture name without an extension (with a warning).
        return;
    }

    let scene_file = texture_scene(ext);
    let loaded = load(scene_file, &common::load_options());
    match (&image, loaded) {
        (Ok(film), Ok(scene)) => {
            assert!(film.width > 0 && film.height > 0, "an empty texture loaded");
            assert_eq!(scene.textures.len(), 1);
            let tex = &scene.textures[0];
            assert_eq!((tex.width, tex.height), (film.width, film.height));
            assert_eq!(tex.texels.len(), film.pixels.len());
            common::render_scene(
                &scene,
                common::RenderChoice {
                    spp: 1,
                    plain_list: false,
                },
            );
        }
        (Ok(film), Err(e)) => {
            common::check_scene_error(scene_file, &e);
            assert!(
                film.width == 0 || film.height == 0,
                "read_image read the image but the scene did not load: {e}"
            );
        }
        (Err(_), Err(e)) => {
            common::check_scene_error(scene_file, &e);
            let text = e.to_string();
            assert!(text.contains(&shown), "error without the image: {text}");
        }
        (Err(e), Ok(_)) => panic!("the scene loaded a texture that read_image refused: {e}"),
    }
});

/// Whether the EXR decoder reads this file: the contents look like EXR, or look like no format
/// and the name ends in `.exr` (the order `read_image` tries them in).
fn is_exr(bytes: &[u8], path: &Path) -> bool {
    match image::guess_format(bytes) {
        Ok(format) => format == image::ImageFormat::OpenExr,
        Err(_) => image::ImageFormat::from_path(path).ok() == Some(image::ImageFormat::OpenExr),
    }
}

fn check_film(film: &Film, float_format: bool) {
    assert_eq!(
        film.pixels.len(),
        film.width as usize * film.height as usize,
        "{}x{} image with {} pixels",
        film.width,
        film.height,
        film.pixels.len()
    );
    if float_format {
        return;
    }
    for p in &film.pixels {
        for c in p.to_array() {
            assert!(
                c.is_finite() && (0.0..=1.0).contains(&c),
                "texel value {c} outside [0, 1]"
            );
        }
    }
}

/// A scene in the scratch folder (`tex-<ext>.json`) whose one quad fills the view and is
/// textured with `img.<ext>` beside it; written once per extension.
fn texture_scene(ext: &str) -> &'static Path {
    static PATHS: OnceLock<Vec<(String, PathBuf)>> = OnceLock::new();
    let paths = PATHS.get_or_init(|| {
        // One render thread: fuzzing processes run side by side.
        std::env::set_var("RAYON_NUM_THREADS", "1");
        KINDS
            .iter()
            .filter(|(e, _)| !e.is_empty())
            .map(|&(e, name)| {
                let text = format!(
                    r#"{{
  "nbounces": 1,
  "camera": {{ "type": "pinhole", "width": 4, "height": 4, "fov": 60 }},
  "scene": {{
    "backgroundcolor": [0.1, 0.1, 0.1],
    "lightsources": [ {{ "type": "pointlight", "position": [0, 0, 0], "intensity": [1, 1, 1] }} ],
    "shapes": [ {{ "type": "quad",
      "v0": [-2, 2, -2], "v1": [2, 2, -2], "v2": [2, -2, -2], "v3": [-2, -2, -2],
      "material": {{ "kd": 0.9, "tPath": "{name}" }} }} ]
  }}
}}
"#
                );
                let path = common::write_input(&format!("tex-{e}.json"), text.as_bytes());
                (e.to_string(), path)
            })
            .collect()
    });
    paths
        .iter()
        .find(|(e, _)| e == ext)
        .map(|(_, p)| p.as_path())
        .expect("a scene for every extension")
}
