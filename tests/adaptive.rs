//! Adaptive sampling: fewer samples where a pixel has converged, the same bytes on any thread
//! count and in any crop, and usage errors for bad thresholds.

mod common;

use std::process::Command;

use raytracer::film::PixelRect;
use raytracer::render::adaptive::Adaptive;
use raytracer::render::{render, RenderOptions, RenderOutput};
use raytracer::scene::{load, LoadOptions, Scene};

fn penumbra() -> Scene {
    let options = LoadOptions {
        width: Some(48),
        height: Some(36),
        ..LoadOptions::default()
    };
    load(&common::repo().join("scenes/penumbra.json"), &options).unwrap()
}

fn adaptive(spp: u32, threshold: f32) -> RenderOptions {
    RenderOptions {
        spp,
        adaptive: Some(Adaptive {
            threshold,
            time_limit: None,
        }),
        ..RenderOptions::default()
    }
}

fn on_threads(n: usize, scene: &Scene, options: &RenderOptions) -> RenderOutput {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(|| render(scene, options).unwrap())
}

fn bits(out: &RenderOutput) -> Vec<[u32; 3]> {
    out.film
        .pixels
        .iter()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn converged_pixels_stop_and_penumbrae_go_on() {
    let scene = penumbra();
    let out = render(&scene, &adaptive(64, 0.01)).unwrap();
    let counts = out.sample_counts.clone().unwrap();
    let (min, max) = (*counts.iter().min().unwrap(), *counts.iter().max().unwrap());
    // No pixel stops before the early decision (8 samples, where it takes half the threshold);
    // here none stops there, and some stop at the first decision at the full threshold.
    assert_eq!(min, 16, "some pixel converges at the first decision");
    assert_eq!(max, 64, "some penumbra pixel takes every sample");
    let total: u64 = counts.iter().map(|&k| u64::from(k)).sum();
    // Most of this small image is penumbra; still, a tenth of the work or more is skipped.
    assert!(total < 64 * counts.len() as u64 * 9 / 10, "{total} samples");
    // Every count is a round boundary at or past the early decision.
    assert!(counts.iter().all(|k| [8, 16, 32, 64].contains(k)));

    // A tighter threshold takes more samples and lands nearer the uniform render.
    let uniform = render(
        &scene,
        &RenderOptions {
            spp: 64,
            ..RenderOptions::default()
        },
    )
    .unwrap();
    let tight = render(&scene, &adaptive(64, 0.001)).unwrap();
    let tight_total: u64 = tight
        .sample_counts
        .unwrap()
        .iter()
        .map(|&k| u64::from(k))
        .sum();
    assert!(tight_total > total);
    let (loose_mse, tight_mse) = (
        common::mse(&out.film, &uniform.film),
        common::mse(&tight.film, &uniform.film),
    );
    assert!(tight_mse < loose_mse, "{tight_mse} vs {loose_mse}");
    assert!(loose_mse < 1e-3, "{loose_mse}");

    // A loose threshold lets the flattest pixels stop at the early decision.
    let loose = render(&scene, &adaptive(64, 0.08)).unwrap();
    let counts = loose.sample_counts.unwrap();
    assert_eq!(counts.iter().min(), Some(&8));
    assert!(counts.iter().all(|k| [8, 16, 32, 64].contains(k)));
}

#[test]
fn the_same_bits_on_any_thread_count_and_in_any_crop() {
    let scene = penumbra();
    let options = adaptive(32, 0.02);
    let one = on_threads(1, &scene, &options);
    let two = on_threads(2, &scene, &options);
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(one.sample_counts, two.sample_counts);
    let whole_counts = one.sample_counts.clone().unwrap();
    for crop in [
        PixelRect {
            x0: 10,
            y0: 5,
            x1: 30,
            y1: 21,
        },
        PixelRect {
            x0: 0,
            y0: 0,
            x1: 1,
            y1: 36,
        },
        PixelRect {
            x0: 47,
            y0: 35,
            x1: 48,
            y1: 36,
        },
    ] {
        let part = render(
            &scene,
            &RenderOptions {
                crop: Some(crop),
                ..options.clone()
            },
        )
        .unwrap();
        let counts = part.sample_counts.unwrap();
        for y in crop.y0..crop.y1 {
            for x in crop.x0..crop.x1 {
                let (i, j) = (
                    ((y - crop.y0) * crop.width() + (x - crop.x0)) as usize,
                    (y * 48 + x) as usize,
                );
                assert_eq!(counts[i], whole_counts[j], "({x}, {y}) in {crop}");
                assert_eq!(
                    part.film.pixels[i].to_array().map(f32::to_bits),
                    one.film.pixels[j].to_array().map(f32::to_bits),
                    "({x}, {y}) in {crop}"
                );
            }
        }
    }
    // Sample ranges are refused: adaptive decisions need every sample from the first.
    let ranged = RenderOptions {
        samples: Some(0..16),
        ..options
    };
    assert!(render(&scene, &ranged).is_err());
}

#[test]
fn a_time_limit_keeps_the_rounds_each_pixel_finished() {
    let scene = penumbra();
    // A limit far shorter than the render: the first round is always complete, and every pixel
    // holds whole rounds.
    let options = RenderOptions {
        spp: 1 << 16,
        adaptive: Some(Adaptive {
            threshold: 0.0,
            time_limit: Some(std::time::Duration::from_millis(1)),
        }),
        ..RenderOptions::default()
    };
    let out = render(&scene, &options).unwrap();
    let counts = out.sample_counts.unwrap();
    assert!(counts
        .iter()
        .all(|&k| (4..1 << 16).contains(&k) && k.is_power_of_two()));
    assert!(out.film.pixels.iter().all(|p| p.is_finite()));
}

fn raytracer(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn command_line_tiles_sample_map_and_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::copy(
        common::repo().join("scenes/penumbra.json"),
        d.join("s.json"),
    )
    .unwrap();
    let base = ["s.json", "--spp", "32", "--adaptive", "--width", "40", "-q"];
    let with = |out: &str, extra: &[&str]| {
        let mut v = vec![base[0], out];
        v.extend_from_slice(&base[1..]);
        v.extend_from_slice(extra);
        raytracer(d, &v)
    };
    let o = with("whole.png", &["--sample-map", "map.png"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let map = raytracer::image_io::read_image(&d.join("map.png")).unwrap();
    assert_eq!((map.width, map.height), (40, 30));
    for c in 0..2 {
        let o = with(
            &format!("t{c}.exr"),
            &["--tile", &format!("{c},0"), "--tiles", "2,1"],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let o = raytracer(d, &["merge", "merged.png", "t1.exr", "t0.exr"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read(d.join("merged.png")).unwrap(),
        std::fs::read(d.join("whole.png")).unwrap()
    );
    for (extra, flag) in [
        (&["--noise-threshold", "0"][..], "--noise-threshold"),
        (&["--noise-threshold=-1"], "--noise-threshold"),
        (&["--noise-threshold", "NaN"], "--noise-threshold"),
        (&["--sample-range", "0..8"], "--sample-range"),
        (&["--spp", "0"], "--spp"),
        (&["--time-limit", "0"], "--time-limit"),
        (&["--time-limit", "NaN"], "--time-limit"),
    ] {
        let o = with("x.png", extra);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(flag), "{extra:?}: {err}");
    }
    let o = raytracer(d, &["s.json", "x.png", "--noise-threshold", "0.1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!d.join("x.png").exists());
}
