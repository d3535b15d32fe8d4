//! The hand-made suite of broken inputs in `tests/bad_input/`: each is run through the command
//! line. Every one must exit with status 1 (not a panic), print a message that names the file, the
//! place (line:column or JSON path) and the rule broken, and leave the output path as it was: an
//! existing image there is neither replaced nor joined by stray files.

mod common;

use std::process::Command;

use common::repo;

/// (file, fragments its message must contain). The file name itself is always required too.
const CASES: &[(&str, &[&str])] = &[
    ("syntax-unclosed.json", &[":1:13:", "invalid JSON"]),
    (
        "syntax-trailing-garbage.json",
        &[":2:1:", "more than one JSON value"],
    ),
    ("syntax-missing-comma.json", &[":1:16:", "comma"]),
    ("syntax-single-quotes.json", &[":1:3:", "Single-quoted"]),
    ("empty.json", &[":1:1:", "empty"]),
    ("binary.json", &["not UTF-8"]),
    ("root-array.json", &["(root)", "JSON object"]),
    ("root-string.json", &["(root)", "JSON object"]),
    (
        "no-camera.json",
        &["(root)", "missing required key 'camera'"],
    ),
    ("camera-not-object.json", &["camera:", "expected an object"]),
    ("width-string.json", &["camera.width", "expected a number"]),
    ("width-zero.json", &["camera.width", "at least 1×1"]),
    ("height-negative.json", &["camera.height", "whole number"]),
    (
        "width-fraction.json",
        &["camera.width", "whole number", "8.5"],
    ),
    (
        "size-absurd.json",
        &["camera.width", "limit of 134217728 pixels", "--max-pixels"],
    ),
    (
        "fov-nan.json",
        &["camera.fov", "NaN is not a finite number"],
    ),
    ("fov-zero.json", &["camera.fov", "between 0 and 180"]),
    ("fov-180.json", &["camera.fov", "between 0 and 180"]),
    ("fov-missing.json", &["camera:", "'fov'"]),
    (
        "position-two-numbers.json",
        &["camera.position", "3 numbers", "2 elements"],
    ),
    (
        "position-string-element.json",
        &["camera.position[1]", "expected a number"],
    ),
    (
        "lookat-zero.json",
        &["camera.lookat", "viewing direction is zero"],
    ),
    ("nbounces-negative.json", &["nbounces", "whole number"]),
    (
        "nbounces-huge.json",
        &["nbounces", "limit of 64", "--max-bounces"],
    ),
    ("nbounces-string.json", &["nbounces", "expected a number"]),
    (
        "background-two-numbers.json",
        &["scene.backgroundcolor", "3 numbers"],
    ),
    (
        "shapes-not-array.json",
        &["scene.shapes", "expected an array"],
    ),
    (
        "shape-not-object.json",
        &["scene.shapes[0]", "a shape is an object"],
    ),
    ("shape-missing-type.json", &["scene.shapes[0]", "'type'"]),
    (
        "sphere-radius-negative.json",
        &["scene.shapes[0].radius", "> 0", "-1"],
    ),
    (
        "sphere-radius-zero.json",
        &["scene.shapes[0].radius", "> 0"],
    ),
    (
        "sphere-radius-infinity.json",
        &["scene.shapes[0].radius", "not a finite number"],
    ),
    (
        "sphere-radius-huge.json",
        &["scene.shapes[0].radius", "too large"],
    ),
    (
        "sphere-missing-center.json",
        &["scene.shapes[0]", "'center'"],
    ),
    ("triangle-missing-corner.json", &["scene.shapes[0]", "'v2'"]),
    ("triangle-zero-area.json", &["scene.shapes[0]", "zero area"]),
    ("quad-zero-area.json", &["scene.shapes[0]", "zero area"]),
    (
        "cylinder-axis-zero.json",
        &["scene.shapes[0].axis", "must not be zero"],
    ),
    (
        "cylinder-height-negative.json",
        &["scene.shapes[0].height", "> 0"],
    ),
    (
        "mesh-index-out-of-range.json",
        &[
            "scene.shapes[0].faces[0]",
            "index 3 is out of range",
            "3 vertices",
        ],
    ),
    (
        "mesh-index-negative.json",
        &["scene.shapes[0].faces[0]", "index -1 is out of range"],
    ),
    (
        "mesh-face-two-indices.json",
        &["scene.shapes[0].faces[0]", "at least 3"],
    ),
    ("mesh-no-faces.json", &["scene.shapes[0]", "no faces"]),
    (
        "mesh-file-missing.json",
        &[
            "scene.shapes[0].mPath",
            "not-there.ply",
            "not found",
            "tried",
        ],
    ),
    (
        "mesh-ply-lies-about-counts.json",
        &[
            "scene.shapes[0].mPath",
            "lying.ply",
            "1000000",
            "truncated or corrupt",
        ],
    ),
    (
        "mesh-ply-garbage.json",
        &["scene.shapes[0].mPath", "garbage.ply", "PLY header"],
    ),
    (
        "mesh-ply-bad-index.json",
        &[
            "scene.shapes[0].mPath",
            "bad-index.ply",
            "line 13",
            "out of range",
        ],
    ),
    (
        "mesh-obj-bad-index.json",
        &[
            "scene.shapes[0].mPath",
            "bad-index.obj",
            "line 4",
            "out of range",
        ],
    ),
    (
        "mesh-unknown-format.json",
        &["scene.shapes[0].mPath", ".stl", ".ply and .obj"],
    ),
    (
        "texture-missing.json",
        &["material.tPath", "none.png", "not found", "tried"],
    ),
    (
        "texture-truncated.json",
        &["material.tPath", "truncated.png", "cannot load the texture"],
    ),
    (
        "texture-not-an-image.json",
        &[
            "material.tPath",
            "not-an-image.png",
            "cannot load the texture",
        ],
    ),
    (
        "material-not-object.json",
        &["scene.shapes[0].material", "is an object"],
    ),
    (
        "material-unknown-name.json",
        &["scene.shapes[0].material", "no material named 'gold'"],
    ),
    ("kd-negative.json", &["material.kd", "≥ 0"]),
    ("eta-zero-glass.json", &["material.eta", "> 0"]),
    (
        "specular-exponent-negative.json",
        &["scene.shapes[0].material", "exponent", "≥ 0"],
    ),
    (
        "light-missing-position.json",
        &["scene.lightsources[0]", "'position'"],
    ),
    (
        "light-not-object.json",
        &["scene.lightsources[0]", "a light is an object"],
    ),
    (
        "light-intensity-string.json",
        &["scene.lightsources[0].intensity", "found a string"],
    ),
    (
        "arealight-no-geometry.json",
        &["scene.lightsources[0]", "needs corners"],
    ),
    (
        "arealight-samples-absurd.json",
        &[
            "scene.lightsources[0].samples",
            "limit of 65536",
            "--max-light-samples",
        ],
    ),
    (
        "arealight-samples-negative.json",
        &["scene.lightsources[0].samples", "whole number"],
    ),
    ("thinlens-no-focus.json", &["camera:", "focus distance"]),
    (
        "thinlens-negative-aperture.json",
        &["camera:", "aperture", "≥ 0"],
    ),
    (
        "rendermode-number.json",
        &["rendermode", "expected a string"],
    ),
    ("exposure-negative.json", &["camera.exposure", "≥ 0"]),
];

#[test]
fn every_broken_input_fails_cleanly_and_touches_nothing() {
    let dir = repo().join("tests/bad_input");
    let on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json") && !n.starts_with("fuzz-"))
        .collect();
    for name in &on_disk {
        assert!(
            CASES.iter().any(|(c, _)| c == name),
            "{name} has no expectation"
        );
    }
    assert!(CASES.len() >= 40);
    for (name, needles) in CASES {
        let scene = dir.join(name);
        assert!(scene.is_file(), "{name} missing");
        let out_dir = tempfile::tempdir().unwrap();
        let out = out_dir.path().join("render.png");
        std::fs::write(&out, b"an earlier render").unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_raytracer"))
            .arg(&scene)
            .arg(&out)
            .output()
            .unwrap();
        let msg = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{name}: {msg}");
        assert!(!msg.contains("panicked"), "{name}: {msg}");
        assert!(
            msg.contains(name),
            "{name}: the message does not name the file: {msg}"
        );
        for n in *needles {
            assert!(msg.contains(n), "{name}: the message lacks '{n}': {msg}");
        }
        assert_eq!(std::fs::read(&out).unwrap(), b"an earlier render", "{name}");
        assert_eq!(
            std::fs::read_dir(out_dir.path()).unwrap().count(),
            1,
            "{name}: stray files"
        );
    }
}
