//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use raytracer::film::{to_rgb8, Film, ToneMap};
use raytracer::math::Vec3;
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, load_str, LoadOptions, Scene};

/// Runs the `raytracer` binary with `args`.
pub fn raytracer(args: &[&dyn AsRef<std::ffi::OsStr>]) -> std::process::Output {
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_raytracer"));
    for a in args {
        cmd.arg(a);
    }
    cmd.output().expect("run raytracer")
}

/// What a run of the binary printed on standard error.
pub fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Writes `json` as `scene.json` in a fresh temporary folder (kept alive by the returned guard).
pub fn write_scene(json: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("scene.json");
    std::fs::write(&path, json).expect("write scene");
    (dir, path)
}

pub fn load_json(json: &str) -> Scene {
    let (_dir, path) = write_scene(json);
    load(&path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

pub fn render_json(json: &str, options: &RenderOptions) -> Film {
    render(&load_json(json), options).unwrap().film
}

pub fn render_default(json: &str) -> Film {
    render_json(json, &RenderOptions::default())
}

/// Root of the repository.
pub fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The bundled scenes (`scenes/*.json`), in name order.
pub fn bundled_scenes() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(repo().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    v.sort();
    v
}

/// Mean squared error over all channels.
pub fn mse(a: &Film, b: &Film) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(x, y)| {
            let d = *x - *y;
            (d * d).element_sum() as f64
        })
        .sum();
    sum / (3 * a.pixels.len()) as f64
}

pub fn max_abs_diff(a: &Film, b: &Film) -> f32 {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0, f32::max)
}

pub fn is_black(c: Vec3) -> bool {
    c == Vec3::ZERO
}

/// 8-bit RGB bytes of `film` as the `render` command writes it for `scene` (the scene's default
/// tone map and display exposure), its radiance scaled by `brightness`.
pub fn written_rgb8(scene: &Scene, film: &Film, brightness: f32) -> Vec<u8> {
    let map = ToneMap::chosen(None, scene.tone_map);
    to_rgb8(film, map, scene.display_exposure(map) * brightness)
}

/// An 8-bit picture: width, height and RGB bytes, row by row from the top.
pub type Rgb8 = (u32, u32, Vec<u8>);

/// A CGR test scene rendered as the `render` command writes it, with its `"binary"` render mode
/// switched to `mode` when one is given.
pub fn cgr_render(path: &Path, mode: Option<&str>) -> Rgb8 {
    let mut text = std::fs::read_to_string(path).expect("test scene readable");
    if let Some(mode) = mode {
        let i = text
            .find("\"binary\"")
            .expect("the scene names its render mode");
        text.replace_range(i..i + "\"binary\"".len(), &format!("\"{mode}\""));
    }
    let scene = load_str(&text, path, &LoadOptions::default()).expect("test scene loads");
    let film = render(&scene, &RenderOptions::default())
        .expect("renders")
        .film;
    (film.width, film.height, written_rgb8(&scene, &film, 1.0))
}

/// An 8-bit image file's bytes, or `None` when there is no such file.
pub fn read_rgb8(path: &Path) -> Option<Rgb8> {
    if !path.is_file() {
        return None;
    }
    let film = raytracer::image_io::read_image(path).expect("image readable");
    let bytes = film
        .pixels
        .iter()
        .flat_map(|p| p.to_array())
        .map(|v| (v * 255.0).round() as u8)
        .collect();
    Some((film.width, film.height, bytes))
}

/// Mean absolute difference of two images' 8-bit values, over every pixel and channel.
pub fn mean_abs_diff(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len());
    let sum: u64 = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| u64::from(x.abs_diff(y)))
        .sum();
    sum as f64 / a.len() as f64
}
