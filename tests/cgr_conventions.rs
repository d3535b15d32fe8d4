//! The CGR variant's conventions (no light fall-off, an ambient term, mirrors that blend, the
//! camera's `exposure` not scaling radiance) are read from the only evidence there is: three
//! students' independent renders of the course's own test scenes
//! (`../shared/coursework/corpus/reference/student_renders/`). Each test scene is rendered at the
//! students' size and compared with every student's render by mean absolute difference on 8-bit
//! values (all channels); the students disagree with each other, so ours must be no further from
//! them than they are from one another: our largest distance to a student at most their largest
//! pairwise distance, and our mean distance at most their mean pairwise distance.

use std::path::{Path, PathBuf};

use raytracer::film::{to_rgb8, ToneMap};
use raytracer::image_io::read_image;
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load_str, LoadOptions};

const STUDENTS: [&str; 3] = [
    "Trenza1ore__std-raytracer__TestSuite__",
    "chxag__CGR-Raytracing-CW2__TestSuite__",
    "HlnnnWnng__High-Performance-Raytracer-Image-Render__TestSuite__",
];

/// The course's test scenes, as the renders name them, and the scene file each comes from (the
/// course ships `scene.json` in binary mode; `phong_scene` is the same file in phong mode).
const SCENES: [(&str, &str, Option<&str>); 5] = [
    ("phong_scene", "scene.json", Some("phong")),
    ("binary_scene", "scene.json", None),
    ("simple_phong", "simple_phong.json", None),
    ("mirror_image", "mirror_image.json", None),
    ("binary_primitives", "binary_primitives.json", None),
];

fn corpus_dir() -> Option<PathBuf> {
    let dir = match std::env::var_os("RAYTRACER_CORPUS") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/coursework/corpus"),
    };
    dir.join("reference/student_renders")
        .is_dir()
        .then_some(dir)
}

/// 8-bit RGB bytes as the `render` command writes them with the default tone map.
fn our_render(corpus: &Path, file: &str, mode: Option<&str>) -> (u32, u32, Vec<u8>) {
    let path = corpus.join(format!("chxag__CGR-Raytracing-CW2__TestSuite__{file}"));
    let mut text = std::fs::read_to_string(&path).expect("test scene readable");
    if let Some(mode) = mode {
        let i = text
            .find("\"binary\"")
            .expect("the scene names its render mode");
        text.replace_range(i..i + "\"binary\"".len(), &format!("\"{mode}\""));
    }
    let scene = load_str(&text, &path, &LoadOptions::default()).expect("test scene loads");
    let out = render(&scene, &RenderOptions::default()).expect("renders");
    let map = ToneMap::Linear;
    let bytes = to_rgb8(&out.film, map, scene.display_exposure(map));
    (out.film.width, out.film.height, bytes)
}

fn student_render(corpus: &Path, student: &str, name: &str) -> Option<(u32, u32, Vec<u8>)> {
    let path = corpus.join(format!("reference/student_renders/{student}{name}.png"));
    if !path.is_file() {
        return None;
    }
    let film = read_image(&path).expect("student render readable");
    let bytes = film
        .pixels
        .iter()
        .flat_map(|p| p.to_array())
        .map(|v| (v * 255.0).round() as u8)
        .collect();
    Some((film.width, film.height, bytes))
}

fn mean_abs_diff(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len());
    let sum: u64 = a.iter().zip(b).map(|(&x, &y)| x.abs_diff(y) as u64).sum();
    sum as f64 / a.len() as f64
}

#[test]
fn cgr_test_scenes_sit_among_the_students_renders() {
    let Some(corpus) = corpus_dir() else {
        eprintln!("corpus not found next to the repository; set RAYTRACER_CORPUS to run this test");
        return;
    };
    let mut failures = Vec::new();
    for (name, file, mode) in SCENES {
        let renders: Vec<(&str, Vec<u8>)> = STUDENTS
            .iter()
            .filter_map(|s| {
                let (w, h, b) = student_render(&corpus, s, name)?;
                assert_eq!((w, h), (1200, 800), "{s}{name}");
                Some((s.split("__").next().unwrap_or(s), b))
            })
            .collect();
        assert!(renders.len() >= 2, "{name}: fewer than two student renders");
        let (w, h, ours) = our_render(&corpus, file, mode);
        assert_eq!((w, h), (1200, 800), "{name}");

        let mut spread = Vec::new();
        for (i, (_, a)) in renders.iter().enumerate() {
            for (_, b) in &renders[i + 1..] {
                spread.push(mean_abs_diff(a, b));
            }
        }
        let ours: Vec<(&str, f64)> = renders
            .iter()
            .map(|(who, b)| (*who, mean_abs_diff(&ours, b)))
            .collect();
        let max = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0, f64::max);
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let (spread_max, spread_mean) = (max(&mut spread.iter().copied()), mean(&spread));
        let ours_d: Vec<f64> = ours.iter().map(|(_, d)| *d).collect();
        let (ours_max, ours_mean) = (max(&mut ours_d.iter().copied()), mean(&ours_d));
        println!(
            "{name:18} ours: {}  | students' spread: max {spread_max:.1}, mean {spread_mean:.1}",
            ours.iter()
                .map(|(w, d)| format!("{w} {d:.1}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        if ours_max > spread_max || ours_mean > spread_mean {
            failures.push(format!(
                "{name}: our distance to the students (max {ours_max:.1}, mean {ours_mean:.1}) is past their own spread (max {spread_max:.1}, mean {spread_mean:.1})"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
