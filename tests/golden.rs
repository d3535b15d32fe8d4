//! Golden-image regression: every bundled scene is rendered small (96 pixels wide, 4 samples per
//! pixel) and compared with its reference in `tests/golden/` by MSE and mean FLIP
//! (`raytracer::metric`, the code behind `raytracer compare`). See `tests/golden/README.md` for how
//! the references were made and how to update them on purpose.
//!
//! The tolerances are stated below, and the test proves for each scene that they are tight: the
//! reference shifted by one pixel, rendered with its textures turned upside down, or made 2%
//! brighter or darker must each fail them.

mod common;

use common::{bundled_scenes, repo, written_rgb8};
use raytracer::film::{Film, ToneMap};
use raytracer::integrator::TraceOptions;
use raytracer::math::Vec3;
use raytracer::metric::{flip_map, mean_flip, mse, Region};
use raytracer::render::{render, RenderOptions};
use raytracer::scene::{load, LoadOptions, Scene};
use raytracer::texture::Texture;

/// Largest MSE (linear RGB in [0, 1]) a render may have against its reference.
const MAX_MSE: f64 = 1e-6;
/// Largest mean FLIP a render may have against its reference.
const MAX_FLIP: f64 = 1e-3;
const WIDTH: u32 = 96;
const SPP: u32 = 4;

fn load_small(path: &std::path::Path) -> Scene {
    let options = LoadOptions {
        width: Some(WIDTH),
        ..Default::default()
    };
    load(path, &options).unwrap_or_else(|e| panic!("{e}"))
}

/// The render as its 8-bit PNG would hold it, back in [0, 1].
fn displayed(scene: &Scene) -> Film {
    displayed_with(scene, TraceOptions::default()).0
}

/// [`displayed`] with `trace` options, and the rays the render traced.
fn displayed_with(scene: &Scene, trace: TraceOptions) -> (Film, u64) {
    let out = render(
        scene,
        &RenderOptions {
            spp: SPP,
            trace,
            ..Default::default()
        },
    )
    .unwrap();
    (quantised(&out.film, scene, 1.0), out.counts.total())
}

/// The film as the `render` command writes it (the scene's default tone map and exposure), with
/// its radiance scaled by `brightness`.
fn quantised(film: &Film, scene: &Scene, brightness: f32) -> Film {
    let bytes = written_rgb8(scene, film, brightness);
    let pixels = bytes
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32) / 255.0)
        .collect();
    Film::from_pixels(film.width, film.height, pixels)
}

fn fails(reference: &Film, test: &Film) -> bool {
    let r = Region::full(reference.width, reference.height);
    mse(reference, test, r) > MAX_MSE || mean_flip(reference, test, r) > MAX_FLIP
}

#[test]
fn renders_match_their_golden_images() {
    let update = std::env::var("RAYTRACER_UPDATE_GOLDEN").is_ok_and(|v| v == "1");
    let out_dir = repo().join("target/golden-failures");
    let mut failures = Vec::new();
    for path in bundled_scenes() {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let golden_path = repo().join("tests/golden").join(format!("{name}.png"));
        let scene = load_small(&path);
        let ours = displayed(&scene);
        if update {
            raytracer::image_io::write_image(&golden_path, &ours, ToneMap::Linear, 1.0).unwrap();
            println!("updated {}", golden_path.display());
            continue;
        }
        let golden = raytracer::image_io::read_image(&golden_path)
            .unwrap_or_else(|e| panic!("{e} (create it with RAYTRACER_UPDATE_GOLDEN=1)"));
        assert_eq!(
            (golden.width, golden.height),
            (ours.width, ours.height),
            "{name}"
        );
        let region = Region::full(golden.width, golden.height);
        let (e, f) = (
            mse(&golden, &ours, region),
            mean_flip(&golden, &ours, region),
        );
        println!("{name}: MSE {e:.2e}, mean FLIP {f:.2e}");
        if e > MAX_MSE || f > MAX_FLIP {
            std::fs::create_dir_all(&out_dir).unwrap();
            let render_path = out_dir.join(format!("{name}-render.png"));
            let diff_path = out_dir.join(format!("{name}-diff.png"));
            raytracer::image_io::write_image(&render_path, &ours, ToneMap::Linear, 1.0).unwrap();
            let heat =
                raytracer::metric::heat_map(golden.width, golden.height, &flip_map(&golden, &ours));
            raytracer::image_io::write_image(&diff_path, &heat, ToneMap::Linear, 1.0).unwrap();
            failures.push(format!(
                "{name}: MSE {e:.3e} (max {MAX_MSE:e}), FLIP {f:.3e} (max {MAX_FLIP:e}); render {}, FLIP map {}",
                render_path.display(),
                diff_path.display()
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "golden images differ:\n{}",
        failures.join("\n")
    );
}

/// The tolerances catch what they are meant to: for every scene, a one-pixel shift, textures
/// turned upside down and a 2% brightness change each fail them (a change that leaves every
/// byte of the image as it was — e.g. brightening pure red — is not a change).
#[test]
fn tolerances_catch_shifts_flips_and_brightness_changes() {
    for path in bundled_scenes() {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let scene = load_small(&path);
        let raw = render(
            &scene,
            &RenderOptions {
                spp: SPP,
                ..Default::default()
            },
        )
        .unwrap()
        .film;
        let reference = quantised(&raw, &scene, 1.0);
        let (w, h) = (reference.width, reference.height);

        let mut shifted = reference.clone();
        for y in 0..h {
            for x in (1..w).rev() {
                shifted.set(x, y, reference.get(x - 1, y));
            }
        }
        assert!(
            fails(&reference, &shifted),
            "{name}: a one-pixel shift passes"
        );

        for factor in [1.02f32, 0.98] {
            let scaled = quantised(&raw, &scene, factor);
            if scaled.pixels != reference.pixels {
                assert!(
                    fails(&reference, &scaled),
                    "{name}: a brightness factor of {factor} passes"
                );
            }
        }

        if !scene.textures.is_empty() {
            let mut flipped = scene.clone();
            for t in &mut flipped.textures {
                let (tw, th) = (t.width as usize, t.height as usize);
                let texels = t.texels();
                let rows = (0..th).rev();
                let upside_down = rows.flat_map(|y| texels[y * tw..(y + 1) * tw].to_vec());
                *t = Texture::from_texels(t.width, t.height, upside_down.collect())
                    .with_offset(t.offset);
            }
            let wrong = displayed(&flipped);
            assert!(
                fails(&reference, &wrong),
                "{name}: upside-down textures pass"
            );
        }
    }
}

/// The same scene gives the same pixels on one thread and on all threads, and twice in a row.
#[test]
fn golden_scenes_render_identically_on_any_thread_count() {
    for path in bundled_scenes().into_iter().take(6) {
        let scene = load_small(&path);
        let on = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| {
                    render(
                        &scene,
                        &RenderOptions {
                            spp: SPP,
                            ..Default::default()
                        },
                    )
                    .unwrap()
                    .film
                })
        };
        let (one, all, again) = (on(1), on(0), on(0));
        assert!(
            one.pixels == all.pixels && all.pixels == again.pixels,
            "{}",
            path.display()
        );
    }
}

/// Largest MSE (displayed 8-bit values in [0, 1]) the command line's default work skipping may
/// add to a scene's full-work render (`docs/adaptive.md`).
const MAX_SKIP_MSE: f64 = 1e-5;

/// The command line traces reflection and refraction rays only down to a weight of 1/255
/// (`--adc-bailout`, on unless `--no-skip`): on every bundled scene that keeps the picture within
/// [`MAX_SKIP_MSE`] of tracing every ray. A cut-off that skips every secondary ray must break that
/// bound somewhere, so the comparison is not blind.
#[test]
fn the_default_cutoff_keeps_every_bundled_scene_within_its_bound() {
    let with_cutoff = |scene: &Scene, cutoff: Option<f32>| {
        displayed_with(
            scene,
            TraceOptions {
                cutoff,
                ..Default::default()
            },
        )
    };
    let (mut rays_full, mut rays_skip) = (0u64, 0u64);
    let mut worst_without_secondary = 0.0f64;
    for path in bundled_scenes() {
        let scene = load_small(&path);
        let (full, n_full) = with_cutoff(&scene, None);
        let (skip, n_skip) = with_cutoff(&scene, Some(raytracer::integrator::DEFAULT_CUTOFF));
        let (none, _) = with_cutoff(&scene, Some(1.0));
        let region = Region::full(full.width, full.height);
        let e = mse(&full, &skip, region);
        println!(
            "{}: MSE {e:.2e}, rays {n_skip} of {n_full}",
            path.file_name().unwrap().to_string_lossy()
        );
        assert!(e <= MAX_SKIP_MSE, "{}: MSE {e}", path.display());
        rays_full += n_full;
        rays_skip += n_skip;
        worst_without_secondary = worst_without_secondary.max(mse(&full, &none, region));
    }
    println!("all bundled scenes: {rays_skip} of {rays_full} rays with the cut-off");
    assert!(rays_skip < rays_full);
    assert!(worst_without_secondary > MAX_SKIP_MSE);
}
