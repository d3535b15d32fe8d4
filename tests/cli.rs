//! The command line: exit codes, messages that name the file and place, and output files that are
//! written whole or not at all.

mod common;

use std::path::Path;
use std::process::Command;

use common::*;

const SMALL: &str = r#"{ "nbounces": 1,
  "camera": { "type": "pinhole", "width": 24, "height": 16, "fov": 40,
              "position": [0, -4, 1], "lookat": [0, 1, -0.1], "up": [0, 0, 1] },
  "scene": { "backgroundcolor": [0.1, 0.1, 0.1],
    "lightsources": [ { "type": "arealight", "v0": [-1, -1, 3], "v1": [1, -1, 3], "v2": [1, 1, 3], "v3": [-1, 1, 3],
                        "samples": 2, "method": "random", "is": [40, 40, 40], "id": [40, 40, 40] } ],
    "shapes": [ { "type": "sphere", "center": [0, 0, 0.5], "radius": 0.5,
                  "material": { "kd": 0.8, "ks": 0.2, "specularexponent": 8, "diffusecolor": [0.9, 0.3, 0.2] } } ] } }"#;

#[test]
fn renders_the_official_example_to_png_and_ppm() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("example.png");
    let scene = repo().join("scenes/example.json");
    let out = raytracer(&[&scene, &png, &"--width", &"200", &"--quiet"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stderr.is_empty(), "--quiet printed: {}", stderr(&out));
    let film = raytracer::image_io::read_image(&png).unwrap();
    assert_eq!((film.width, film.height), (200, 200));

    let ppm = dir.path().join("example.ppm");
    let out = raytracer(&[&scene, &ppm, &"--width", &"40", &"--height", &"30"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let bytes = std::fs::read(&ppm).unwrap();
    assert!(bytes.starts_with(b"P6\n40 30\n255\n"));
    assert_eq!(bytes.len(), "P6\n40 30\n255\n".len() + 40 * 30 * 3);
    // The summary line names resolution, samples, time, rays and throughput.
    let summary = stderr(&out);
    assert!(
        summary.contains("40×30") && summary.contains("1 spp") && summary.contains("Mrays/s"),
        "{summary}"
    );
}

#[test]
fn same_bytes_on_one_and_two_threads_and_the_seed_matters() {
    let (dir, scene) = write_scene(SMALL);
    let run = |name: &str, threads: &str, seed: &str| {
        let out_path = dir.path().join(name);
        let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .args([scene.as_os_str(), out_path.as_os_str()])
            .args(["--spp", "4", "--seed", seed, "-q"])
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(out_path).unwrap()
    };
    let one = run("a.png", "1", "0");
    let two = run("b.png", "2", "0");
    let again = run("c.png", "2", "0");
    assert_eq!(one, two);
    assert_eq!(two, again);
    assert_ne!(one, run("d.png", "2", "5"));
}

#[test]
fn unknown_output_extension_is_a_usage_error() {
    let (dir, scene) = write_scene(SMALL);
    let out_path = dir.path().join("out.bmp");
    let o = raytracer(&[&scene, &out_path]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains(".ppm, .png or .exr"), "{}", stderr(&o));
    assert!(!out_path.exists());
    // Bad flags are usage errors too.
    let o = raytracer(&[&scene, &dir.path().join("x.png"), &"--spp", &"0"]);
    assert_eq!(o.status.code(), Some(2));
    let o = raytracer(&[&scene, &dir.path().join("x.png"), &"--tonemap", &"gamma"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn output_equal_to_the_input_is_refused_and_the_scene_kept() {
    let (_dir, scene) = write_scene(SMALL);
    let before = std::fs::read(&scene).unwrap();
    let ppm_named_scene = scene.with_extension("ppm");
    std::fs::copy(&scene, &ppm_named_scene).unwrap();
    let o = raytracer(&[&ppm_named_scene, &ppm_named_scene]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read(&ppm_named_scene).unwrap(), before);
}

/// Broken scenes: exit 1, a message with the file and the place, and no output file (an existing
/// one is left as it was).
#[test]
fn bad_scenes_fail_with_file_line_column_and_path() {
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "syntax",
            "{ \"camera\": { \"width\": 10,, } }",
            &["scene.json:1:", "invalid JSON"],
        ),
        ("empty", "", &["scene.json", "empty"]),
        (
            "missing width",
            r#"{ "camera": { "height": 10, "fov": 30 } }"#,
            &["scene.json:1:", "camera", "'width'"],
        ),
        (
            "wrong type",
            "{ \"camera\": {\n \"width\": \"ten\", \"height\": 10, \"fov\": 30 } }",
            &["scene.json:2:11", "camera.width", "expected a number"],
        ),
        (
            "nan",
            r#"{ "camera": { "width": 10, "height": 10, "fov": NaN } }"#,
            &["camera.fov", "finite"],
        ),
        (
            "negative radius",
            r#"{ "camera": { "width": 10, "height": 10, "fov": 30 },
            "scene": { "shapes": [ { "type": "sphere", "center": [0,0,-3], "radius": -1 } ] } }"#,
            &["scene.shapes[0].radius", "> 0"],
        ),
        (
            "huge image",
            r#"{ "camera": { "width": 1000000, "height": 1000000, "fov": 30 } }"#,
            &["camera.width", "limit", "--max-pixels"],
        ),
        (
            "huge nbounces",
            r#"{ "nbounces": 100000, "camera": { "width": 10, "height": 10, "fov": 30 } }"#,
            &["nbounces", "limit"],
        ),
        (
            "negative nbounces",
            r#"{ "nbounces": -1, "camera": { "width": 10, "height": 10, "fov": 30 } }"#,
            &["nbounces"],
        ),
        (
            "face index",
            r#"{ "camera": { "width": 10, "height": 10, "fov": 30 },
            "scene": { "shapes": [ { "type": "trimesh", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0,1,7]] } ] } }"#,
            &["scene.shapes[0].faces[0]", "out of range"],
        ),
        (
            "missing texture",
            r#"{ "camera": { "width": 10, "height": 10, "fov": 30 },
            "scene": { "shapes": [ { "type": "sphere", "center": [0,0,-3], "radius": 1,
              "material": { "tPath": "../textures/nothing.png" } } ] } }"#,
            &["material.tPath", "nothing.png", "not found", "tried"],
        ),
        (
            "missing mesh",
            r#"{ "camera": { "width": 10, "height": 10, "fov": 30 },
            "scene": { "shapes": [ { "type": "mesh", "mPath": "bunny.ply" } ] } }"#,
            &["mPath", "bunny.ply", "not found"],
        ),
    ];
    for (name, json, needles) in cases {
        let (dir, scene) = write_scene(json);
        let out_path = dir.path().join("out.png");
        std::fs::write(&out_path, b"keep me").unwrap();
        let o = raytracer(&[&scene, &out_path]);
        let msg = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {msg}");
        assert!(!msg.contains("panicked"), "{name}: {msg}");
        for n in *needles {
            assert!(msg.contains(n), "{name}: message lacks '{n}': {msg}");
        }
        assert_eq!(std::fs::read(&out_path).unwrap(), b"keep me", "{name}");
        let others: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(others.len(), 2, "{name}: stray files left behind");
    }
}

#[test]
fn missing_scene_and_unwritable_output_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let o = raytracer(&[&dir.path().join("nope.json"), &dir.path().join("o.png")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("nope.json"));

    let (dir, scene) = write_scene(SMALL);
    let out_path = dir.path().join("no/such/folder/out.png");
    let o = raytracer(&[&scene, &out_path]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("folder"), "{}", stderr(&o));
    assert!(!Path::new(&out_path).exists());
}

#[test]
fn unknown_types_are_skipped_with_a_warning_naming_the_nearest() {
    let json = SMALL.replace("\"type\": \"sphere\"", "\"type\": \"sphereee\"");
    let (dir, scene) = write_scene(&json);
    let o = raytracer(&[&scene, &dir.path().join("o.png")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let msg = stderr(&o);
    assert!(
        msg.contains("warning") && msg.contains("scene.shapes[0].type") && msg.contains("'sphere'"),
        "{msg}"
    );
}

#[test]
fn exr_output_is_linear() {
    let (dir, scene) = write_scene(SMALL);
    let exr = dir.path().join("o.exr");
    let o = raytracer(&[&scene, &exr, &"-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let film = raytracer::image_io::read_image(&exr).unwrap();
    // The background is 0.1 exactly, not tone-mapped or quantised.
    assert_eq!(film.get(0, 0), raytracer::math::Vec3::splat(0.1));
}

/// The atomic write goes through a private temporary file; the image must still get the
/// permissions of any new file in that folder.
#[cfg(unix)]
#[test]
fn output_gets_ordinary_file_permissions() {
    use std::os::unix::fs::PermissionsExt;
    let (dir, scene) = write_scene(SMALL);
    let out_path = dir.path().join("o.png");
    let o = raytracer(&[&scene, &out_path, &"-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let plain = dir.path().join("plain.txt");
    std::fs::write(&plain, b"x").unwrap();
    let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode(&out_path), mode(&plain));
}

/// Ctrl-C during a render stops it without writing: exit status 130, the earlier image at the
/// output path intact, no temporary files left.
#[cfg(unix)]
#[test]
fn interrupt_leaves_the_output_alone() {
    let dir = tempfile::tempdir().unwrap();
    let out_path = dir.path().join("demo.png");
    std::fs::write(&out_path, b"an earlier render").unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_raytracer"))
        .arg(repo().join("scenes/demo.json"))
        .arg(&out_path)
        .args(["--spp", "64", "--quiet"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(700));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(stderr(&o).contains("no image written"));
    assert_eq!(std::fs::read(&out_path).unwrap(), b"an earlier render");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

/// `raytracer compare`: metrics on stdout, exit 0 within thresholds, 3 when worse, 1 for images
/// that cannot be compared, 2 for usage errors; `--diff` writes a heat map.
#[test]
fn compare_reports_metrics_and_judges_thresholds() {
    let (dir, scene) = write_scene(SMALL);
    let a = dir.path().join("a.png");
    let b = dir.path().join("b.png");
    assert!(raytracer(&[&scene, &a, &"-q"]).status.success());
    assert!(raytracer(&[&scene, &b, &"-q", &"--exposure", &"1.5"])
        .status
        .success());
    let compare = |args: &[&dyn AsRef<std::ffi::OsStr>]| {
        let mut all: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&"compare"];
        all.extend_from_slice(args);
        raytracer(&all)
    };
    let same = compare(&[&a, &a]);
    assert_eq!(same.status.code(), Some(0));
    let out = String::from_utf8_lossy(&same.stdout).into_owned();
    assert!(
        out.contains("mse 0.000000e0") && out.contains("flip 0.000000"),
        "{out}"
    );

    let diff = dir.path().join("diff.png");
    let o = compare(&[&a, &b, &"--max-mse", &"1e-9", &"--diff", &diff]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("--max-mse"));
    assert!(raytracer::image_io::read_image(&diff).is_ok());
    assert_eq!(
        compare(&[&a, &b, &"--max-mse", &"1", &"--max-flip", &"1"])
            .status
            .code(),
        Some(0)
    );
    assert_eq!(
        compare(&[&a, &b, &"--region", &"0,0,4,4"]).status.code(),
        Some(0)
    );

    let other = dir.path().join("other.png");
    assert!(raytracer(&[&scene, &other, &"-q", &"--width", &"12"])
        .status
        .success());
    let o = compare(&[&a, &other]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("differ in size"));
    let o = compare(&[&a, &dir.path().join("missing.png")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("missing.png"));
    assert_eq!(
        compare(&[&a, &b, &"--region", &"0,0,400,4"]).status.code(),
        Some(1)
    );
    assert_eq!(
        compare(&[&a, &b, &"--region", &"nonsense"]).status.code(),
        Some(2)
    );
}

#[test]
fn output_inside_a_file_is_an_error() {
    let (dir, scene) = write_scene(SMALL);
    let out_path = dir.path().join("scene.json/out.png");
    let o = raytracer(&[&scene, &out_path]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("out.png"));
}

/// `SMALL` with `extra` members added at its top level.
fn small_with(extra: &str) -> String {
    SMALL.replacen('{', &format!("{{ {extra}"), 1)
}

#[test]
fn strict_turns_every_warning_into_an_error_and_writes_nothing() {
    let text = small_with(r#""pixelsampel": 4,"#).replace(r#""kd": 0.8"#, r#""kdd": 0.8"#);
    let (dir, scene) = write_scene(&text);
    let out = dir.path().join("out.png");
    let o = raytracer(&[&scene, &out, &"--strict", &"--quiet"]);
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(
        msg.contains(": pixelsampel: unknown key 'pixelsampel' (did you mean 'pixelsample'?)"),
        "{msg}"
    );
    assert!(
        msg.contains("scene.shapes[0].material.kdd: unknown key 'kdd' (did you mean 'kd'?)"),
        "{msg}"
    );
    assert!(msg.contains("2 warnings"), "{msg}");
    assert_eq!(msg.matches("error: ").count(), 3, "{msg}");
    // No image, no temporary file: the folder holds the scene alone.
    assert!(!out.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);

    // Without --strict the same scene renders, with the warnings.
    let o = raytracer(&[&scene, &out]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o).matches("warning: ").count(), 2, "{}", stderr(&o));
    std::fs::remove_file(&out).unwrap();

    // study --strict refuses it before writing anything too.
    let study_dir = dir.path().join("study");
    let o = raytracer(&[
        &"study",
        &scene,
        &"--quick",
        &"--strict",
        &"--out",
        &study_dir,
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!study_dir.exists());

    // A scene without warnings renders under --strict.
    let (dir, clean) = write_scene(SMALL);
    let out = dir.path().join("out.png");
    let o = raytracer(&[&clean, &out, &"--strict"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.is_file());
}

#[test]
fn the_scenes_samples_per_pixel_are_used_unless_spp_is_given() {
    let (dir, with_samples) = write_scene(&small_with(r#""pixelsample": 4,"#));
    let plain = dir.path().join("plain.json");
    std::fs::write(&plain, SMALL).unwrap();
    let run = |scene: &Path, name: &str, args: &[&str], threads: &str| {
        let out = dir.path().join(name);
        let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .arg(scene)
            .arg(&out)
            .args(args)
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        (std::fs::read(out).unwrap(), stderr(&o))
    };
    let (scene_spp, summary) = run(&with_samples, "a.png", &[], "2");
    assert!(summary.contains(", 4 spp,"), "{summary}");
    // The same image as asking for 4 on the command line, on any number of threads.
    assert_eq!(scene_spp, run(&plain, "b.png", &["--spp", "4"], "2").0);
    assert_eq!(scene_spp, run(&with_samples, "c.png", &[], "1").0);
    // The command line wins.
    let (one, summary) = run(&with_samples, "d.png", &["--spp", "1"], "2");
    assert!(summary.contains(", 1 spp,"), "{summary}");
    assert_eq!(one, run(&plain, "e.png", &[], "2").0);
    assert_ne!(one, scene_spp);

    // A scene-wide light sample count replaces each area light's own (2 random samples here).
    let light_samples = dir.path().join("light.json");
    std::fs::write(&light_samples, small_with(r#""lightsample": 7,"#)).unwrap();
    let seven = dir.path().join("seven.json");
    std::fs::write(&seven, SMALL.replace(r#""samples": 2"#, r#""samples": 7"#)).unwrap();
    let (scene_light, _) = run(&light_samples, "f.png", &[], "2");
    assert_eq!(scene_light, run(&seven, "g.png", &[], "2").0);
    assert_ne!(scene_light, run(&plain, "h.png", &[], "2").0);
}

/// `raytracer compare a b | head -1`: a reader that goes away is not a panic, and the exit status
/// still judges the images.
#[test]
fn a_closed_standard_output_is_not_a_panic() {
    let (dir, scene) = write_scene(SMALL);
    let a = dir.path().join("a.png");
    assert!(raytracer(&[&scene, &a, &"-q"]).status.success());
    for args in [
        vec![
            "compare".to_string(),
            a.display().to_string(),
            a.display().to_string(),
        ],
        vec!["bench".to_string(), "--help".to_string()],
    ] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .args(&args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        if args[0] == "compare" {
            assert_eq!(out.status.code(), Some(0), "{err}");
        }
    }
}

/// The default render skips reflection and refraction rays of weight below 1/255; `--no-skip`
/// and `--adc-bailout 0` both trace every ray (the same bytes) and trace more rays than the
/// default on a scene of glass; `--no-skip` with a cut-off is a usage error.
#[test]
fn no_skip_traces_every_ray_the_default_skips_faint_ones() {
    let dir = tempfile::tempdir().unwrap();
    let glass = common::repo().join("scenes/glass.json");
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .args([glass.as_os_str(), out.as_os_str()])
            .args(["--width", "48", "--threads", "1"])
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let line = stderr(&o);
        let rays: u64 = line
            .split(" rays")
            .next()
            .and_then(|s| s.rsplit(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("no ray count in: {line}"));
        (std::fs::read(out).unwrap(), rays)
    };
    let (default, default_rays) = run("default.exr", &[]);
    let (full, full_rays) = run("full.exr", &["--no-skip"]);
    let (zero, zero_rays) = run("zero.exr", &["--adc-bailout", "0"]);
    assert_eq!(full, zero);
    assert_eq!(full_rays, zero_rays);
    assert!(default_rays < full_rays, "{default_rays} vs {full_rays}");
    assert_ne!(default, full);
    let o = raytracer(&[
        &glass,
        &dir.path().join("x.png"),
        &"--no-skip",
        &"--adc-bailout",
        &"0.1",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--no-skip"), "{}", stderr(&o));
}
