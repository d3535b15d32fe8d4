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

use common::{cgr_render, mean_abs_diff, read_rgb8, repo, Rgb8};

/// (picture, scene file, render mode to switch to, bound on the mean absolute difference).
const PICTURES: [(&str, &str, Option<&str>, f64); 5] = [
    ("scene_binary", "scene.json", None, 0.5),
    ("binary_primitives", "binary_primitives.json", None, 0.5),
    ("scene_phong", "scene.json", Some("phong"), 4.0),
    ("simple_phong", "simple_phong.json", None, 4.0),
    ("mirror_image", "mirror_image.json", None, 4.0),
];

/// The picture with each pixel taken from `at(x, y)`.
fn remapped((width, height, bytes): &Rgb8, at: impl Fn(u32, u32) -> (u32, u32)) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len());
    for y in 0..*height {
        for x in 0..*width {
            let (sx, sy) = at(x, y);
            let i = 3 * (sy * width + sx) as usize;
            out.extend_from_slice(&bytes[i..i + 3]);
        }
    }
    out
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
        let (rw, rh, reference) =
            read_rgb8(&dir.join(format!("{picture}.png"))).expect("the course's picture is there");
        let render = cgr_render(&dir.join(file), mode);
        let (w, h) = (render.0, render.1);
        assert_eq!((w, h), (rw, rh), "{picture}");
        let d = mean_abs_diff(&render.2, &reference);
        let mirrored = mean_abs_diff(&remapped(&render, |x, y| (w - 1 - x, y)), &reference);
        let flipped = mean_abs_diff(&remapped(&render, |x, y| (x, h - 1 - y)), &reference);
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
