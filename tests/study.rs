//! Samplers and the study command: the Sobol sampler and the light overrides keep renders
//! deterministic, the work-skipping switches change nothing unless asked for, and a quick study
//! writes the expected CSV rows and a PNG plot. No timing is asserted.

mod common;

use std::process::Command;

use common::repo;
use raytracer::integrator::{TraceOptions, DEFAULT_CUTOFF};
use raytracer::metric::{mean_flip, Region};
use raytracer::render::{render, RenderOptions};
use raytracer::sampling::Method;
use raytracer::scene::{load, LoadOptions, Scene};

fn penumbra(width: u32) -> Scene {
    let options = LoadOptions {
        width: Some(width),
        ..Default::default()
    };
    load(&repo().join("scenes/penumbra.json"), &options).unwrap()
}

fn with_trace(trace: TraceOptions) -> RenderOptions {
    RenderOptions {
        spp: 2,
        trace,
        ..Default::default()
    }
}

#[test]
fn sobol_renders_are_identical_on_any_thread_count() {
    let scene = penumbra(48);
    let options = RenderOptions {
        pixel_method: Method::Sobol,
        ..with_trace(TraceOptions {
            light_method: Some(Method::Sobol),
            light_samples: Some(16),
            ..Default::default()
        })
    };
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&scene, &options).unwrap().film)
    };
    let (one, two) = (on(1), on(2));
    assert!(one.pixels == two.pixels);
    // And it differs from the scene's own jittered sampling, yet agrees with it closely.
    let own = render(&scene, &with_trace(TraceOptions::default()))
        .unwrap()
        .film;
    assert!(own.pixels != one.pixels);
    let flip = mean_flip(&own, &one, Region::full(48, 36));
    assert!(flip < 0.05, "{flip}");
}

#[test]
fn overrides_that_restate_the_scene_change_no_pixel() {
    // penumbra.json's light is jittered with 4×4 = 16 samples.
    let scene = penumbra(48);
    let own = render(&scene, &with_trace(TraceOptions::default()))
        .unwrap()
        .film;
    let restated = render(
        &scene,
        &with_trace(TraceOptions {
            light_method: Some(Method::Jittered),
            light_samples: Some(16),
            ..Default::default()
        }),
    )
    .unwrap()
    .film;
    assert!(own.pixels == restated.pixels);
}

#[test]
fn work_skipping_stays_close_to_the_plain_render() {
    let scene = penumbra(64);
    let plain = render(&scene, &with_trace(TraceOptions::default())).unwrap();
    let adaptive = render(
        &scene,
        &with_trace(TraceOptions {
            adaptive_lights: true,
            ..Default::default()
        }),
    )
    .unwrap();
    // Fewer shadow rays, nearly the same image (the occluders here are larger than the gaps
    // between the probes' rays).
    assert!(adaptive.counts.shadow < plain.counts.shadow);
    let r = Region::full(64, 48);
    let flip = mean_flip(&plain.film, &adaptive.film, r);
    assert!(flip < 0.01, "{flip}");
    // No reflective or refractive surface: the cut-off changes nothing.
    let cut = render(
        &scene,
        &with_trace(TraceOptions {
            cutoff: Some(DEFAULT_CUTOFF),
            ..Default::default()
        }),
    )
    .unwrap();
    assert!(cut.film.pixels == plain.film.pixels);
}

#[test]
fn the_cutoff_prunes_weak_branches_of_glass() {
    let scene = load(
        &repo().join("scenes/glass.json"),
        &LoadOptions {
            width: Some(64),
            ..Default::default()
        },
    )
    .unwrap();
    let plain = render(&scene, &with_trace(TraceOptions::default())).unwrap();
    let cut = render(
        &scene,
        &with_trace(TraceOptions {
            cutoff: Some(DEFAULT_CUTOFF),
            ..Default::default()
        }),
    )
    .unwrap();
    assert!(cut.counts.secondary <= plain.counts.secondary);
    let r = Region::full(plain.film.width, plain.film.height);
    let flip = mean_flip(&plain.film, &cut.film, r);
    assert!(flip < 0.01, "{flip}");
}

#[test]
fn quick_study_writes_the_csv_rows_and_a_png_plot() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg("study")
        .arg(repo().join("scenes/penumbra.json"))
        .arg("--quick")
        .arg("--out")
        .arg(dir.path())
        .args(["--region", "8,8,24,16", "--width", "40"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("[13/13]"), "no progress: {stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    for m in ["random", "jittered", "sobol"] {
        assert!(stdout.lines().any(|l| l.starts_with(m)), "{stdout}");
    }
    assert!(stdout.contains("time to reach MSE"), "{stdout}");

    let csv = std::fs::read_to_string(dir.path().join("study.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("sampler,samples,seconds,mse,mse_region,flip")
    );
    let rows: Vec<(String, u32)> = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 6, "{l}");
            for v in &f[2..] {
                let x: f64 = v.parse().unwrap();
                assert!(x.is_finite() && x >= 0.0, "{l}");
            }
            (f[0].to_string(), f[1].parse().unwrap())
        })
        .collect();
    let expected: Vec<(String, u32)> = [
        ("random", [1, 2, 4, 8, 16].as_slice()),
        ("jittered", [1, 4, 16].as_slice()),
        ("sobol", [1, 2, 4, 8, 16].as_slice()),
    ]
    .iter()
    .flat_map(|(m, ns)| ns.iter().map(move |&n| (m.to_string(), n)))
    .collect();
    assert_eq!(rows, expected);

    let plot = image::open(dir.path().join("study.png")).unwrap();
    assert_eq!((plot.width(), plot.height()), (1200, 520));
    let reference = raytracer::image_io::read_image(&dir.path().join("reference.exr")).unwrap();
    assert_eq!((reference.width, reference.height), (40, 30));
}

/// `study --adaptive`: uniform runs at 1 … 64 pixel samples and one adaptive run per threshold,
/// each adaptive run between the first decision (16) and the cap on average, looser thresholds
/// taking fewer samples, every ratio inside the uniform runs' range positive; a plot and the
/// reference. Its flags are checked as usage errors.
#[test]
fn an_adaptive_study_compares_at_equal_error() {
    let dir = tempfile::tempdir().unwrap();
    let study = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .arg("study")
            .arg(repo().join("scenes/thinlens.json"))
            .args(["--quick", "--out"])
            .arg(dir.path())
            .args(extra)
            .output()
            .unwrap()
    };
    let out = study(&[
        "--adaptive",
        "--thresholds",
        "0.04,0.01",
        "--variance-samples",
        "32",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("[10/10]"), "no progress: {stderr}");
    let csv = std::fs::read_to_string(dir.path().join("study.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some(
            "render,threshold,samples,mean_samples,seconds,mse,mse_region,flip,uniform_seconds,\
             ratio,uniform_samples,samples_ratio,known_noise_ratio"
        )
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    let uniform: Vec<u32> = rows
        .iter()
        .filter(|r| r[0] == "uniform")
        .map(|r| r[2].parse().unwrap())
        .collect();
    assert_eq!(uniform, [1, 2, 4, 8, 16, 32, 64]);
    let adaptive: Vec<&Vec<String>> = rows.iter().filter(|r| r[0] == "adaptive").collect();
    assert_eq!(adaptive.len(), 2);
    // The best allocations: the last rows, shares of uniform's samples. The thin-lens scene's
    // noise sits in its defocused half, so the share is well below 1; at the uniform runs' own
    // convergence (16 to 64 spp here) it is another share, below 1 as well.
    let [one_over_n, at_rate] = &rows[rows.len() - 2..] else {
        unreachable!()
    };
    assert_eq!(one_over_n[0], "best_allocation", "{one_over_n:?}");
    assert_eq!(at_rate[0], "best_allocation_at_rate", "{at_rate:?}");
    for last in [one_over_n, at_rate] {
        let bound: f64 = last[9].parse().unwrap();
        assert!(bound > 0.0 && bound < 0.6, "{last:?}");
        assert_eq!(last[11], last[9], "{last:?}");
    }
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("best allocation: "), "{stdout}");
    assert!(
        stdout.contains("measured by 8 renders of 32 spp"),
        "{stdout}"
    );
    let mean = |r: &Vec<String>| r[3].parse::<f64>().unwrap();
    for r in &adaptive {
        assert_eq!(r.len(), 13, "{r:?}");
        // The rule with each pixel's noise known: an allocation like any other, so not below
        // the best one at the same rate (up to the bound's correction for its estimate's bias).
        let known: f64 = r[12].parse().unwrap();
        let best: f64 = at_rate[9].parse().unwrap();
        assert!(known >= 0.9 * best && known <= 1.5, "{r:?}");
        assert!((16.0..=64.0).contains(&mean(r)), "{r:?}");
        let mse: f64 = r[6].parse().unwrap();
        assert!(mse.is_finite() && mse > 0.0, "{r:?}");
        if !r[9].is_empty() {
            assert!(r[9].parse::<f64>().unwrap() > 0.0, "{r:?}");
        }
        // The samples ratio: the adaptive mean over the uniform samples at the same error, which
        // lie inside the uniform runs' range whenever a time ratio was given.
        assert_eq!(r[10].is_empty(), r[9].is_empty(), "{r:?}");
        if !r[10].is_empty() {
            let uniform: f64 = r[10].parse().unwrap();
            let ratio: f64 = r[11].parse().unwrap();
            assert!((1.0..=64.0).contains(&uniform), "{r:?}");
            assert!((ratio - mean(r) / uniform).abs() < 1e-5, "{r:?}");
        }
    }
    assert!(mean(adaptive[0]) <= mean(adaptive[1]), "{adaptive:?}");
    let plot = image::open(dir.path().join("study.png")).unwrap();
    assert_eq!((plot.width(), plot.height()), (900, 560));
    assert!(dir.path().join("reference.exr").exists());
    // Where the best allocation puts its samples: the image's size, and not one colour, since
    // the thin-lens scene's noise sits in its defocused half.
    let allocation = image::open(dir.path().join("allocation.png"))
        .unwrap()
        .to_rgb8();
    assert_eq!((allocation.width(), allocation.height()), (48, 36));
    let first = allocation.get_pixel(0, 0);
    assert!(allocation.pixels().any(|p| p != first));

    // Without --variance-samples the noise is measured at the cap, --quick's 64 samples.
    let out = study(&["--adaptive", "--thresholds", "0.04"]);
    assert!(out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("measured by 8 renders of 64 spp"),
        "{stdout}"
    );

    for bad in [
        &["--thresholds", "0.01"][..],
        &["--adaptive", "--thresholds", "0"],
        &["--adaptive", "--skip-work"],
        &["--variance-samples", "32"],
        &["--adaptive", "--variance-samples", "0"],
    ] {
        let out = study(bad);
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
    }
}
