//! `raytracer bench`: a smoke run prints every row of Table 1 and writes the same rows as CSV;
//! timings are not checked.

mod common;

use std::process::Command;

use raytracer::accel::Isa;

use common::repo;

const ACCELS: [&str; 7] = ["auto", "none", "flat", "median", "sah", "sah4", "sah8"];

#[test]
fn quick_table_has_every_scene_light_and_accelerator() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("table.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .args(["bench", "--quick", "--threads", "2", "--csv"])
        .arg(&csv)
        .current_dir(repo())
        .output()
        .expect("run raytracer bench");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let scenes = [
        "example", "demo", "grid-1x4", "grid-2x4", "grid-2x8", "grid-4x8",
    ];
    let csv = std::fs::read_to_string(&csv).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), scenes.len() * 2 * ACCELS.len(), "{csv}");
    for scene in scenes {
        for light in ["point", "area"] {
            for accel in ACCELS {
                let row = rows
                    .iter()
                    .find(|r| {
                        r[col("scene")] == scene
                            && r[col("light")] == light
                            && r[col("accel")] == accel
                    })
                    .unwrap_or_else(|| panic!("no row {scene} {light} {accel}:\n{csv}"));
                // Rendered (not skipped) with a ray count, or skipped with an estimate.
                assert!(
                    !row[col("rays")].is_empty() || row[col("note")].starts_with("skipped"),
                    "{row:?}"
                );
                // The same row in the printed table.
                assert!(
                    stdout.lines().any(|l| {
                        let f: Vec<&str> = l.split_whitespace().collect();
                        f.first() == Some(&scene) && f.contains(&light) && f.contains(&accel)
                    }),
                    "{scene} {light} {accel} missing from:\n{stdout}"
                );
            }
        }
    }
    // `none` builds nothing, `flat` one leaf, and `auto` the four-wide tree, on every scene.
    for r in &rows {
        let accel = r[col("accel")];
        assert_eq!(r[col("built")] == "list", accel == "none", "{r:?}");
        assert_eq!(r[col("built")] == "flat", accel == "flat", "{r:?}");
        if accel == "auto" {
            assert_eq!(r[col("built")], "sah4", "{r:?}");
        }
    }
}

#[test]
fn quick_ray_throughput_reports_every_set() {
    let out = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .args(["bench", "--rays", "--quick"])
        .output()
        .expect("run raytracer bench --rays");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    // Every tree traces the same rays: the same number of hits in each set, whatever the
    // instructions its queries run with.
    for set in ["primary", "shadow", "incoherent", "render"] {
        let rows: Vec<Vec<&str>> = stdout
            .lines()
            .map(|l| l.split_whitespace().collect::<Vec<_>>())
            .filter(|f| f.first() == Some(&"G2S8") && f.contains(&set))
            .collect();
        let row = |accel: &str, simd: &str| {
            rows.iter()
                .find(|f| f.get(2) == Some(&accel) && f.get(3) == Some(&simd))
                .unwrap_or_else(|| panic!("{set} with {accel} ({simd}) missing:\n{stdout}"))
        };
        // grid tris accel simd build_ms median_build_ms bytes_per_tri set rays hits … (the
        // render row has no hits)
        let counts = if set == "render" { 8..9 } else { 8..10 };
        let sah = row("sah", "baseline");
        let mut trees = vec![row("sah4", "baseline"), row("sah8", Isa::detect().name())];
        if Isa::detect() != Isa::BASELINE {
            trees.push(row("sah8", "baseline"));
        }
        assert_eq!(rows.len(), 1 + trees.len(), "{set}:\n{stdout}");
        for wide in trees {
            assert_eq!(
                sah[counts.clone()],
                wide[counts.clone()],
                "{set}: ray or hit counts differ with {wide:?}"
            );
        }
    }
}

/// `--export` writes the grid's triangles and ray sets whole: as many triangles as the grid has,
/// one primary ray per pixel, and one shadow and one incoherent ray per primary hit (the hits the
/// CSV reports), every number finite and every direction a unit vector.
#[test]
fn exported_rays_are_the_benchmarks_rays() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("rays.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .args(["bench", "--rays", "--quick", "--threads", "1", "--export"])
        .arg(dir.path())
        .arg("--csv")
        .arg(&csv)
        .output()
        .expect("run raytracer bench --rays --export");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |what: &str, width: usize| -> Vec<Vec<f32>> {
        let bytes = std::fs::read(dir.path().join(format!("grid_G2_S8.{what}.f32"))).unwrap();
        assert_eq!(bytes.len() % (4 * width), 0, "{what}");
        let numbers: Vec<f32> = bytes
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        assert!(numbers.iter().all(|x| x.is_finite()), "{what}");
        numbers.chunks(width).map(<[f32]>::to_vec).collect()
    };
    // G²·2·S² sphere triangles and the ground's two, G = 2 and S = 8.
    assert_eq!(read("tris", 9).len(), 4 * 2 * 64 + 2);
    let csv = std::fs::read_to_string(&csv).unwrap();
    let hits_column = csv
        .lines()
        .next()
        .and_then(|header| header.split(',').position(|h| h == "hits"))
        .expect("the CSV has a hits column");
    let primary_hits: usize = csv
        .lines()
        .find(|l| l.contains(",primary,"))
        .and_then(|l| l.split(',').nth(hits_column))
        .and_then(|h| h.parse().ok())
        .expect("the CSV's primary row gives its hits");
    for (what, width, rays) in [
        ("primary", 6, 640 * 480),
        ("shadow", 7, primary_hits),
        ("incoherent", 6, primary_hits),
    ] {
        let rows = read(what, width);
        assert_eq!(rows.len(), rays, "{what}");
        for r in &rows {
            let len = (r[3] * r[3] + r[4] * r[4] + r[5] * r[5]).sqrt();
            assert!((len - 1.0).abs() < 1e-4, "{what}: direction {r:?}");
        }
        if width == 7 {
            assert!(
                rows.iter().all(|r| r[6] > 0.0),
                "shadow rays end at the light"
            );
        }
    }
}

#[test]
fn bench_usage_errors_exit_2_and_render_usage_is_unchanged() {
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .args(args)
            .output()
            .unwrap()
    };
    assert_eq!(run(&["bench", "--runs", "0"]).status.code(), Some(2));
    assert_eq!(run(&["bench", "--huge"]).status.code(), Some(2));
    assert_eq!(run(&["bench", "--bogus"]).status.code(), Some(2));
    assert_eq!(run(&["bench", "--kinds"]).status.code(), Some(2));
    assert_eq!(
        run(&["bench", "--kinds", "scenes/glass.json", "--rays"])
            .status
            .code(),
        Some(2)
    );
    assert_eq!(run(&["bench", "--help"]).status.code(), Some(0));
    // The render command line still wants SCENE OUT.
    assert_eq!(run(&["scenes/example.json"]).status.code(), Some(2));
}

/// `bench --kinds`: a row per kind of ray, with the counts the scene implies: a camera ray per
/// pixel, reflection and refraction rays only where hits spawn them, shadow rays towards the
/// lights, and hits never above rays. A scene that cannot be read is an error naming it.
#[test]
fn kinds_report_every_kind_of_ray_of_a_scene() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("kinds.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .args([
            "bench",
            "--kinds",
            "scenes/glass.json",
            "--runs",
            "1",
            "--threads",
            "1",
            "--csv",
        ])
        .arg(&csv)
        .current_dir(repo())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(&csv).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let kinds: Vec<&str> = rows.iter().map(|r| r[col("kind")]).collect();
    assert_eq!(
        kinds,
        ["camera", "reflection", "refraction", "shadow"],
        "{csv}"
    );
    let n = |r: &Vec<&str>, c: &str| r[col(c)].parse::<u64>().unwrap();
    // glass.json is 320×240 with glass and mirror spheres and a light.
    assert_eq!(n(&rows[0], "rays"), 320 * 240);
    for r in &rows {
        assert!(n(r, "hits") <= n(r, "rays"), "{r:?}");
        assert!(n(r, "rays") > 0, "{r:?}");
        assert!(r[col("ns_per_ray")].parse::<f64>().unwrap() > 0.0, "{r:?}");
    }
    // A reflection ray at every glass or mirror hit, a refraction ray at most at each of those.
    assert!(n(&rows[1], "rays") <= n(&rows[0], "hits"));
    assert!(n(&rows[2], "rays") <= n(&rows[1], "rays"));
    let missing = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .args(["bench", "--kinds", "no-such-scene.json"])
        .current_dir(repo())
        .output()
        .unwrap();
    assert_ne!(missing.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("no-such-scene.json"));
}
