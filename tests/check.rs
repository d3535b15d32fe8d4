//! `raytracer check`: what a render would do, said before it starts: the scene's variant,
//! integrator, image and contents, its warnings and errors with their places, and an estimate of
//! its rays and time, as text or JSON, with a render's exit codes.

mod common;

use std::process::Output;

use common::*;
use jsonc_parser::JsonValue;

fn check(args: &[&dyn AsRef<std::ffi::OsStr>]) -> Output {
    let mut all: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&"check"];
    all.extend_from_slice(args);
    raytracer(&all)
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A small 2021–23 scene with one key no renderer reads (`kdd`, line 4).
const WARNED: &str = r#"{ "nbounces": 2,
  "camera": { "type": "pinhole", "width": 40, "height": 30, "fov": 45,
              "position": [0, 0, 4], "lookat": [0, 0, -1], "up": [0, 1, 0] },
  "scene": { "backgroundcolor": [0.1, 0.1, 0.1], "kdd": 1,
    "lightsources": [ { "type": "pointlight", "position": [2, 2, 2], "intensity": [1, 1, 1] } ],
    "shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1,
                  "material": { "kd": 0.8, "diffusecolor": [0.9, 0.3, 0.2] } },
                { "type": "triangle", "v0": [-2, -1, -1], "v1": [2, -1, -1], "v2": [0, -1, -3],
                  "material": { "kd": 0.5, "diffusecolor": [0.5, 0.5, 0.5] } } ] } }"#;

#[test]
fn a_scene_is_described_without_being_rendered() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("warned.json");
    std::fs::write(&scene, WARNED).unwrap();
    let out = check(&[&scene, &"--spp", &"4"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = stdout(&out);
    for expected in [
        "2021–23 file, Whitted; 40×30, 4 samples a pixel, 2 bounces",
        "2 primitives (1 triangles), 1 lights, 0 textures",
        "warning: ",
        "warned.json:4:",
        "kdd",
        "estimate: ",
        " M rays",
    ] {
        assert!(text.contains(expected), "no {expected:?} in:\n{text}");
    }
    // Nothing but the scene is in the folder: no image was written.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn json_reports_every_scene_and_bad_ones_fail_with_their_place() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, "{ \"camera\": { \"width\": 4 }\n  \"scene\": 3 }").unwrap();
    let good = repo().join("scenes/sphere.json");
    let out = check(&[&good, &bad, &"--json", &"--threads", &"1"]);
    assert_eq!(out.status.code(), Some(1), "a bad scene is exit 1");
    let text = stdout(&out);
    let value = jsonc_parser::parse_to_value(&text, &Default::default())
        .expect("valid JSON")
        .expect("a value");
    let JsonValue::Array(reports) = value else {
        panic!("not an array: {text}");
    };
    assert_eq!(reports.len(), 2);
    let object = |i: usize| match reports.get(i) {
        Some(JsonValue::Object(o)) => o,
        _ => panic!("report {i} is not an object: {text}"),
    };
    let sphere = object(0);
    assert_eq!(sphere.get_string("integrator").unwrap(), "Whitted");
    assert!(sphere.get("error").is_none(), "{text}");
    let estimate = sphere.get_object("estimate").expect("an estimate");
    let number = |name: &str| -> f64 { estimate.get_number(name).unwrap().parse().unwrap() };
    let (low, seconds, high) = (number("low"), number("seconds"), number("high"));
    assert!(0.0 < low && low < seconds && seconds < high, "{text}");
    assert!(number("rays") > 0.0, "{text}");
    let error = object(1)
        .get_string("error")
        .expect("the bad scene's error");
    assert!(error.contains("bad.json:1:27: invalid JSON"), "{error}");
}

#[test]
fn no_estimate_and_usage_errors() {
    let out = check(&[&repo().join("scenes/example.json"), &"--no-estimate"]);
    assert!(out.status.success());
    let text = stdout(&out);
    assert!(
        text.contains("800×800") && !text.contains("estimate"),
        "{text}"
    );
    assert_eq!(
        check(&[]).status.code(),
        Some(2),
        "no scene is a usage error"
    );
    assert_eq!(
        check(&[&"s.json", &"--threads", &"0"]).status.code(),
        Some(2)
    );
}
