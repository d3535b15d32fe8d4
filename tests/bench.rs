//! `raytracer bench`: a smoke run prints every row of Table 1 and writes the same rows as CSV;
//! timings are not checked.

mod common;

use std::process::Command;

use common::repo;
use raytracer::accel::AUTO_MIN_PRIMITIVES;

const ACCELS: [&str; 4] = ["auto", "none", "median", "sah"];

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
    // `none`, and `auto` on tiny scenes, build nothing.
    for r in &rows {
        let tiny = r[col("prims")].parse::<usize>().unwrap() < AUTO_MIN_PRIMITIVES;
        let accel = r[col("accel")];
        assert_eq!(
            r[col("built")] == "list",
            accel == "none" || (accel == "auto" && tiny),
            "{r:?}"
        );
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
    for set in ["primary", "shadow", "incoherent", "render"] {
        assert!(
            stdout
                .lines()
                .any(|l| l.contains("G2S8") && l.contains(set)),
            "{set} missing:\n{stdout}"
        );
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
    assert_eq!(run(&["bench", "--help"]).status.code(), Some(0));
    // The render command line still wants SCENE OUT.
    assert_eq!(run(&["scenes/example.json"]).status.code(), Some(2));
}
