//! A render split into crops and sample ranges, written as EXR tiles and merged, gives the bytes
//! of the render done whole; tiles that do not make one image are refused by name.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::stderr;
use raytracer::film::{to_rgb8, Film, PixelRect, ToneMap};
use raytracer::parts::merge::{assemble, MergeError, Tile};
use raytracer::parts::{self, exr, Part};
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, LoadOptions, Scene};

/// Odd sizes, so tiles of 16 and crops of any width fall unevenly.
const W: u32 = 37;
const H: u32 = 23;
const SPP: u32 = 5;

fn scene(name: &str) -> Scene {
    let options = LoadOptions {
        width: Some(W),
        height: Some(H),
        ..LoadOptions::default()
    };
    load(&common::repo().join("scenes").join(name), &options).unwrap()
}

fn options() -> RenderOptions {
    RenderOptions {
        spp: SPP,
        ..RenderOptions::default()
    }
}

/// The tile of `crop` and `samples`, through the bytes of its EXR file.
fn tile(scene: &Scene, crop: PixelRect, samples: std::ops::Range<u32>) -> Tile {
    let options = RenderOptions {
        crop: Some(crop),
        samples: Some(samples.clone()),
        keep_sums: true,
        ..options()
    };
    let mut out = render(scene, &options).unwrap();
    assert_eq!(out.window, crop);
    let fingerprint = parts::fingerprint(scene, &options).unwrap();
    let part = Part::of_render(scene, &options, fingerprint, &mut out).unwrap();
    assert_eq!((part.full, part.spp), ((W, H), SPP));
    assert!(part.counts.iter().all(|&k| k == samples.len() as u32));
    let name = format!("{crop}@{}..{}.exr", samples.start, samples.end);
    let bytes = exr::encode(&part).unwrap();
    let part = exr::decode(Path::new(&name), &bytes, 1 << 20).unwrap();
    Tile {
        path: PathBuf::from(name),
        part,
    }
}

fn rect(x0: u32, y0: u32, x1: u32, y1: u32) -> PixelRect {
    PixelRect { x0, y0, x1, y1 }
}

/// Crops of the image cut at the given column and row boundaries.
fn grid(xs: &[u32], ys: &[u32]) -> Vec<PixelRect> {
    let mut out = Vec::new();
    for y in ys.windows(2) {
        for x in xs.windows(2) {
            out.push(rect(x[0], y[0], x[1], y[1]));
        }
    }
    out
}

fn same_bits(a: &Film, b: &Film) -> bool {
    (a.width, a.height) == (b.width, b.height)
        && a.pixels
            .iter()
            .zip(&b.pixels)
            .all(|(p, q)| p.to_array().map(f32::to_bits) == q.to_array().map(f32::to_bits))
}

#[test]
fn every_tiling_and_sample_split_merges_to_the_whole_render() {
    for name in ["penumbra.json", "thinlens.json", "glass.json"] {
        let scene = scene(name);
        let whole = render(&scene, &options()).unwrap().film;
        let all = 0..SPP;
        let even = grid(&[0, 16, 32, W], &[0, 16, H]);
        let uneven = grid(&[0, 1, 2, 20, 36, W], &[0, 1, 22, H]);
        let tilings: Vec<(&str, Vec<Tile>)> = vec![
            (
                "even crops",
                even.iter().map(|&c| tile(&scene, c, all.clone())).collect(),
            ),
            (
                "uneven and one-pixel crops",
                uneven
                    .iter()
                    .rev()
                    .map(|&c| tile(&scene, c, all.clone()))
                    .collect(),
            ),
            (
                "sample ranges",
                [0..1, 3..5, 1..3]
                    .into_iter()
                    .map(|r| tile(&scene, PixelRect::full(W, H), r))
                    .collect(),
            ),
            (
                "mixed: samples 0..2 in one tiling, 2..5 in another",
                even.iter()
                    .map(|&c| tile(&scene, c, 0..2))
                    .chain(uneven.iter().map(|&c| tile(&scene, c, 2..5)))
                    .collect(),
            ),
        ];
        for (what, tiles) in tilings {
            let merged = assemble(&tiles).unwrap();
            assert!(same_bits(&merged, &whole), "{name}, {what}");
            assert_eq!(
                to_rgb8(&merged, ToneMap::Srgb, 1.0),
                to_rgb8(&whole, ToneMap::Srgb, 1.0)
            );
        }
    }
}

#[test]
fn a_crop_is_exactly_those_pixels_of_the_whole_render() {
    let scene = scene("thinlens.json");
    let whole = render(&scene, &options()).unwrap().film;
    let crop = rect(5, 3, 22, 20);
    let out = render(
        &scene,
        &RenderOptions {
            crop: Some(crop),
            samples: Some(1..4),
            ..options()
        },
    )
    .unwrap();
    let part = render(
        &scene,
        &RenderOptions {
            crop: Some(crop),
            ..options()
        },
    )
    .unwrap()
    .film;
    assert_eq!((part.width, part.height), (17, 17));
    for y in crop.y0..crop.y1 {
        for x in crop.x0..crop.x1 {
            let p = part.get(x - crop.x0, y - crop.y0);
            assert_eq!(p.to_array(), whole.get(x, y).to_array(), "({x}, {y})");
        }
    }
    // The mean of samples 1..4 alone is a different estimate of the same pixels.
    assert_eq!(out.film.pixels.len(), part.pixels.len());
    assert_ne!(out.film.pixels, part.pixels);
}

#[test]
fn gaps_overlaps_and_foreign_tiles_are_refused_by_name() {
    let scene = scene("penumbra.json");
    let left = tile(&scene, rect(0, 0, 20, H), 0..SPP);
    let right = tile(&scene, rect(20, 0, W, H), 0..SPP);
    let right_some = tile(&scene, rect(20, 0, W, H), 0..3);
    let overlapping = tile(&scene, rect(19, 5, 21, 6), 2..4);

    let e = assemble(&[left.clone(), right_some.clone()]).unwrap_err();
    assert!(
        matches!(
            e,
            MergeError::Gap {
                x: 20,
                y: 0,
                missing: (3, 5)
            }
        ),
        "{e}"
    );

    let e = assemble(&[left.clone(), right.clone(), overlapping.clone()]).unwrap_err();
    let text = e.to_string();
    assert!(matches!(e, MergeError::Overlap { .. }), "{text}");
    assert!(text.contains(&left.path.display().to_string()), "{text}");
    assert!(
        text.contains(&overlapping.path.display().to_string()),
        "{text}"
    );

    let other = tile(&self::scene("glass.json"), rect(20, 0, W, H), 0..SPP);
    let e = assemble(&[left.clone(), other]).unwrap_err();
    assert!(matches!(e, MergeError::Mismatch { .. }), "{e}");

    let mut other_spp = right.clone();
    other_spp.part.spp = 6;
    let e = assemble(&[left.clone(), other_spp]).unwrap_err();
    assert!(matches!(e, MergeError::Size { .. }), "{e}");

    // A different seed is a different render.
    let seeded = RenderOptions {
        seed: 1,
        ..options()
    };
    assert_ne!(
        parts::fingerprint(&scene, &seeded).unwrap(),
        parts::fingerprint(&scene, &options()).unwrap()
    );
    assert!(matches!(assemble(&[]), Err(MergeError::NoTiles)));
}

#[test]
fn render_refuses_crops_and_ranges_that_do_not_fit() {
    let scene = scene("penumbra.json");
    for (crop, samples) in [
        (Some(rect(0, 0, W + 1, H)), None),
        (Some(rect(3, 3, 3, 9)), None),
        (None, Some(0..SPP + 1)),
        (None, Some(2..2)),
    ] {
        let options = RenderOptions {
            crop,
            samples,
            ..options()
        };
        assert!(render(&scene, &options).is_err(), "{options:?}");
    }
}

// The command line, end to end.

fn raytracer(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run raytracer")
}

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "{:?}: {}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
}

/// A temporary folder with a copy of the bundled scene `name` as `scene.json`.
fn folder_with(name: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        common::repo().join("scenes").join(name),
        dir.path().join("scene.json"),
    )
    .unwrap();
    dir
}

const SIZE: [&str; 4] = ["--width", "37", "--height", "23"];

fn render_args<'a>(out: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let textures = concat!(env!("CARGO_MANIFEST_DIR"), "/textures");
    let mut v = vec![
        "scene.json",
        out,
        "--spp",
        "5",
        "-q",
        "--asset-dir",
        textures,
    ];
    v.extend_from_slice(&SIZE);
    v.extend_from_slice(extra);
    v
}

#[test]
fn merge_on_the_command_line_gives_the_bytes_of_the_whole_render() {
    let dir = folder_with("penumbra.json");
    let d = dir.path();
    for out in ["whole.png", "whole.exr", "whole.ppm"] {
        ok(&raytracer(d, &render_args(out, &["--tonemap", "srgb"])));
    }
    let tiles = [
        ("t0.exr", "0,0,37,9", "0..5"),
        ("t1.exr", "0,9,1,23", "0..5"),
        ("t2.exr", "1,9,37,23", "0..2"),
        ("t3.exr", "1,9,37,23", "2..5"),
    ];
    for (out, crop, range) in tiles {
        ok(&raytracer(
            d,
            &render_args(out, &["--crop", crop, "--sample-range", range]),
        ));
    }
    for out in ["merged.png", "merged.exr", "merged.ppm"] {
        let o = raytracer(
            d,
            &[
                "merge",
                out,
                "t3.exr",
                "t1.exr",
                "t0.exr",
                "t2.exr",
                "--tonemap",
                "srgb",
            ],
        );
        ok(&o);
        let whole = out.replace("merged", "whole");
        assert_eq!(
            std::fs::read(d.join(out)).unwrap(),
            std::fs::read(d.join(&whole)).unwrap(),
            "{out} vs {whole}"
        );
    }
}

/// `"use_tone_mapping": true` (Kierandon's files) makes Reinhard the default tone map of the
/// render and of a merge of its tiles, without a warning; `--tonemap` still decides.
#[test]
fn a_files_tone_map_is_the_default_of_render_and_merge() {
    let dir = folder_with("cornell.json");
    let d = dir.path();
    let text = std::fs::read_to_string(d.join("scene.json")).unwrap();
    let asks = text.replacen('{', "{\"use_tone_mapping\": true, ", 1);
    std::fs::write(d.join("asks.json"), asks).unwrap();
    let args = |scene: &'static str, out: &'static str, extra: &[&'static str]| {
        let mut v = vec![scene, out, "--spp", "2", "--width", "24", "--height", "16"];
        v.extend_from_slice(extra);
        v
    };
    let read = |name: &str| std::fs::read(d.join(name)).unwrap();
    let o = raytracer(d, &args("asks.json", "asks.png", &[]));
    ok(&o);
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    for (out, map) in [("reinhard.png", "reinhard"), ("linear.png", "linear")] {
        ok(&raytracer(d, &args("scene.json", out, &["--tonemap", map])));
    }
    assert_eq!(read("asks.png"), read("reinhard.png"));
    assert_ne!(read("asks.png"), read("linear.png"));
    ok(&raytracer(
        d,
        &args("asks.json", "flag.png", &["--tonemap", "linear"]),
    ));
    assert_eq!(read("flag.png"), read("linear.png"));

    ok(&raytracer(
        d,
        &args("asks.json", "t0.exr", &["--sample-range", "0..1"]),
    ));
    ok(&raytracer(
        d,
        &args("asks.json", "t1.exr", &["--sample-range", "1..2"]),
    ));
    ok(&raytracer(d, &["merge", "merged.png", "t0.exr", "t1.exr"]));
    assert_eq!(read("merged.png"), read("reinhard.png"));
    ok(&raytracer(
        d,
        &[
            "merge",
            "merged_linear.png",
            "t0.exr",
            "t1.exr",
            "--tonemap",
            "linear",
        ],
    ));
    assert_eq!(read("merged_linear.png"), read("linear.png"));
}

#[test]
fn grid_tiles_named_by_cell_merge_to_the_whole_render() {
    let dir = folder_with("thinlens.json");
    let d = dir.path();
    ok(&raytracer(d, &render_args("whole.png", &[])));
    let mut names = Vec::new();
    for row in 0..2 {
        for col in 0..3 {
            let name = format!("cell-{col}-{row}.exr");
            let cell = format!("{col},{row}");
            ok(&raytracer(
                d,
                &render_args(&name, &["--tile", &cell, "--tiles", "3,2"]),
            ));
            names.push(name);
        }
    }
    let mut args = vec!["merge", "merged.png"];
    args.extend(names.iter().map(String::as_str));
    ok(&raytracer(d, &args));
    assert_eq!(
        std::fs::read(d.join("merged.png")).unwrap(),
        std::fs::read(d.join("whole.png")).unwrap()
    );
    for bad in [
        &["--tile", "3,0", "--tiles", "3,2"][..],
        &["--tile", "0,0", "--tiles", "38,1"],
        &["--tile", "0,0"],
        &["--tile", "0,0", "--tiles", "2,2", "--crop", "0,0,4,4"],
        &["--tile", "0", "--tiles", "2,2"],
    ] {
        let o = raytracer(d, &render_args("x.exr", bad));
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("--tile"), "{bad:?}: {}", stderr(&o));
        assert!(!d.join("x.exr").exists());
    }
}

#[test]
fn bad_tiles_and_flags_are_clean_errors_and_write_nothing() {
    let dir = folder_with("penumbra.json");
    let d = dir.path();
    ok(&raytracer(
        d,
        &render_args("a.exr", &["--crop", "0,0,20,23"]),
    ));
    ok(&raytracer(
        d,
        &render_args("b.exr", &["--crop", "20,0,37,23"]),
    ));
    ok(&raytracer(d, &render_args("plain.exr", &[])));
    let tile = std::fs::read(d.join("a.exr")).unwrap();
    std::fs::write(d.join("cut.exr"), &tile[..tile.len() / 2]).unwrap();
    std::fs::write(d.join("out.png"), b"keep me").unwrap();

    // Usage errors: exit 2, the message names the flag.
    for (args, needle) in [
        (render_args("x.exr", &["--crop", "0,0,38,23"]), "--crop"),
        (render_args("x.exr", &["--crop", "5,0,5,23"]), "--crop"),
        (
            render_args("x.exr", &["--sample-range", "3..3"]),
            "--sample-range",
        ),
        (
            render_args("x.exr", &["--sample-range", "4..2"]),
            "--sample-range",
        ),
        (
            render_args("x.exr", &["--sample-range", "0..6"]),
            "--sample-range",
        ),
        (render_args("x.png", &["--crop", "0,0,4,4"]), ".exr"),
    ] {
        let o = raytracer(d, &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert!(!d.join("x.exr").exists() && !d.join("x.png").exists());
    }

    // Bad tiles: exit 1, the message names the file, the existing output is kept.
    let text = std::fs::read_to_string(d.join("scene.json")).unwrap();
    std::fs::write(d.join("other.json"), text.replace("160", "150")).unwrap();
    let mut other = vec![
        "other.json",
        "o.exr",
        "--spp",
        "5",
        "-q",
        "--crop",
        "20,0,37,23",
    ];
    other.extend_from_slice(&SIZE);
    ok(&raytracer(d, &other));
    ok(&raytracer(
        d,
        &render_args("seeded.exr", &["--crop", "20,0,37,23", "--seed", "1"]),
    ));
    for (tiles, needle) in [
        (vec!["a.exr"], "gap"),
        (vec!["a.exr", "b.exr", "a.exr"], "overlap"),
        (vec!["a.exr", "o.exr"], "different renders"),
        (vec!["a.exr", "seeded.exr"], "different renders"),
        (
            vec!["a.exr", "plain.exr"],
            "plain.exr: not a raytracer tile",
        ),
        (vec!["a.exr", "cut.exr"], "cut.exr"),
        (vec!["a.exr", "scene.json"], "scene.json"),
        (vec!["a.exr", "missing.exr"], "missing.exr"),
    ] {
        let mut args = vec!["merge", "out.png"];
        args.extend_from_slice(&tiles);
        let o = raytracer(d, &args);
        assert_eq!(o.status.code(), Some(1), "{tiles:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{tiles:?}: {}", stderr(&o));
        assert_eq!(std::fs::read(d.join("out.png")).unwrap(), b"keep me");
    }
    // The output may not be one of the tiles.
    let o = raytracer(d, &["merge", "a.exr", "a.exr", "b.exr"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read(d.join("a.exr")).unwrap(), tile);
    let leftovers: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}
