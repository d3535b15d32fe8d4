//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use raytracer::film::Film;
use raytracer::math::Vec3;
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, LoadOptions, Scene};

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
