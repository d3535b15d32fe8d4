//! The CGR course's four test scenes against the course's own renders of them
//! (`../shared/coursework/official/cgr2024/`, 1200×800, taken losslessly from the coursework
//! specification). `scene.json` is rendered twice, in binary mode as given and in phong mode, as
//! the specification asks.
//!
//! Metric: mean absolute difference of 8-bit RGB values over every pixel and channel, our render
//! written as the `render` command writes it (the scene's default tone map). Bounds: 0.5 of 255
//! for the binary renders (only edge pixels may differ), 4 of 255 for the shaded ones. An
//! orientation check renders each picture mirrored left–right and upside down: each must be at
//! least three times as far from the course's picture as the render itself.

mod common;

use common::*;
use raytracer::film::{to_rgb8, ToneMap};
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load_str, LoadOptions};

/// (picture, scene file, render mode to switch to, bound on the mean absolute difference).
const PICTURES: [(&str, &str, Option<&str>, f64); 5] = [
    ("scene_binary", "scene.json", None, 0.5),
    ("binary_primitives", "binary_primitives.json", None, 0.5),
    ("scene_phong", "scene.json", Some("phong"), 4.0),
    ("simple_phong", "simple_phong.json", None, 4.0),
    ("mirror_image", "mirror_image.json", None, 4.0),
];

struct Rgb8 {
    width: usize,
    height: usize,
    bytes: Vec<u8>,
}

impl Rgb8 {
    /// The image with each pixel taken from `at(x, y)`.
    fn remapped(&self, at: impl Fn(usize, usize) -> (usize, usize)) -> Rgb8 {
        let mut bytes = Vec::with_capacity(self.bytes.len());
        for y in 0..self.height {
            for x in 0..self.width {
                let (sx, sy) = at(x, y);
                let i = 3 * (sy * self.width + sx);
                bytes.extend_from_slice(&self.bytes[i..i + 3]);
            }
        }
        Rgb8 { bytes, ..*self }
    }

    fn mean_abs_diff(&self, other: &Rgb8) -> f64 {
        assert_eq!((self.width, self.height), (other.width, other.height));
        let sum: u64 = self
            .bytes
            .iter()
            .zip(&other.bytes)
            .map(|(&a, &b)| u64::from(a.abs_diff(b)))
            .sum();
        sum as f64 / self.bytes.len() as f64
    }
}

fn ours(dir: &std::path::Path, file: &str, mode: Option<&str>) -> Rgb8 {
    let path = dir.join(file);
    let mut text = std::fs::read_to_string(&path).expect("scene readable");
    if let Some(mode) = mode {
        text = text.replacen("\"binary\"", &format!("\"{mode}\""), 1);
    }
    let scene = load_str(&text, &path, &LoadOptions::default()).expect("scene loads");
    let film = render(&scene, &RenderOptions::default()).unwrap().film;
    let map = ToneMap::chosen(None, scene.tone_map);
    Rgb8 {
        width: film.width as usize,
        height: film.height as usize,
        bytes: to_rgb8(&film, map, scene.display_exposure(map)),
    }
}

fn course(dir: &std::path::Path, picture: &str) -> Rgb8 {
    let film = raytracer::image_io::read_image(&dir.join(format!("{picture}.png")))
        .expect("course picture readable");
    Rgb8 {
        width: film.width as usize,
        height: film.height as usize,
        bytes: film
            .pixels
            .iter()
            .flat_map(|p| p.to_array())
            .map(|v| (v * 255.0).round() as u8)
            .collect(),
    }
}

#[test]
fn cgr_test_scenes_match_the_course_renders() {
    let dir = repo().join("../shared/coursework/official/cgr2024");
    if !dir.is_dir() {
        eprintln!("the course's CGR pictures are not next to the repository; skipped");
        return;
    }
    let mut failures = Vec::new();
    for (picture, file, mode, bound) in PICTURES {
        let reference = course(&dir, picture);
        let render = ours(&dir, file, mode);
        let (w, h) = (render.width, render.height);
        let d = render.mean_abs_diff(&reference);
        let mirrored = render
            .remapped(|x, y| (w - 1 - x, y))
            .mean_abs_diff(&reference);
        let flipped = render
            .remapped(|x, y| (x, h - 1 - y))
            .mean_abs_diff(&reference);
        println!(
            "{picture:18} {d:5.2}/255 (bound {bound}); mirrored {mirrored:5.2}, upside down {flipped:5.2}"
        );
        if d > bound {
            failures.push(format!("{picture}: {d:.2}/255 is past {bound}"));
        }
        if mirrored < 3.0 * d || flipped < 3.0 * d {
            failures.push(format!(
                "{picture}: a mirrored ({mirrored:.2}) or upside-down ({flipped:.2}) render fits nearly as well as ours ({d:.2})"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
